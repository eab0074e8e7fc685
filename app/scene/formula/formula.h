/* formula — a fractal formula is one GLSL file: its distance estimate, its colouring and its
 * parameters, declared in the file as annotated uniforms that fathom reads at run time (in the
 * spirit of Fragmentarium's sliders). No C changes for a new formula: drop the file in
 * shaders/fractal/, in the user's folder (formula_user_dir()), or name it with --formula FILE.
 *
 *   // @formula One line: what it is and whose (cite the paper or article).
 *   // @iterations 12 [1, 64]      FRACTAL_ITERATIONS (a loop bound): default and range
 *   // @bound 2 * size             radius of a sphere about the origin that holds the set at every
 *   //                             value the ranges allow (check-formula checks it at their ends):
 *   //                             an expression of the parameters (+ - * / ( ) abs sqrt min max
 *   //                             pow floor, a vector's components c.x c.y c.z)
 *   // @step 0.9                   the step factor its estimate needs: an expression (a rougher estimate
 *   //                             at some values may need less); quality.step_factor is capped at it
 *   // @trap 0.4 1.1               the orbit trap's values (two expressions) spread over the palette
 *   // @loops iterations * 4       loop iterations one estimate runs, all its loops together (an
 *   //                             expression; default iterations + 1): what it spends of the loop
 *   //                             budget (shaders/common/budget.glsl); check-formula measures it
 *   // @require min_radius < fixed_radius "min_radius must be below fixed_radius"
 *   // @deep whole power           written against real/real3 (fractal/common.glsl), so it compiles
 *   //                             in double for a deep zoom; "whole KEY..." names parameters that
 *   //                             must be whole numbers there (the Mandelbulb's power)
 *   // @exact                      its estimate is the exact distance, not only a bound (the Menger
 *   //                             sponge's): `fathom mesh` meshes its zero level, not half a voxel out
 *   uniform float uPower;   // @param 8 [2, 16] the exponent n of z -> z^n + c
 *   uniform float uScale;   // @param 2 [-4, 4] not (-1.05, 1.05) the scale factor s
 *   uniform int uFolds;     // @param 3 [1, 8] folds per iteration
 *   uniform vec3 uJulia;    // @param 0.3,0.2,0.1 [-2, 2] the fixed c of the Julia set
 *   uniform bool uSwap;     // @param false swap x and z each iteration
 *   uniform vec3 uTint;     // @color 0.9,0.6,0.3 a colour (components 0..1)
 *
 * The estimate comes in one of two forms:
 *   - its own: `real formulaDE(real3 p, out float trap)`, a distance bound at world point p and an
 *     orbit trap (the Menger sponge, the kaleidoscopic and quaternion formulas);
 *   - a step formula, z → f(z) + c: it declares `// @de log` (orbits grow like a power: the
 *     estimate is ½ ln r · r / dr) or `// @de linear` (like a scale: r / dr) and `// @escape EXPR`,
 *     and gives only `void formulaStep(inout real3 z, inout real dr, inout float trap)`: z ← f(z),
 *     dr ← |f'(z)| dr, and trap the smallest of some measure of z along the orbit (@trap's range).
 *     The loop in fractal/iterate.glsl adds c, so every step formula has a Julia mode (fractal.julia,
 *     fractal.julia_c) and can be one half of a hybrid (fractal.hybrid: another step formula's
 *     steps alternate with its own). Such a file declares nothing at global scope but its uniforms
 *     and formulaStep (shared helpers live in fractal/common.glsl), so two of them fit in one shader.
 * fractal/map.glsl makes map() and the colouring from either; a formula that colours its own way
 * defines FORMULA_ALBEDO, PROGRAM_ALBEDO and programAlbedo().
 *
 * A parameter's scene key is its uniform's name without the 'u', in snake case (uMinRadius ->
 * min_radius): "fractal": {"formula": "mandelbox", "min_radius": 0.4}, --set fractal.min_radius=0.4.
 * Every formula also takes the fractal block's own keys (FORMULA_COMMON_KEYS). Pure C. */
#ifndef FATHOM_FORMULA_H
#define FATHOM_FORMULA_H

#include <stdbool.h>

#include "util.h"

#include "scene/formula/formula_types.h"

/* Reads the declarations of a formula's text; `source` names it in messages ("NAME.glsl:LINE: ..."). */
bool formula_parse(const char *text, const char *source, formula *f, err_t *err);

/* Finds and reads a formula: a path to a .glsl file (absolute, or relative to dir: a scene file's
 * folder; NULL: the current folder), or a name: a shipped formula (shaders/fractal/) by that name, else
 * a file in the user's folder. A user's file never replaces a shipped formula of the same name. */
bool formula_load(const char *name_or_path, const char *dir, formula *f, err_t *err);

/* The user's formula folder: $FATHOM_FORMULAS, else $XDG_CONFIG_HOME/fathom/formulas, else
 * ~/.config/fathom/formulas (it need not exist). */
void formula_user_dir(char *out, size_t n);

/* The names of every formula fathom can find, one a line (shipped, then the user's), then a line
 * "note: FILE is ignored: ..." for each user file that has a shipped formula's name. */
void formula_list(strbuf *out);

/* --help-formula: the summary, and each parameter with its type, default, range and meaning. */
void formula_describe(const formula *f, strbuf *out);

/* Evaluates an expression over the parameters' values (values[i] is params[i]'s; a name is its first
 * component, NAME.x .y .z .w a vector's each; "iterations" is known too). False with a message on a
 * malformed expression or an unknown name. */
bool formula_eval(const formula *f, const char *expr, const float (*values)[4], int iterations, double *out, err_t *err);


/* The parameter whose scene key is `key`, or NULL. */
const formula_param *formula_find(const formula *f, const char *key);

#endif
