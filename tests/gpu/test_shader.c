/* Shader assembly without GL: #include expansion with #line, and driver logs mapped back to files. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"

#include "gpu/shader.h"

static char root[64];

static void put(const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", root, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int setup(void **st)
{
    (void)st;
    strcpy(root, "/tmp/fathom-shader-XXXXXX");
    if (!mkdtemp(root))
        return -1;
    char dir[128];
    snprintf(dir, sizeof dir, "%s/common", root);
    mkdir(dir, 0755);
    put("main.frag", "// line 1\n#include \"common/a.glsl\"\nfloat x = A;\n#include \"gen.glsl\"\n#include \"common/a.glsl\"\nvoid main() {}\n");
    put("common/a.glsl", "#define A 1.0\n#include \"common/b.glsl\"\nfloat a = B;\n");
    put("common/b.glsl", "#define B 2.0\n");
    put("broken.frag", "#include \"common/missing.glsl\"\n");
    put("bad_syntax.frag", "\n\n  #include common/a.glsl\n");
    return 0;
}

static int teardown(void **st)
{
    (void)st;
    return remove_tree(root);
}

static void expands_with_line_directives(void **st)
{
    (void)st;
    strbuf out = {0};
    shader_files files = {0};
    shader_virtual virt[] = {{"gen.glsl", "float g = 3.0;\n"}};
    err_t e;
    if (!shader_expand(root, "main.frag", virt, 1, &out, &files, &e))
        fail_msg("%s", e.msg);
    static const char want[] =
        "#line 1 0\n"
        "// line 1\n"
        "#line 100001 1\n"
        "#define A 1.0\n"
        "#line 200001 2\n"
        "#define B 2.0\n"
        "#line 100003 1\n"
        "float a = B;\n"
        "#line 3 0\n"
        "float x = A;\n"
        "#line 300001 3\n"
        "float g = 3.0;\n"
        "#line 5 0\n"
        "\n" /* the second include of common/a.glsl: already in, so an empty line keeps numbering */
        "void main() {}\n";
    assert_string_equal(out.data, want);
    assert_int_equal(files.count, 4);
    assert_string_equal(files.names[0], "main.frag");
    assert_string_equal(files.names[1], "common/a.glsl");
    assert_string_equal(files.names[2], "common/b.glsl");
    assert_string_equal(files.names[3], "gen.glsl");
    sb_free(&out);
}

/* Expanding `file` fails with a message holding `want`. */
static void refused(const char *file, const char *want)
{
    strbuf out = {0};
    shader_files files = {0};
    err_t e;
    assert_false(shader_expand(root, file, NULL, 0, &out, &files, &e));
    if (!strstr(e.msg, want))
        fail_msg("%s: got '%s', expected '%s'", file, e.msg, want);
    sb_free(&out);
}

static void include_errors_name_file_and_line(void **st)
{
    (void)st;
    refused("broken.frag", "broken.frag:1: cannot include \"common/missing.glsl\"");
    refused("bad_syntax.frag", "bad_syntax.frag:3: malformed #include");
    refused("nope.frag", "nope.frag");
}

/* The include jail's two rules each hold alone (issue 58 item 17: dropping either survived): a link to a folder
 * beside the root whose name only starts like the root's (ROOT + "x") leads out, though a bare prefix test
 * passes it; a ".." part is refused as such, even where it would resolve inside. */
static void include_jail_rules(void **st)
{
    (void)st;
    char sibling[128], cmd[1024];
    snprintf(sibling, sizeof sibling, "%sx", root);
    snprintf(cmd, sizeof cmd, "mkdir -p '%s' && echo 'float evil;' > '%s/evil.glsl' && ln -sf '%s/evil.glsl' '%s/common/sib.glsl'",
             sibling, sibling, sibling, root);
    assert_int_equal(system(cmd), 0);
    put("sib.frag", "#include \"common/sib.glsl\"\nvoid main() {}\n");
    put("dots.frag", "#include \"common/../common/b.glsl\"\nvoid main() {}\n");
    refused("sib.frag", "it leads out of the folder it is found in");
    refused("dots.frag", "a '..' part");
    snprintf(cmd, sizeof cmd, "rm -rf '%s' '%s/common/sib.glsl'", sibling, root);
    assert_int_equal(system(cmd), 0);
}

static void translates_driver_logs(void **st)
{
    (void)st;
    shader_files files = {.count = 2};
    strcpy(files.names[0], "csg.frag");
    strcpy(files.names[1], "common/march.glsl");
    strbuf out = {0};
    shader_translate_log("1:12(5): error: `foo' undeclared\n0:3(1): warning: unused\n", &files, &out);
    assert_string_equal(out.data, "common/march.glsl:12: error: `foo' undeclared\ncsg.frag:3: warning: unused\n");
    sb_free(&out);
    shader_translate_log("1(40) : error C1008: undefined variable \"foo\"\nplain line", &files, &out);
    assert_string_equal(out.data, "common/march.glsl:40: error C1008: undefined variable \"foo\"\nplain line\n");
    sb_free(&out);
    /* Mesa's semantic errors report source 0: the file id in the line number still finds the file */
    shader_translate_log("0:100077(19): error: `undeclared_thing' undeclared\n", &files, &out);
    assert_string_equal(out.data, "common/march.glsl:77: error: `undeclared_thing' undeclared\n");
    sb_free(&out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(expands_with_line_directives),
        cmocka_unit_test(include_errors_name_file_and_line),
        cmocka_unit_test(include_jail_rules),
        cmocka_unit_test(translates_driver_logs),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
