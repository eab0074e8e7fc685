/* frag — Fragmentarium fragments, unmodified, as fathom formulas. A DE fragment (a .frag file that
 * defines `float DE(vec3)` and includes a DE renderer) is read as data: fathom's own preprocessor
 * resolves its #include lines, reads its annotations and presets, and hands the GL compiler a
 * translation that keeps every line where it was (so a compiler error names the fragment's own line).
 *
 *   #include "X.frag"   fathom's compatible include set first (shaders/frag/: MathUtils, Complex, and
 *                       DE-Raytracer for every DE renderer of the collections: Fast-, Soft-, DE-Kn2...),
 *                       else a file in the including file's folder: a plain relative name (no '/'
 *                       at the start, no '..' part, letters, digits and "_-. /"), whose real path
 *                       stays inside the fragment's folder. Nothing else is ever opened.
 *   uniform T NAME; slider[LO,DEFAULT,HI]       float, int, vec2/3/4 (vectors as (x,y,..) triples);
 *   uniform bool NAME; checkbox[true]           color[R,G,B] (vec3), color[LO,DEFAULT,HI,R,G,B] (vec4: a
 *                                               colour and its intensity in w): each a parameter under
 *                                               the name NAME (--set fractal.NAME=...), no fixed count.
 *                                               `Locked`: a compile-time constant (scene_fractal_defines).
 *                                               An int slider named Iterations is fathom's
 *                                               fractal.iterations (a loop bound the compiler sees).
 *   #group NAME, #info TEXT                     the parameters' group; the formula's description
 *   #preset NAME ... #endpreset                 named views (frag_preset_shot)
 *   #vertex...#endvertex                        the vertex shader's code, joined to the fragment's: its
 *                                               varyings globals, its init() run once a pixel (frag_vertex.c)
 *   #camera, #donotrun, #buffer, #TexParameter: the host's business: blanked (#TexParameter kept for textures).
 * Refused, in one line each: a fragment with its own main() (a whole renderer), a 2D fragment, one
 * without DE() or a DE renderer, textures (file[...]), a missing include (with the include chain).
 * The renderer contract (shaders/frag/raytracer.frag, shaders/frag/glue.glsl): DE() is the estimate, init()
 * (providesInit) runs once per pixel, orbitTrap colours the surface with X, Y, Z, R, BaseColor and
 * OrbitStrength, baseColor() (providesColor) is the albedo hook. The renderers' hit rule (fractal.hit_rule
 * = fragment: Detail relative to the distance travelled, out of steps as background: common/march.glsl)
 * and look (fractal.look = fragment: camera and spot light, AO, fog, glow, background, post:
 * shaders/frag/look.glsl, display.frag) are a fragment's defaults, each one setting from fathom's. Pure C. */
#ifndef FATHOM_FRAG_H
#define FATHOM_FRAG_H

#include <stdbool.h>

#include "scene/formula/formula_types.h"
#include "util.h"

enum { FRAG_PRESET_MAX = 64, FRAG_PRESET_NAME_MAX = 64 };

/* Whether path names a fragment (ends in .frag). */
bool frag_is_fragment(const char *path);

/* Reads and translates the fragment at `path` (absolute) into f: its parameters, summary and name; the
 * translated texts are kept for frag_text until the file is translated again. */
bool frag_load(const char *path, formula *f, err_t *err);

/* The translated text of a file a fragment's program includes, by the absolute path fathom's
 * translation names it with; NULL when it is no translated fragment file. */
const char *frag_text(const char *path);

/* FNV-1a 64 of the translated texts of the fragment at path and its includes (0: none): what the
 * program cache keys a fragment's program on, so an edited include recompiles too. */
unsigned long long frag_digest(const char *path);

/* The GLSL initialiser of a Locked parameter's value v ("vec3(1, 2, 3)"), into out. */
void frag_literal(const formula_param *q, const float *v, char *out, size_t n);

/* The names of the fragment's presets (KeyFrame presets left out), in file order; their count. */
int frag_presets(const char *path, char names[][FRAG_PRESET_NAME_MAX], int max, err_t *err);

/* The preset's view as a shot text (view/shot.h) of the fractal scene with this fragment: the camera
 * (Eye, Target, Up, FOV = tan(vertical fov / 2), Aperture, FocalPlane, EquiRectangular), Detail and
 * MaxDistance (fractal.detail, fractal.max_distance: Fragmentarium's hit rule, a fragment's default),
 * FudgeFactor and MaxRaySteps (quality.step_factor, quality.max_steps: the renderers' 1 and 56 where the
 * preset is silent), Iterations and every parameter it sets. `name` NULL: where FragM starts, the first
 * preset whose name holds "default" in any case, else the sliders' defaults (3D.frag's camera: Eye
 * (0, 0, -10), FOV 0.4); false with err when `name` is no preset. Lines for the host's own controls
 * (lights, tone mapping...) are listed in *ignored (malloc'd, may be NULL). */
bool frag_preset_shot(const char *path, const char *name, strbuf *shot, char **ignored, err_t *err);

/* The fragment's KeyFrame presets (KeyFrame.001, ...) as a flight (view/path.h's file, into flight): a key
 * each, `seconds` apart in all (FragM spreads its keyframes evenly over the animation's length, 10 s by
 * default), at its Eye, toward its Target, with its Up and FOV, and a set track for every number parameter
 * each key gives. false with err when it has fewer than two. */
bool frag_keyframes_flight(const char *path, double seconds, strbuf *flight, err_t *err);

/* The index among frag_presets' names of the preset frag_preset_shot(path, name) opens; -1 for the
 * sliders' defaults (or an unreadable file). */
int frag_preset_index(const char *path, const char *name);

#endif
