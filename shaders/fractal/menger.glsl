// @formula The Menger sponge (K. Menger, 1926) as an exact distance, not the usual bound: iterations are its levels
// @iterations 4 [1, 7]
// @bound size * 1.7320508
// @step 1
// @trap 0 1
// @loops 4 * iterations + 1
// @deep
// @exact
//
// Its loops: up to 2ᴺ paths of N levels, but the pruning below keeps an estimate to at most 2N + 3
// loop iterations wherever check-formula probes it (N = 1 … 7); @loops declares twice that.
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

#define FORMULA_EXACT 1 // fractal/map.glsl: no bounding sphere

const real3 MENGER_CORNER = real3(2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0);
const real3 MENGER_EDGE = real3(2.0 / 3.0, 2.0 / 3.0, 0.0);

real formulaDE(real3 p, out float trap)
{
    const int N = FRACTAL_ITERATIONS;
    const int PATHS = 1 << N;
    real size = uSize;
    real3 q0 = p / size;
    real best = 1e10;
    int m = 0;
    trap = 0.0;
    for (int guard = 0; guard < PATHS && m < PATHS; guard++, m++) {
        real3 q = q0;
        real scale = 1.0;
        bool pruned = false;
        for (int l = 0; l < N; l++) {
            q = foldOctahedral(q);
            real3 a = 3.0 * (q - MENGER_CORNER), b = 3.0 * (q - MENGER_EDGE);
            real da = realBox(a, 1.0), db = realBox(b, 1.0);
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
            best = min(best, realBox(q, 1.0) * scale);
    }
    return best * size;
}

// Colour by how deep the nearest hole is: follow the nearer cube down and note where the point sits.
#define FORMULA_ALBEDO 1
#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    real3 q = worldOf(p) / real(uSize);
    float trap = 1.0;
    for (int l = 0; l < FRACTAL_ITERATIONS; l++) {
        q = foldOctahedral(q);
        real3 a = 3.0 * (q - MENGER_CORNER), b = 3.0 * (q - MENGER_EDGE);
        q = realBox(a, 1.0) <= realBox(b, 1.0) ? a : b;
        trap = min(trap, float(length(q.yz)) / 1.5 + float(l) * 0.02);
    }
    return base * paletteColor(trap);
}
