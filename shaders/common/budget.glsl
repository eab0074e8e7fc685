// The loop budget: every loop of a pixel's invocation, counted together, stays below what the driver
// allows, and a pixel whose loops were cut anyway is flagged, never drawn from a cut computation.
//
// Mesa's llvmpipe keeps one counter per shader invocation for all its loops together and ends every
// loop once 65,535 iterations have run in all (its loop limiter; measured with a compute shader: ten
// passes of a 10,000-step loop stop at 65,523 iterations, and a loop after an exhausted one runs its
// body once), silently. A deep march through a formula of many iterations runs into it: the pixel came
// out as sky. fathom counts what its loops spend (a march step 1, a formula's estimate its declared
// @loops, formula.h) and stops marching at LOOP_BUDGET (the C side sets it below the limit on
// llvmpipe; a GPU has no such limit), which leaves the pixel unresolved by fathom's own rule. And a
// formula whose own loops run longer than it declares is caught after the fact: loopsWereCut() runs a
// two-iteration loop, which a spent limiter ends after one.
#ifndef LOOP_BUDGET
#define LOOP_BUDGET 2147483647
#endif
uniform int uLoopProbe; // 2: the sentinel loop's length (a uniform, so the compiler cannot unroll it)

int loopSpent = 0;    // loop iterations this invocation has spent, by fathom's count
bool loopOut = false; // the budget ran out: marches stop, the pixel is unresolved

// Spends n iterations; false once the budget has run out.
bool loopSpend(int n)
{
    loopSpent += n;
    loopOut = loopOut || loopSpent > LOOP_BUDGET - n;
    return !loopOut;
}

// Whether the driver cut this invocation's loops: its sentinel loop ran short.
bool loopsWereCut()
{
    int ran = 0;
    for (int i = 0; i < uLoopProbe; i++)
        ran++;
    return ran < uLoopProbe;
}
