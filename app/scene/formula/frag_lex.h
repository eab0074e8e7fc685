/* frag_lex — the reading of a fragment's text that frag.c, frag_uniform.c and frag_presets.c share:
 * lines, blanks, numbers and lists of names (below them all: tests/tree/calls.sh). Pure C. */
#ifndef FATHOM_FRAG_LEX_H
#define FATHOM_FRAG_LEX_H

#include <stdbool.h>
#include <stddef.h>

#include "util.h"

/* The next line of *p (without its \r), cut at n - 1 bytes; false at the end. */
bool frag_next_line(const char **p, char *line, size_t n);
/* p past spaces and tabs */
const char *frag_skip(const char *p);
/* Adds name (n bytes) to a list of names ('\n'-separated) once. */
void frag_add_name(strbuf *list, const char *name, size_t n);
/* The numbers of a value "a, b, c" (a "Locked"/"NotLocked" word after them is the host's lock state), up to
 * max, into out; their count. */
int frag_values(const char *v, double *out, int max);
/* Up to `count` numbers "a, b, c" or, for count > 1, "(a, b, c)" from *p; false unless all are there. */
bool frag_numbers(const char **p, float *v, int count);

#endif
