/* CLI parsing: values, ranges and the error each bad value gets. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "check.h"

#include "cli/cli.h"

#define ARGV(...) ((char *[]){"fathom", __VA_ARGS__, NULL})
#define ARGC(...) ((int)(sizeof((char *[]){"fathom", __VA_ARGS__}) / sizeof(char *)))
#define PARSE(o, e, ...) cli_parse(ARGC(__VA_ARGS__), ARGV(__VA_ARGS__), o, e)

static void defaults(void **st)
{
    (void)st;
    cli_options o;
    err_t e;
    assert_true(cli_parse(1, (char *[]){"fathom", NULL}, &o, &e));
    assert_string_equal(o.scene, "csg");
    assert_null(o.output);
    assert_int_equal(o.width, 0);
    assert_int_equal(o.spp, 0);
    assert_int_equal(o.set_count, 0);
}

static void full_offline_line(void **st)
{
    (void)st;
    cli_options o;
    err_t e;
    assert_true(PARSE(&o, &e, "--scene", "csg", "--output", "shot.exr", "--size", "1920x1080", "--spp", "64",
                      "--camera", "1,2.5,-3", "--look-at=0,0,0", "--fov", "40", "--aov", "depth,normal,steps,variance,samples",
                      "--set", "camera.fov=30", "--quality", "final"));
    assert_string_equal(o.output, "shot.exr");
    assert_int_equal(o.width, 1920);
    assert_int_equal(o.height, 1080);
    assert_int_equal(o.spp, 64);
    assert_true(o.has_camera);
    assert_near(o.camera[1], 2.5f, 0);
    assert_near(o.camera[2], -3.0f, 0);
    assert_true(o.has_look_at);
    assert_near(o.fov_deg, 40.0f, 0);
    assert_int_equal(o.aovs, AOV_DEPTH | AOV_NORMAL | AOV_STEPS | AOV_VARIANCE | AOV_SAMPLES);
    assert_int_equal(o.set_count, 2);
    assert_string_equal(o.sets[0], "camera.fov=30");
    assert_string_equal(o.sets[1], "quality.preset=final");
}

/* --quick and --full set the runs unless --runs says otherwise */
static void bench_depths(void **st)
{
    (void)st;
    cli_options o;
    err_t e;
    assert_true(PARSE(&o, &e, "bench", "--quick"));
    assert_true(o.bench && o.quick && !o.full);
    assert_int_equal(o.runs, 3);
    assert_true(PARSE(&o, &e, "bench", "--full"));
    assert_int_equal(o.runs, 9);
    assert_true(PARSE(&o, &e, "bench", "--quick", "--runs", "7"));
    assert_int_equal(o.runs, 7);
    assert_true(PARSE(&o, &e, "bench"));
    assert_int_equal(o.runs, 5);
}

static void expect_error(int argc, char **argv, const char *needle)
{
    cli_options o;
    err_t e = {{0}};
    assert_false(cli_parse(argc, argv, &o, &e));
    if (!strstr(e.msg, needle))
        fail_msg("error '%s' does not mention '%s'", e.msg, needle);
}

static void bad_values(void **st)
{
    (void)st;
    expect_error(ARGC("--size", "0x-3"), ARGV("--size", "0x-3"), "--size");
    expect_error(ARGC("--size", "640"), ARGV("--size", "640"), "WxH");
    expect_error(ARGC("--size", "640x360x2"), ARGV("--size", "640x360x2"), "--size");
    expect_error(ARGC("--size", "99999x10"), ARGV("--size", "99999x10"), "--size");
    expect_error(ARGC("--spp", "-1"), ARGV("--spp", "-1"), "--spp");
    expect_error(ARGC("--backend", "vulkan"), ARGV("--backend", "vulkan"), "use auto, fragment or compute");
    expect_error(ARGC("--truth", "path"), ARGV("--truth", "path"), "belong to fathom bench");
    expect_error(ARGC("--quick"), ARGV("--quick"), "belong to fathom bench");
    expect_error(ARGC("bench", "--quick", "--full"), ARGV("bench", "--quick", "--full"), "pick one");
    expect_error(ARGC("--spp", "3.5"), ARGV("--spp", "3.5"), "--spp");
    expect_error(ARGC("--fov", "400"), ARGV("--fov", "400"), "--fov");
    expect_error(ARGC("--fov", "0"), ARGV("--fov", "0"), "--fov");
    expect_error(ARGC("--fov", "nan"), ARGV("--fov", "nan"), "--fov");
    expect_error(ARGC("--camera", "1,2"), ARGV("--camera", "1,2"), "X,Y,Z");
    expect_error(ARGC("--camera", "1,2,3,4"), ARGV("--camera", "1,2,3,4"), "X,Y,Z");
    expect_error(ARGC("--camera", "1,inf,3"), ARGV("--camera", "1,inf,3"), "X,Y,Z");
    expect_error(ARGC("--set", "novalue"), ARGV("--set", "novalue"), "KEY=VALUE");
    /* a preset name is a command-line value: checked here (exit 2), not later as a scene error */
    expect_error(ARGC("--quality", "high"), ARGV("--quality", "high"), "draft, interactive, final, reference");
    expect_error(ARGC("--frobnicate"), ARGV("--frobnicate"), "unknown option");
    expect_error(ARGC("--spp"), ARGV("--spp"), "needs a value");
    expect_error(ARGC("--output", "x.jpg"), ARGV("--output", "x.jpg"), ".png or .exr");
    expect_error(ARGC("--aov", "depth"), ARGV("--aov", "depth"), "--output");
    expect_error(ARGC("--output", "a.png", "--aov", "depth"), ARGV("--output", "a.png", "--aov", "depth"), "EXR");
    expect_error(ARGC("--output", "a.exr", "--aov", "color"), ARGV("--output", "a.exr", "--aov", "color"), "--aov");
}

static void size_and_vec_parsers(void **st)
{
    (void)st;
    int w, h;
    assert_true(cli_parse_size("97x61", &w, &h));
    assert_int_equal(w, 97);
    assert_int_equal(h, 61);
    assert_false(cli_parse_size("x61", &w, &h));
    assert_false(cli_parse_size("97x", &w, &h));
    assert_false(cli_parse_size("97 x61", &w, &h));
    double v[3];
    assert_true(cli_parse_vec3("-1e-3,2,3.25", v));
    assert_true(v[0] == -1e-3 && v[2] == 3.25);
    /* a deep zoom's camera keeps a double's digits (a float would round it to 0.3) */
    assert_true(cli_parse_vec3("0.30000000000001,0,0", v) && v[0] != 0.3 && fabs(v[0] - 0.30000000000001) < 1e-16);
    assert_false(cli_parse_vec3("1,,3", v));
    assert_false(cli_parse_vec3("1e30,1e30,1e30", v)); /* said "same point" as its look-at before */
    assert_true(cli_parse_vec3("1e7,-1e7,0", v));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(defaults),
        cmocka_unit_test(full_offline_line),
        cmocka_unit_test(bench_depths),
        cmocka_unit_test(bad_values),
        cmocka_unit_test(size_and_vec_parsers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
