/* frag_lex — lines, blanks, numbers and lists of names in a fragment's text (frag_lex.h). */
#include "scene/formula/frag_lex.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/formula/formula_types.h"

/* The next line of *p into line (its \r dropped, cut at n - 1 bytes); false at the end. */
bool frag_next_line(const char **p, char *line, size_t n)
{
    if (!**p)
        return false;
    const char *eol = strchr(*p, '\n');
    size_t len = eol ? (size_t)(eol - *p) : strlen(*p), full = len;
    if (len && (*p)[len - 1] == '\r')
        len--;
    snprintf(line, n, "%.*s", (int)(len < n ? len : n - 1), *p);
    *p += full + (eol ? 1 : 0);
    return true;
}

const char *frag_skip(const char *p)
{
    while (*p == ' ' || *p == '\t' || *p == '\f')
        p++;
    return p;
}

/* Adds name (n bytes) to a list of names once. */
void frag_add_name(strbuf *list, const char *name, size_t n)
{
    char entry[FORMULA_KEY_MAX + 3]; /* "\nNAME\n": a name is cut at FORMULA_KEY_MAX - 1 bytes */
    n = n < FORMULA_KEY_MAX ? n : FORMULA_KEY_MAX - 1;
    snprintf(entry, sizeof entry, "\n%.*s\n", (int)n, name);
    if (!list->data)
        sb_append(list, "\n");
    if (!strstr(list->data, entry))
        sb_append(list, entry + 1);
}

bool frag_numbers(const char **p, float *v, int count)
{
    const char *c = frag_skip(*p);
    bool paren = count > 1 && *c == '(';
    if (paren)
        c++;
    for (int i = 0; i < count; i++) {
        char *end;
        c = frag_skip(c);
        double d = strtod(c, &end);
        if (end == c || !isfinite((float)d))
            return false;
        v[i] = (float)d;
        c = frag_skip(end);
        if (i + 1 < count && *c++ != ',')
            return false;
    }
    if (paren && *c++ != ')')
        return false;
    *p = frag_skip(c);
    return true;
}

/* The value's numbers (a "Locked"/"NotLocked" word after them is the host's lock state). */
int frag_values(const char *v, double *out, int max)
{
    int n = 0;
    for (const char *c = v; n < max;) {
        char *end;
        double d = strtod(c, &end);
        if (end == c || !isfinite(d))
            break;
        out[n++] = d;
        c = frag_skip(end);
        if (*c != ',')
            break;
        c++;
    }
    return n;
}
