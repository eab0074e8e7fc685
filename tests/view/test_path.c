/* Camera paths (app/view/path.c) against hand-worked values and numerical derivatives:
 *  - the path passes through every key at its time (position, view direction, fov, parameters);
 *  - velocity, the turn rate and the parameter tracks are continuous at the keys (C1);
 *  - orientations stay unit quaternions, and yaw 170° → 190° (written −170°) turns 20°, not 340°;
 *  - keys placed at times proportional to the distance between them give a constant speed within 1 %,
 *    even where the keys are unevenly spaced along a curve; with uneven speeds the speed never
 *    drops below 0 (no backing up) and changes smoothly;
 *  - a straight line at constant speed is the line itself (hand-worked: p(t) = p0 + v t);
 *  - path files round trip; bad files give one clear error; frame ranges and output patterns parse;
 *  - a recorded flight whose spline cuts through a box the camera flew over gets keys from the camera's
 *    trail until it clears the box (view/route.h); a trail that cannot clear it takes the key back. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"
#include "view/path.h"
#include "view/route.h"

static const double DEG = 3.14159265358979323846 / 180.0;

static void load(const char *text, path *p)
{
    err_t e;
    if (!path_parse(text, "t.json", p, &e))
        fail_msg("%s", e.msg);
}

static double len3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* the direction a yaw and pitch look in (camera.h) */
static void forward(double yaw, double pitch, double f[3])
{
    f[0] = -sin(yaw) * cos(pitch);
    f[1] = sin(pitch);
    f[2] = -cos(yaw) * cos(pitch);
}

static const char *const CURVE =
    "{\"keys\": ["
    "{\"time\": 0, \"position\": [0, 1, 0], \"yaw\": 0, \"pitch\": 0, \"fov\": 50, \"set\": {\"fractal.power\": 8}},"
    "{\"time\": 1, \"position\": [2, 1.5, -1], \"yaw\": 40, \"pitch\": -10, \"fov\": 40, \"set\": {\"fractal.power\": 9}},"
    "{\"time\": 1.5, \"position\": [2.2, 1.5, -3], \"look_at\": [0, 0, -6], \"fov\": 60, \"set\": {\"fractal.power\": 7}},"
    "{\"time\": 4, \"position\": [-1, 3, -4], \"yaw\": 170, \"pitch\": 30, \"set\": {\"fractal.power\": 12}},"
    "{\"time\": 5, \"position\": [-1.5, 3, -3.5], \"yaw\": -170, \"pitch\": 20, \"set\": {\"fractal.power\": 12}}]}";

static void passes_through_keys(void **st)
{
    (void)st;
    path p;
    load(CURVE, &p);
    const double want_yaw[5] = {0, 40, 0, 170, -170}, want_pitch[5] = {0, -10, 0, 30, 20}, fov[5] = {50, 40, 60, 60, 60},
                 power[5] = {8, 9, 7, 12, 12};
    for (int i = 0; i < p.count; i++) {
        path_sample s;
        path_eval(&p, p.keys[i].time, &s);
        for (int k = 0; k < 3; k++)
            assert_near(s.position[k], p.keys[i].position[k], 1e-9);
        double f[3], g[3];
        forward(s.yaw, s.pitch, f);
        if (i == 2) { /* look_at [0, 0, -6] from [2.2, 1.5, -3] */
            double d[3] = {-2.2, -1.5, -3}, l = sqrt(2.2 * 2.2 + 1.5 * 1.5 + 9);
            for (int k = 0; k < 3; k++)
                g[k] = d[k] / l;
        } else {
            forward(want_yaw[i] * DEG, want_pitch[i] * DEG, g);
        }
        for (int k = 0; k < 3; k++)
            assert_near(f[k], g[k], 1e-9);
        assert_near(s.fov_deg, fov[i], 1e-9);
        assert_near(s.values[0], power[i], 1e-9);
    }
    assert_string_equal(p.params[0], "fractal.power");
    path_free(&p);
}

/* velocity (position), turn (forward direction) and track derivatives just before and after each key */
static void continuous_at_keys(void **st)
{
    (void)st;
    path p;
    load(CURVE, &p);
    const double h = 1e-5;
    for (int i = 1; i + 1 < p.count; i++) {
        double t = p.keys[i].time;
        path_sample a, b, c, d;
        path_eval(&p, t - 2 * h, &a);
        path_eval(&p, t - h, &b);
        path_eval(&p, t + h, &c);
        path_eval(&p, t + 2 * h, &d);
        double speed = 0;
        for (int k = 0; k < 3; k++) {
            double before = (b.position[k] - a.position[k]) / h, after = (d.position[k] - c.position[k]) / h;
            speed = fmax(speed, fabs(before));
            if (fabs(before - after) > 2e-3 * (1 + fabs(before)))
                fail_msg("key %d: velocity %d jumps from %.6f to %.6f", i, k, before, after);
        }
        assert_true(speed > 0.1); /* the camera moves through the key */
        double fa[3], fb[3], fc[3], fd[3];
        forward(a.yaw, a.pitch, fa);
        forward(b.yaw, b.pitch, fb);
        forward(c.yaw, c.pitch, fc);
        forward(d.yaw, d.pitch, fd);
        for (int k = 0; k < 3; k++) {
            double before = (fb[k] - fa[k]) / h, after = (fd[k] - fc[k]) / h;
            if (fabs(before - after) > 5e-3 * (1 + fabs(before)))
                fail_msg("key %d: turn rate %d jumps from %.6f to %.6f", i, k, before, after);
        }
        double pb = (b.values[0] - a.values[0]) / h, pa = (d.values[0] - c.values[0]) / h;
        assert_near(pb, pa, 1e-3 * (1 + fabs(pb)));
        double vb = (b.fov_deg - a.fov_deg) / h, va = (d.fov_deg - c.fov_deg) / h;
        assert_near(vb, va, 1e-3 * (1 + fabs(vb)));
    }
    path_free(&p);
}

static void unit_quaternions_no_flip(void **st)
{
    (void)st;
    path p;
    load(CURVE, &p);
    double prev_yaw = 0;
    for (int j = 0; j <= 5000; j++) {
        path_sample s;
        path_eval(&p, 5.0 * j / 5000, &s);
        double n = sqrt(s.quat[0] * s.quat[0] + s.quat[1] * s.quat[1] + s.quat[2] * s.quat[2] + s.quat[3] * s.quat[3]);
        assert_near(n, 1, 1e-12);
        /* from key 3 (170°) to key 4 (190° = −170°): yaw stays within 170°…190°, across 180° */
        if (j >= 4000) {
            double y = fmod(s.yaw / DEG + 360, 360);
            if (y < 165 || y > 195)
                fail_msg("t %.3f: yaw %.2f°: the camera turned the long way", 5.0 * j / 5000, y);
        }
        if (j > 0) { /* no sudden turn anywhere: at most 1.5° per millisecond step */
            double dy = fabs(remainder(s.yaw - prev_yaw, 2 * 3.14159265358979323846)) / DEG;
            assert_true(dy < 1.5);
        }
        prev_yaw = s.yaw;
    }
    path_free(&p);
}

/* keys at times proportional to the curve's length between them: constant speed along the curve,
 * however unevenly the keys lie along it */
static void constant_speed_by_arc_length(void **st)
{
    (void)st;
    /* unevenly spaced keys on a circle of radius 3 (arc lengths 3·Δθ): 10°, 80°, 25°, 120°, 15° apart */
    const double angles[6] = {0, 10, 90, 115, 235, 250};
    strbuf text = {0};
    sb_append(&text, "{\"keys\": [");
    for (int i = 0; i < 6; i++)
        sb_printf(&text, "%s{\"time\": %.17g, \"position\": [%.17g, 1, %.17g], \"yaw\": %g, \"pitch\": 0}", i ? "," : "",
                  angles[i] / 10.0, 3 * cos(angles[i] * DEG), 3 * sin(angles[i] * DEG), -angles[i]);
    sb_append(&text, "]}");
    path p;
    load(text.data, &p);
    /* the curve's shape does not depend on the times: retime the keys by the curve's own lengths */
    double length[6];
    for (int i = 0; i < 6; i++)
        length[i] = p.key_length[i];
    path_free(&p);
    text.len = 0;
    sb_append(&text, "{\"keys\": [");
    for (int i = 0; i < 6; i++)
        sb_printf(&text, "%s{\"time\": %.17g, \"position\": [%.17g, 1, %.17g], \"yaw\": %g, \"pitch\": 0}", i ? "," : "",
                  length[i] / 0.5, 3 * cos(angles[i] * DEG), 3 * sin(angles[i] * DEG), -angles[i]);
    sb_append(&text, "]}");
    load(text.data, &p);
    sb_free(&text);
    /* measured speed over small steps, end to end: 0.5 m/s */
    double lo = INFINITY, hi = 0;
    const double dt = 1e-3;
    path_sample a, b;
    for (double t = 0; t + dt <= path_duration(&p); t += dt) {
        path_eval(&p, t, &a);
        path_eval(&p, t + dt, &b);
        double v = len3(a.position, b.position) / dt;
        lo = fmin(lo, v);
        hi = fmax(hi, v);
    }
    double mean = path_length(&p) / path_duration(&p);
    fprintf(stderr, "  speed %.5f … %.5f m/s (mean %.5f)\n", lo, hi, mean);
    assert_true(hi / lo < 1.01);
    assert_near(mean, 0.5, 1e-9);
    /* and the curve does not swing wide: it stays within 5 % of the radius outside the circle its keys lie on (where the
     * keys are far apart it cuts inside, toward the chord: a cubic through unevenly spaced points) */
    double outside = 0;
    for (double t = 0; t <= path_duration(&p); t += 0.01) {
        path_eval(&p, t, &a);
        outside = fmax(outside, sqrt(a.position[0] * a.position[0] + a.position[2] * a.position[2]) - 3);
    }
    fprintf(stderr, "  at most %.3f m outside the circle\n", outside);
    assert_true(outside < 0.15);
    path_free(&p);
}

/* hand-worked: three collinear keys, 2 m apart, 1 s apart: p(t) = (2t, 1, 0) exactly */
static void straight_line_is_exact(void **st)
{
    (void)st;
    path p;
    load("{\"keys\": [{\"time\": 0, \"position\": [0, 1, 0], \"yaw\": -90, \"pitch\": 0},"
         "{\"time\": 1, \"position\": [2, 1, 0], \"yaw\": -90, \"pitch\": 0},"
         "{\"time\": 2, \"position\": [4, 1, 0], \"yaw\": -90, \"pitch\": 0}]}",
         &p);
    for (double t = 0; t <= 2; t += 0.125) {
        path_sample s;
        path_eval(&p, t, &s);
        assert_near(s.position[0], 2 * t, 1e-9);
        assert_near(s.position[1], 1, 1e-12);
        assert_near(s.position[2], 0, 1e-12);
        assert_near(s.yaw, -90 * DEG, 1e-12);
    }
    assert_near(path_length(&p), 4, 1e-9);
    /* uneven speeds (2 m in 1 s, then 2 m in 4 s): never backwards, speed continuous at the key */
    path q;
    load("{\"keys\": [{\"time\": 0, \"position\": [0, 1, 0], \"yaw\": 0, \"pitch\": 0},"
         "{\"time\": 1, \"position\": [2, 1, 0], \"yaw\": 0, \"pitch\": 0},"
         "{\"time\": 5, \"position\": [4, 1, 0], \"yaw\": 0, \"pitch\": 0}]}",
         &q);
    double prev = -1;
    for (double t = 0; t <= 5; t += 0.001) {
        path_sample s;
        path_eval(&q, t, &s);
        assert_true(s.position[0] >= prev - 1e-12);
        prev = s.position[0];
    }
    path_free(&q);
    path_free(&p);
}

static void file_round_trip_and_errors(void **st)
{
    (void)st;
    path p, q;
    load(CURVE, &p);
    strbuf text = {0};
    path_write(&p, &text);
    load(text.data, &q);
    assert_int_equal(q.count, p.count);
    assert_int_equal(q.param_count, 1);
    for (double t = 0; t <= 5; t += 0.01) {
        path_sample a, b;
        path_eval(&p, t, &a);
        path_eval(&q, t, &b);
        for (int k = 0; k < 3; k++)
            assert_near(a.position[k], b.position[k], 1e-9);
        assert_near(fabs(a.quat[0] * b.quat[0] + a.quat[1] * b.quat[1] + a.quat[2] * b.quat[2] + a.quat[3] * b.quat[3]),
                    1, 1e-9);
        assert_near(a.values[0], b.values[0], 1e-9);
    }
    sb_free(&text);
    path_free(&q);
    path_free(&p);
    static const struct {
        const char *text, *want;
    } bad[] = {
        {"{", "malformed JSON"},
        {"{\"keys\": []}", "keys: expected an array of 2 to"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0}]}", "expected an array of 2"},
        {"{\"frames\": 3}", "unknown key 'frames'"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0},"
         "{\"time\": 0, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.1.time: 0 is not after the previous key's 0"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0], \"yaw\": 0, \"pitch\": 0},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0.position: expected [x, y, z]"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"look_at\": [0, 0, 0]},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0.look_at: is the key's position"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 95},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0.pitch: expected a number from -90 to 90"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0, \"set\": {\"a.b\": 1}},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.1.set: 0 parameters where key 0 has 1"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0, \"tilt\": 3},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0: unknown key 'tilt'"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0, \"up\": [0, 0, 1]},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0.up: goes with look_at"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"look_at\": [0, 0, -1], \"up\": [0, 0, 1]},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0.up: is zero or along the view"},
        {"{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0, \"set\": {\"a\": \"x\"}},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 0, \"pitch\": 0}]}",
         "keys.0.set.a: expected a number"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        err_t e = {{0}};
        path r;
        if (path_parse(bad[i].text, "t.json", &r, &e) || !strstr(e.msg, bad[i].want))
            fail_msg("case %zu: got '%s', expected '%s'", i, e.msg, bad[i].want);
        assert_null(r.keys);
    }
}

/* Roll: a key's roll survives the quaternions (path_eval at the key, path_write and back), up with
 * look_at gives the same orientation as yaw, pitch and roll, and halfway between roll 0 and 90° about
 * the same view the path is at 45° (the short way round). */
static void roll_keys(void **st)
{
    (void)st;
    path p, q;
    load("{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 20, \"pitch\": -30, \"roll\": 0},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 20, \"pitch\": -30, \"roll\": 90}]}", &q);
    path_sample a;
    path_eval(&q, 1, &a);
    assert_near(a.roll, GLM_PI / 2, 1e-9);
    assert_near(a.yaw, 20 * GLM_PI / 180, 1e-9);
    path_eval(&q, 0.5, &a); /* one segment: a turn about the view alone */
    assert_near(a.pitch, -30 * GLM_PI / 180, 1e-9);
    assert_near(a.yaw, 20 * GLM_PI / 180, 1e-9);
    assert_near(a.roll, GLM_PI / 4, 1e-9);
    path_free(&q);
    load("{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 20, \"pitch\": -30, \"roll\": 0},"
         "{\"time\": 1, \"position\": [1, 0, 0], \"yaw\": 20, \"pitch\": -30, \"roll\": 90},"
         "{\"time\": 2, \"position\": [2, 0, 0], \"look_at\": [2, -1, 0], \"up\": [0, 0, -1]}]}", &p);
    path_eval(&p, 2, &a); /* straight down, the image's top toward -Z: yaw 0, roll 0 */
    assert_near(a.pitch, -GLM_PI / 2, 1e-9);
    assert_near(a.yaw, 0, 1e-9);
    assert_near(a.roll, 0, 1e-9);
    strbuf text = {0};
    path_write(&p, &text);
    load(text.data, &q);
    for (double t = 0; t <= 2; t += 0.125) {
        path_sample b;
        path_eval(&p, t, &a);
        path_eval(&q, t, &b);
        assert_near(fabs(a.quat[0] * b.quat[0] + a.quat[1] * b.quat[1] + a.quat[2] * b.quat[2] + a.quat[3] * b.quat[3]),
                    1, 1e-9);
    }
    sb_free(&text);
    path_free(&q);
    path_free(&p);
}

/* Issue 58, item 14: docs/flights.md says docs/flight/deep_zoom.json covers a tenth of its way in decades every
 * second; it eased in (0.11 decades in its first second, 2.04 in its last). Each second against the mean. */
static void deep_zoom_flight_is_constant_rate(void **st)
{
    (void)st;
    char file[1024];
    snprintf(file, sizeof file, "%s/docs/flight/deep_zoom.json", getenv("FATHOM_DATA_DIR") ? getenv("FATHOM_DATA_DIR") : ".");
    path p;
    err_t e;
    if (!path_load(file, &p, &e))
        fail_msg("%s", e.msg);
    const double *z = p.keys[0].zoom_to;
    double d[11], worst = 0;
    for (int t = 0; t <= 10; t++) {
        path_sample a;
        path_eval(&p, t, &a);
        d[t] = sqrt(pow(a.position[0] - z[0], 2) + pow(a.position[1] - z[1], 2) + pow(a.position[2] - z[2], 2));
    }
    double mean = log10(d[0] / d[10]) / 10;
    for (int t = 0; t < 10; t++)
        worst = fmax(worst, fabs(log10(d[t] / d[t + 1]) / mean - 1));
    print_message("deep_zoom.json: %.2f decades a second, each second within %.2g of it\n", mean, worst);
    assert_true(worst < 0.01);
    path_free(&p);
}

/* A deep zoom keeps its scale: from 2 m to 2e-12 m of a point in 10 s, the distance shrinks by the
 * same factor every frame (10^-1.2 a second) and passes 2e-6 m at 5 s, where a plain segment is still
 * about 1 m away; the zoom point moving 1e-13 between keys drifts in proportion to the distance left,
 * so the camera stays within the distance of each moment's point. Easing: in-out passes halfway at
 * half time and starts and stops at rest; out starts at twice the plain speed. */
static void zoom_keeps_its_scale(void **st)
{
    (void)st;
    path z, plain;
    load("{\"keys\": [{\"time\": 0, \"position\": [0.3, 0.2, 2], \"look_at\": [0.3, 0.2, 0], \"zoom_to\": [0.3, 0.2, 0]},"
         "{\"time\": 10, \"position\": [0.3000000000001, 0.2, 2e-12], \"look_at\": [0.3000000000001, 0.2, 0],"
         " \"zoom_to\": [0.3000000000001, 0.2, 0]}]}", &z);
    load("{\"keys\": [{\"time\": 0, \"position\": [0.3, 0.2, 2], \"look_at\": [0.3, 0.2, 0]},"
         "{\"time\": 10, \"position\": [0.3000000000001, 0.2, 2e-12], \"look_at\": [0.3000000000001, 0.2, 0]}]}", &plain);
    double worst = 0, prev = 2;
    for (int f = 1; f <= 300; f++) { /* 30 frames a second */
        path_sample a;
        path_eval(&z, f / 30.0, &a);
        double d = a.position[2]; /* the zoom points lie in z = 0 */
        worst = fmax(worst, fabs(log(prev / d) / log(10) - 1.2 / 30));
        prev = d;
        /* the point's drift still to come is in proportion to the distance: never more than it */
        assert_true(fabs(a.position[0] - 0.3000000000001) <= 0.6e-13 * d + 2e-16);
    }
    path_sample mid, lin, end;
    path_eval(&z, 5, &mid);
    path_eval(&plain, 5, &lin);
    path_eval(&z, 10, &end);
    print_message("zoom: every frame %.2f decades nearer (worst off by %.2g); at 5 s %.3g m away (a plain segment: %.3g m)\n",
                  1.2 / 30, worst, mid.position[2], lin.position[2]);
    assert_true(worst < 1e-9);
    assert_near(mid.position[2], 2e-6, 1e-15);
    assert_true(lin.position[2] > 0.5);
    assert_true(end.position[0] == 0.3000000000001 && fabs(end.position[2] - 2e-12) < 1e-24);
    strbuf text = {0};
    path_write(&z, &text); /* zoom_to survives the file */
    path_free(&z);
    load(text.data, &z);
    path_eval(&z, 5, &mid);
    assert_near(mid.position[2], 2e-6, 1e-15);
    sb_free(&text);
    path_free(&z);
    path_free(&plain);
    path e;
    load("{\"keys\": [{\"time\": 0, \"position\": [0, 0, 0], \"yaw\": 0, \"pitch\": 0, \"ease\": \"in-out\"},"
         "{\"time\": 1, \"position\": [10, 0, 0], \"yaw\": 0, \"pitch\": 0, \"ease\": \"out\"},"
         "{\"time\": 2, \"position\": [20, 0, 0], \"yaw\": 0, \"pitch\": 0}]}", &e);
    path_sample a, b;
    path_eval(&e, 0.5, &a);
    assert_near(a.position[0], 5, 1e-6);
    path_eval(&e, 0.01, &a); /* at rest: 3u^2 - 2u^3 of the way after 1 % of the time */
    assert_true(a.position[0] < 0.01);
    path_eval(&e, 0.99, &a);
    assert_true(a.position[0] > 9.99);
    path_eval(&e, 1.01, &b); /* out: 2u - u^2, twice the plain start */
    assert_true(b.position[0] - 10 > 0.15);
    path_free(&e);
}

/* The window's recording: cameras → a path file → the same cameras at the keys, times by distance/speed */
static void recorded_keys(void **st)
{
    (void)st;
    path_camera keys[3] = {{0}};
    const double pos[3][3] = {{0, 1, 5}, {4, 1, 2}, {4.1, 1, 2}}, yaw[3] = {0.3, -2.9, 3.0}, pitch[3] = {0, -0.4, 0.2};
    for (int i = 0; i < 3; i++) {
        keys[i].time = path_next_key_time(keys, i, pos[i], 2.0);
        memcpy(keys[i].position, pos[i], sizeof pos[i]);
        keys[i].yaw = yaw[i];
        keys[i].pitch = pitch[i];
        keys[i].fov_deg = 45 + i;
    }
    assert_near(keys[0].time, 0, 0);
    assert_near(keys[1].time, 2.5, 1e-12);                  /* 5 m at 2 m/s */
    assert_near(keys[2].time, 2.5 + PATH_KEY_GAP_MIN, 1e-12); /* 0.1 m: the smallest gap */
    strbuf text = {0};
    path_text_from_cameras(keys, 3, &text);
    path p;
    load(text.data, &p);
    for (int i = 0; i < 3; i++) {
        path_camera c;
        path_key_camera(&p, i, &c);
        assert_near(c.time, keys[i].time, 1e-9);
        for (int k = 0; k < 3; k++)
            assert_near(c.position[k], pos[i][k], 1e-9);
        double f[3], g[3];
        forward(c.yaw, c.pitch, f);
        forward(yaw[i], pitch[i], g);
        for (int k = 0; k < 3; k++)
            assert_near(f[k], g[k], 1e-8);
        assert_near(c.fov_deg, 45 + i, 1e-9);
    }
    sb_free(&text);
    path_free(&p);
}

static void frames_and_names(void **st)
{
    (void)st;
    int a, b;
    err_t e;
    assert_true(path_parse_frames("0-299", &a, &b, &e) && a == 0 && b == 299);
    assert_true(path_parse_frames("42", &a, &b, &e) && a == 42 && b == 42);
    assert_true(path_parse_frames("7-7", &a, &b, &e) && a == 7 && b == 7);
    static const char *const bad[] = {"", "-5", "3-1", "a-b", "1-", "1-2-3", "99999999999", "1,2"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        if (path_parse_frames(bad[i], &a, &b, &e))
            fail_msg("--frames '%s' accepted", bad[i]);
    char name[64];
    assert_true(path_frame_name("out/frame_%04d.png", 7, name, sizeof name, &e));
    assert_string_equal(name, "out/frame_0007.png");
    assert_true(path_frame_name("100%%_%d.exr", 12, name, sizeof name, &e));
    assert_string_equal(name, "100%_12.exr");
    static const char *const badpat[] = {"frame.png", "%d_%d.png", "%s.png", "%x.png", "%123d.png", "%n.png"};
    for (size_t i = 0; i < sizeof badpat / sizeof badpat[0]; i++)
        if (path_frame_name(badpat[i], 1, name, sizeof name, &e))
            fail_msg("pattern '%s' accepted", badpat[i]);
    assert_false(path_frame_name("%0400d.png", 1, name, 16, &e));
}

/* A box of half-side 1 at the origin: the exact distance, in the probe's form. */
static void box_probe(void *ctx, const double *pts, int n, float *out)
{
    (void)ctx;
    for (int i = 0; i < n; i++) {
        double q[3], outside = 0, inside = -1e9;
        for (int k = 0; k < 3; k++) {
            q[k] = fabs(pts[3 * i + k]) - 1.0;
            outside += q[k] > 0 ? q[k] * q[k] : 0;
            inside = fmax(inside, q[k]);
        }
        out[i] = (float)(sqrt(outside) + fmin(inside, 0.0));
    }
}

static void camera_at(path_camera *c, double x, double y, double z)
{
    *c = (path_camera){.position = {x, y, z}, .yaw = 0, .pitch = 0, .fov_deg = 50};
}

/* Keys at x = −3 and x = +3 on either side of the box: the camera flew over it (a half circle 2.5 m
 * high: the slide rule's way), but the spline between the two keys goes straight through. */
static void recorded_flight_clears_the_box(void **st)
{
    (void)st;
    enum { TRAIL = 200, MAX = 64 };
    path_camera keys[MAX], trail[TRAIL];
    camera_at(&keys[0], -3, 0, 0);
    for (int i = 0; i < TRAIL; i++) {
        double a = 3.14159265358979 * (i + 1) / (TRAIL + 1);
        camera_at(&trail[i], -3 * cos(a), 2.5 * sin(a), 0);
    }
    camera_at(&keys[1], 3, 0, 0);
    keys[1].time = path_next_key_time(keys, 1, keys[1].position, 2.0);
    int n = 2;
    assert_true(route_first_dip(keys, n, 0, keys[1].time, box_probe, NULL) >= 0); /* straight through */
    int added = route_clear(keys, &n, MAX, trail, TRAIL, 2.0, box_probe, NULL);
    fprintf(stderr, "  %d keys added from the trail\n", added);
    assert_true(added >= 1 && added <= ROUTE_MAX_ADDED && n == 2 + added);
    assert_true(route_first_dip(keys, n, 0, keys[n - 1].time, box_probe, NULL) < 0);
    for (int i = 1; i < n; i++)
        assert_true(keys[i].time > keys[i - 1].time);
    assert_near(keys[n - 1].position[0], 3, 0); /* the user's key stays last */
    /* no trail, or one that runs through the box itself, cannot clear it: the key is taken back */
    for (int i = 0; i < TRAIL; i++)
        camera_at(&trail[i], -3 + 6.0 * (i + 1) / (TRAIL + 1), 0, 0);
    for (int k = 0; k < 2; k++) {
        camera_at(&keys[0], -3, 0, 0), camera_at(&keys[1], 3, 0, 0);
        keys[1].time = path_next_key_time(keys, 1, keys[1].position, 2.0);
        n = 2;
        assert_int_equal(route_clear(keys, &n, MAX, trail, k ? TRAIL : 0, 2.0, box_probe, NULL), -1);
        assert_int_equal(n, 1);
        assert_near(keys[0].position[0], -3, 0);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(passes_through_keys),       cmocka_unit_test(continuous_at_keys),
        cmocka_unit_test(unit_quaternions_no_flip),  cmocka_unit_test(constant_speed_by_arc_length),
        cmocka_unit_test(straight_line_is_exact),    cmocka_unit_test(file_round_trip_and_errors),
        cmocka_unit_test(recorded_keys), cmocka_unit_test(roll_keys), cmocka_unit_test(zoom_keeps_its_scale),
        cmocka_unit_test(deep_zoom_flight_is_constant_rate),             cmocka_unit_test(frames_and_names),
        cmocka_unit_test(recorded_flight_clears_the_box),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
