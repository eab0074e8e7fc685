// @formula Quaternion Julia sets (Norton 1982; Hart, Sandin and Kauffman 1989): q → q² + c in the quaternions, a 3D slice at w
// @iterations 12 [1, 64]
// @loops 2 * iterations + 2
// @bound max(1.8, 1.05 * (1 + sqrt(1 + 4 * sqrt(c.x * c.x + c.y * c.y + c.z * c.z + cw * cw))) / 2)
// @step 1
// @trap 0 1
// @deep
//
// q = (x, y, z, w) with the point's w fixed at the slice; q² = (a² − |v|², 2 a v) for q = (a, v).
// The estimate is a bound that holds everywhere (below): the chain of Hart, Sandin and Kauffman's
// ½ · |q| · ln |q| / |q'| (1989), whose derivative |q'| → 2 |q| |q'| vanishes near the critical point.
// The set lies within |q| ≤ R = (1 + √(1 + 4|c|)) / 2: beyond it |q² + c| ≥ |q|² − |c| > |q|, so the
// orbit only grows (the fixed 1.8 clipped c = (−2, 0, 0), where R = 2).
#include "fractal/common.glsl"
uniform vec3 uC;      // @param -0.2,0.6,0.2 [-2, 2] c's first three components (1, i, j)
uniform float uCw;    // @param 0.0 [-2, 2] c's fourth component (k)
uniform float uSlice; // @param 0.0 [-2, 2] the w of the 3D slice drawn

const float QJ_ESCAPE2 = 256.0; // |q|² beyond which q only grows

real formulaDE(real3 p, out float trap)
{
    real4 q = real4(p, uSlice), c = real4(uC, uCw);
    real r[FRACTAL_ITERATIONS + 1]; // |q| along the orbit
    r[0] = length(q);
    int n = 0;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        q = real4(q.x * q.x - dot(q.yzw, q.yzw), 2.0 * q.x * q.yzw) + c;
        real q2 = dot(q, q);
        trap = min(trap, float(sqrt(q2)));
        r[++n] = sqrt(q2);
        if (q2 > QJ_ESCAPE2)
            break;
    }
    // The last point is at least |q| − R from the set (it lies within R); an orbit still within R is
    // inside (for the iterations given). Back along the orbit: for x in the set (so is x² + c), a point
    // q at distance d from it has |q² − x²| ≤ |q − x| (|q| + |x|) ≤ d (2|q| + d), and q² + c is at least
    // d' from the set, so d ≥ √(|q|² + d') − |q| = d' / (√(|q|² + d') + |q|). Far from 0 that is the
    // running derivative's d' / 2|q|; near 0 (the critical point) it stays √d', where |q'| → 0 made
    // Hart's ½ |q| ln|q| / |q'| infinite (+Inf at the origin, 4.4 times the distance elsewhere).
    real d = r[n] - 0.5 * (1.0 + sqrt(1.0 + 4.0 * length(c)));
    if (d <= 0.0)
        return real(0.0);
    for (int k = n - 1; k >= 0; k--)
        d = d / (sqrt(r[k] * r[k] + d) + r[k]);
    return d;
}
