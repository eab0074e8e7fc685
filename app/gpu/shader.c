#include "gpu/shader.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

static bool expand(const char *root, const char *file, const shader_virtual *virt, int nvirt, strbuf *out,
                   shader_files *files, int depth, const char *from, int from_line, err_t *err)
{
    if (depth > MAX_INCLUDE_DEPTH)
        return err_set(err, "%s:%d: includes nest deeper than %d (a cycle?)", from, from_line, MAX_INCLUDE_DEPTH);
    if (files->count == SHADER_MAX_FILES || strlen(file) >= SHADER_NAME_MAX)
        return err_set(err, "%s:%d: too many shader files or name too long: '%s'", from, from_line, file);
    int id = files->count++;
    snprintf(files->names[id], SHADER_NAME_MAX, "%s", file);

    char *text = NULL;
    const char *src = NULL;
    for (int i = 0; i < nvirt; i++)
        if (!strcmp(virt[i].name, file))
            src = virt[i].text;
    if (!src) {
        char path[PATH_MAX_LEN];
        err_t e;
        if (!util_join(root, file, path, sizeof path) || !util_read_file(path, &text, NULL, &e)) {
            if (from)
                return err_set(err, "%s:%d: cannot include \"%s\": %s", from, from_line, file, e.msg);
            return err_set(err, "shader '%s': %s", file, e.msg);
        }
        src = text;
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
            if (file_id(files, inc) < 0) {
                if (!expand(root, inc, virt, nvirt, out, files, depth + 1, file, line, err)) {
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
    return expand(root, file, virt, nvirt, out, files, 0, NULL, 0, err);
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
    if (!shader_expand(root, file, virt, nvirt, &src, &files, err)) {
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
