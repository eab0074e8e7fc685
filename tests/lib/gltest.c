#include "gltest.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>
#include <epoxy/gl.h>

#include "gpu/gpu.h"
#include "gpu/render.h"
#include "gpu/render_probe.h"


int gl_setup(void **st)
{
    (void)st;
    err_t e;
    if (!gpu_open(&(gpu_desc){.headless = true}, &e) || !render_init(&e)) {
        fprintf(stderr, "GL setup failed: %s\n", e.msg);
        return -1;
    }
    fprintf(stderr, "GL: %s, %s backend\n", gpu_describe(), render_backend_name(render_backend_used()));
    return 0;
}

int gl_teardown(void **st)
{
    (void)st;
    render_shutdown();
    gpu_close();
    return 0;
}

void load_text(const char *json, const char *const *sets, int nsets, scene *s)
{
    err_t e;
    char path[PATH_MAX_LEN];
    snprintf(path, sizeof path, "%s/tests/probe.json", FATHOM_SOURCE_DIR);
    if (!scene_load_text(json, path, sets, nsets, s, &e))
        fail_msg("scene: %s", e.msg);
}

void load_fractal(const char *program, const char *fractal, const char *quality_json, scene *s)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"program\": \"%s\", \"environment\": {\"intensity\": 0.5},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0.4, 0.8, 0.3], \"shadow\": \"soft\"}],"
             " \"fractal\": %s, \"quality\": %s}", program, fractal, quality_json);
    load_text(json, NULL, 0, s);
}

void gl_probe(const scene *s, const char *extra, const float *pts, int n, float *out)
{
    err_t e;
    if (!render_probe(s, extra, pts, n, out, &e))
        fail_msg("probe: %s", e.msg);
}

void draw(const scene *s, const camera *cam, int w, int h, int spp, const char *extra, float *aov, float *rgba)
{
    err_t e;
    if (!render_set_scene(s, extra, &e))
        fail_msg("render_set_scene: %s", e.msg);
    render_resize(w, h);
    render_begin(cam);
    for (int i = 0; i < spp; i++)
        render_sample();
    if (aov)
        render_read_aovs(aov);
    if (rgba)
        render_read_linear(rgba);
    assert_int_equal(glGetError(), GL_NO_ERROR);
}

camera cam_at(double ex, double ey, double ez, double tx, double ty, double tz, double fov_deg)
{
    /* float-rounded, as the float renderer sees them: the references start their rays where the GPU does */
    return camera_look_at((double[3]){(float)ex, (float)ey, (float)ez}, (double[3]){(float)tx, (float)ty, (float)tz},
                          (float)(fov_deg * DEG2RAD));
}

dray pixel_ray(const camera *c, int x, int row, int w, int h)
{
    camera_basis b = camera_get_basis(c);
    double t = tan(0.5 * (double)c->fov_y);
    double sx = (2.0 * (x + 0.5) / w - 1.0) * t * w / h;
    double sy = (2.0 * ((h - 1 - row) + 0.5) / h - 1.0) * t;
    dray r;
    double len = 0;
    for (int i = 0; i < 3; i++) {
        r.o[i] = c->position[i];
        r.d[i] = b.forward[i] + sx * b.right[i] + sy * b.up[i];
        len += r.d[i] * r.d[i];
    }
    for (int i = 0; i < 3; i++)
        r.d[i] /= sqrt(len);
    return r;
}

void check_finite(const char *what, const float *aov, const float *rgba, int n)
{
    for (int i = 0; i < n; i++) {
        const float *a = aov + i * AOV, *c = rgba + i * 4;
        for (int k = 0; k < 4; k++)
            if (!isfinite(c[k]))
                fail_msg("%s: pixel %d colour channel %d is %g", what, i, k, (double)c[k]);
        for (int k = 0; k < AOV; k++)
            if (k != 3 && !isfinite(a[k]))
                fail_msg("%s: pixel %d AOV channel %d is %g", what, i, k, (double)a[k]);
        if (isnan(a[3]) || a[3] < 0 || (isinf(a[3]) && (a[0] != 0 || a[1] != 0 || a[2] != 0)))
            fail_msg("%s: pixel %d depth %g with normal (%g %g %g)", what, i, (double)a[3], (double)a[0],
                     (double)a[1], (double)a[2]);
        if (fabsf(a[4]) < 1) /* negative: the ray ran out of steps (aov.h) */
            fail_msg("%s: pixel %d took %g steps", what, i, (double)a[4]);
    }
}

