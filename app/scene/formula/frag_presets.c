/* frag_presets — a fragment's #preset blocks as named views (frag.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "scene/formula/frag.h"
#include "scene/formula/frag_internal.h"
#include "view/shot.h"

enum { PRESET_LINES_MAX = 256, PRESET_LINE_MAX = 256 };

/* One preset's "KEY = VALUE" lines. */
typedef struct preset {
    char name[FRAG_PRESET_NAME_MAX];
    char key[PRESET_LINES_MAX][64], value[PRESET_LINES_MAX][160];
    int count;
} preset;

/* KeyFrame.001 ...: a flight's keys, not a view (left to a flight: not read yet). */
static bool keyframe(const char *name) { return !strncmp(name, "KeyFrame", 8) || !strncmp(name, "Keyframe", 8); }

/* Whether a preset named `name` is where FragM starts: its name holds "default", in any case. */
static bool is_default(const char *name)
{
    for (const char *c = name; *c; c++)
        if (!strncasecmp(c, "default", 7))
            return true;
    return false;
}

/* The preset `name` of the fragment's text into out (NULL: the first whose name holds "default" in any
 * case, as FragM starts; else none, the sliders' defaults: an empty preset named ""); false when there is
 * no such preset. names/count: every preset's name (count may be NULL); *index (may be NULL): the one
 * taken among them, -1 for the sliders' defaults. kf >= 0: the kf-th KeyFrame preset instead (a flight's key;
 * the others leave them out). */
static bool find(const char *text, const char *name, preset *out, char names[][FRAG_PRESET_NAME_MAX], int max,
                 int *count, int *index, int kf)
{
    char line[PRESET_LINE_MAX];
    const char *p = text;
    bool in = false, found = false, take = false;
    int n = 0, keys = 0;
    if (out)
        *out = (preset){0};
    if (index)
        *index = -1;
    while (frag_next_line(&p, line, sizeof line)) {
        const char *c = frag_skip(line);
        if (!in && !strncmp(c, "#preset", 7)) {
            in = true;
            char this[FRAG_PRESET_NAME_MAX];
            snprintf(this, sizeof this, "%s", frag_skip(c + 7));
            for (char *e = this + strlen(this); e > this && (e[-1] == ' ' || e[-1] == '\t'); e--)
                e[-1] = '\0';
            if (keyframe(this)) {
                take = !found && keys++ == kf;
                if (take && out)
                    snprintf(out->name, sizeof out->name, "%s", this);
                found |= take;
                continue;
            }
            if (names && n < max)
                snprintf(names[n], FRAG_PRESET_NAME_MAX, "%s", this);
            take = kf < 0 && !found && (name ? !strcmp(this, name) : is_default(this));
            if (take && out)
                snprintf(out->name, sizeof out->name, "%s", this);
            if (take && index)
                *index = n;
            found |= take;
            n++;
        } else if (in && !strncmp(c, "#endpreset", 10)) {
            in = take = false;
        } else if (in && take && out && out->count < PRESET_LINES_MAX) {
            const char *eq = strchr(c, '=');
            if (!eq)
                continue;
            int k = (int)(eq - c);
            while (k > 0 && (c[k - 1] == ' ' || c[k - 1] == '\t'))
                k--;
            snprintf(out->key[out->count], sizeof out->key[0], "%.*s", k, c);
            snprintf(out->value[out->count], sizeof out->value[0], "%s", frag_skip(eq + 1));
            out->count++;
        }
    }
    if (count)
        *count = n;
    return found || (!name && kf < 0);
}

int frag_presets(const char *path, char names[][FRAG_PRESET_NAME_MAX], int max, err_t *err)
{
    char *text;
    if (!frag_read(path, path, &text, err))
        return -1;
    int n = 0;
    find(text, NULL, NULL, names, max, &n, NULL, -1);
    free(text);
    return n < max ? n : max;
}


int frag_preset_index(const char *path, const char *name)
{
    char *text;
    err_t e;
    int index = -1;
    if (frag_read(path, path, &text, &e)) {
        find(text, name, NULL, NULL, 0, NULL, &index, -1);
        free(text);
    }
    return index;
}


/* The camera keys of 3D.frag: true when key was one (taken into cam, or a wrong value: *bad). */
static bool camera_key(const char *key, const char *value, double eye[3], double target[3], double up[3], camera *cam,
                       bool *bad)
{
    double v[3];
    int n = frag_values(value, v, 3);
    if (!strcmp(key, "Eye") || !strcmp(key, "Target") || !strcmp(key, "Up")) {
        double *to = key[0] == 'E' ? eye : key[0] == 'T' ? target : up;
        *bad |= n != 3;
        for (int i = 0; i < n; i++)
            to[i] = v[i];
    } else if (!strcmp(key, "FOV")) { /* tan of half the vertical field of view (3D.frag scales y in [-1, 1]) */
        *bad |= n != 1 || v[0] <= 0;
        cam->fov_y = n == 1 && v[0] > 0 ? (float)(2 * atan(v[0])) : cam->fov_y;
    } else if (!strcmp(key, "Aperture")) {
        cam->lens.aperture = n == 1 && v[0] > 0 ? (float)v[0] : 0;
    } else if (!strcmp(key, "FocalPlane")) {
        cam->lens.focus = n == 1 && v[0] > 0 ? (float)v[0] : 0;
    } else if (!strcmp(key, "EquiRectangular")) {
        cam->lens.projection = !strncmp(value, "true", 4) ? PROJECTION_EQUIRECTANGULAR : PROJECTION_PERSPECTIVE;
    } else {
        return false;
    }
    return true;
}

/* A parameter's override from a preset's value, clamped into its range (noted in *clamped). */
static bool param_set(const formula_param *q, const char *value, char *out, size_t n, bool *clamped)
{
    double v[4];
    int comps = formula_components(q->type), got;
    if (q->type == FORMULA_BOOL) {
        bool t = !strncmp(value, "true", 4), f = !strncmp(value, "false", 5);
        snprintf(out, n, "fractal.%s=%s", q->key, t ? "true" : "false");
        return t || f;
    }
    if ((got = frag_values(value, v, 4)) != comps)
        return false;
    int at = snprintf(out, n, "fractal.%s=", q->key);
    for (int i = 0; i < comps && at > 0 && (size_t)at < n; i++) {
        double lo = q->lo, hi = q->hi;
        if (q->type == FORMULA_COLOR4 && i < 3) /* the colour; the range is its intensity's */
            lo = 0, hi = 1;
        double c = fmin(fmax(v[i], lo), hi);
        *clamped |= (float)c != (float)v[i]; /* a range widened to a preset's value holds it as a float */
        at += snprintf(out + at, n - (size_t)at, q->type == FORMULA_INT ? "%s%.0f" : "%s%.9g", i ? "," : "", c);
    }
    return true;
}

/* The renderer's accuracy keys, onto fathom's: Detail and MaxDistance (Fragmentarium's hit rule, relative
 * to the distance travelled: fractal.detail), FudgeFactor (the step factor), MaxRaySteps, Iterations. */
static bool quality_key(const formula *f, const char *key, const char *value, char *out, size_t n)
{
    double v;
    if (frag_values(value, &v, 1) != 1)
        return false;
    if (!strcmp(key, "Detail"))
        snprintf(out, n, "fractal.detail=%.9g", fmin(fmax(v, -7), 0));
    else if (!strcmp(key, "MaxDistance"))
        snprintf(out, n, "fractal.max_distance=%.9g", fmin(fmax(v, 1e-3), 1e6));
    else if (!strcmp(key, "FudgeFactor"))
        snprintf(out, n, "quality.step_factor=%.9g", fmin(fmax(v, 0.01), 1));
    else if (!strcmp(key, "MaxRaySteps"))
        snprintf(out, n, "quality.max_steps=%d", (int)fmin(fmax(v, 8), 4096));
    else if (!strcmp(key, "Iterations") && f->iterations_hi > 1)
        snprintf(out, n, "fractal.iterations=%d", (int)fmin(fmax(v, f->iterations_lo), f->iterations_hi));
    else
        return false;
    return true;
}

/* Every line of the preset: the camera into cam, the rest as overrides into sets; what fathom does not
 * take goes to ignored. */
static void preset_sets(const preset *pr, const formula *f, camera *cam, char (*sets)[256], int *count, strbuf *ignored)
{
    double eye[3] = {0, 0, -10}, target[3] = {0, 0, 0}, up[3] = {0, 1, 0}; /* 3D.frag's defaults */
    bool bad = false, clamped = false;
    *count = 0;
    sets[(*count)++][0] = '\0'; /* the formula's override: frag_preset_shot */
    for (int i = 0; i < pr->count; i++) {
        const char *key = pr->key[i], *value = pr->value[i];
        if (camera_key(key, value, eye, target, up, cam, &bad))
            continue;
        char set[256];
        bool taken = *count < SHOT_SET_MAX && quality_key(f, key, value, set, sizeof set);
        for (int k = 0; !taken && k < f->param_count && *count < SHOT_SET_MAX; k++)
            if (!strcmp(f->params[k].key, key))
                taken = param_set(&f->params[k], value, set, sizeof set, &clamped);
        if (taken)
            snprintf(sets[(*count)++], 256, "%s", set);
        else
            sb_printf(ignored, "%s%s", ignored->len ? ", " : "", key);
    }
    double fov = cam->fov_y;
    camera_lens lens = cam->lens;
    *cam = camera_degenerate(eye, target) ? camera_look_at(eye, (double[3]){0, 0, 0}, (float)fov)
                                          : camera_look_at_up(eye, target, up, (float)fov);
    cam->lens = lens;
    /* where the preset is silent, the DE renderers' own defaults (every one of fathom's set: frag.c) */
    static const char *const DEFAULTS[][2] = {{"MaxRaySteps", "quality.max_steps=56"},
                                              {"FudgeFactor", "quality.step_factor=1"},
                                              {"Specular", "fractal.Specular=4"}}; /* Fast-Raytracer's */
    size_t defaults = f->frag_light >= FRAG_LIGHT_PHONG ? 3 : 2;
    for (size_t d = 0; d < defaults && *count < SHOT_SET_MAX; d++) {
        bool said = false;
        for (int i = 0; i < pr->count; i++)
            said |= !strcmp(pr->key[i], DEFAULTS[d][0]);
        if (!said)
            snprintf(sets[(*count)++], 256, "%s", DEFAULTS[d][1]);
    }
    if (clamped)
        sb_printf(ignored, "%s(values outside a slider's range were clamped into it)", ignored->len ? "; " : "");
}

bool frag_preset_shot(const char *path, const char *name, strbuf *shot, char **ignored_out, err_t *err)
{
    formula f;
    char *text;
    if (!frag_load(path, &f, err) || !frag_read(path, path, &text, err))
        return false;
    preset *pr = calloc(1, sizeof *pr);
    char (*sets)[256] = calloc(SHOT_SET_MAX, 256);
    char names[FRAG_PRESET_MAX][FRAG_PRESET_NAME_MAX];
    int count = 0;
    bool ok = pr && sets;
    if (ok && !find(text, name, pr, names, FRAG_PRESET_MAX, &count, NULL, -1)) {
        strbuf known = {0};
        for (int i = 0; i < count && i < FRAG_PRESET_MAX; i++)
            sb_printf(&known, "%s\"%s\"", i ? ", " : "", names[i]);
        ok = err_set(err, "%s has no preset \"%s\" (its presets: %s)", f.name, name, known.data ? known.data : "none");
        sb_free(&known);
    }
    free(text);
    if (ok) {
        camera cam = {.fov_y = (float)(2 * atan(0.4))}; /* 3D.frag's default FOV */
        strbuf ignored = {0};
        int n;
        preset_sets(pr, &f, &cam, sets, &n, &ignored);
        snprintf(sets[0], 256, "fractal.formula=%s", path);
        const char *list[SHOT_SET_MAX];
        for (int i = 0; i < n; i++)
            list[i] = sets[i];
        char scene[PATH_MAX_LEN], lens[3][256];
        int k = 0; /* the lens is the scene's (camera.*), not the shot camera's */
        if (cam.lens.aperture > 0)
            snprintf(lens[k++], 256, "camera.aperture=%.9g", (double)cam.lens.aperture);
        if (cam.lens.focus > 0 && cam.lens.aperture > 0)
            snprintf(lens[k++], 256, "camera.focus=%.9g", (double)cam.lens.focus);
        if (cam.lens.projection == PROJECTION_EQUIRECTANGULAR)
            snprintf(lens[k++], 256, "camera.projection=equirectangular");
        for (int i = 0; i < k && n < SHOT_SET_MAX; i++)
            list[n++] = lens[i];
        snprintf(scene, sizeof scene, "%s/scenes/fractals/fractal.json", util_data_dir());
        shot_describe(scene, list, n, &cam, 1280, 720, shot); /* fathom's default size */
        if (ignored_out)
            *ignored_out = ignored.data;
        else
            sb_free(&ignored);
    }
    free(pr);
    free(sets);
    return ok;
}

/* A flight key's parameter: "fractal.NAME=V", one number (a flight's set tracks are numbers). */
static bool scalar_set(const char *set)
{
    const char *eq = strchr(set, '=');
    char *end;
    return !strncmp(set, "fractal.", 8) && eq && (strtod(eq + 1, &end), *end == '\0' && end > eq + 1);
}

/* The k-th KeyFrame preset's camera and overrides (preset_sets); their count. */
static int key_sets(const char *text, const formula *f, int k, preset *pr, char (*sets)[256], camera *cam)
{
    strbuf ignored = {0};
    int n;
    *cam = (camera){.fov_y = (float)(2 * atan(0.4))}; /* 3D.frag's default FOV */
    find(text, NULL, pr, NULL, 0, NULL, NULL, k);
    preset_sets(pr, f, cam, sets, &n, &ignored);
    sb_free(&ignored);
    return n;
}

bool frag_keyframes_flight(const char *path, double seconds, strbuf *flight, err_t *err)
{
    formula f;
    char *text;
    if (!frag_load(path, &f, err) || !frag_read(path, path, &text, err))
        return false;
    preset *pr = calloc(1, sizeof *pr);
    char(*sets)[256] = calloc(SHOT_SET_MAX, 256), (*first)[256] = calloc(SHOT_SET_MAX, 256);
    int count = 0, nfirst = 0;
    while (pr && find(text, NULL, pr, NULL, 0, NULL, NULL, count))
        count++;
    bool ok = pr && sets && first && (count >= 2 || err_set(err, "%s has %d KeyFrame presets: a flight needs two or more",
                                                           f.name, count));
    for (int k = 0; ok && k < count; k++) { /* the parameters every key sets: the first key's, each checked */
        camera cam;
        int n = key_sets(text, &f, k, pr, sets, &cam);
        if (k == 0)
            for (int i = 1; i < n; i++)
                if (scalar_set(sets[i]))
                    memcpy(first[nfirst++], sets[i], 256);
        for (int j = 0; j < nfirst; j++) { /* a key that leaves one out: it is no track */
            size_t key = strcspn(first[j], "=");
            bool has = false;
            for (int i = 1; i < n; i++)
                has |= !strncmp(sets[i], first[j], key + 1);
            if (!has)
                memmove(first[j], first[j + 1], (size_t)(nfirst - j - 1) * 256), nfirst--, j--;
        }
    }
    sb_append(flight, "{ \"keys\": [\n");
    for (int k = 0; ok && k < count; k++) {
        camera cam;
        int n = key_sets(text, &f, k, pr, sets, &cam);
        camera_basis b = camera_get_basis(&cam);
        const double *e = cam.position;
        sb_printf(flight, "  { \"time\": %.9g, \"position\": [%.9g, %.9g, %.9g], \"look_at\": [%.9g, %.9g, %.9g], "
                          "\"up\": [%.9g, %.9g, %.9g], \"fov\": %.9g, \"set\": {",
                  seconds * k / (count - 1), e[0], e[1], e[2], e[0] + b.forward[0], e[1] + b.forward[1],
                  e[2] + b.forward[2], (double)b.up[0], (double)b.up[1], (double)b.up[2], (double)cam.fov_y * 180 / 3.14159265358979323846);
        for (int j = 0; j < nfirst; j++) {
            size_t key = strcspn(first[j], "=");
            for (int i = 1; i < n; i++)
                if (!strncmp(sets[i], first[j], key + 1))
                    sb_printf(flight, "%s\"%.*s\": %s", j ? ", " : "", (int)key, sets[i], sets[i] + key + 1);
        }
        sb_printf(flight, "} }%s\n", k + 1 < count ? "," : "");
    }
    sb_append(flight, "] }\n");
    free(text);
    free(pr);
    free(sets);
    free(first);
    return ok;
}
