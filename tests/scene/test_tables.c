/* The tables every concept is generated from: QUALITY_KNOBS (app/scene/quality.h), PROGRAM_LIST
 * (app/scene/program.h) and the named uniforms the scene module uploads. Each check compares the generated
 * parts with each other or with the shader sources, so a row that drifts from its uses fails here. */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

#include "check.h"

#include "scene/scene.h"

/* Every preset's struct equals its column in the table, and the preamble names every GLSL knob once. */
static void presets_and_preamble_follow_the_table(void **st)
{
    (void)st;
    for (int p = 0; p < PRESET_COUNT; p++) {
        quality q = preset_quality((quality_preset)p);
        strbuf pre = {0};
        quality_preamble(&q, &pre);
        for (int k = 0; k < KNOB_COUNT; k++) {
            const knob_def *d = knob_get_def((knob_id)k);
            assert_near(knob_value(&q, (knob_id)k), d->preset[p], 1e-6 * (1 + d->preset[p]));
            assert_true(d->preset[p] >= d->min && d->preset[p] <= d->max);
            if (!d->glsl)
                continue;
            char line[96];
            if (d->type == KNOB_INT)
                snprintf(line, sizeof line, "#define %s %d\n", d->glsl, (int)d->preset[p]);
            else
                snprintf(line, sizeof line, "#define %s %.9g\n", d->glsl, (double)(float)d->preset[p]);
            if (!strstr(pre.data, line))
                fail_msg("preset %s: preamble lacks '%s'", preset_name((quality_preset)p), line);
        }
        sb_free(&pre);
    }
    knob_id id;
    assert_true(knob_from_name("hit_k", &id));
    assert_int_equal(id, KNOB_hit_k);
    assert_false(knob_from_name("no_such_knob", &id));
}

/* The window's step rule: = then − comes back, and steps stay inside the knob's range. */
static void window_steps_round_trip_and_clamp(void **st)
{
    (void)st;
    int stepped = 0;
    for (int k = 0; k < KNOB_COUNT; k++) {
        if (!knob_window_steps((knob_id)k))
            continue;
        stepped++;
        const knob_def *d = knob_get_def((knob_id)k);
        double v = d->preset[PRESET_INTERACTIVE], up = knob_step((knob_id)k, v, +1);
        if (up < d->max)
            assert_near(knob_step((knob_id)k, up, -1), v, 1e-9);
        assert_true(knob_step((knob_id)k, d->max, +1) <= d->max);
        assert_true(knob_step((knob_id)k, d->min, -1) >= d->min);
    }
    assert_true(stepped >= 4);
}

/* Every knob is a key of the scene file's "quality" block: in range accepted, out of range refused,
 * whole numbers required where the knob is an integer. */
static void every_knob_is_a_scene_key(void **st)
{
    (void)st;
    static const char TEXT[] = "{\"program\": \"csg\", \"materials\": {\"a\": {}},"
                               " \"objects\": [{\"shape\": \"sphere\", \"material\": \"a\"}]}";
    for (int k = 0; k < KNOB_COUNT; k++) {
        const knob_def *d = knob_get_def((knob_id)k);
        char set[96];
        scene s;
        err_t e;
        snprintf(set, sizeof set, "quality.%s=%.9g", d->name, d->max);
        const char *ok[] = {set};
        if (!scene_load_text(TEXT, "/tmp/t.json", ok, 1, &s, &e))
            fail_msg("%s at its max: %s", set, e.msg);
        assert_near(knob_value(&s.quality, (knob_id)k), d->max, 1e-6 * d->max);
        scene_free(&s);
        snprintf(set, sizeof set, "quality.%s=%.9g", d->name, d->max * 2 + 1);
        assert_false(scene_load_text(TEXT, "/tmp/t.json", ok, 1, &s, &e));
        assert_non_null(strstr(e.msg, d->name));
        if (d->type == KNOB_INT) {
            snprintf(set, sizeof set, "quality.%s=%.9g", d->name, d->min + 0.5);
            assert_false(scene_load_text(TEXT, "/tmp/t.json", ok, 1, &s, &e));
            assert_non_null(strstr(e.msg, "whole number"));
        }
    }
}

/* Program names round-trip, each program's GLSL file exists, and every name is in the error message. */
static void programs_registry(void **st)
{
    (void)st;
    strbuf names = {0};
    program_names(&names);
    for (int p = 0; p < PROGRAM_COUNT; p++) {
        const program_def *d = program_get((program_kind)p);
        program_kind back;
        assert_true(program_from_name(d->name, &back));
        assert_int_equal(back, p);
        assert_non_null(d->parse);
        assert_non_null(strstr(names.data, d->name));
        if (d->map_file) {
            char path[PATH_MAX_LEN];
            snprintf(path, sizeof path, "%s/shaders/%s", util_data_dir(), d->map_file);
            if (!util_file_exists(path))
                fail_msg("program %s: %s does not exist", d->name, path);
        }
    }
    sb_free(&names);
}

/* ---- uniforms: every name the scene module uploads is declared by some shader ---------------------- */

/* Every shader file, concatenated: each .glsl under shaders/ and its folders (one level). */
/* Every .glsl and .frag under shaders/ and its folders (one level: common, csg, fractal, shapes, ...). */
static void read_shaders(const char *dir, bool folders, strbuf *all)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    for (struct dirent *e; (e = readdir(d));) {
        size_t n = strlen(e->d_name);
        char path[PATH_MAX_LEN * 2], *text;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (folders && e->d_name[0] != '.' && stat(path, &st) == 0 && S_ISDIR(st.st_mode))
            read_shaders(path, false, all);
        if (n < 5 || (strcmp(e->d_name + n - 5, ".glsl") && strcmp(e->d_name + n - 5, ".frag")))
            continue;
        err_t err;
        if (!util_read_file(path, &text, NULL, &err))
            fail_msg("%s", err.msg);
        sb_append(all, text);
        free(text);
    }
    closedir(d);
}

static char *all_shaders(void)
{
    strbuf all = {0};
    char dir[PATH_MAX_LEN];
    snprintf(dir, sizeof dir, "%s/shaders", util_data_dir());
    read_shaders(dir, true, &all);
    return all.data;
}

typedef struct seen {
    const char *shaders;
    int count, missing;
} seen;

static void check_declared(void *user, const char *name, uniform_type type, int comps, int count, const void *data)
{
    (void)data;
    seen *s = user;
    s->count++;
    /* a hybrid's second formula's uniforms: its own declarations, renamed by #define in program.glsl */
    if (!strncmp(name, HYBRID_PREFIX, strlen(HYBRID_PREFIX)))
        name += strlen(HYBRID_PREFIX);
    assert_true(comps >= 1 && comps <= 4 && count >= 0);
    assert_true(type == UNIFORM_FLOAT || type == UNIFORM_INT);
    /* declared on a line "uniform TYPE a, b[N];": the name as a whole word after the type */
    size_t len = strlen(name);
    bool found = false;
    for (const char *line = s->shaders; line && *line && !found; line = strchr(line, '\n'), line = line ? line + 1 : NULL) {
        if (strncmp(line, "uniform ", 8))
            continue;
        const char *end = strpbrk(line, ";\n");
        for (const char *p = line; (p = strstr(p, name)) && p < end && !found; p++)
            found = (p[-1] == ' ' || p[-1] == ',') && (p[len] == ';' || p[len] == '[' || p[len] == ',' || p[len] == ' ');
    }
    if (!found) {
        s->missing++;
        print_error("uniform %s is uploaded but no shader declares it\n", name);
    }
}

static void uploaded_uniforms_are_declared(void **st)
{
    (void)st;
    char *shaders = all_shaders();
    strbuf names = {0};
    scene_list(&names, false);
    int scenes = 0;
    for (char *line = strtok(names.data, "\n"); line; line = strtok(NULL, "\n"), scenes++) {
        scene s;
        err_t e;
        if (!scene_load(line, NULL, 0, &s, &e))
            fail_msg("%s", e.msg);
        seen sn = {.shaders = shaders};
        scene_uniforms(&s, &(uniform_sink){check_declared, &sn});
        assert_true(sn.count > 10);
        assert_int_equal(sn.missing, 0);
        scene_free(&s);
    }
    assert_true(scenes >= 7);
    sb_free(&names);
    free(shaders);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(presets_and_preamble_follow_the_table),
        cmocka_unit_test(window_steps_round_trip_and_clamp),
        cmocka_unit_test(every_knob_is_a_scene_key),
        cmocka_unit_test(programs_registry),
        cmocka_unit_test(uploaded_uniforms_are_declared),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
