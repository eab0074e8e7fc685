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

float hitEps(float t)
{
    float floatFloor = PRECISION_REL * (length(uCamPos) + t);
    return max(max(float(HIT_K) * uPixelAngle * t, HIT_EPS_MIN), floatFloor);
}

#include "common/hit.glsl"

// side = +1 marches outside solids, -1 inside (refraction); pathT = path length before this ray,
// so thresholds keep growing with the total distance from the eye.
//
// Over-relaxation (OVER_RELAX = ω > 1; Keinert, Schäfer, Korndörfer, Ganse, Stamminger, "Enhanced
// Sphere Tracing", 2014): step ω·d instead of d. Each distance is an empty ball; while consecutive
// balls overlap the stretch between them is empty. When they do not, the long step may have passed
// a surface: go back to the plain step from the last point and march plainly from there.
#ifndef PROGRAM_CAST_RAY // a program may march its own way (terrain)
Hit castRay(vec3 ro, vec3 rd, float tmax, float side, float pathT)
{
    Hit h = Hit(false, 0.0, -1.0, 0);
    float omega = float(OVER_RELAX);
    float t = 0.0, tPrev = 0.0, rPrev = 0.0;
    for (int i = 0; i < MAX_STEPS; i++) {
        h.steps = i + 1;
        vec2 d = map(ro + rd * t);
        float dist = side * d.x;
        if (omega > 1.0 && i > 0 && abs(dist) + rPrev < t - tPrev) {
            t = tPrev + rPrev * float(STEP_FACTOR);
            omega = 1.0;
            continue;
        }
        // Plain marching: any distance below the threshold, negative too (a camera inside a solid), is a
        // hit. Relaxed: a step may land inside with its ball still overlapping the last one; then the
        // signed distance steps back out, as in Keinert et al.
        if (omega > 1.0 ? abs(dist) < hitEps(pathT + t) : dist < hitEps(pathT + t)) {
            h.hit = true;
            h.mat = d.y;
            break;
        }
        tPrev = t;
        rPrev = abs(dist);
        t += omega * dist * float(STEP_FACTOR);
        if (t > tmax)
            break;
    }
    h.t = t;
    return h;
}
#endif

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
