// @formula The Menger sponge (K. Menger, 1926) as an exact distance, not the usual bound: iterations are its levels
// @iterations 4 [1, 7]
// @bound size * 1.7320508
// @step 1
//
// The Menger sponge, level FRACTAL_ITERATIONS, as an exact distance (not the usual bound).
// The sponge is symmetric under the cube's 48 reflections, so folding p into x ≥ y ≥ z ≥ 0 keeps its
// distance. A level is 20 cubes of a third the size; in that region the nearest of them is the
// corner cube (⅔,⅔,⅔) or the edge cube (⅔,⅔,0): every other one is a mirror image lying on the far
// side of a mirror plane, hence farther. So the exact distance is the minimum over 2ᴺ paths of
// corner/edge choices; a path is dropped as soon as its cube's box distance (a lower bound for
// everything inside it) is no better than the best found, trying the nearer cube first.
#include "fractal/common.glsl"
uniform float uSize; // @param 1 [0.001, 10000] half the cube's side (metres)

const vec3 MENGER_CORNER = vec3(2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0);
const vec3 MENGER_EDGE = vec3(2.0 / 3.0, 2.0 / 3.0, 0.0);

vec3 foldOctahedral(vec3 q)
{
    q = abs(q);
    if (q.x < q.y) q.xy = q.yx;
    if (q.y < q.z) q.yz = q.zy;
    if (q.x < q.y) q.xy = q.yx;
    return q;
}

float mengerDE(vec3 p)
{
    const int N = FRACTAL_ITERATIONS;
    const int PATHS = 1 << N;
    float size = uSize;
    vec3 q0 = p / size;
    float best = 1e10;
    int m = 0;
    for (int guard = 0; guard < PATHS && m < PATHS; guard++, m++) {
        vec3 q = q0;
        float scale = 1.0;
        bool pruned = false;
        for (int l = 0; l < N; l++) {
            q = foldOctahedral(q);
            vec3 a = 3.0 * (q - MENGER_CORNER), b = 3.0 * (q - MENGER_EDGE);
            float da = sdBox(a, vec3(1.0)), db = sdBox(b, vec3(1.0));
            bool second = ((m >> (N - 1 - l)) & 1) == 1;
            bool takeA = (da <= db) != second;
            scale /= 3.0;
            if ((takeA ? da : db) * scale >= best) {
                m |= (1 << (N - 1 - l)) - 1; // skip every path below this cube
                pruned = true;
                break;
            }
            q = takeA ? a : b;
        }
        if (!pruned)
            best = min(best, sdBox(q, vec3(1.0)) * scale);
    }
    return best * size;
}

vec2 map(vec3 p) { return vec2(mengerDE(p), 0.0); }

// Colour by how deep the nearest hole is: follow the nearer cube down and note where the point sits.
#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    vec3 q = p / uSize;
    float trap = 1.0;
    for (int l = 0; l < FRACTAL_ITERATIONS; l++) {
        q = foldOctahedral(q);
        vec3 a = 3.0 * (q - MENGER_CORNER), b = 3.0 * (q - MENGER_EDGE);
        q = sdBox(a, vec3(1.0)) <= sdBox(b, vec3(1.0)) ? a : b;
        trap = min(trap, length(q.yz) / 1.5 + float(l) * 0.02);
    }
    return base * paletteColor(trap);
}
