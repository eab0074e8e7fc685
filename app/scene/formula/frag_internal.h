/* frag_internal — what frag.c, frag_uniform.c and frag_presets.c share (frag.h). Pure C. */
#ifndef FATHOM_FRAG_INTERNAL_H
#define FATHOM_FRAG_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>

#include "scene/formula/formula_types.h"
#include "scene/formula/frag_lex.h"
#include "util.h"

/* A fragment declares no bound: fathom frames it like Fragmentarium's default camera (Eye 10 away,
 * FOV 0.4: ±4 in view) and marches its DE without a bounding sphere (FORMULA_EXACT). */
#define FRAG_BOUND "4"

enum { FRAG_SEEN_MAX = 24 };

typedef struct frag_ctx {
    formula *f;
    err_t *err;
    char root[PATH_MAX_LEN];       /* the fragment's folder (real path): its includes stay inside */
    char include_dir[PATH_MAX_LEN]; /* its collection's Include folder (real path), or "" */
    char chain[1024];              /* " (included from A.frag:3)..." for messages */
    char seen[FRAG_SEEN_MAX][PATH_MAX_LEN];
    int seen_count;
    char group[FORMULA_KEY_MAX];   /* the #group the next parameter is in */
    char comment[FORMULA_TEXT_MAX]; /* the comment line just before: the next parameter's description */
    bool in_vertex, in_preset, has_de, has_renderer;
    bool vertex_init;              /* a #vertex section defined init(): fragVertexInit (frag_vertex.c) */
    strbuf varyings;               /* the names its #vertex sections declared varying */
    size_t statements;             /* in the stranger's files (not fathom's include set) */
    int depth;                     /* of braces, in the file being read */
    strbuf functions, macros;      /* the names the files define at the top level, each followed by '\n' */
} frag_ctx;

/* Reads a fragment file: plain text, at most FRAG_FILE_MAX bytes (shown: its name in messages). */
bool frag_read(const char *path, const char *shown, char **text, err_t *err);
/* Translates the file at path (absolute; `ours`: one of fathom's include set) and its includes. */
bool frag_translate(frag_ctx *x, const char *path, const char *shown, bool ours, int depth);
/* A file a fragment names (an include, a texture): a plain relative name (no '/' first, no '..' part,
 * letters, digits and "_-. /"), in home or the collection's Include folder, whose real path stays inside
 * the fragment's folder or that Include folder; into path (absolute), or false with *why ("no such file"
 * when it is nowhere). */
bool frag_find_file(const frag_ctx *x, const char *rel, const char *home, char *path, size_t n, const char **why);
/* "#TexParameter NAME GL_TEXTURE_... VALUE" (after the word): kept in the formula for the GPU. */
void frag_texparameter(frag_ctx *x, const char *args);
/* Widens each number parameter's range to hold every value a preset of the fragment's text gives it (Syntopia's
 * host takes them as they are). */
void frag_widen_to_presets(const char *text, formula *f);
/* A line of a #vertex section (frag_vertex.c), rewritten in place for the one shader (its varyings globals, its
 * init() fragVertexInit()); true when it is the vertex shader's alone (blanked). */
bool frag_vertex_line(frag_ctx *x, char *line, size_t line_n, char *code, size_t code_n);
/* Whether code (past its blanks) declares again, outside the sections, only varyings a #vertex section made
 * globals or bare uniforms ("uniform int P, Q;") naming its parameters. */
bool frag_repeated_declaration(const frag_ctx *x, const char *code);
/* A "uniform ..." line (code: its code, comments blanked): a parameter and its translated line. */
bool frag_uniform(frag_ctx *x, const char *line, const char *code, const char *shown, int n, strbuf *out);
#endif
