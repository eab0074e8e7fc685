// Sphere tracing against the scene's map(). Needs: vec2 map(vec3 p) -> (distance, material).
//
// Hit threshold: a ray has hit when the distance bound drops below eps(t) = HIT_K * t * pixel angle,
// i.e. HIT_K pixel footprints at the distance travelled, so the image keeps its character at any
// resolution. HIT_EPS_MIN keeps eps above float resolution near the eye.

#ifndef HIT_EPS_MIN
#define HIT_EPS_MIN 1e-5
#endif
// New rays (shadow, reflection, refraction) start this many hit thresholds off the surface, along the
// normal: the point we hit lies up to eps from the surface, so a ray started there would hit it again
// at once (self-shadowing "acne"; the shadows chapter's epsilon offset).
#ifndef SURFACE_OFFSET_K
#define SURFACE_OFFSET_K 4.0
#endif

// Positions are float: near |p| a step below about 4 ulps (|p| · 2⁻²¹, PRECISION_REL from the C
// preamble) cannot be resolved and would only add noise, so the threshold never goes below that.
// In a deep zoom positions are relative to the eye (uCamPos = 0), so that floor is relative to the
// distance travelled, and the double origin's own resolution is added (common/uniforms.glsl).
float positionFloor(float t)
{
#ifdef PRECISION_DOUBLE
    return PRECISION_REL * t + uOriginFloor;
#else
    return PRECISION_REL * (length(uCamPos) + t);
#endif
}

float hitEps(float t)
{
#ifdef HIT_RELATIVE // Fragmentarium's rule: relative to the distance travelled (castRay below; fractal/common.glsl)
    return max(uHitRelative * t, positionFloor(t));
#elif defined(HIT_DISTANCE) // an absolute hit distance (fractal.hit_distance), not the footprint rule
    return max(HIT_DISTANCE, positionFloor(t));
#else
    return max(max(float(HIT_K) * footprintAt(t), HIT_EPS_MIN), positionFloor(t));
#endif
}

#include "common/hit.glsl"

// side = +1 marches outside solids, -1 inside (refraction); pathT = path length before this ray,
// so thresholds keep growing with the total distance from the eye.
//
// Over-relaxation (OVER_RELAX = ω > 1; Keinert, Schäfer, Korndörfer, Ganse, Stamminger, "Enhanced
// Sphere Tracing", 2014): step ω·d instead of d. Each distance is an empty ball; while consecutive
// balls overlap the stretch between them is empty. When they do not, the long step may have passed
// a surface: go back to the plain step from the last point and march plainly from there.
//
// A hit is a surface, not a near miss (REFINE_STEPS > 0, for programs whose distance is exact or a
// bound). The footprint threshold eps(t) only ends the big relaxed steps. Below it the march goes on:
// approaching (the distance fell since the last step) it takes plain sphere-tracing steps, which
// never pass a surface; passing by (the distance grew) it steps max(d, eps), so a ray that skims a
// long face does not crawl along it (only a feature thinner than eps right beside that face could be
// stepped over). A program whose map() is a bound far below the distance (the noise terrain's
// Lipschitz-scaled field) may set NEAR_MIN_STEP (in thresholds) so its hits converge in a few steps
// instead of hundreds; the price is that such a step can cross a chord shorter than itself (the rim
// of a silhouette, a corner sliver): silhouettes shrink and depth may lie behind by up to that step. A hit is either a distance within float resolution of 0, or a sign change, whose
// bracket [outside, inside] is narrowed by REFINE_STEPS Illinois regula-falsi steps (Dowell &
// Jarratt 1971); the hit is the bracket's outside end, so depth is never behind the surface. A ray
// that passes within eps of a surface without crossing it is a miss: silhouettes, thin shells and
// narrow gaps keep their true size (tests/gpu/test_silhouette.c). A program whose surface *is* defined
// by the footprint (fractals at a level of detail: PROGRAM_FOOTPRINT_SURFACE) keeps the plain rule.
// (A secant step toward the predicted crossing converged faster on grazing hits, but stepped across
// corner slivers up to 2 eps thick, and as a guess for rays out of steps it put hits behind a crossing
// it had skipped.)
//
// A ray that runs out of MAX_STEPS short of tmax is neither a hit nor a miss: tailMarch() below.
//
// A program whose map() is far below the distance (PROGRAM_SLOW_BOUND) marches to the crossing at every
// REFINE_STEPS, 0 included (the crossing then unrefined: the outside end plus its own bound): "within
// eps" of such a bound is up to its slack (20 thresholds) from the surface, and a ray that grazes a far
// ridge stopped there drew a band of false ground above the horizon (2,049 pixels of the noise terrain
// at the draft preset).
#ifndef NEAR_MIN_STEP
#define NEAR_MIN_STEP 0.0
#endif
#ifndef NORMAL_EPS_FRACTION
#define NORMAL_EPS_FRACTION 0.05
#endif
#if (REFINE_STEPS > 0 || defined(PROGRAM_SLOW_BOUND)) && !defined(PROGRAM_FOOTPRINT_SURFACE)
#define MARCH_REFINES 1
#else
#define MARCH_REFINES 0
#endif

// The surface between a (outside, distance fa > 0) and b (inside, fb < 0), by Illinois regula falsi.
// The answer is the outside end moved on by its own distance bound (STEP_FACTOR of it, as a march step):
// never past the surface, and exact head-on. Without that last step a bracket whose secants all land
// inside (a sphere's distance along a ray is convex) would keep its outside end where it started.
// A slow bound marches to the crossing at REFINE_STEPS 0 too (above) and refines it at least this much:
// its tail steps 2 thresholds, and the bracket's outside end alone left 135 depths of the noise terrain's
// draft view short by up to that (4 steps still left one 1.5 thresholds short).
#if defined(PROGRAM_SLOW_BOUND) && REFINE_STEPS < 8
#define CROSSING_STEPS 8
#else
#define CROSSING_STEPS REFINE_STEPS
#endif
float refineCrossing(vec3 ro, vec3 rd, float side, float a, float fa, float b, float fb, float pathT, inout int steps)
{
    int lastSide = 0;
    float da = fa; // the distance bound at a (fa is halved by Illinois)
    for (int i = 0; i < CROSSING_STEPS; i++) {
        float floorEps = positionFloor(pathT + a);
        if (b - a <= floorEps || fa <= floorEps)
            break;
        float t = clamp(a + (b - a) * fa / (fa - fb), a, b);
        float f = side * map(ro + rd * t).x;
        steps++;
        if (f >= 0.0) { // on the surface counts as outside: the bracket then closes on it (with "> 0" a
                        // step landing exactly on a plane left the outside end where it was: depth short)
            a = t;
            fa = da = f;
            if (lastSide == 1)
                fb *= 0.5; // Illinois: the stale end's weight halves, so both ends keep moving
            lastSide = 1;
        } else {
            b = t;
            fb = f;
            if (lastSide == -1)
                fa *= 0.5;
            lastSide = -1;
        }
    }
    return min(a + da * float(STEP_FACTOR), b);
}

#ifndef PROGRAM_CAST_RAY
// The distance the march steps by. A program may give a bound along the ray instead of around the
// point (PROGRAM_MAP_ALONG: vec2 mapAlong(vec3 p, vec3 dir), no surface within that distance along
// dir: Galin et al. 2020, "Segment tracing using local Lipschitz bounds"), which can be far longer
// where the field changes slowly in that direction. Its sign and material are map()'s.
#ifdef PROGRAM_MAP_ALONG
vec2 marchMap(vec3 p, vec3 dir) { return mapAlong(p, dir); }
#else
vec2 marchMap(vec3 p, vec3 dir) { return map(p); }
#endif
#endif

#if defined(HIT_RELATIVE) && !defined(PROGRAM_CAST_RAY)
// Fragmentarium's DE renderers' rule (app/scene/formula/frag.h), as their trace() has it (DE-Raytracer
// of Syntopia's Fragmentarium and of 3Dickulus' FragM; Fast-, Soft-, IBL- and the DE-Kn renderers alike):
// each step adds d·F (F = FudgeFactor, the step factor) to t, and the ray has hit when that step is
// below 10^Detail · t, t taken after the step; the hit is then moved back by the difference,
// t − (10^Detail·t − d·F). A ray that runs out of MaxRaySteps (MAX_STEPS), or goes past MaxDistance, is
// background: no tail, no refinement. (The renderers also shorten the first step by a random share,
// Dither, against banding; fathom's jittered samples do without.) The bounding sphere of fathom's own
// formulas is stepped through, never stopped on.
Hit castRay(vec3 ro, vec3 rd, float tmax, float side, float pathT)
{
    Hit h = Hit(false, 0.0, -1.0, 0, false, 0);
    float t = 0.0;
    tmax = min(tmax, uFragMaxDistance);
    bool boundPrev = true;
    float stepPrev = 0.0;
    for (int i = 0; i < MAX_STEPS && loopSpend(1); i++) {
        h.steps = i + 1;
        vec2 d = map(ro + rd * t);
        float step = side * d.x * float(STEP_FACTOR);
        bool bound = isBound(d);
        h.boundSteps += bound ? 1 : 0;
        if (!bound && !boundPrev && step > stepPrev && stepPrev > 0.0) // passed by (as castRay below)
            sampleGrazed = sampleGrazed || stepPrev < GRAZE_FOOTPRINTS * footprintAt(pathT + t) + hitEps(pathT + t);
        boundPrev = bound;
        stepPrev = step;
        t += step;
        float eps = hitEps(pathT + t);
        if (!bound && step < eps) {
            h.hit = true;
            h.mat = d.y;
            t = max(t - (eps - step), 0.0);
            break;
        }
        if (t > tmax)
            break;
    }
    if (loopOut) { // out of the loop budget (common/budget.glsl): unresolved
        h.hit = false;
        h.exhausted = true;
    }
    h.t = t;
    return h;
}
#elif !defined(PROGRAM_CAST_RAY) // a program may march its own way (terrain)

// A ray that runs out of MAX_STEPS short of tmax has found nothing yet: it is neither a hit nor a miss.
// It goes on, up to TAIL_STEPS more, taking steps of at least TAIL_MIN_STEP thresholds (so it cannot
// crawl: a ray that skims a surface for a long way is what runs out), and ends as any ray ends: a
// crossing refined to the surface, a hit within the threshold (a fractal's footprint), or past tmax, a
// miss. A forced step toward a surface is checked: if the two distance balls leave a gap between
// them (landing outside or inside), the gap is walked by its own balls, at least TAIL_GAP_STEP
// thresholds a step, and the first crossing found there is the one refined (a half-gap sample alone
// still passed through 17 rounded edges of 10,093 pixels and hit what lay behind). The tolerance this
// leaves is stated: something thinner than half a threshold in a gap, or than a forced step beside a
// face the ray skims, can be stepped over. A ray still unresolved after that is flagged (h.exhausted,
// the steps AOV negative, magenta in the heat map) and drawn as a miss: never a guess drawn as geometry.
#ifndef TAIL_MIN_STEP
#define TAIL_MIN_STEP 4.0
#endif
#ifndef TAIL_GAP_STEP
#define TAIL_GAP_STEP 0.5
#endif
#ifndef TAIL_STEPS
#define TAIL_STEPS MAX_STEPS
#endif
void tailMarch(inout Hit h, inout float t, vec3 ro, vec3 rd, float tmax, float side, float pathT, float tPrev,
               float fPrev)
{
    bool forced = false; // the last step was longer than its distance bound, toward a surface
    for (int i = 0; i < TAIL_STEPS && !h.hit && loopSpend(1); i++) {
        vec2 d = marchMap(ro + rd * t, rd * side);
        float dist = side * d.x, eps = hitEps(pathT + t);
        bool bound = isBound(d);
        h.steps++;
        // A forced step toward a surface whose two distance balls leave a gap may have passed through
        // something thinner than the step (a torus's tube seen end on, a rounded edge): walk the gap.
        // (not where hits are footprints: there a threshold is the surface's own tolerance)
#if MARCH_REFINES
        if (forced && !bound && fPrev + abs(dist) < t - tPrev) {
            // walk the gap by its own distance balls, at least TAIL_GAP_STEP thresholds a step; landing
            // inside, the first crossing may lie in the gap (through a thin solid into the next)
            float s = tPrev + fPrev, gapEnd = t - abs(dist);
            for (int k = 0; k < int(TAIL_MIN_STEP / TAIL_GAP_STEP) + 1 && s < gapEnd; k++) {
                vec2 g = marchMap(ro + rd * s, rd * side);
                float fs = side * g.x;
                h.steps++;
                if (!isBound(g) && fs < 0.0) { // inside something the forced step passed through
                    t = refineCrossing(ro, rd, side, tPrev, fPrev, s, fs, pathT, h.steps);
                    h.hit = true;
                    h.mat = map(ro + rd * t).y;
                    return;
                }
                tPrev = s; // the bracket for a crossing at t starts at the last sample outside
                fPrev = fs;
                s += max(fs, TAIL_GAP_STEP * eps);
            }
        }
#endif
#if MARCH_REFINES
        if (!bound && abs(dist) <= positionFloor(pathT + t)) {
            h.hit = true;
        } else if (!bound && dist < 0.0) { // crossed since the last sample: locate the surface
            t = refineCrossing(ro, rd, side, tPrev, fPrev, t, dist, pathT, h.steps);
            d = map(ro + rd * t);
            h.hit = true;
        }
#else
        h.hit = !bound && dist < eps;
#endif
        if (h.hit) {
            h.mat = d.y;
            return;
        }
        bool approaching = dist < fPrev;
        float step = bound ? dist : max(dist * float(STEP_FACTOR), TAIL_MIN_STEP * eps);
        forced = !bound && approaching && step > dist; // checked above: a pass-by keeps the main march's tolerance
        tPrev = t;
        fPrev = dist;
        t += step;
        if (t > tmax)
            return; // a miss
    }
    h.exhausted = true;
}

// Coverage from the cone (COVERAGE = 1; Hart 1996, "Sphere tracing", on cone tracing for anti-aliasing;
// Quilez's per-pixel coverage from the closest approach): while coverTrack is set (the primary ray of
// a pixel's centre sample), the march keeps the pass-by (a local minimum of the distance to a surface
// it then moves away from) that comes closest relative to the pixel's width there: coverRatio pixel
// widths from the surface, at coverT; sdf_main.glsl turns it into the share of the pixel that surface
// covers. It needs a distance close to the true one, so only programs whose hits are surfaces and
// whose bound is tight take it: a fractal's estimate runs below the distance (the Mandelbox's by up to
// half), which made silhouettes too wide (its edge error 0.0285 without, 0.0349 with).
#if COVERAGE && MARCH_REFINES && !defined(PROGRAM_SLOW_BOUND)
#define MARCH_COVERAGE 1
#endif
bool coverTrack = false;
float coverRatio = 1e30, coverT = 0.0;

Hit castRay(vec3 ro, vec3 rd, float tmax, float side, float pathT)
{
    Hit h = Hit(false, 0.0, -1.0, 0, false, 0);
    float omega = float(OVER_RELAX);
    bool relaxedPrev = false; // the last step was ω times its bound (over-relaxation): check it
    float t = 0.0, tPrev = 0.0, rPrev = 0.0, fPrev = 0.0; // rPrev = |fPrev|: the last ball's radius
    float floorBase = positionFloor(pathT); // float resolution at t = 0
    bool boundPrev = true;
    for (int i = 0; i < MAX_STEPS && loopSpend(1); i++) {
        h.steps = i + 1;
        vec2 d = marchMap(ro + rd * t, rd * side);
        float dist = side * d.x;
        float eps = hitEps(pathT + t);
        bool bound = isBound(d);
        h.boundSteps += bound ? 1 : 0;
        if (!bound && !boundPrev && dist > fPrev && fPrev > 0.0) { // passed by at tPrev
            float footprint = footprintAt(pathT + tPrev);
            sampleGrazed = sampleGrazed || fPrev < GRAZE_FOOTPRINTS * footprint + (MARCH_REFINES == 1 ? 0.0 : eps);
#ifdef MARCH_COVERAGE
            if (coverTrack && fPrev / footprint < coverRatio) {
                coverRatio = fPrev / footprint;
                coverT = tPrev;
            }
#endif
        }
        boundPrev = bound;
        if (relaxedPrev && (abs(dist) + rPrev < t - tPrev || (MARCH_REFINES == 1 && dist < 0.0))) {
            t = tPrev + rPrev * float(STEP_FACTOR);
            relaxedPrev = false;
            continue;
        }
        float step = omega * dist * float(STEP_FACTOR);
        bool relaxed = omega > 1.0;
#if MARCH_REFINES
        // on the surface, or inside at the start (a camera inside a solid); a negative distance later
        // is a crossing and is refined (a "dist <= floor" test here took an overshoot as the hit, up to
        // a passing-by step behind the surface: seen where many solids overlap, test_silhouette)
        if (!bound && (abs(dist) <= floorBase + PRECISION_REL * t || (i == 0 && dist < 0.0))) {
            h.hit = true;
        } else if (!bound && dist < 0.0) { // crossed since the last step: locate the surface
            t = refineCrossing(ro, rd, side, tPrev, fPrev, t, dist, pathT, h.steps);
            d = map(ro + rd * t);
            h.hit = true;
        } else if (!bound && dist < eps) {
            bool approaching = i == 0 || dist < fPrev;
            step = approaching ? max(dist * float(STEP_FACTOR), NEAR_MIN_STEP * eps) : max(dist, eps);
            relaxed = false;
        }
#else
        // (a relaxed step that lands inside fails the balls' check above: an outside ball and an inside
        // one never overlap; inside at the start is a camera in a solid, a hit as with plain steps)
        if (!bound && dist < eps)
            h.hit = true;
#endif
        if (h.hit) {
            h.mat = d.y;
            break;
        }
        tPrev = t;
        fPrev = dist;
        rPrev = abs(dist);
        relaxedPrev = relaxed;
        t += step;
        if (t > tmax)
            break;
    }
    if (!h.hit && t <= tmax && h.steps >= MAX_STEPS) // out of steps: not yet a hit, nor a miss
        tailMarch(h, t, ro, rd, tmax, side, pathT, tPrev, fPrev);
    if (loopOut) { // out of the loop budget (common/budget.glsl): unresolved, whatever it had found
        h.hit = false;
        h.exhausted = true;
    }
    h.t = t;
    return h;
}
#endif

#ifndef MARCH_COVERAGE // a program that marches its own way (terrain) has no pass-bys to give
#define MARCH_COVERAGE 0
#endif

// The finite-difference step of normals. Where hits are surfaces (MARCH_REFINES) a small fraction of the
// threshold: a step of a whole threshold mixes in the other solid's gradient within eps of a crease, a
// bright or dark line a pixel wide where two solids meet (the mirror's foot on the ground). Where the
// surface is the footprint's (fractals), the threshold itself, so normals are as smooth as the surface.
// Never below a few float steps of the position, where differences would be rounding noise.
float normalEps(float eps, float t)
{
#if MARCH_REFINES
    return max(NORMAL_EPS_FRACTION * eps, 16.0 * positionFloor(t));
#else
    return eps;
#endif
}

#ifndef PROGRAM_NORMAL // a program may know its normals better (terrain: from the heightfield)
// Gradient of the distance by the tetrahedron of central differences (four map() calls).
// Where the gradient vanishes (the centre of a sphere, a point on a symmetry plane of a solid that a
// camera sits inside) normalize() would return NaN: `fallback` (unit) is returned instead.
vec3 calcNormal(vec3 p, float eps, vec3 fallback)
{
    const vec2 k = vec2(1.0, -1.0);
    vec3 g = k.xyy * map(p + k.xyy * eps).x + k.yyx * map(p + k.yyx * eps).x +
             k.yxy * map(p + k.yxy * eps).x + k.xxx * map(p + k.xxx * eps).x;
    float len = length(g);
    return len > 1e-20 ? g / len : fallback;
}
#endif

// The outward normal where a ray hit a surface of material mat: a terrain's water's (terrain/terrain.glsl:
// its material says so; a normal from the geometry near a shore, where the ground lies within eps of the
// level, would tilt there); everything else the program's.
vec3 hitNormal(float mat, vec3 p, float eps, vec3 fallback)
{
#if FX_WATER
    if (isWater(mat))
        return waterNormal(p);
#endif
    return calcNormal(p, eps, fallback);
}
