/* scene — a scene file (JSON, see scenes/README.md) turned into a scene struct. Pure: files in, data out.
 *
 * Files: scene.c (entry points, the top level, the preamble and uniforms), scene_json.c (reading
 * with error context), scene_blocks.c (materials, lights, environment, camera, fog, quality,
 * effects), scene_csg.c (the CSG tree → map()), scene_programs.c (each program's block),
 * scene_set.c (--set overrides).
 *
 * Conventions: right-handed world, Y up, metres. Angles in degrees in the file, radians in code.
 * Colours are linear RGB. Point lights fall off as 1/d² (intensity is radiant intensity, W/sr-like);
 * directional lights give irradiance `intensity` on a surface facing them.
 *
 * CSG: the file's "objects" tree becomes a GLSL `vec2 map(vec3 p)` (distance, material index).
 * Every primitive is an exact signed distance; rotations and translations keep it exact; union,
 * intersection and difference give a bound (the smooth variants a bound within k/4 of it).
 * Material of a surface point = the material of the primitive whose surface it is.
 * Many primitives: bounded primitives at the top level (or in plain unions, without position or
 * rotation) go to a primitive list behind a bounding volume hierarchy (app/data/droplets/bvh.h) once there are
 * CSG_LIST_MIN of them, so 10,000 compile like 10; at most CSG_CODE_MAX primitives are compiled as
 * code (inside other operations), a limit stated in the error before anything compiles.
 */
#ifndef FATHOM_SCENE_H
#define FATHOM_SCENE_H

#include <stdbool.h>

#include "util.h"
#include "data/sky/sky.h"
#include "scene/effect.h"
#include "scene/formula/formula.h"
#include "scene/program.h"
#include "scene/quality.h"
#include "scene/uniforms.h"
#include "view/camera.h"

enum { CSG_LIST_MIN = 32, CSG_CODE_MAX = 256, CSG_LIST_MAX = 1 << 20 };
/* The primitive list as the csg program reads it (shaders/csg/list.glsl): CSG_LIST_TEXELS RGBA texels a
 * primitive, CSG_NODE_TEXELS a BVH node, in textures CSG_TEXTURE_WIDTH texels wide. */
enum { CSG_LIST_TEXELS = 5, CSG_NODE_TEXELS = 2, CSG_TEXTURE_WIDTH = 4096 };

enum { SCENE_MAX_MATERIALS = 16, SCENE_MAX_LIGHTS = 8, SCENE_MAX_TEXTURES = 4, SCENE_NAME_MAX = 64,
       SCENE_MAX_IMAGERY = 4 };

typedef struct scene_material {
    char name[SCENE_NAME_MAX];
    float base_color[3];
    float metallic, roughness;
    float transmission; /* 0 opaque, 1 glass */
    float ior;
    float absorption[3]; /* Beer–Lambert coefficient inside, per metre */
    float emission[3];
    int texture;    /* index into scene.textures, -1 none; multiplies base_color */
    float uv_scale; /* texture repeats per metre */
    int relief;          /* index into scene.textures of a heightmap (parallax occlusion), -1 none */
    float relief_depth;  /* metres below the surface that the heightmap's black lies */
} scene_material;

typedef enum light_type { LIGHT_POINT, LIGHT_DIRECTIONAL } light_type;
typedef enum shadow_mode { SHADOW_NONE, SHADOW_HARD, SHADOW_SOFT } shadow_mode;

typedef struct scene_light {
    light_type type;
    float vec[3]; /* point: position; directional: unit direction toward the light */
    float color[3];
    float intensity;
    shadow_mode shadow;
    float softness; /* soft shadows: penumbra sharpness k (larger = harder) */
} scene_light;

typedef enum effect_mode { EFFECT_AUTO, EFFECT_ON, EFFECT_OFF } effect_mode;
typedef enum scene_water { WATER_NONE, WATER_LEVEL, WATER_FILL, WATER_RASTER } scene_water;

/* How a fractal's formula is computed: "auto" switches to double where a float cannot resolve the
 * view (the renderer decides, app/gpu/render.c), when the formula allows it (@deep). */
typedef enum fractal_precision { PRECISION_AUTO, PRECISION_FLOAT, PRECISION_DOUBLE } fractal_precision;
/* When a ray has hit (common/march.glsl): fathom's footprint rule (HIT_K pixel footprints, the quality
 * presets' knob), or Fragmentarium's DE renderers' rule (relative to the distance travelled: frag.h). */
typedef enum fractal_hit_rule { HIT_RULE_FOOTPRINT, HIT_RULE_FRAGMENT } fractal_hit_rule;
/* How a fractal is lit and shown: fathom's lights, materials and effects, or a Fragmentarium fragment's own
 * renderer (its camera light, spot light, AO, fog, glow, background and post: shaders/frag/look.glsl). */
typedef enum fractal_look { LOOK_FATHOM, LOOK_FRAGMENT } fractal_look;
/* A hybrid's second formula's uniforms are renamed with this prefix (uPower -> uHybrid_uPower). */
#define HYBRID_PREFIX "uHybrid_"

/* Fractal programs' parameters (the "fractal" block). Each program reads the ones it names. */
typedef struct scene_fractal {
    formula formula;     /* the formula's declarations, read from its GLSL file (formula.h) */
    float values[FORMULA_MAX_PARAMS][4]; /* its parameters' values, in its declared order */
    bool has_hybrid;     /* "hybrid": a second step formula alternates with the first */
    formula hybrid;
    float hybrid_values[FORMULA_MAX_PARAMS][4];
    int steps[2];        /* a hybrid's cycle: steps of the formula, then steps of the hybrid */
    bool julia;          /* step formulas: c is julia_c for every point (a Julia set), not the point */
    float julia_c[3];
    float escape;        /* step formulas: the escape radius (formula.h @escape) */
    float trap[2];       /* the orbit trap's range over the palette (@trap) */
    int loops;           /* loop iterations one estimate runs (@loops; a hybrid's larger) */
    fractal_precision precision;
    bool deep_ok;        /* the formula (and hybrid) can compile in double with these values */
    bool deep_now;       /* this variant is compiled in double (PRECISION_DOUBLE) */
    int iterations;      /* iterations of the formula (Menger: levels of the sponge) */
    float bound_radius;  /* a sphere that holds the whole set (marching starts at it) */
    float step;          /* the formula's @step at these values (1: none declared): caps quality.step_factor */
    float palette[3][3]; /* orbit-trap colours: near, middle, far */
    float glow;          /* glow strength; 0 = off */
    float glow_color[3];
    float hit_distance;  /* an absolute hit distance; 0: the rule's own threshold */
    fractal_hit_rule hit_rule; /* fathom's footprint rule, or Fragmentarium's (a fragment's default) */
    float detail;        /* the Fragmentarium rule's Detail: a ray stops where DE·step_factor < 10^detail · t */
    float max_distance;  /* the Fragmentarium rule's MaxDistance: rays past it are background */
    fractal_look look;   /* a fragment's default: its own */
} scene_fractal;

typedef struct scene {
    char path[PATH_MAX_LEN], dir[PATH_MAX_LEN];
    char name[SCENE_NAME_MAX];
    char title[256];
    program_kind program;

    double cam_position[3], cam_look_at[3]; /* double: a deep zoom's view (view/camera.h) */
    float cam_fov_deg;
    double cam_up[3];    /* the direction the image's top faces (default +Y: a level horizon) */
    float cam_roll_deg;  /* turned further about the view (camera.h's sign) */
    camera_lens cam_lens; /* focus, eye_separation 0: not set (scene_lens) */
    bool cam_auto; /* "camera": "auto" (terrain): camera, distances, fog and layers framed from the DEM */

    float env_color[3];
    float env_intensity;
    bool has_cubemap;
    char cubemap[6][PATH_MAX_LEN]; /* +X -X +Y -Y +Z -Z */

    bool has_sky; /* "environment": {"sky": "physical"}: Hillaire's atmosphere (data/sky/sky.h, scene_sun.c) */
    struct scene_sky {
        float sun[3];           /* toward the sun: the sun light's direction */
        float irradiance[3];    /* the sun's above the atmosphere: its light's colour × intensity */
        float ms[SKY_MS_N][3];  /* Ψ_ms by altitude for this sun */
        float scale;            /* world height units a metre (a terrain's exaggeration) */
    } sky;

    bool has_fog;
    float fog_color[3], fog_density; /* density σ0 at fog_height, per metre */
    float fog_falloff, fog_height;   /* σ(y) = σ0 · exp(−falloff · (y − height)) */

    scene_material materials[SCENE_MAX_MATERIALS];
    int material_count;
    scene_light lights[SCENE_MAX_LIGHTS];
    int light_count;
    char textures[SCENE_MAX_TEXTURES][PATH_MAX_LEN];
    bool texture_linear[SCENE_MAX_TEXTURES]; /* heights: linear float, not sRGB colour */
    int texture_count;

    quality_preset preset;
    quality quality;
    effect_mode effect_modes[EFFECT_COUNT];
    unsigned effects; /* derived from content, then effect_modes applied */

    scene_fractal fractal;

    struct scene_torus { /* program torus: its "torus" block */
        float major, minor;
        int material;
    } torus;

    struct scene_terrain {
        char heightmap[PATH_MAX_LEN];
        float spacing[2], height_min, height_max, exaggeration;
        bool exaggeration_set; /* the scene (or an override) gives it: "camera": "auto" keeps it */
        bool maxmip;      /* method: "maxmip" (exact, hierarchical) or "linear" (the lab's search) */
        bool fill_nodata; /* nodata: "hole" (rays pass) or "fill" (GDALFillNodata) */
        int cache_mb;     /* the GPU's share of a DEM in MB (0: auto); a larger DEM streams (gpu/res_heightfield.c) */
        bool patch_normals; /* normals: "smooth" (vertex normals blended across the cell) or "patch" (exact) */
        float sand_line, snow_line; /* metres: sand below, snow above (after exaggeration) */
        bool elevation_ramp;        /* "colors": "elevation": a hypsometric tint by true height, no layers */
        float grass_slope;          /* grass where the normal's y is above this, else rock */
        /* "imagery": rasters draped on a DEM in order, each with its opacity (gpu/res_imagery.c) */
        char imagery[SCENE_MAX_IMAGERY][PATH_MAX_LEN];
        float imagery_opacity[SCENE_MAX_IMAGERY];
        int imagery_count;
        /* "vectors": GPS tracks, paths, places burnt onto the drape above the imagery (gpu/res_imagery.c) */
        char vectors[SCENE_MAX_IMAGERY][PATH_MAX_LEN];
        float vector_color[SCENE_MAX_IMAGERY][4]; /* RGB and opacity */
        float vector_width[SCENE_MAX_IMAGERY];    /* metres (0: a DEM texel) */
        int vector_count;
        /* "water": a level in metres (the DEM's heights): water wherever the ground lies below it; "fill": the
         * lakes the DEM implies (data/geo/water.h); or a raster of water-surface heights on the DEM's grid (a
         * flood model's, or fathom water's). Drawn with the material named "water" (added, clear water, when
         * the scene has none): common/sdf_main.glsl's glass */
        bool curvature;   /* "curvature": true: drawn on the Earth's curvature (terrain/terrain.glsl) */
        bool has_water;
        scene_water water_mode;
        float water_level;
        char water_raster[PATH_MAX_LEN];
        int water_material;
        /* program noise: f(p) = y − base − amplitude · fbm(p · frequency), `octaves` octaves */
        float base, amplitude, frequency;
        int octaves;
    } terrain;
    bool adaptive_speed; /* window: flying speed follows the distance to the surface */

    struct scene_sun { /* "sun": a directional light placed by date, hour and place (scene_sun.c) */
        bool on;
        char date[16];            /* "YYYY-MM-DD" */
        float hour, utc_offset;   /* local hours; the zone's offset from UTC in hours */
        double latitude, longitude; /* degrees; NaN: the DEM's centre */
        int light;                /* which light it moves (a directional one) */
        double azimuth, elevation; /* where it came out, degrees from true north (the HUD and the tests) */
        double convergence;        /* degrees from the DEM's grid north to true north at its centre (0: none) */
    } sun;

    /* "droplets": liquid spheres from a file (app/data/droplets/droplets.h), a layer any program can hold; the file
     * is read when the scene goes to the GPU (render_scene.c), like a terrain's heightmap */
    bool has_droplets;
    struct scene_droplets {
        char file[PATH_MAX_LEN];
        float scale;         /* multiplies the file's positions and radii */
        float ior;           /* of the liquid (water 1.33) */
        float absorption[3]; /* Bouguer–Beer–Lambert coefficient inside, per metre */
        float roughness;     /* of the liquid's surface, for the lights' highlights */
        bool bvh;            /* "structure": "bvh" instead of the uniform grid (to compare) */
    } droplets;

    char *map_glsl; /* the program's virtual "program.glsl": the CSG map, or an #include of the fractal */
    int primitive_count;
    /* csg: the primitive list and its BVH, packed as texels (4 floats each); NULL when none */
    float *csg_list, *csg_nodes;
    int csg_list_count, csg_node_count;
} scene;

/* A scene's text carried by a shot or a preset (shot.h), standing in for the file at `path` from now
 * on, whether that file is there or not (the shot reopens as it was made, on any machine). Files the
 * scene names are still found relative to that path's folder. */
void scene_provide_text(const char *path, const char *text);

/* Finds the file for a scene name ("csg" -> <data>/scenes/csg.json) or checks a path. */
bool scene_locate(const char *name_or_path, char *out, size_t n, err_t *err);

/* Parses the scene file, applies the "key=value" overrides in order, validates every key and value,
 * derives the effect set and generates map(). Syntax errors name line and column. */
bool scene_load(const char *name_or_path, const char *const *sets, int set_count, scene *s, err_t *err);

/* scene_load, recording every tunable value it reads into params (scene/params.h: the window's panel). */
struct param_list;
bool scene_load_params(const char *name_or_path, const char *const *sets, int set_count, scene *s,
                       struct param_list *params, err_t *err);

/* The same from text already in memory (path is used for messages and relative paths). */
bool scene_load_text(const char *text, const char *path, const char *const *sets, int set_count, scene *s,
                     err_t *err);

void scene_free(scene *s);

/* The "sun" block's light set from its date, hour and place (scene_sun.c); true when there is none. */
bool scene_apply_sun(scene *s, err_t *err);
/* The physical sky's sun, its light through the air, the ambient from the sky's mean and the Ψ_ms
 * table (scene_sun.c); true when the scene has no physical sky. */
bool scene_apply_sky(scene *s, err_t *err);

/* The files of the formulas that draw s (its fractal's, its hybrid's), NULL where none: what a shot
 * records (view/shot.h). */
void scene_formula_files(const scene *s, const char *files[2]);

/* The `#define` block (no #version) the scene compiles: program, effects, quality knobs, counts and
 * the program's own defines. Two scenes compile to the same program exactly when these (and their
 * map()) are equal. */
void scene_preamble(const scene *s, strbuf *out);

/* The scene's named uniforms: materials, lights, environment, fog, then the program's own. Texture
 * units and sizes are the renderer's (render_scene.c). */
void scene_uniforms(const scene *s, const uniform_sink *u);

/* Deep zoom: whether a fractal view from camera c (an image `height` rows high) whose nearest surface
 * lies `distance` away needs double precision: its hit threshold there (hit_k · distance · pixel
 * angle) comes within DEEP_MARGIN of a float's resolution at the eye (PRECISION_REL · (|eye| +
 * distance)). A view that needs it has it only where the formula allows it (deep_ok) and the scene
 * asks for "auto" ("double": always). `now`: the current choice; going back to float takes twice the
 * margin, so a camera hovering at the limit does not switch every frame. */
#define DEEP_MARGIN 4.0
struct camera;
bool scene_needs_double(const scene *s, double distance, const struct camera *c, int height, bool now);

/* The scene's lens with what it leaves unset filled in: focus at the look-at distance, the eyes a
 * thirtieth of the focus apart (the stereographers' 1/30 rule). */
camera_lens scene_lens(const scene *s);
/* A camera at eye looking at `at` with the scene's up, roll and lens (focus unset: |at − eye|). */
camera scene_camera(const scene *s, const double eye[3], const double at[3], float fov_deg);

/* Whether quality knob k has any effect in s (its scope, quality.h): the bench sweeps only those, the
 * window shows only those. */
bool scene_knob_applies(const scene *s, knob_id k);

/* Lists the shipped scenes' names into out, one a line in --list-scenes order (scenes/, then
 * scenes/fractals/); with titles, each name padded and followed by the scene's title. */
void scene_list(strbuf *out, bool titles);

#endif
