// The csg program's primitive list: bounded primitives read from textures and found through a
// bounding volume hierarchy (app/data/droplets/bvh.h, packed by app/scene/scene_csg.c), so thousands of primitives cost
// a few dozen distance evaluations per map() call instead of thousands of lines of shader.
// Included by the generated program.glsl after listShape(), which it defines for the shapes present.
//
// uCsgList: 5 texels a primitive: (position, shape), (world-to-object row 0, material),
//   (row 1, k.x), (row 2, k.y), (k.z, k.w, -, -). uCsgNodes: 2 texels a node: (lo, first), (hi, count);
//   count 0: an inner node whose children are first and first + 1; else a leaf of primitives
//   first … first + count − 1. Both are CSG_TEXTURE_WIDTH texels wide, read in row-major order.
uniform sampler2D uCsgList;
uniform sampler2D uCsgNodes;

const int CSG_WIDTH = 4096; // CSG_TEXTURE_WIDTH
const int CSG_STACK = 32;   // ≥ BVH depth + 1 (median split: depth ≤ log2(n / 4) + 2; 21 for CSG_LIST_MAX)

vec4 csgTexel(sampler2D t, int i) { return texelFetch(t, ivec2(i % CSG_WIDTH, i / CSG_WIDTH), 0); }

// Signed distance from p to the box [lo, hi]. For any solid S inside the box, sd_S(p) >= sd_box(p):
// outside S, its distance is at least the box's; inside, the way out of S is no longer than the way
// out of the box. So it bounds the primitives' union from below, inside overlapping ones too (an
// unsigned 0 would not: it would skip a node whose primitive is deeper inside than the best so far).
float csgBoxDistance(vec3 p, vec3 lo, vec3 hi)
{
    vec3 q = max(lo - p, p - hi);
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

vec2 csgPrimitive(vec3 p, int i)
{
    vec4 a = csgTexel(uCsgList, 5 * i), r0 = csgTexel(uCsgList, 5 * i + 1), r1 = csgTexel(uCsgList, 5 * i + 2);
    vec4 r2 = csgTexel(uCsgList, 5 * i + 3), e = csgTexel(uCsgList, 5 * i + 4);
    vec3 d = p - a.xyz;
    vec3 q = vec3(dot(r0.xyz, d), dot(r1.xyz, d), dot(r2.xyz, d));
    return vec2(listShape(int(a.w), q, vec4(r1.w, r2.w, e.x, e.y)), r0.w);
}

// The union of `best` (the rest of the scene's distance and material) and the list's primitives.
// Exact where the primitives are: nodes are skipped only when their box is farther than the best.
vec2 listMap(vec3 p, vec2 best)
{
    int stack[CSG_STACK];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        int n = stack[--sp];
        vec4 lo = csgTexel(uCsgNodes, 2 * n), hi = csgTexel(uCsgNodes, 2 * n + 1);
        if (csgBoxDistance(p, lo.xyz, hi.xyz) >= best.x)
            continue;
        int first = int(lo.w), count = int(hi.w);
        if (count > 0) {
            for (int i = first; i < first + count; i++) {
                vec2 d = csgPrimitive(p, i);
                if (d.x < best.x)
                    best = d;
            }
            continue;
        }
        // both children; the nearer is popped first so the bound tightens sooner
        vec4 alo = csgTexel(uCsgNodes, 2 * first), ahi = csgTexel(uCsgNodes, 2 * first + 1);
        vec4 blo = csgTexel(uCsgNodes, 2 * first + 2), bhi = csgTexel(uCsgNodes, 2 * first + 3);
        float da = csgBoxDistance(p, alo.xyz, ahi.xyz), db = csgBoxDistance(p, blo.xyz, bhi.xyz);
        bool aFirst = da <= db;
        float dFar = aFirst ? db : da, dNear = aFirst ? da : db;
        if (dFar < best.x && sp < CSG_STACK)
            stack[sp++] = aFirst ? first + 1 : first;
        if (dNear < best.x && sp < CSG_STACK)
            stack[sp++] = aFirst ? first : first + 1;
    }
    return best;
}
