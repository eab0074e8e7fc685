// The escape-time loop of the step formulas (app/scene/formula/formula.h): a formula that declares @de and
// @escape gives only its map f as `formulaStep(z, dr, trap)`, z ← f(z) and dr ← |f′(z)| · dr (and
// its orbit trap: the smallest of some measure of z along the orbit), and this loop adds c. app/scene/scene_programs.c includes it after the formula, renaming each formula's
// step (formulaStepA, and formulaStepB for a hybrid's second formula).
//
// Mandelbrot mode: c is the point p itself, so the running derivative dr = |∂z/∂p| gains a 1 each
// step (dr → |f′| dr + 1). Julia mode (uJulia): c is the fixed uJuliaC for every point and z starts
// at p, so dr → |f′| dr (Hart, Sandin and Kauffman 1989, "Ray tracing deterministic 3-D fractals").
// A hybrid (FORMULA_HYBRID) takes uStepsA steps of its first formula, then uStepsB of its second, in
// a cycle; the derivative of the composition is the product of the steps' derivatives, so one dr is
// carried through both. The estimate is ½ · ln r · r / dr (FORMULA_DE_LOG: orbits that grow like a
// power, the Mandelbulb's) or r / dr (orbits that grow linearly, the Mandelbox's); an orbit still
// bounded after every iteration is inside.
uniform float uEscape; // orbits beyond this radius only grow: the formula's @escape (a hybrid's rule: scene_programs.c)
uniform bool uJulia;
uniform vec3 uJuliaC;
#ifdef FORMULA_HYBRID
uniform int uStepsA, uStepsB;
#endif

#define FORMULA_LOOP_COUNTED 1 // each iteration spends one of the loop budget (common/budget.glsl)
real formulaDE(real3 p, out float trap)
{
    real3 z = p, c = uJulia ? real3(uJuliaC) : p;
    real dr = 1.0, dc = uJulia ? 0.0 : 1.0, r = length(z);
    bool escaped = false;
    trap = 1e10;
    for (int i = 0; i < FRACTAL_ITERATIONS; i++) {
        loopSpend(uFormulaStepLoops);
        r = length(z);
        escaped = r > real(uEscape);
        if (escaped)
            break;
#ifdef FORMULA_HYBRID
        if (i % (uStepsA + uStepsB) < uStepsA)
            formulaStepA(z, dr, trap);
        else
            formulaStepB(z, dr, trap);
#else
        formulaStepA(z, dr, trap);
#endif
        z += c;
        dr += dc;
    }
    r = length(z);
#if FORMULA_DE_LOG
    // bounded is false for a NaN orbit: a formula that breaks shows as NaN, never as inside; dr = 0
    // (a Julia orbit through z = 0) is inside
    bool bounded = !escaped && r <= real(uEscape);
    return bounded || dr == 0.0 ? real(0.0) : 0.5 * realLog(r) * r / dr;
#else
    return r / abs(dr);
#endif
}
