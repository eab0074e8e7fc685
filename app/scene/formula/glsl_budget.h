/* glsl_budget — bounds that see what the GL compiler sees. A formula or fragment is a stranger's text,
 * and Mesa 22.3's compiler dies (SIGSEGV, inside the process) or runs for minutes on text that is small
 * on disk: a macro bomb (#define M1 M0 M0, nested: 2^N tokens), a line of 10,000 characters, brackets
 * nested 3,000 deep. So the program's whole source is measured before the driver sees it, with its
 * macros expanded as the GLSL preprocessor expands them (object- and function-like, arguments expanded
 * before substitution, the result rescanned with what follows, a macro not expanded inside itself) under
 * a work budget: the measure stops, and refuses, as soon as the budget is spent, so no text can make it
 * slow. Conditional sections (#if) are measured on both sides (an upper bound). Pure C. */
#ifndef FATHOM_GLSL_BUDGET_H
#define FATHOM_GLSL_BUDGET_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

/* The bounds. The shipped programs' largest (sdf.frag of the Himalaya at final) expands to 22,300
 * tokens, its longest statement 110 tokens, its deepest brackets 8, its longest line 182 bytes (measured
 * 2026-11-28); Mesa compiles 16,000-term expressions and dies at 30,000. */
enum {
    GLSL_TOKENS_MAX = 200000,    /* the whole program, expanded */
    GLSL_STATEMENT_MAX = 20000,  /* tokens between two of ; { } */
    GLSL_DEPTH_MAX = 256,        /* ( [ { open at once */
    GLSL_LINE_MAX = 4096,        /* bytes on one line, as written */
    GLSL_MACRO_DEPTH_MAX = 64    /* macros inside macros */
};

typedef struct glsl_measure {
    size_t tokens, statement_max;
    int depth_max, line_max;
} glsl_measure;

/* Measures source (NUL-terminated); false with a message naming what is over which bound (for file,
 * the name shown) and what to do. m may be NULL. */
bool glsl_budget_check(const char *source, const char *file, glsl_measure *m, err_t *err);

#endif
