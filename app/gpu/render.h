/* render — draws a scene into a floating-point accumulation target, one jittered sample at a time,
 * and turns it into display colour. Needs a current GL 3.3 core context; does not care whose.
 *
 * Targets (all width × height, RGBA32F, NUM_TARGETS = 4): 0 accumulated linear radiance (additive
 * blending; alpha counts the pixel's samples), 1 normal.xyz + depth, 2 steps + exit direction, 3 the
 * sum of squared samples (the variance in aov.h). The first sample after render_begin() is unjittered
 * (pixel centres) and is the only one that writes targets 1 and 2, so AOVs are exact per-pixel
 * probes; later samples add to 0 and 3 only. Programs are compiled once per variant (preamble +
 * generated map) and cached. The module's files: render.c (targets, samples, backends),
 * render_output.c (display and readback), render_programs.c (the program cache), render_scene.c
 * (the scene's GPU resources, render_resource.h); probes are render_probe.h's.
 */
#ifndef FATHOM_RENDER_H
#define FATHOM_RENDER_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "view/aov.h"
#include "view/camera.h"
#include "scene/scene.h"
#include "util.h"

/* Backends: how an image's samples run. Both run the same GLSL (common/sdf_main.glsl's renderPixel)
 * into the same targets; only the entry point differs.
 *   fragment  a full-screen triangle (sdf.frag): any GL 3.3 core context
 *   compute   compute dispatches in tiles (sdf.comp): GL 4.3; a datacenter GPU runs pixel shaders on a
 *             small part of the chip (an H100: 2 of its TPCs) and compute shaders on all of it
 *   auto      compute on a hardware GPU with GL 4.3, fragment on a software rasteriser (llvmpipe) or
 *             an older GL (render_auto_is_compute; docs/gpu/README.md: the measurement) */
typedef enum render_backend { BACKEND_AUTO, BACKEND_FRAGMENT, BACKEND_COMPUTE } render_backend;

/* Parses "auto", "fragment" or "compute"; false on anything else. */
bool render_parse_backend(const char *name, render_backend *out);
const char *render_backend_name(render_backend b);
/* The backend render_init takes: --backend, else the environment's FATHOM_BACKEND, else auto. Call
 * before render_init. */
void render_request_backend(render_backend b);

/* Needs a current context. Resolves the backend (an error when compute was asked for and the GL lacks
 * it, or FATHOM_BACKEND names none). */
bool render_init(err_t *err);
void render_shutdown(void);
/* The backend render_init resolved (never auto), and whether this GL has compute shaders. */
render_backend render_backend_used(void);
bool render_has_compute(void);
bool render_auto_is_compute(void);
/* The compute path's most pixels a dispatch (0: the default, 2^20); a frame's rows go in tiles of a
 * multiple of the work group's height. Tests make it small to cover the tiles' seams. */
void render_set_compute_tile(int pixels);
/* Switches the backend after render_init (auto: the rule render_init applies); the next
 * render_set_scene takes its program (the bench compares the two in one run). */
bool render_switch_backend(render_backend b, err_t *err);

/* Makes s the scene to draw; the renderer keeps its own copy (the caller may free or change s at once).
 * extra_defines (may be NULL) is appended to the variant preamble: tests use it to switch a guard off.
 * Loads textures, compiles or reuses the program. */
bool render_set_scene(const scene *s, const char *extra_defines, err_t *err);

/* Switches compiled-in effects off at run time (bit 1 << effect; default all on): the bench measures
 * what an effect costs compiled in but unused. */
void render_set_runtime_effects(unsigned mask);

void render_resize(int width, int height);
/* Renders into the bottom-left width × height of the targets (at most render_resize's size), which
 * render_display stretches to its output (bilinear): the window flies at a lower internal resolution.
 * Readback reads the active size. A change restarts accumulation. */
void render_set_active(int width, int height);
void render_active_size(int *width, int *height);

/* The target (render_resize's size) holds the part of a full_width × full_height image whose top-left
 * pixel is (left, top): offline shots of any size render in bands. render_resize resets it to the
 * whole image. Call before render_begin. */
void render_set_window(int full_width, int full_height, int left, int top);
void render_begin(const camera *c); /* new view: restart accumulation */

/* Deep zoom: a double program works in coordinates relative to an origin, the eye, held here in
 * double (render_begin sets it); probes take their points relative to it too (0 everywhere else).
 * render_probe.h's render_fit_precision picks the precision. */
void render_origin(double origin[3]);
void render_set_origin(const double origin[3]);
bool render_has_fp64(void);
/* Uploads the view to prog: the eye (relative to the origin) and the pixel's angle of the last
 * render_begin, and the origin when prog reads one (a double program). Probes see the view too. */
void render_origin_uniforms(GLuint prog);
void render_sample(void);           /* add one sample */
int render_samples(void);
/* The next `rows` rows (from the top) of the current sample: the window spreads a full-size sample
 * over display frames so it keeps reading input. True when the sample is complete. */
bool render_sample_band(int rows);
/* Keeps the current (moving, smaller) image: until a still image's first sample reaches a row, the
 * display shows this one stretched there. */
void render_keep_preview(void);
/* Rows of the current sample render_sample_band has done (0: none, or the sample is complete). */
int render_band_rows(void);
/* Adaptive sampling, by the scene's quality.tolerance (0: off, every pixel takes every sample; so too
 * under the path tracer, the unbiased truth whose two samples may agree by chance). From
 * sample RENDER_ADAPTIVE_MIN on, everywhere, only pixels whose mean's standard error (as displayed) is above the
 * tolerance, whose rays passed a surface by within the pixel's footprint, or whose block holds an edge
 * their samples cannot yet place take more (shaders/errormask.frag); once none is left, further samples
 * cost nothing. With render_set_adaptive(true) (the window), samples before it go only where the edge mask is set
 * (shaders/edgemask.frag: colour, depth, hit or normal differs in the 3x3 block), unless a lens or the
 * path tracer makes every pixel vary; off by default (its 3x3 block would make a band's or a tile's
 * border rows differ from the whole image's). */
void render_set_adaptive(bool on);
enum { RENDER_ADAPTIVE_MIN = 2 }; /* the samples every pixel takes before the tolerance can stop it */
/* An edge of displayed contrast C in a pixel's 3x3 block keeps the pixel going until it has C / (this ·
 * tolerance) samples (shaders/errormask.frag): n stratified samples place an edge within about C / n. */
#define RENDER_EDGE_STEP 2.5f
/* Draws a mask program (edgemask.frag with edges, errormask.frag without) over a w × h target bound as the
 * draw framebuffer: accum is target 0's texture (sums, alpha the samples), second the normals and depth
 * (edges) or the squares (target 3). The renderer's own masks and render_probe_error_mask use it. */
void render_mask_draw(unsigned prog, unsigned accum, unsigned second, int w, int h, float tolerance, bool edges);
/* Rows beyond a band's edges that a band of an image must render with it to agree with the whole
 * image bit for bit: the error mask reads the 3x3 block, so each masked sample's decisions reach a row
 * further (0 when s does not sample adaptively at spp samples). Even, as bands' offsets are. */
int render_adaptive_margin(const scene *s, int spp);
/* The sub-pixel point of an image's first sample: Halton point k (0, the default: the pixel centre).
 * Moving frames that change it frame to frame let a reprojected history gather detail. */
void render_set_first_jitter(int k);
/* A stretched (moving) image: depth-aware upsampling, no blending across silhouettes, or plain
 * bilinear (the default: bench --interactive measures both, and bilinear is nearer the full frame). */
void render_set_edge_aware(bool on);
/* Pixels the last mask kept. */
int render_adaptive_pixels(void);
/* Samples a pixel of the current image has taken, on average (adaptive sampling stops many early). */
double render_mean_samples(void);

typedef enum render_view { VIEW_COLOR, VIEW_STEPS, VIEW_DIFFERENCE } render_view;

/* Keeps the current image as the reference that VIEW_DIFFERENCE compares against. */
void render_grab_reference(void);
/* The root-mean-square difference of the current image's linear colour to the grabbed reference
 * (each pixel's mean over its samples; the same size); −1 without a reference. Reads both back. */
double render_reference_rmse(void);
/* The steps heat map's top (VIEW_STEPS: blue 0 … red at this many steps); 0: the scene's MAX_STEPS. */
void render_set_heat_max(float steps);
float render_heat_max(void);
/* The AOVs of one pixel of the active image (row 0 at the top; variance and samples left 0): what is
 * under the cursor. False before the first sample or outside the image. */
bool render_read_pixel(int x, int y_from_top, float out[AOV_FLOATS]);

/* Tone-mapped sRGB colour (or the steps heat map) into framebuffer `fbo` (0 = window), the active image
 * stretched to width × height (bilinear; texel for texel when the sizes are equal). */
void render_display(GLuint fbo, int width, int height, float exposure, render_view view);

/* Readback, rows top first. srgb8: RGBA 8-bit after render_display's mapping. linear: averaged RGBA.
 * aovs: AOV_FLOATS a pixel, laid out as aov.h says (depth +inf on a miss). */
void render_read_srgb8(uint8_t *rgba, float exposure);
void render_read_linear(float *rgba);
/* srgb8 of the active image stretched to width × height (at most the targets' size), as the window shows it. */
void render_read_stretched_srgb8(uint8_t *rgba, int width, int height, float exposure);
void render_read_aovs(float *aov8);
/* Pixels of the current image left unresolved (drawn as a miss): their primary ray ran out of steps
 * and its tail, or (counted also in *loops when not NULL) the pixel ran out of the loop budget. */
long render_unresolved_pixels(long *loops);

/* Frees what the current scene put on the GPU (textures, heightfield, droplets). */
void render_release_scene(void);
/* The loaded terrain's texture tiles (1 x 1 when it fits one texture); false without a terrain. */
bool render_terrain_tiles(int *tiles_x, int *tiles_y);

/* The current scene's droplets and their grid (NULL when it has none), and the seconds reading the
 * file and building the grid took (either pointer may be NULL). */
struct droplets;
const struct droplets *render_droplets(double *read_s, double *grid_s);

/* Recompiles every cached program from the files on disk; on error keeps the old programs. */
bool render_reload(err_t *err);


/* The #define preamble of the current scene's variant (for --print-variant). */
void render_preamble(const scene *s, const char *extra_defines, strbuf *out);

#endif
