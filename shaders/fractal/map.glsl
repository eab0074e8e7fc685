// map() and the orbit-trap colouring for every formula: app/scene/scene_programs.c includes this
// after the formula, whose estimate is `real formulaDE(real3 p, out float trap)` (its own, or the
// step formulas' loop in fractal/iterate.glsl). Positions arrive relative to the eye in a deep zoom:
// worldOf() (fractal/common.glsl) makes them world positions in the precision the formula runs in.
// What an estimate spends of the loop budget (common/budget.glsl): the step formulas' loop counts its
// own iterations as it runs them (fractal/iterate.glsl); a formula with its own estimate spends what it
// declares (@loops, formula.h), which check-formula measures.
void spendEstimate()
{
#ifndef FORMULA_LOOP_COUNTED
    loopSpend(uFormulaLoops);
#endif
}

vec2 map(vec3 p)
{
    real3 P = worldOf(p);
    float trap;
#ifndef FORMULA_EXACT // an exact distance (menger.glsl) is a better step than the bounding sphere's
    // the bounding sphere and its margin: fractal/common.glsl
    float bound = float(length(P)) - uBoundRadius, eps = boundThreshold(p);
    if (bound > max(BOUND_MARGIN, BOUND_MARGIN_THRESHOLDS * eps))
        return vec2(bound, MATERIAL_BOUND);
    spendEstimate();
    float de = float(formulaDE(P, trap));
    if (bound > BOUND_MARGIN && de > eps)
        return vec2(de, MATERIAL_BOUND);
    return vec2(de, 0.0);
#else
    spendEstimate();
    return vec2(float(formulaDE(P, trap)), 0.0);
#endif
}

#ifndef FORMULA_ALBEDO // a formula may colour its surface its own way (menger.glsl)
#define PROGRAM_ALBEDO 1
vec3 programAlbedo(vec3 p, vec3 n, vec3 dpdx, vec3 dpdy, vec3 base)
{
    float trap;
    spendEstimate();
    formulaDE(worldOf(p), trap);
    return base * paletteColor(smoothstep(uTrapRange.x, uTrapRange.y, trap));
}
#endif
