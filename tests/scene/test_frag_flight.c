/* A Fragmentarium fragment's KeyFrame presets as a flight (scene/formula/frag.h frag_keyframes_flight): what
 * `fathom render --path FILE.frag` flies. Pure C. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "scene/formula/frag.h"
#include "view/camera.h"
#include "view/path.h"

/* A fragment's KeyFrame presets as a flight: a key each, evenly over the length, at its Eye toward its Target,
 * with a set track for each number parameter every key gives; fewer than two keyframes: said. */
static void keyframes(void **st)
{
    (void)st;
    char file[PATH_MAX_LEN];
    snprintf(file, sizeof file, "%s/docs/fragments/mandelbox.frag", FATHOM_SOURCE_DIR);
    strbuf text = {0};
    err_t e;
    path p;
    if (!frag_keyframes_flight(file, 10, &text, &e) || !path_parse(text.data, file, &p, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(p.count, 3);
    const double times[3] = {0, 5, 10}, eyes[3][3] = {{7.8, 5.1, -9.2}, {9.6, 2.4, -4.8}, {8.4, 4.2, 7.4}};
    for (int k = 0; k < 3; k++) {
        assert_float_equal(p.keys[k].time, times[k], 1e-9);
        for (int i = 0; i < 3; i++)
            assert_float_equal(p.keys[k].position[i], eyes[k][i], 1e-6);
    }
    assert_non_null(strstr(text.data, "\"fractal.Scale\": 2.3")); /* the keys' parameter: a track */
    assert_null(strstr(text.data, "quality.")); /* the renderer's defaults are the scene's, not a track */
    path_sample s;
    path_eval(&p, 5, &s); /* at a key's time, its view: Eye toward Target, Up up */
    camera want = camera_look_at_up(eyes[1], (const double[3]){0, 0.5, 0}, (const double[3]){0, 1, 0}, 0.8f);
    assert_float_equal(s.yaw, want.yaw, 1e-5);
    assert_float_equal(s.pitch, want.pitch, 1e-5);
    assert_true(fabs(s.fov_deg - 2 * atan(0.4) * 180 / 3.14159265358979323846) < 1e-4); /* FOV 0.4 */
    path_free(&p);
    sb_free(&text);
    char one[PATH_MAX_LEN];
    snprintf(one, sizeof one, "%s/tests/frag/sphere.frag", FATHOM_SOURCE_DIR); /* one KeyFrame preset */
    assert_false(frag_keyframes_flight(one, 10, &text, &e));
    assert_non_null(strstr(e.msg, "sphere has 1 KeyFrame presets: a flight needs two or more"));
    sb_free(&text);
}

int main(void)
{
    setenv("FATHOM_DATA_DIR", FATHOM_SOURCE_DIR, 1);
    const struct CMUnitTest tests[] = {cmocka_unit_test(keyframes)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
