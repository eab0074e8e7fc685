/* path_file — a path's file (reading, writing), the window's recorded keys, and frame numbers (path.h). */
#include "view/path.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/camera.h"
#include "view/path_internal.h"

static const double DEG = 3.14159265358979323846 / 180.0;

/* ---- the file ---- */

static bool num(const cJSON *o, const char *key, double lo, double hi, double *v, const char *name, int i, err_t *err)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble) || it->valuedouble < lo || it->valuedouble > hi)
        return err_set(err, "%s: keys.%d.%s: expected a number from %g to %g", name, i, key, lo, hi);
    *v = it->valuedouble;
    return true;
}

static bool vec3_of(const cJSON *o, const char *key, double v[3], const char *name, int i, err_t *err)
{
    const cJSON *it = cJSON_GetObjectItemCaseSensitive(o, key);
    if (!cJSON_IsArray(it) || cJSON_GetArraySize(it) != 3)
        return err_set(err, "%s: keys.%d.%s: expected [x, y, z] in metres", name, i, key);
    for (int k = 0; k < 3; k++) {
        const cJSON *c = cJSON_GetArrayItem(it, k);
        if (!cJSON_IsNumber(c) || !isfinite(c->valuedouble) || fabs(c->valuedouble) > CAMERA_MAX_COORD)
            return err_set(err, "%s: keys.%d.%s: expected [x, y, z], each a number within ±%g m", name, i, key,
                           CAMERA_MAX_COORD);
        v[k] = c->valuedouble;
    }
    return true;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* The key's orientation: yaw and pitch, or look_at (with up: the image's top toward it), then roll. */
static bool key_orientation(const cJSON *k, path_key *K, int i, const char *name, err_t *err)
{
    double yaw = 0, pitch = 0, roll = 0; /* set on every path below; GCC -O3 cannot see it */
    bool has_angles = cJSON_GetObjectItemCaseSensitive(k, "yaw") || cJSON_GetObjectItemCaseSensitive(k, "pitch");
    bool has_up = cJSON_GetObjectItemCaseSensitive(k, "up") != NULL;
    if (cJSON_GetObjectItemCaseSensitive(k, "look_at")) {
        double at[3], up[3] = {0, 1, 0}, f[3], r[3];
        if (has_angles)
            return err_set(err, "%s: keys.%d: give yaw and pitch or look_at, not both", name, i);
        if (!vec3_of(k, "look_at", at, name, i, err) || (has_up && !vec3_of(k, "up", up, name, i, err)))
            return false;
        double l = path_dist(at, K->position);
        if (camera_degenerate(K->position, at)) /* a deep zoom's key looks at a point 1e-12 away */
            return err_set(err, "%s: keys.%d.look_at: is the key's position: the camera needs a point to look at", name, i);
        for (int c = 0; c < 3; c++)
            f[c] = (at[c] - K->position[c]) / l;
        cross(f, up, r);
        double rl = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]), ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
        if (!(rl > 1e-6 * ul)) {
            if (has_up)
                return err_set(err, "%s: keys.%d.up: is zero or along the view: give the direction the image's top "
                                    "should face", name, i);
            double level[3] = {cos(atan2(-f[0], -f[2])), 0, -sin(atan2(-f[0], -f[2]))}; /* straight up or down */
            memcpy(r, level, sizeof r);
            rl = 1;
        }
        for (int c = 0; c < 3; c++)
            r[c] /= rl;
        path_frame_angles(f, r, &yaw, &pitch, &roll);
        if (!has_up) /* the level camera, as before: pitch stops short of ±90° */
            pitch = fmax(-CAMERA_MAX_PITCH, fmin(CAMERA_MAX_PITCH, pitch));
    } else {
        if (has_up)
            return err_set(err, "%s: keys.%d.up: goes with look_at (with yaw and pitch, give roll)", name, i);
        if (!num(k, "yaw", -1e4, 1e4, &yaw, name, i, err) || !num(k, "pitch", -90, 90, &pitch, name, i, err))
            return false;
        yaw *= DEG;
        pitch *= DEG;
    }
    double more = 0;
    if (cJSON_GetObjectItemCaseSensitive(k, "roll") && !num(k, "roll", -1e4, 1e4, &more, name, i, err))
        return false;
    path_q_from_angles(yaw, pitch, roll + more * DEG, K->quat);
    return true;
}

/* "zoom_to" (a point apart from the key's position) and "ease" (path.h). */
static bool key_zoom_ease(const cJSON *k, path_key *K, int i, const char *name, err_t *err)
{
    K->zoom = cJSON_GetObjectItemCaseSensitive(k, "zoom_to") != NULL;
    if (K->zoom && !vec3_of(k, "zoom_to", K->zoom_to, name, i, err))
        return false;
    if (K->zoom && !(path_dist(K->position, K->zoom_to) > 1e-300))
        return err_set(err, "%s: keys.%d.zoom_to: is the key's position: a zoom needs a distance to close in on", name, i);
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(k, "ease");
    if (!e)
        return true;
    for (int m = 0; cJSON_IsString(e) && m < PATH_EASE_COUNT; m++)
        if (!strcmp(e->valuestring, PATH_EASES[m])) {
            K->ease = m;
            return true;
        }
    return err_set(err, "%s: keys.%d.ease: expected \"none\", \"in\", \"out\" or \"in-out\"", name, i);
}

static bool parse_key(path *p, const cJSON *k, int i, const char *name, err_t *err)
{
    path_key *K = &p->keys[i];
    static const char *const allowed[] = {"time", "position", "yaw", "pitch", "roll", "look_at", "up", "fov", "set",
                                          "zoom_to", "ease", NULL};
    if (!cJSON_IsObject(k))
        return err_set(err, "%s: keys.%d: expected an object with time, position and yaw/pitch or look_at", name, i);
    for (const cJSON *it = k->child; it; it = it->next) {
        bool ok = false;
        for (const char *const *a = allowed; *a && !ok; a++)
            ok = it->string && !strcmp(it->string, *a);
        if (!ok)
            return err_set(err, "%s: keys.%d: unknown key '%s' (allowed: time, position, yaw, pitch, roll, look_at, up, fov, set, zoom_to, ease)",
                           name, i, it->string ? it->string : "");
    }
    if (!num(k, "time", -PATH_MAX_TIME, PATH_MAX_TIME, &K->time, name, i, err) || !vec3_of(k, "position", K->position, name, i, err))
        return false;
    if (i > 0 && !(K->time > K[-1].time))
        return err_set(err, "%s: keys.%d.time: %g is not after the previous key's %g; times must increase", name, i,
                       K->time, K[-1].time);
    if (!key_orientation(k, K, i, name, err))
        return false;
    if (i > 0 && path_q_dot(K->quat, K[-1].quat) < 0) /* the short way round */
        for (int c = 0; c < 4; c++)
            K->quat[c] = -K->quat[c];
    K->fov_deg = i > 0 ? K[-1].fov_deg : 50;
    if ((cJSON_GetObjectItemCaseSensitive(k, "fov") && !num(k, "fov", 1, 179, &K->fov_deg, name, i, err)) ||
        !key_zoom_ease(k, K, i, name, err))
        return false;
    const cJSON *set = cJSON_GetObjectItemCaseSensitive(k, "set");
    int n = 0;
    if (set && !cJSON_IsObject(set))
        return err_set(err, "%s: keys.%d.set: expected an object of scene keys and numbers, e.g. {\"fractal.power\": 8}",
                       name, i);
    for (const cJSON *it = set ? set->child : NULL; it; it = it->next, n++) {
        if (!cJSON_IsNumber(it) || !isfinite(it->valuedouble))
            return err_set(err, "%s: keys.%d.set.%s: expected a number (tracks interpolate numbers)", name, i, it->string);
        if (n >= PATH_MAX_PARAMS || strlen(it->string) >= PATH_PARAM_NAME)
            return err_set(err, "%s: keys.%d.set: at most %d parameters, names shorter than %d", name, i,
                           PATH_MAX_PARAMS, PATH_PARAM_NAME);
        if (i == 0)
            snprintf(p->params[n], PATH_PARAM_NAME, "%s", it->string);
        else if (n >= p->param_count || strcmp(p->params[n], it->string))
            return err_set(err, "%s: keys.%d.set: lists '%s' where key 0 lists %s: every key sets the same "
                                "parameters, in the same order",
                           name, i, it->string, n < p->param_count ? p->params[n] : "nothing more");
        K->values[n] = it->valuedouble;
    }
    if (i == 0)
        p->param_count = n;
    else if (n != p->param_count)
        return err_set(err, "%s: keys.%d.set: %d parameters where key 0 has %d: every key sets the same ones", name, i,
                       n, p->param_count);
    return true;
}

bool path_parse(const char *text, const char *name, path *p, err_t *err)
{
    memset(p, 0, sizeof *p);
    cJSON *root = cJSON_Parse(text);
    if (!root)
        return err_set(err, "%s: malformed JSON (check commas, quotes and brackets)", name);
    const cJSON *keys = cJSON_GetObjectItemCaseSensitive(root, "keys");
    bool ok = true;
    int n = cJSON_IsArray(keys) ? cJSON_GetArraySize(keys) : 0;
    for (const cJSON *it = cJSON_IsObject(root) ? root->child : NULL; it && ok; it = it->next)
        if (!it->string || strcmp(it->string, "keys"))
            ok = err_set(err, "%s: unknown key '%s' (a path file holds \"keys\")", name, it->string ? it->string : "");
    if (ok && (n < 2 || n > PATH_MAX_KEYS))
        ok = err_set(err, "%s: keys: expected an array of 2 to %d keyframes, each {\"time\", \"position\", \"yaw\", "
                          "\"pitch\"} or with \"look_at\"",
                     name, PATH_MAX_KEYS);
    if (ok) {
        p->count = n;
        p->keys = util_calloc((size_t)n, sizeof *p->keys, "path keys");
        int i = 0;
        for (const cJSON *k = keys->child; k && ok; k = k->next, i++)
            ok = parse_key(p, k, i, name, err);
    }
    cJSON_Delete(root);
    if (!ok) {
        path_free(p);
        return false;
    }
    path_prepare(p);
    return true;
}

bool path_load(const char *file, path *p, err_t *err)
{
    char *text;
    memset(p, 0, sizeof *p);
    if (!util_read_file(file, &text, NULL, err))
        return false;
    bool ok = path_parse(text, file, p, err);
    free(text);
    return ok;
}

void path_write(const path *p, strbuf *out)
{
    sb_append(out, "{\n  \"keys\": [\n");
    for (int i = 0; i < p->count; i++) {
        const path_key *K = &p->keys[i];
        double yaw, pitch, roll;
        path_q_to_angles(K->quat, &yaw, &pitch, &roll);
        sb_printf(out, "    {\"time\": %.17g, \"position\": [%.17g, %.17g, %.17g], \"yaw\": %.17g, \"pitch\": %.17g, "
                       "\"roll\": %.17g, \"fov\": %.17g",
                  K->time, K->position[0], K->position[1], K->position[2], yaw / DEG,
                  fmax(-90.0, fmin(90.0, pitch / DEG)), roll / DEG, K->fov_deg);
        if (K->zoom)
            sb_printf(out, ", \"zoom_to\": [%.17g, %.17g, %.17g]", K->zoom_to[0], K->zoom_to[1], K->zoom_to[2]);
        if (K->ease)
            sb_printf(out, ", \"ease\": \"%s\"", PATH_EASES[K->ease]);
        if (p->param_count) {
            sb_append(out, ", \"set\": {");
            for (int k = 0; k < p->param_count; k++)
                sb_printf(out, "%s\"%s\": %.17g", k ? ", " : "", p->params[k], K->values[k]);
            sb_append(out, "}");
        }
        sb_printf(out, "}%s\n", i + 1 < p->count ? "," : "");
    }
    sb_append(out, "  ]\n}\n");
}

/* ---- recording ---- */

double path_next_key_time(const path_camera *keys, int n, const double position[3], double speed)
{
    if (n == 0)
        return 0;
    double gap = speed > 0 ? path_dist(keys[n - 1].position, position) / speed : PATH_KEY_GAP_MIN;
    return keys[n - 1].time + fmax(PATH_KEY_GAP_MIN, fmin(PATH_KEY_GAP_MAX, gap));
}

void path_text_from_cameras(const path_camera *keys, int n, strbuf *out)
{
    sb_append(out, "{\n  \"keys\": [\n");
    for (int i = 0; i < n; i++)
        sb_printf(out, "    {\"time\": %.9g, \"position\": [%.9g, %.9g, %.9g], \"yaw\": %.9g, \"pitch\": %.9g, "
                       "\"roll\": %.9g, \"fov\": %.9g}%s\n",
                  keys[i].time, keys[i].position[0], keys[i].position[1], keys[i].position[2], keys[i].yaw / DEG,
                  keys[i].pitch / DEG, keys[i].roll / DEG, keys[i].fov_deg, i + 1 < n ? "," : "");
    sb_append(out, "  ]\n}\n");
}

void path_key_camera(const path *p, int i, path_camera *out)
{
    const path_key *K = &p->keys[i];
    out->time = K->time;
    memcpy(out->position, K->position, sizeof out->position);
    path_q_to_angles(K->quat, &out->yaw, &out->pitch, &out->roll);
    out->fov_deg = K->fov_deg;
}

/* ---- frames ---- */

static bool whole(const char *s, const char **end, long *v)
{
    if (*s < '0' || *s > '9')
        return false;
    char *e;
    errno = 0;
    *v = strtol(s, &e, 10);
    *end = e;
    return errno == 0 && *v <= 100000000;
}

bool path_parse_frames(const char *s, int *first, int *last, err_t *err)
{
    long a, b;
    const char *e;
    if (!whole(s, &e, &a))
        return err_set(err, "bad --frames '%s': expected a frame number or a range A-B (e.g. 0-299)", s);
    b = a;
    if (*e == '-' && !whole(e + 1, &e, &b))
        return err_set(err, "bad --frames '%s': expected a frame number or a range A-B (e.g. 0-299)", s);
    if (*e)
        return err_set(err, "bad --frames '%s': expected a frame number or a range A-B (e.g. 0-299)", s);
    if (b < a)
        return err_set(err, "bad --frames '%s': the range ends before it starts", s);
    *first = (int)a;
    *last = (int)b;
    return true;
}

bool path_frame_name(const char *pattern, int frame, char *out, size_t n, err_t *err)
{
    int conversions = 0;
    for (const char *c = pattern; *c; c++) {
        if (*c != '%')
            continue;
        if (c[1] == '%') {
            c++;
            continue;
        }
        const char *d = c + 1;
        while (*d >= '0' && *d <= '9')
            d++;
        if (*d != 'd' || d - c > 3)
            return err_set(err, "output pattern '%s': only %%d with an optional width (%%04d) may stand for the "
                                "frame number; write %%%% for a %% sign",
                           pattern);
        conversions++;
        c = d;
    }
    if (conversions != 1)
        return err_set(err, "output pattern '%s': needs exactly one %%d (e.g. frame_%%04d.png) for the frame number",
                       pattern);
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-nonliteral"
    int w = snprintf(out, n, pattern, frame);
#pragma GCC diagnostic pop
    if (w < 0 || (size_t)w >= n)
        return err_set(err, "output pattern '%s': the file name is too long", pattern);
    return true;
}
