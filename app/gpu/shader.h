/* shader — GLSL assembly and compilation.
 *
 * Shader files hold no #version line. A program's source is
 *     #version 330 core             (430 core for a compute shader)
 *     <preamble: the variant's #defines>
 *     #line 1 0
 *     <the file, with every #include "path" expanded in place>
 * Paths are relative to the shaders root; "virtual" files (generated text, e.g. program.glsl)
 * are looked up first. Includes are a jail, for formulas come from strangers: an #include in a file
 * names a relative .glsl path (letters, digits, '_', '-', '.', '/'; no ".." part), found under the
 * shader root or, for a formula file outside it, under that file's own folder, and a link that leads
 * out of that folder is refused; only fathom's generated text may name a formula file by its absolute
 * path. So no compiler error can quote a line of a file that is not a shader. Each file is included at most once per program. Each file starts, and each
 * expansion is followed, by `#line id·SHADER_LINE_STRIDE+N id` (one id per file; the id rides in the
 * line number too because Mesa drops the source-string number for some errors), so a driver log
 * "0:600012(3): error" becomes "common/march.glsl:12: error". A failed build returns 0 and the translated log; callers keep their
 * last good program.
 */
#ifndef FATHOM_SHADER_H
#define FATHOM_SHADER_H

#include <epoxy/gl.h>
#include <stdbool.h>

#include "util.h"

enum { SHADER_MAX_FILES = 64, SHADER_NAME_MAX = 512, SHADER_LINE_STRIDE = 100000 };

/* What a program takes from files outside the shader tree (a user's formula and its own includes),
 * checked before the driver sees it: Mesa 22.3's compiler dies (SIGSEGV, inside the process) on 10,000
 * dependent statements or an expression of 30,000 terms; 3,000 statements (1.9 s) and 16,000 terms
 * compile. The shipped formulas use at most 55 statements in 7.9 KB. */
enum { SHADER_FOREIGN_BYTES_MAX = 24 * 1024, SHADER_FOREIGN_STATEMENTS_MAX = 2000 };

typedef struct shader_virtual {
    const char *name;
    const char *text;
} shader_virtual;

typedef struct shader_files {
    char names[SHADER_MAX_FILES][SHADER_NAME_MAX]; /* index = #line source-string id */
    int count;
    size_t foreign_bytes, foreign_statements; /* from files outside the shader tree, so far */
} shader_files;

/* Expands `file` into out (appends). Pure but for reading files under root. */
bool shader_expand(const char *root, const char *file, const shader_virtual *virt, int nvirt, strbuf *out,
                   shader_files *files, err_t *err);

/* Rewrites a driver log (Mesa "S:L(C): msg" or NVIDIA "S(L) : msg") to "file:L: msg" lines. */
void shader_translate_log(const char *log, const shader_files *files, strbuf *out);

/* Compiles and links vert + frag with the preamble; 0 and err on failure. */
GLuint shader_build(const char *root, const char *vert, const char *frag, const char *preamble,
                    const shader_virtual *virt, int nvirt, err_t *err);
/* Compiles and links one compute shader (GLSL 4.30: needs GL 4.3) with the preamble; 0 and err on failure. */
GLuint shader_build_compute(const char *root, const char *comp, const char *preamble, const shader_virtual *virt,
                            int nvirt, err_t *err);

#endif
