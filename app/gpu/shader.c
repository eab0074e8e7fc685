/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include "gpu/shader.h"

#include <ctype.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/formula/frag.h"
#include "scene/formula/glsl_budget.h"

enum { MAX_INCLUDE_DEPTH = 16 };

/* Mesa 22.3 keeps the line of a `#line L S` but reports semantic errors (an undeclared name) with
 * source string 0, so the file id is also carried in the line number: L = id · SHADER_LINE_STRIDE + line.
 * Drivers that honour S (parser errors on Mesa, NVIDIA) and those that do not both map back. */
static int line_mark(int id, int line) { return id * SHADER_LINE_STRIDE + line; }

static int file_id(shader_files *files, const char *name)
{
    for (int i = 0; i < files->count; i++)
        if (!strcmp(files->names[i], name))
            return i;
    return -1;
}

/* Whether real (a resolved path) lies inside the folder dir (resolved too) */
static bool inside(const char *real, const char *dir)
{
    size_t n = strlen(dir);
    return !strncmp(real, dir, n) && (real[n] == '/' || (n == 1 && dir[0] == '/'));
}

/* The jail (shader.h): an #include in a file names a relative .glsl path of plain characters with no
 * ".." part. Empty when it does, else why not. */
static const char *include_refusal(const char *inc)
{
    size_t n = strlen(inc);
    if (inc[0] == '/')
        return "an absolute path";
    if (n < 6 || strcmp(inc + n - 5, ".glsl"))
        return "not a .glsl file";
    for (const char *c = inc; *c; c++)
        if (!isalnum((unsigned char)*c) && !strchr("_-./", *c))
            return "a character other than letters, digits, '_', '-', '.' and '/'";
    for (const char *c = inc; c; c = strchr(c, '/'), c = c ? c + 1 : NULL)
        if (!strncmp(c, "..", 2) && (c[2] == '/' || c[2] == '\0'))
            return "a '..' part";
    return "";
}

/* Resolves include inc of a file whose own folder is home (NULL: a file of the shader tree): under
 * root, else under home; the real path (links resolved) must stay inside the folder it was found in.
 * Into path and *new_home (the folder that file's own includes may also use). */
static bool resolve_include(const char *root, const char *home, const char *inc, char *path, size_t n,
                            char *new_home, size_t hn, const char **why)
{
    const char *dirs[2] = {root, home};
    for (int i = 0; i < 2; i++) {
        char joined[PATH_MAX_LEN], real[PATH_MAX], base[PATH_MAX];
        if (!dirs[i] || !util_join(dirs[i], inc, joined, sizeof joined) || !realpath(joined, real))
            continue;
        if (!realpath(dirs[i], base) || !inside(real, base) || strlen(real) >= n) {
            *why = "it leads out of the folder it is found in";
            return false;
        }
        snprintf(path, n, "%s", real);
        snprintf(new_home, hn, "%s", i == 0 ? "" : home);
        return true;
    }
    *why = "no such file under the shader folder or the formula's own";
    return false;
}

/* Adds a foreign file's text to what the program takes from outside the shader tree; false past the
 * bounds (shader.h) */
static bool foreign_within_bounds(shader_files *files, const char *src, const char *file, err_t *err)
{
    files->foreign_bytes += strlen(src);
    for (const char *c = src; *c; c++)
        files->foreign_statements += *c == ';';
    if (files->foreign_bytes > SHADER_FOREIGN_BYTES_MAX)
        return err_set(err, "%s: a formula (with its own includes) is larger than %d KB: the GL compiler could "
                            "crash on it; shorten it", file, SHADER_FOREIGN_BYTES_MAX / 1024);
    if (files->foreign_statements > SHADER_FOREIGN_STATEMENTS_MAX)
        return err_set(err, "%s: a formula (with its own includes) has more than %d statements: the GL compiler "
                            "could crash on it; shorten it", file, SHADER_FOREIGN_STATEMENTS_MAX);
    return true;
}

/* The text of a file that is not generated: a formula file by its absolute path (only generated text
 * names one: expand checks), an include found by resolve_include, or a top-level file under root.
 * *text is malloc'd; own_home gets the folder its own includes may also use ("" for the tree). */
static bool read_source(const char *root, const char *file, const char *home, const char *from, int from_line,
                        char **text, char own_home[PATH_MAX_LEN], err_t *err)
{
    char path[PATH_MAX_LEN];
    err_t e = {"no such file"};
    bool found;
    if (file[0] == '/') {
        found = snprintf(path, sizeof path, "%s", file) < (int)sizeof path;
        util_dirname(file, own_home, PATH_MAX_LEN);
    } else if (from) {
        const char *why = "";
        found = resolve_include(root, home, file, path, sizeof path, own_home, PATH_MAX_LEN, &why);
        snprintf(e.msg, sizeof e.msg, "%s", why);
    } else {
        found = util_join(root, file, path, sizeof path);
    }
    if (found && util_read_file_max(path, UTIL_SOURCE_FILE_MAX, text, NULL, &e))
        return true;
    if (from)
        return err_set(err, "%s:%d: cannot include \"%s\": %s", from, from_line, file, e.msg);
    return err_set(err, "shader '%s': %s", file, e.msg);
}

static bool expand(const char *root, const char *file, const shader_virtual *virt, int nvirt, strbuf *out,
                   shader_files *files, int depth, const char *from, int from_line, const char *home, err_t *err)
{
    const char *where = from ? from : file; /* the top-level file has no includer */
    if (depth > MAX_INCLUDE_DEPTH)
        return err_set(err, "%s:%d: includes nest deeper than %d (a cycle?)", where, from_line, MAX_INCLUDE_DEPTH);
    if (files->count == SHADER_MAX_FILES || strlen(file) >= SHADER_NAME_MAX)
        return err_set(err, "%s:%d: too many shader files or name too long: '%s'", where, from_line, file);
    int id = files->count++;
    snprintf(files->names[id], SHADER_NAME_MAX, "%s", file);

    char *text = NULL, own_home[PATH_MAX_LEN] = "";
    const char *src = NULL;
    bool generated = false; /* fathom's own text: it may name a formula file by its absolute path */
    for (int i = 0; i < nvirt; i++)
        if (!strcmp(virt[i].name, file))
            src = virt[i].text, generated = true;
    if (!src && file[0] == '/' && (src = frag_text(file))) /* a fragment as fathom translated it (scene/formula/frag.h) */
        generated = true;
    const char *ext = strrchr(file, '.'); /* never the raw file: its annotations are not GLSL */
    if (!src && file[0] == '/' && ext && (!strcmp(ext, ".frag") || !strcmp(ext, ".frag:prelude") ||
                                          !strcmp(ext, ".frag:postlude")))
        return err_set(err, "%s: the fragment's translation is no longer kept: reload the scene (R)", file);
    if (!src && !read_source(root, file, home, from, from_line, &text, own_home, err))
        return false;
    src = src ? src : text;
    if (!strncmp(src, "\xef\xbb\xbf", 3)) /* a UTF-8 byte-order mark: not GLSL (an editor's) */
        src += 3;
    if (own_home[0] && !foreign_within_bounds(files, src, file, err)) {
        free(text);
        return false;
    }
    sb_printf(out, "#line %d %d\n", line_mark(id, 1), id);
    int line = 1;
    for (const char *p = src; *p;) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        const char *q = p;
        while (q < p + n && isspace((unsigned char)*q))
            q++;
        if ((size_t)(p + n - q) > 8 && !strncmp(q, "#include", 8)) {
            const char *a = strchr(q, '"');
            const char *b = a ? strchr(a + 1, '"') : NULL;
            if (!a || !b || b > p + n) {
                free(text);
                return err_set(err, "%s:%d: malformed #include, expected #include \"path\"", file, line);
            }
            char inc[SHADER_NAME_MAX];
            snprintf(inc, sizeof inc, "%.*s", (int)(b - a - 1), a + 1);
            const char *refused = include_refusal(inc);
            if (*refused && !(generated && inc[0] == '/')) {
                free(text);
                return err_set(err, "%s:%d: #include \"%s\" refused: %s (an include names a .glsl file under "
                                    "the shader folder or the formula's own, e.g. \"fractal/common.glsl\")",
                               file, line, inc, refused);
            }
            if (file_id(files, inc) < 0) {
                if (!expand(root, inc, virt, nvirt, out, files, depth + 1, file, line,
                            own_home[0] ? own_home : NULL, err)) {
                    free(text);
                    return false;
                }
                sb_printf(out, "#line %d %d\n", line_mark(id, line + 1), id);
            } else {
                sb_append(out, "\n");
            }
        } else {
            sb_appendn(out, p, n);
            sb_append(out, "\n");
        }
        line++;
        p = eol ? eol + 1 : p + n;
    }
    free(text);
    return true;
}

bool shader_expand(const char *root, const char *file, const shader_virtual *virt, int nvirt, strbuf *out,
                   shader_files *files, err_t *err)
{
    return expand(root, file, virt, nvirt, out, files, 0, NULL, 0, NULL, err);
}

void shader_translate_log(const char *log, const shader_files *files, strbuf *out)
{
    for (const char *p = log; *p;) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(n < sizeof line ? n : sizeof line - 1), p);
        int src, ln, used = 0;
        /* Mesa: "0:12(5): error: ..."  NVIDIA: "0(12) : error C0000: ..." */
        if ((sscanf(line, "%d:%d(%*d):%n", &src, &ln, &used) == 2 && used > 0) ||
            (sscanf(line, "%d(%d) :%n", &src, &ln, &used) == 2 && used > 0)) {
            if (ln >= SHADER_LINE_STRIDE) { /* the file id rides in the line number */
                src = ln / SHADER_LINE_STRIDE;
                ln %= SHADER_LINE_STRIDE;
            }
            const char *name = (src >= 0 && src < files->count) ? files->names[src] : "?";
            const char *msg = line + used;
            while (*msg == ' ')
                msg++;
            sb_printf(out, "%s:%d: %s\n", name, ln, msg);
        } else if (n > 0) {
            sb_printf(out, "%s\n", line);
        }
        p = eol ? eol + 1 : p + n;
    }
}

static GLuint compile(GLenum type, const char *root, const char *file, const char *preamble,
                      const shader_virtual *virt, int nvirt, err_t *err)
{
    strbuf src = {0};
    shader_files files = {0};
    /* compute shaders are GLSL 4.30; the rest keeps the GL 3.3 path */
    sb_printf(&src, "#version %s core\n%s", type == GL_COMPUTE_SHADER ? "430" : "330", preamble ? preamble : "");
    char shown[SHADER_NAME_MAX + 64];
    bool ok_text = shader_expand(root, file, virt, nvirt, &src, &files, err);
    snprintf(shown, sizeof shown, "%s%s", file, files.foreign_bytes ? " with the scene's formula" : "");
    ok_text = ok_text && glsl_budget_check(src.data, shown, NULL, err); /* bounds that see what the compiler sees */
    if (!ok_text) {
        sb_free(&src);
        return 0;
    }
    GLuint sh = glCreateShader(type);
    const char *text = src.data;
    glShaderSource(sh, 1, &text, NULL);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    sb_free(&src);
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
        char *log = util_calloc((size_t)len + 1, 1, "a shader log");
        glGetShaderInfoLog(sh, len, NULL, log);
        strbuf msg = {0};
        shader_translate_log(log, &files, &msg);
        err_set_lines(err, "shader compile error in %s:\n%s", file,
                msg.data ? msg.data : "(no log)");
        sb_free(&msg);
        free(log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

/* Links the compiled shaders (deleting them) into a program; names say which in an error. */
static GLuint link(const GLuint *shaders, int n, const char *names, err_t *err)
{
    GLuint prog = glCreateProgram();
    for (int i = 0; i < n; i++)
        glAttachShader(prog, shaders[i]);
    glLinkProgram(prog);
    for (int i = 0; i < n; i++)
        glDeleteShader(shaders[i]);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {0};
        glGetProgramInfoLog(prog, sizeof log - 1, NULL, log);
        err_set_lines(err, "shader link error (%s): %s", names, log);
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

GLuint shader_build(const char *root, const char *vert, const char *frag, const char *preamble,
                    const shader_virtual *virt, int nvirt, err_t *err)
{
    GLuint sh[2] = {compile(GL_VERTEX_SHADER, root, vert, preamble, virt, nvirt, err), 0};
    if (!sh[0])
        return 0;
    sh[1] = compile(GL_FRAGMENT_SHADER, root, frag, preamble, virt, nvirt, err);
    if (!sh[1]) {
        glDeleteShader(sh[0]);
        return 0;
    }
    char names[2 * SHADER_NAME_MAX];
    snprintf(names, sizeof names, "%s + %s", vert, frag);
    return link(sh, 2, names, err);
}

GLuint shader_build_compute(const char *root, const char *comp, const char *preamble, const shader_virtual *virt,
                            int nvirt, err_t *err)
{
    GLuint cs = compile(GL_COMPUTE_SHADER, root, comp, preamble, virt, nvirt, err);
    return cs ? link(&cs, 1, comp, err) : 0;
}
