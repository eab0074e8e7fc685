/* Fragmentarium fragments drawn (scene/formula/frag.h, shaders/frag/): what each must draw, against closed
 * forms — a sphere fragment's depth at every pixel, an absolute hit distance (fractal.hit_distance)
 * growing its silhouette by exactly that distance, the renderers' orbit-trap colouring and the baseColor() hook
 * as albedo, init() once a pixel, MathUtils' rotation convention through a helper from the fragment's
 * own folder, a Locked parameter recompiled — and, when FATHOM_FRAG_CORPUS names a folder (the
 * public collections, not committed), every DE fragment under it: opened, compiled, drawn at its
 * default preset without NaN and not flat, with a one-line reason for each that is not. */
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "gltest.h"
#include "data/media/image_io.h"
#include "gpu/render.h"
#include "scene/formula/frag.h"
#include "view/shot.h"

enum { FW = 64, FH = 48 };

/* The fractal scene with tests/frag/NAME and the sets (one sample, no anti-aliasing). */
static void frag_scene(const char *name, const char *const *extra, int n, scene *s)
{
    char json[2 * PATH_MAX_LEN];
    snprintf(json, sizeof json,
             "{\"program\": \"fractal\", \"fractal\": {\"formula\": \"%s/tests/frag/%s\"}, \"camera\": {\"position\": "
             "[0, 0, -5], \"look_at\": [0, 0, 0]}, \"environment\": {\"color\": [1, 1, 1], \"intensity\": 1}, "
             "\"quality\": {\"preset\": \"interactive\", \"step_factor\": 0.9}}",
             FATHOM_SOURCE_DIR, name);
    const char *sets[16] = {"quality.spp=1", "effects.aa=off"};
    for (int i = 0; i < n; i++)
        sets[2 + i] = extra[i];
    load_text(json, sets, 2 + n, s);
}

/* The first hit of the ray o + t d (unit d) with the sphere (centre c, radius r); +inf on a miss. */
static double sphere_hit(const double *o, const double *d, const double *c, double r)
{
    double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
    double b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    double disc = b * b - (oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - r * r);
    return disc < 0 ? INFINITY : -b - sqrt(disc);
}

/* Pixels where hit and miss disagree with a sphere's closed form, and the largest depth error (in
 * pixel footprints) where both hit. A fractal's surface is drawn at a level of detail (the footprint
 * rule: a ray within hit_k footprints of it has hit it; fractal/common.glsl), or grown by an absolute
 * hit distance: `grow` is that distance (0: the footprint rule), and rays that pass within two
 * footprints of the grown silhouette may go either way. */
static int against_sphere(const scene *s, const camera *cam, double cx, double cy, double cz, double r, double grow,
                          double *worst)
{
    float *aov = malloc(sizeof(float) * FW * FH * AOV);
    const double c[3] = {cx, cy, cz};
    draw(s, cam, FW, FH, 1, NULL, aov, NULL);
    int wrong = 0;
    *worst = 0;
    for (int row = 0; row < FH; row++)
        for (int x = 0; x < FW; x++) {
            dray ray = pixel_ray(cam, x, row, FW, FH);
            double oc[3] = {c[0] - ray.o[0], c[1] - ray.o[1], c[2] - ray.o[2]};
            double along = oc[0] * ray.d[0] + oc[1] * ray.d[1] + oc[2] * ray.d[2];
            double miss = sqrt(fmax(oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - along * along, 0));
            double footprint = camera_pixel_angle(cam, FH) * along, edge = grow > 0 ? r + grow : r;
            double want = miss < edge ? sphere_hit(ray.o, ray.d, c, edge) : INFINITY;
            double got = aov[(row * FW + x) * AOV + AOV_SLOT_DEPTH];
            bool band = fabs(miss - edge) < 2 * footprint + (grow > 0 ? 0 : 1.0 * footprint);
            if (isinf(want) != isinf(got))
                wrong += !band;
            else if (!isinf(want) && !band)
                *worst = fmax(*worst, fabs(got - want) / (camera_pixel_angle(cam, FH) * want));
        }
    free(aov);
    return wrong;
}

static void sphere_depth(void **st)
{
    (void)st;
    scene s;
    const char *sets[] = {"fractal.Radius=1.5"};
    frag_scene("sphere.frag", sets, 1, &s);
    camera cam = cam_at(0.3, 0.2, -5, 0, 0, 0, 2 * atan(0.4) / DEG2RAD);
    double worst;
    int wrong = against_sphere(&s, &cam, 0, 0, 0, 1.5, 0, &worst);
    /* the footprint rule stops within hit_k footprints: a silhouette pixel may go either way */
    if (wrong > 0 || worst > 2)
        fail_msg("%d pixels disagree with the sphere, depth off by %.3f footprints", wrong, worst);
    const char *moved[] = {"fractal.Radius=0.75", "fractal.Centre=0,0.5,0"}; /* a vec3 parameter moves it */
    scene_free(&s);
    frag_scene("sphere.frag", moved, 2, &s);
    wrong = against_sphere(&s, &cam, 0, 0.5, 0, 0.75, 0, &worst);
    if (wrong > 0 || worst > 2)
        fail_msg("moved: %d pixels disagree, depth off by %.3f footprints", wrong, worst);
    scene_free(&s);
}

/* fractal.hit_distance: a ray stops where DE < that distance, so the silhouette is the sphere grown by it. */
static void absolute_hit_distance(void **st)
{
    (void)st;
    scene s;
    const char *sets[] = {"fractal.Radius=1", "fractal.hit_distance=0.25", "quality.max_steps=1024"};
    frag_scene("sphere.frag", sets, 3, &s);
    camera cam = cam_at(0, 0, -5, 0, 0, 0, 40);
    double worst;
    int grown = against_sphere(&s, &cam, 0, 0, 0, 1, 0.25, &worst), plain = against_sphere(&s, &cam, 0, 0, 0, 1, 0, &worst);
    if (grown > 0 || plain < 40)
        fail_msg("hit_distance 0.25: %d pixels off the sphere of radius 1.25, %d off radius 1", grown, plain);
    scene_free(&s);
}

/* The albedo at the image's centre pixel (a hit). */
static void centre_albedo(const scene *s, float out[3])
{
    camera cam = cam_at(0, 0, -5, 0, 0, 0, 30);
    float *aov = malloc(sizeof(float) * FW * FH * AOV);
    draw(s, &cam, FW, FH, 1, NULL, aov, NULL);
    const float *a = aov + (size_t)((FH / 2) * FW + FW / 2) * AOV;
    if (isinf(a[AOV_SLOT_DEPTH]))
        fail_msg("the centre pixel missed");
    for (int i = 0; i < 3; i++)
        out[i] = a[AOV_SLOT_ALBEDO + i];
    free(aov);
}

/* A fragment's colour as albedo: to the power Gamma (2 by default) in its own look (frag/look.glsl), from
 * sRGB-ish display values (2.2) in fathom's (frag/glue.glsl). */
static double decode_power = 2.0;
static float decode(double c) { return (float)pow(fmin(fmax(c, 0), 1), decode_power); }

static void trap_colouring(void **st)
{
    (void)st;
    scene s;
    /* trap (0.2, 0.4, 0.6, r² 0.25): the colour is mix(BaseColor, 3 Σ colour·strength·trap, OrbitStrength) */
    const char *sets[] = {"fractal.OrbitStrength=0.5", "fractal.BaseColor=1,0,0", "fractal.X=1,0,0,0.5",
                          "fractal.Y=0,1,0,0.25", "fractal.Z=0,0,1,0.5", "fractal.R=1,1,1,0.2"};
    frag_scene("trap.frag", sets, 6, &s);
    float got[3];
    centre_albedo(&s, got);
    double sum[3] = {0.2 * 0.5 + 0.5 * 0.2, 0.4 * 0.25 + 0.5 * 0.2, 0.6 * 0.5 + 0.5 * 0.2};
    double base[3] = {1, 0, 0};
    for (int i = 0; i < 3; i++)
        assert_float_equal(got[i], decode(base[i] + 0.5 * (3 * sum[i] - base[i])), 2e-3);
    scene_free(&s);
    /* cycling colours: each trap colour cycles as 0.5 + 0.5 cos(trap · Cycles + colour) */
    const char *cyc[] = {"fractal.OrbitStrength=1", "fractal.CycleColors=true", "fractal.Cycles=2", "fractal.X=0,0,0,1",
                         "fractal.Y=0,0,0,0", "fractal.Z=0,0,0,0", "fractal.R=0,0,0,0"};
    frag_scene("trap.frag", cyc, 7, &s);
    centre_albedo(&s, got);
    assert_float_equal(got[0], decode(3 * (0.5 + 0.5 * cos(0.2 * 2)) * 0.2), 2e-3);
    scene_free(&s);
}

/* tests/frag/NAME with the sets into s, which must draw a sphere of `radius` about the origin (seen from
 * 5 units with a vertical field of view of fov degrees). */
static void sphere_of(const char *name, const char *const *sets, int n, double radius, double fov, scene *s)
{
    frag_scene(name, sets, n, s);
    camera cam = cam_at(0, 0, -5, 0, 0, 0, fov);
    double worst;
    int wrong = against_sphere(s, &cam, 0, 0, 0, radius, 0, &worst);
    if (wrong > 0)
        fail_msg("%s: %d pixels off the sphere of radius %g", name, wrong, radius);
}

static void hooks(void **st)
{
    (void)st;
    scene s;
    /* init(): radius = 2 Radius; baseColor() (0.2, 0.5, 0.8) mixed into BaseColor (1, 0, 0) by 0.5 */
    const char *sets[] = {"fractal.Radius=0.5", "fractal.OrbitStrength=0.5", "fractal.BaseColor=1,0,0"};
    sphere_of("hooks.frag", sets, 3, 1.0, 40, &s);
    float got[3];
    centre_albedo(&s, got);
    assert_float_equal(got[0], decode(0.6), 2e-3);
    assert_float_equal(got[1], decode(0.25), 2e-3);
    assert_float_equal(got[2], decode(0.4), 2e-3);
    scene_free(&s);
    /* fathom's look: the same colour, decoded as display values */
    const char *fathom[] = {"fractal.Radius=0.5", "fractal.OrbitStrength=0.5", "fractal.BaseColor=1,0,0",
                            "fractal.look=fathom"};
    frag_scene("hooks.frag", fathom, 4, &s);
    centre_albedo(&s, got);
    decode_power = 2.2;
    assert_float_equal(got[0], decode(0.6), 2e-3);
    assert_float_equal(got[2], decode(0.4), 2e-3);
    decode_power = 2.0;
    scene_free(&s);
}

/* A #vertex section's code joins the fragment's: its init() (the vertex shader's, once a vertex in Fragmentarium)
 * runs once a pixel, its varying a global the fragment reads, its slider a parameter; the fragment part's own
 * "varying float K; uniform float S;" are the same names again. */
static void vertex_section(void **st)
{
    (void)st;
    scene s;
    const char *sets[] = {"fractal.S=0.75", "fractal.look=fathom"};
    sphere_of("vertex.frag", sets, 2, 1.5, 50, &s); /* radius 2 S */
    scene_free(&s);
}

/* MathUtils' rotationMatrix3(z, 90°) is Fragmentarium's: the transpose of Rodrigues', so (1, 0, 0)
 * goes to (0, −1, 0); the helper comes from the fragment's own folder; its boxFold and its global
 * `floor` are its own (renamed), fathom's code after it unharmed. */
static void rotation_convention(void **st)
{
    (void)st;
    scene s;
    frag_scene("rotated.frag", NULL, 0, &s);
    camera cam = cam_at(0, 0, -5, 0, 0, 0, 50);
    double worst;
    int wrong = against_sphere(&s, &cam, 0, -1, 0, 0.4, 0, &worst);
    if (wrong > 0)
        fail_msg("%d pixels off a ball at (0, -1, 0)", wrong);
    scene_free(&s);
}

static void locked(void **st)
{
    (void)st;
    scene s;
    frag_scene("locked.frag", NULL, 0, &s);
    strbuf pre = {0};
    scene_preamble(&s, &pre);
    assert_non_null(strstr(pre.data, "#define FRAG_LOCKED_Radius float(1)\n"));
    sb_free(&pre);
    camera cam = cam_at(0, 0, -5, 0, 0, 0, 40);
    double worst;
    assert_true(against_sphere(&s, &cam, 0, 0, 0, 1.0, 0, &worst) == 0);
    scene_free(&s);
    const char *sets[] = {"fractal.Radius=0.5"}; /* a new constant: a new program */
    frag_scene("locked.frag", sets, 1, &s);
    assert_true(against_sphere(&s, &cam, 0, 0, 0, 0.5, 0, &worst) == 0);
    scene_free(&s);
}

/* ---- textures --------------------------------------------------------------------------------------- */

/* The textures' folder, made before and removed after the test (whether it passes or not). */
static char tex_dir[] = "/tmp/fathom-fragtex-XXXXXX";
static int make_tex_dir(void **st)
{
    (void)st;
    memcpy(tex_dir, "/tmp/fathom-fragtex-XXXXXX", sizeof tex_dir);
    return mkdtemp(tex_dir) ? 0 : -1;
}
static int remove_tex_dir(void **st)
{
    (void)st;
    char path[PATH_MAX_LEN + 32];
    for (const char *const *f = (const char *const[]){"quad.png", "tex.frag", NULL}; *f; f++)
        snprintf(path, sizeof path, "%s/%s", tex_dir, *f), remove(path);
    return rmdir(tex_dir);
}

/* A fragment's texture (uniform sampler2D tex; file[quad.png]) bound as FragM binds it: the image's bytes
 * as they are (not decoded from sRGB), its bottom row first (texture() at (0.25, 0.25) is the lower-left
 * texel), and a #TexParameter honoured (nearest: the texel itself between texel centres). */
static void textures(void **st)
{
    (void)st;
    char png[PATH_MAX_LEN + 16], frag[PATH_MAX_LEN + 16], json[2 * PATH_MAX_LEN];
    const uint8_t px[16] = {200, 0, 0, 255, 0, 200, 0, 255, 0, 0, 200, 255, 200, 200, 200, 255}; /* red green / blue white */
    err_t e;
    snprintf(png, sizeof png, "%s/quad.png", tex_dir);
    if (!image_write_u8(png, 2, 2, 4, px, &e))
        fail_msg("%s", e.msg);
    snprintf(frag, sizeof frag, "%s/tex.frag", tex_dir);
    FILE *f = fopen(frag, "w");
    assert_non_null(f);
    fputs("#define providesColor\n#include \"DE-Raytracer.frag\"\nuniform sampler2D tex; file[quad.png]\n"
          "#TexParameter tex GL_TEXTURE_MAG_FILTER GL_NEAREST\n"
          "uniform vec2 At; slider[(0,0),(0.25,0.25),(1,1)]\nfloat DE(vec3 p) { return length(p) - 1.0; }\n"
          "vec3 baseColor(vec3 p, vec3 n) { return texture(tex, At).rgb; }\n", f);
    fclose(f);
    snprintf(json, sizeof json, "{\"program\": \"fractal\", \"fractal\": {\"formula\": \"%s\"}}", frag);
    static const struct { const char *at; float want[3]; } CASES[] = {
        {"fractal.At=0.25,0.25", {0, 0, 200}}, /* the lower-left texel: blue */
        {"fractal.At=0.75,0.75", {0, 200, 0}}, /* the upper-right: green */
        {"fractal.At=0.6,0.4", {200, 200, 200}}, /* between texel centres, nearest: the lower-right, white */
    };
    for (size_t i = 0; i < sizeof CASES / sizeof *CASES; i++) {
        scene s;
        const char *sets[] = {"quality.spp=1", "effects.aa=off", "fractal.OrbitStrength=1", CASES[i].at};
        load_text(json, sets, 4, &s);
        float got[3];
        centre_albedo(&s, got);
        for (int k = 0; k < 3; k++) /* the look's albedo: the colour to the power Gamma (2) */
            if (fabsf(got[k] - powf(CASES[i].want[k] / 255.0f, 2)) > 2e-3f)
                fail_msg("%s: channel %d is %.4f, expected %.4f", CASES[i].at, k, (double)got[k],
                         (double)powf(CASES[i].want[k] / 255.0f, 2));
        scene_free(&s);
    }
}

/* ---- the collections (FATHOM_FRAG_CORPUS) ----------------------------------------------------------- */

typedef struct corpus {
    int files, opened, drawn;
    strbuf report;
} corpus;

static bool is_de_fragment(const char *path)
{
    char *text;
    err_t e;
    if (!util_read_file(path, &text, NULL, &e))
        return false;
    bool de = false;
    for (const char *c = strstr(text, "float"); c && !de; c = strstr(c + 5, "float")) {
        const char *p = c + 5;
        while (*p == ' ' || *p == '\t')
            p++;
        de = p > c + 5 && !strncmp(p, "DE", 2) && (p[2] == '(' || p[2] == ' ');
    }
    free(text);
    return de;
}

/* One fragment at its default preset, 64x48, one sample: "ok", or why not. */
static void corpus_one(corpus *k, const char *path)
{
    k->files++;
    strbuf shot = {0};
    shot_desc d = {0};
    err_t e = {""};
    char names[1][FRAG_PRESET_NAME_MAX];
    scene s;
    bool has = frag_presets(path, names, 1, &e) > 0;
    bool ok = (!has || (frag_preset_shot(path, NULL, &shot, NULL, &e) && shot_parse(shot.data, path, &d, &e)));
    const char *sets[SHOT_SET_MAX + 3];
    int n = 0;
    char use[PATH_MAX_LEN + 32];
    snprintf(use, sizeof use, "fractal.formula=%s", path);
    sets[n++] = use;
    for (int i = 0; i < d.set_count; i++)
        sets[n++] = d.sets[i];
    sets[n++] = "quality.spp=1";
    camera cam = has ? d.cam : cam_at(5.5, 4.2, 7.2, 0, 0, 0, 45);
    ok = ok && scene_load("fractal", sets, n, &s, &e);
    if (ok) {
        k->opened++;
        float *rgba = malloc(sizeof(float) * FW * FH * 4);
        ok = render_set_scene(&s, NULL, &e);
        if (ok) {
            render_resize(FW, FH);
            render_begin(&cam);
            render_sample();
            render_read_linear(rgba);
            int nan = 0, differ = 0;
            for (int i = 0; i < FW * FH; i++) {
                nan += !isfinite(rgba[4 * i]) || !isfinite(rgba[4 * i + 1]) || !isfinite(rgba[4 * i + 2]);
                differ += fabsf(rgba[4 * i] - rgba[0]) + fabsf(rgba[4 * i + 1] - rgba[1]) > 0.02f;
            }
            if (nan)
                snprintf(e.msg, sizeof e.msg, "%d pixels are NaN", nan), ok = false;
            else if (differ < FW * FH / 100)
                snprintf(e.msg, sizeof e.msg, "the image is flat (%d pixels differ from the corner)", differ), ok = false;
        }
        free(rgba);
        scene_free(&s);
    }
    k->drawn += ok;
    for (char *c = e.msg; *c; c++) /* one line a file */
        *c = *c == '\n' || *c == '\t' ? ' ' : *c;
    const char *tail = strstr(path, getenv("FATHOM_FRAG_CORPUS")) ? path + strlen(getenv("FATHOM_FRAG_CORPUS")) : path;
    sb_printf(&k->report, "%s\t%s\n", tail, ok ? "drawn" : e.msg);
    shot_free(&d);
    sb_free(&shot);
}

static void corpus_walk(corpus *k, const char *dir, int depth)
{
    struct dirent **list;
    int n = scandir(dir, &list, NULL, alphasort);
    for (int i = 0; i < n; i++) {
        char path[PATH_MAX_LEN];
        struct stat st;
        const char *name = list[i]->d_name;
        if (name[0] != '.' && strcmp(name, "Include") && snprintf(path, sizeof path, "%s/%s", dir, name) < (int)sizeof path &&
            !stat(path, &st)) {
            size_t len = strlen(name);
            if (S_ISDIR(st.st_mode) && depth < 6)
                corpus_walk(k, path, depth + 1);
            else if (len > 5 && !strcmp(name + len - 5, ".frag") && is_de_fragment(path))
                corpus_one(k, path);
        }
        free(list[i]);
    }
    free(list);
}

static void collections(void **st)
{
    (void)st;
    const char *dir = getenv("FATHOM_FRAG_CORPUS");
    if (!dir || !*dir)
        skip(); /* the public collections are not fathom's to commit */
    corpus k = {0};
    corpus_walk(&k, dir, 0);
    printf("%s", k.report.data ? k.report.data : "");
    printf("corpus: %d DE fragments, %d opened, %d drawn (%.1f %%)\n", k.files, k.opened, k.drawn,
           k.files ? 100.0 * k.drawn / k.files : 0.0);
    const char *min = getenv("FATHOM_FRAG_CORPUS_MIN"); /* the share that must draw [0.9] */
    if (k.files == 0 || k.drawn < (min ? atof(min) : 0.9) * k.files)
        fail_msg("%d of %d DE fragments drawn", k.drawn, k.files);
    sb_free(&k.report);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sphere_depth),        cmocka_unit_test(absolute_hit_distance), cmocka_unit_test(trap_colouring),
        cmocka_unit_test(hooks),               cmocka_unit_test(rotation_convention),   cmocka_unit_test(locked),
        cmocka_unit_test(vertex_section),
        cmocka_unit_test_setup_teardown(textures, make_tex_dir, remove_tex_dir), cmocka_unit_test(collections),
    };
    return cmocka_run_group_tests(tests, gl_setup, gl_teardown);
}
