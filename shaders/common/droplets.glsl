// Liquid droplets (the droplets paper, §3.2; app/data/droplets/droplets.h): analytic spheres read from a file, found
// through a uniform grid walked in 3D-DDA order (Amanatides & Woo 1987). Sub-pixel droplets are not
// traced: the ray goes straight through, dimmed by the droplet's mean transmittance (DROPLET_LOD).
// Needs: fresnelDielectric (common/brdf.glsl), footprintAt (common/uniforms.glsl).
#include "common/hit.glsl" // sampleGrazed, the pass-by flag

uniform samplerBuffer uDroplets;      // droplet i: centre xyz, radius w
uniform usamplerBuffer uDropletIndex; // droplet numbers, cell after cell (BVH: in leaf order)
#if DROPLET_BVH
uniform usamplerBuffer uDropletNodes; // 2 texels a node: (lo, first), (hi, count); lo, hi as float bits
#else
uniform usamplerBuffer uDropletCells; // cell c lists uDropletIndex[cells[c] .. cells[c + 1])
#endif
uniform vec3 uDropletLo, uDropletHi, uDropletCell;
uniform ivec3 uDropletDims;
uniform float uDropletIor, uDropletRoughness;
uniform vec3 uDropletAbsorption;      // per metre inside (Bouguer–Beer–Lambert)
// The level of detail's quadrature over a droplet's disc (app/data/droplets/droplets.c droplets_lod_table):
// mean transmittance = Σ weight_k · exp(−σ · 2r · cosT_k); mean reflectance uDropletReflect.
uniform float uDropletLodWeight[8], uDropletLodCosT[8];
uniform float uDropletReflect;

vec4 droplet(int i) { return texelFetch(uDroplets, i); }

// Ray–sphere in the numerically stable form of Haines, Günther & Akenine-Möller, "Precision
// Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, 2019, ch. 7): the discriminant from
// the centre's distance to the line (no cancellation for a small sphere far away), the smaller root
// from the product of the roots (no cancellation when a root is near 0). rd is a unit vector.
// t0 ≤ t1; false on a miss.
bool sphereRoots(vec3 ro, vec3 rd, vec4 s, out float t0, out float t1)
{
    vec3 f = ro - s.xyz;
    float b = dot(f, rd);
    vec3 l = f - b * rd;
    float disc = s.w * s.w - dot(l, l);
    t0 = t1 = 0.0;
    if (disc < 0.0)
        return false;
    float c = dot(f, f) - s.w * s.w;
    float q = -b - (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc);
    float ta = q != 0.0 ? c / q : 0.0;
    t0 = min(ta, q);
    t1 = max(ta, q);
    return true;
}

// Adaptive sampling's pass-by (common/hit.glsl): the ray passes droplet s, whose nearest point to the
// ray lies within (tmin, tmax), closer than GRAZE_FOOTPRINTS pixel footprints without entering it.
void dropletGraze(vec3 ro, vec3 rd, vec4 s, float tmin, float tmax, float pathT)
{
    vec3 f = ro - s.xyz;
    float tc = -dot(f, rd), miss = length(f + tc * rd) - s.w;
    sampleGrazed = sampleGrazed || (tc > tmin && tc < tmax && miss > 0.0 && miss < GRAZE_FOOTPRINTS * footprintAt(pathT + tc));
}

// The droplet's mean transmittance over its disc (no bending: the ray goes on as it came).
vec3 dropletMeanTransmittance(float r)
{
    vec3 T = vec3(0.0);
    for (int k = 0; k < 8; k++)
        T += uDropletLodWeight[k] * exp(-uDropletAbsorption * (2.0 * r * uDropletLodCosT[k]));
    return T;
}

const bool DROPLET_LOD_ON = float(DROPLET_LOD) > 0.0;

bool dropletIsSubPixel(float r, float pathT)
{
    return r < float(DROPLET_LOD) * footprintAt(pathT);
}

// The first droplet other than `skip` among uDropletIndex[first .. last) that holds p, or −1.
int dropletHolding(vec3 p, int skip, int first, int last)
{
    for (int k = first; k < last; k++) {
        int id = int(texelFetch(uDropletIndex, k).r);
        vec4 s = droplet(id);
        vec3 f = p - s.xyz;
        if (id != skip && dot(f, f) < s.w * s.w)
            return id;
    }
    return -1;
}

// 1 / rd without infinities: an axis the ray does not move on gets 1e30, so slab tests never form 0 · inf.
vec3 safeInverse(vec3 rd)
{
    return 1.0 / mix(rd, vec3(1e-30), equal(rd, vec3(0.0)));
}

#if !DROPLET_BVH
// The nearest droplet the ray enters within (tmin, tmax), skipping droplet `skip` (the one whose
// surface the ray starts on). Sub-pixel droplets before it and before tSurface (at path length
// pathT + t) are passed through: throughput is dimmed by their mean transmittance and `reflected`
// gathers the weight of the light they reflect. `cells` counts the grid cells visited. Returns the
// droplet's number or −1. Culling is tmax = tSurface, the scene's hit: the walk stops there.
int dropletsWalk(vec3 ro, vec3 rd, float tmin, float tmax, float tSurface, int skip, float pathT,
                 inout vec3 throughput, inout vec3 reflected, out float tHit, out int cells)
{
    tHit = tmax;
    cells = 0;
    vec3 inv = safeInverse(rd);
    vec3 ta = (uDropletLo - ro) * inv, tb = (uDropletHi - ro) * inv;
    vec3 tn = min(ta, tb), tf = max(ta, tb);
    float tEnter = max(max(tn.x, tn.y), max(tn.z, tmin));
    float tExit = min(min(tf.x, tf.y), min(tf.z, tmax));
    if (!(tEnter <= tExit)) // also false for NaN from 0 · inf on a face plane
        return -1;
    ivec3 dims = uDropletDims;
    ivec3 cell = clamp(ivec3(floor((ro + rd * tEnter - uDropletLo) / uDropletCell)), ivec3(0), dims - 1);
    ivec3 stepDir = ivec3(sign(rd));
    vec3 boundary = uDropletLo + (vec3(cell) + max(vec3(stepDir), 0.0)) * uDropletCell;
    const float NEVER = 3.4e38;
    vec3 tMax = vec3(rd.x != 0.0 ? (boundary.x - ro.x) * inv.x : NEVER, rd.y != 0.0 ? (boundary.y - ro.y) * inv.y : NEVER,
                     rd.z != 0.0 ? (boundary.z - ro.z) * inv.z : NEVER);
    vec3 tDelta = vec3(rd.x != 0.0 ? uDropletCell.x * abs(inv.x) : NEVER, rd.y != 0.0 ? uDropletCell.y * abs(inv.y) : NEVER,
                       rd.z != 0.0 ? uDropletCell.z * abs(inv.z) : NEVER);
    int best = -1;
    float cellEnter = tEnter;
    int maxCells = dims.x + dims.y + dims.z + 3;
    for (int i = 0; i < maxCells; i++) {
        cells++;
        float cellExit = min(min(tMax.x, tMax.y), min(tMax.z, tExit));
        int c = cell.x + dims.x * (cell.y + dims.y * cell.z);
        int first = int(texelFetch(uDropletCells, c).r), last = int(texelFetch(uDropletCells, c + 1).r);
        // the nearest traced droplet: a sphere's entry lies in a cell the sphere meets, so once the
        // nearest entry so far is inside this cell, no later cell can hold a nearer one
        bool subPixel = false; // met one: the second pass is needed
        for (int k = first; k < last; k++) {
            int id = int(texelFetch(uDropletIndex, k).r);
            vec4 s = droplet(id);
            float t0, t1;
            if (id != skip)
                dropletGraze(ro, rd, s, tmin, tHit, pathT);
            if (id == skip || !sphereRoots(ro, rd, s, t0, t1) || t0 <= tmin || t0 >= tHit)
                continue;
            if (DROPLET_LOD_ON && dropletIsSubPixel(s.w, pathT + t0)) {
                subPixel = true;
                continue;
            }
            tHit = t0;
            best = id;
        }
        // sub-pixel droplets whose entry lies in this cell and before the nearest traced one (each is
        // counted in the one cell its entry lies in)
        for (int k = first; subPixel && k < last; k++) {
            int id = int(texelFetch(uDropletIndex, k).r);
            vec4 s = droplet(id);
            float t0, t1;
            if (id == skip || !sphereRoots(ro, rd, s, t0, t1) || t0 <= tmin || t0 < cellEnter || t0 >= cellExit ||
                t0 >= tHit || t0 >= tSurface || !dropletIsSubPixel(s.w, pathT + t0))
                continue;
            reflected += throughput * uDropletReflect;
            throughput *= dropletMeanTransmittance(s.w);
        }
        if (tHit <= cellExit || cellExit >= tExit)
            break;
        cellEnter = cellExit;
        if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
            cell.x += stepDir.x;
            tMax.x += tDelta.x;
        } else if (tMax.y <= tMax.z) {
            cell.y += stepDir.y;
            tMax.y += tDelta.y;
        } else {
            cell.z += stepDir.z;
            tMax.z += tDelta.z;
        }
        if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, dims)))
            break;
    }
    return best;
}

#endif

#if !DROPLET_BVH
// The droplet other than `skip` that holds point p (−1 when p is in air): the cell of p lists every
// droplet that could.
int dropletAt(vec3 p, int skip)
{
    if (any(lessThan(p, uDropletLo)) || any(greaterThan(p, uDropletHi)))
        return -1;
    ivec3 cell = clamp(ivec3(floor((p - uDropletLo) / uDropletCell)), ivec3(0), uDropletDims - 1);
    int c = cell.x + uDropletDims.x * (cell.y + uDropletDims.y * cell.z);
    return dropletHolding(p, skip, int(texelFetch(uDropletCells, c).r), int(texelFetch(uDropletCells, c + 1).r));
}

#else
// The same two queries through the BVH (to compare with the grid; droplets.structure = "bvh").
const int DROPLET_STACK = 48; // ≥ BVH depth + 1 (median split over 2^24 droplets: depth ≤ 24)

void dropletNode(int n, out vec3 lo, out vec3 hi, out int first, out int count)
{
    uvec4 a = texelFetch(uDropletNodes, 2 * n), b = texelFetch(uDropletNodes, 2 * n + 1);
    lo = uintBitsToFloat(a.xyz);
    hi = uintBitsToFloat(b.xyz);
    first = int(a.w);
    count = int(b.w);
}

// Where the ray enters the box within [tmin, tmax]; a miss gives +inf-like 3e38.
float boxEntry(vec3 ro, vec3 inv, vec3 lo, vec3 hi, float tmin, float tmax)
{
    vec3 ta = (lo - ro) * inv, tb = (hi - ro) * inv;
    vec3 tn = min(ta, tb), tf = max(ta, tb);
    float tEnter = max(max(tn.x, tn.y), max(tn.z, tmin));
    float tExit = min(min(tf.x, tf.y), min(tf.z, tmax));
    return tEnter <= tExit ? tEnter : 3e38;
}

// pass 0: the nearest traced droplet (tHit shrinks); pass 1: sub-pixel droplets before tHit and tSurface.
int dropletsBvhPass(int pass, vec3 ro, vec3 rd, vec3 inv, float tmin, float tSurface, int skip, float pathT,
                    inout float tHit, inout vec3 throughput, inout vec3 reflected, inout int nodes, out bool subPixel)
{
    int stack[DROPLET_STACK];
    int sp = 0, best = -1;
    subPixel = false;
    stack[sp++] = 0;
    while (sp > 0) {
        int n = stack[--sp];
        nodes++;
        vec3 lo, hi;
        int first, count;
        dropletNode(n, lo, hi, first, count);
        float tLimit = pass == 0 ? tHit : min(tHit, tSurface);
        if (boxEntry(ro, inv, lo, hi, tmin, tLimit) >= tLimit)
            continue;
        if (count > 0) {
            for (int k = first; k < first + count; k++) {
                int id = int(texelFetch(uDropletIndex, k).r);
                vec4 s = droplet(id);
                float t0, t1;
                if (pass == 0 && id != skip)
                    dropletGraze(ro, rd, s, tmin, tHit, pathT);
                if (id == skip || !sphereRoots(ro, rd, s, t0, t1) || t0 <= tmin || t0 >= tHit ||
                    (pass == 1 && t0 >= tSurface))
                    continue;
                bool sub = DROPLET_LOD_ON && dropletIsSubPixel(s.w, pathT + t0);
                if (pass == 0 && !sub) {
                    tHit = t0;
                    best = id;
                } else if (pass == 0) {
                    subPixel = true;
                } else if (sub) {
                    reflected += throughput * uDropletReflect;
                    throughput *= dropletMeanTransmittance(s.w);
                }
            }
            continue;
        }
        // both children, the nearer popped first
        vec3 alo, ahi, blo, bhi;
        int f, c;
        dropletNode(first, alo, ahi, f, c);
        dropletNode(first + 1, blo, bhi, f, c);
        float ta = boxEntry(ro, inv, alo, ahi, tmin, tLimit), tb = boxEntry(ro, inv, blo, bhi, tmin, tLimit);
        bool aFirst = ta <= tb;
        if (max(ta, tb) < tLimit && sp < DROPLET_STACK)
            stack[sp++] = aFirst ? first + 1 : first;
        if (min(ta, tb) < tLimit && sp < DROPLET_STACK)
            stack[sp++] = aFirst ? first : first + 1;
    }
    return best;
}

int dropletsWalk(vec3 ro, vec3 rd, float tmin, float tmax, float tSurface, int skip, float pathT,
                 inout vec3 throughput, inout vec3 reflected, out float tHit, out int cells)
{
    vec3 inv = safeInverse(rd);
    tHit = tmax;
    cells = 0;
    bool subPixel;
    int best = dropletsBvhPass(0, ro, rd, inv, tmin, tSurface, skip, pathT, tHit, throughput, reflected, cells, subPixel);
    if (subPixel)
        dropletsBvhPass(1, ro, rd, inv, tmin, tSurface, skip, pathT, tHit, throughput, reflected, cells, subPixel);
    return best;
}

int dropletAt(vec3 p, int skip)
{
    int stack[DROPLET_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        vec3 lo, hi;
        int first, count;
        dropletNode(stack[--sp], lo, hi, first, count);
        if (any(lessThan(p, lo)) || any(greaterThan(p, hi)))
            continue;
        if (count == 0) {
            if (sp + 2 <= DROPLET_STACK) {
                stack[sp++] = first;
                stack[sp++] = first + 1;
            }
            continue;
        }
        int id = dropletHolding(p, skip, first, first + count);
        if (id >= 0)
            return id;
    }
    return -1;
}
#endif

// Crossing the liquid's surface along rd at outward normal nOut, into the droplet (entering) or out of
// it: exact Fresnel for unpolarized light. rd becomes the refracted direction (Snell), or the mirrored
// one under total internal reflection (then the result is 1). Returns the reflected fraction F.
float dropletCross(inout vec3 rd, vec3 nOut, bool entering)
{
    vec3 n = entering ? nOut : -nOut; // faces the incoming ray
    float eta = entering ? 1.0 / uDropletIor : uDropletIor;
    float F = fresnelDielectric(max(-dot(rd, n), 0.0), eta);
    rd = F >= 1.0 ? reflect(rd, n) : normalize(refract(rd, n, eta));
    return F;
}
