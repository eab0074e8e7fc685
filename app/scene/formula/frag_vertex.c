/* frag_vertex — a fragment's #vertex sections (frag_internal.h). Fragmentarium compiles them into the vertex
 * shader: what they compute once a vertex (their init(), into varyings) the fragment shader reads. fathom
 * has one shader, so a section's code joins the fragment's: its varyings become globals, its init() becomes
 * fragVertexInit(), which frag/glue.glsl runs once a pixel before the fragment's own init(), and its
 * "#define provides…" hooks stay the vertex shader's (blanked; its other macros are everyone's). The fragment part's own declarations of those varyings, and a
 * bare "uniform int P, Q;" naming parameters a section declared, are the same names again: blanked. */
#include <ctype.h>
#include <stdio.h>
#include <string.h>

#include "scene/formula/frag_internal.h"

#define NAME_CHARS "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"

/* Whether the list (names each followed by '\n') holds the n bytes of name. */
static bool listed(const strbuf *list, const char *name, size_t n)
{
    for (const char *c = list->data; c && *c; c += strcspn(c, "\n") + 1)
        if (strcspn(c, "\n") == n && !strncmp(c, name, n))
            return true;
    return false;
}

/* The names of a declaration's list "TYPE A, B[2], C;" after its first word (the type). */
static void declared_names(const char *p, strbuf *names)
{
    p = frag_skip(p + strspn(p, NAME_CHARS));
    while (*p && *p != ';') {
        size_t n = strspn(p, NAME_CHARS);
        if (!n)
            break;
        frag_add_name(names, p, n);
        p += n;
        p += strcspn(p, ",;");
        if (*p == ',')
            p = frag_skip(p + 1);
    }
}

bool frag_vertex_line(frag_ctx *x, char *line, size_t line_n, char *code, size_t code_n)
{
    const char *c = frag_skip(code), *d = frag_skip(c + 1);
    if (*c == '#' && !strncmp(d, "define", 6) && !strncmp(frag_skip(d + 6), "provides", 8))
        return true; /* the vertex shader's own hook (providesInit: its init(), fragVertexInit here) */
    if (!strncmp(c, "varying", 7) && isspace((unsigned char)c[7])) {
        declared_names(frag_skip(c + 7), &x->varyings);
        char *v = strstr(line, "varying"), *w = strstr(code, "varying"); /* a global now */
        if (v)
            memset(v, ' ', 7);
        if (w)
            memset(w, ' ', 7);
    }
    /* init() is the vertex shader's: fragVertexInit() here */
    for (char *buf[2] = {line, code}, **b = buf; b < buf + 2; b++) {
        size_t size = b == buf ? line_n : code_n;
        for (char *p = strstr(*b, "init"); p; p = strstr(p + 1, "init")) {
            bool word = (p == *b || !strchr(NAME_CHARS, p[-1])) && !strchr(NAME_CHARS, p[4]);
            if (!word || strlen(*b) + 10 >= size)
                continue;
            memmove(p + 14, p + 4, strlen(p + 4) + 1);
            memcpy(p, "fragVertexInit", 14);
            x->vertex_init |= b == buf;
        }
    }
    return false;
}

bool frag_repeated_declaration(const frag_ctx *x, const char *c)
{
    bool varying = !strncmp(c, "varying", 7) && isspace((unsigned char)c[7]);
    bool uniform = !strncmp(c, "uniform", 7) && isspace((unsigned char)c[7]);
    if (!varying && !uniform)
        return false;
    strbuf names = {0};
    declared_names(frag_skip(c + 7), &names);
    const char *semi = strchr(c, ';');
    bool bare = !semi || !*frag_skip(semi + 1); /* no annotation: an annotated one is frag_uniform's to judge */
    bool all = names.data != NULL;
    for (const char *n = names.data; all && n && *n; n += strcspn(n, "\n") + 1) {
        size_t len = strcspn(n, "\n");
        bool known = listed(&x->varyings, n, len);
        for (int i = 0; uniform && !known && i < x->f->param_count; i++)
            known = strlen(x->f->params[i].key) == len && !strncmp(x->f->params[i].key, n, len);
        all = known && (varying || bare);
    }
    sb_free(&names);
    return all;
}
