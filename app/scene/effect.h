/* effect — the optional effects a scene may compile: one table (EFFECT_LIST), and the rule that
 * derives a scene's effect set from its content.
 *
 * The renderer compiles one program per distinct variant, built from a `#define` preamble
 * (scene_preamble); shader code tests `#if FX_NAME`. An effect that a scene does not use is not in its
 * program at all. Every compiled-in effect can also be switched off at run time (uFxRuntime), so the
 * bench can tell what an effect costs compiled in but unused.
 */
#ifndef FATHOM_EFFECT_H
#define FATHOM_EFFECT_H

#include <stdbool.h>

#include "util.h"

/*        id            name in scene files  what it simulates */
#define EFFECT_LIST(X)                                                                              \
    X(SHADOWS, "shadows", "hard shadow rays toward the lights, started off the surface")            \
    X(SOFT_SHADOWS, "soft_shadows", "penumbrae from the closest miss of shadow rays")                \
    X(AO, "ao", "ambient occlusion: distance samples along the normal")                              \
    X(REFLECTIONS, "reflections", "traced mirror reflections on smooth materials")                   \
    X(REFRACTION, "refraction", "glass: exact Fresnel, Snell, total internal reflection, Beer")      \
    X(FOG, "fog", "exponential fog along primary rays")                                              \
    X(ENVMAP, "envmap", "cube-map environment (else a constant colour)")                             \
    X(TEXTURES, "textures", "filtered material textures (mipmaps, anisotropic)")                     \
    X(AA, "aa", "jittered sub-pixel samples, accumulated progressively")                             \
    X(GLOW, "glow", "fractals: light that grows with the march steps near the surface")               \
    X(RELIEF, "relief", "parallax occlusion mapping of a heightmap on a material (the lab's search)")          \
    X(DROPLETS, "droplets", "liquid droplets from a file: analytic spheres in a grid, Fresnel, Snell, TIR, Beer") \
    X(SKY, "sky", "physical sky: the sun scattered by air, aerosol and ozone (Hillaire 2020), aerial perspective") \
    X(WATER, "water", "water on a DEM at a level: exact shorelines, Fresnel, Snell, TIR, Beer, the terrain mirrored")

typedef enum effect {
#define X(id, name, what) EFFECT_##id,
    EFFECT_LIST(X)
#undef X
    EFFECT_COUNT
} effect;

const char *effect_name(effect e);
const char *effect_summary(effect e);
bool effect_from_name(const char *name, effect *e);

/* A smooth opaque material reflects a traced mirror image when its roughness is at most this. */
#define MIRROR_ROUGHNESS 0.25f

/* "#define FX_NAME 0|1" and "#define FX_NAME_BIT …u" for every effect. */
void effect_preamble(unsigned effects, strbuf *out);

#endif
