/* glsl_budget — see glsl_budget.h. The preprocessor's rules: the GLSL 3.30 specification, section 3.3,
 * which defers to C++'s (ISO C99 6.10.3: argument pre-expansion, rescanning, no recursive expansion). */
#include "scene/formula/glsl_budget.h"

#include <ctype.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { WORK_MAX = 4 * GLSL_TOKENS_MAX, PARAMS_MAX = 32, BUCKETS = 4096, SOURCES_MAX = 256 };

typedef struct tok {
    const char *s;
    unsigned len;
    int param; /* in a macro's body: the parameter it names, else -1 */
} tok;

typedef struct macro {
    tok name;
    int nparams; /* -1: object-like */
    tok params[PARAMS_MAX];
    tok *body;
    int nbody, next; /* next: the older macro in the same bucket */
    bool disabled, removed;
} macro;

/* a source of tokens: the text's, a macro's body, a substituted body (owned) */
typedef struct src {
    tok *t;
    size_t n, i;
    int macro; /* disabled while this source is read; -1: none */
    bool owned;
} src;

typedef struct tokens {
    tok *t;
    size_t n, cap;
} tokens;

typedef struct ctx {
    macro *m;
    int nm, cap, head[BUCKETS];
    size_t work;
    const char *file;
    err_t *err;
    bool failed;
    glsl_measure out;
    size_t statement;
    int depth, cond; /* cond: #if sections open around the directive being read */
    int collecting;  /* reading a call's arguments: a directive among them is dropped, as glcpp drops it */
} ctx;

typedef struct stream {
    src stack[SOURCES_MAX];
    int sp;
    const tok *base; /* the text's tokens; a directive is a '#' token marked DIRECTIVE by tokenize */
    size_t nbase, bi;
    bool text; /* the program's own text (its directives apply), not a macro's argument */
} stream;

enum { DIRECTIVE = -2 }; /* tok.param of a '#' that starts a line of the text */

static bool fail(ctx *c, const char *fmt, const char *what, size_t limit)
{
    if (!c->failed)
        err_set(c->err, fmt, c->file, what, limit);
    c->failed = true;
    return false;
}

static bool spend(ctx *c, size_t n)
{
    c->work += n;
    return c->work <= WORK_MAX ||
           fail(c, "%s: %s past %zu tokens: the GL compiler could crash or run for minutes on it; simplify the macros",
                "its macros expand", (size_t)GLSL_TOKENS_MAX);
}

static bool push_tok(ctx *c, tokens *v, tok t)
{
    if (v->n == v->cap) {
        size_t cap = v->cap ? 2 * v->cap : 64;
        tok *n = realloc(v->t, cap * sizeof *n);
        if (!n)
            return fail(c, "%s: %s (%zu)", "out of memory measuring the source", 0);
        v->t = n, v->cap = cap;
    }
    v->t[v->n++] = t;
    return spend(c, 1);
}

/* ---- the text as tokens ------------------------------------------------------------------------------ */

static bool ident_start(char ch) { return isalpha((unsigned char)ch) || ch == '_'; }
static bool ident_char(char ch) { return isalnum((unsigned char)ch) || ch == '_'; }

/* The next token at *p (comments and blanks skipped; a newline stops when in_directive), or false at
 * the end (of the text, or of the directive's line). */
static bool lex(const char **p, bool in_directive, tok *t)
{
    const char *s = *p;
    for (;;) {
        if (s[0] == '\\' && s[1] == '\n')
            s += 2;
        else if (*s == '\n' && in_directive)
            return *p = s, false;
        else if (isspace((unsigned char)*s))
            s++;
        else if (s[0] == '/' && s[1] == '/')
            while (*s && *s != '\n')
                s++;
        else if (s[0] == '/' && s[1] == '*') {
            const char *e = strstr(s + 2, "*/");
            s = e ? e + 2 : s + strlen(s);
        } else
            break;
    }
    if (!*s)
        return *p = s, false;
    const char *b = s;
    if (ident_start(*s))
        while (ident_char(*s))
            s++;
    else if (s[0] == '#' && s[1] == '#')
        s += 2;
    else if (isdigit((unsigned char)*s) || (*s == '.' && isdigit((unsigned char)s[1])))
        while (ident_char(*s) || *s == '.' || ((*s == '+' || *s == '-') && (s[-1] == 'e' || s[-1] == 'E')))
            s++;
    else
        s++;
    *t = (tok){b, (unsigned)(s - b), -1};
    *p = s;
    return true;
}

static bool same(tok a, tok b) { return a.len == b.len && !memcmp(a.s, b.s, a.len); }
static bool is(tok a, const char *word) { return a.len == strlen(word) && !memcmp(a.s, word, a.len); }

static unsigned bucket(tok t)
{
    uint32_t h = 2166136261u;
    for (unsigned i = 0; i < t.len; i++)
        h = (h ^ (unsigned char)t.s[i]) * 16777619u;
    return h % BUCKETS;
}

/* The macro named t, or -1; each step along a bucket's chain is work (names made to share one bucket
 * cannot make the measure slow). */
static int lookup(ctx *c, tok t)
{
    if (!ident_start(t.s[0]))
        return -1;
    for (int i = c->head[bucket(t)]; i >= 0 && spend(c, 1); i = c->m[i].next)
        if (same(c->m[i].name, t))
            return c->m[i].removed ? -1 : i;
    return -1;
}

/* "#define NAME[(PARAMS)] BODY" or "#undef NAME" at p (after the '#'); other directives are ignored. */
static bool directive(ctx *c, const char *p)
{
    tok kw, name;
    if (!lex(&p, true, &kw))
        return true;
    if (is(kw, "if") || is(kw, "ifdef") || is(kw, "ifndef"))
        c->cond++;
    if (is(kw, "endif") && c->cond > 0)
        c->cond--;
    if (!(is(kw, "define") || is(kw, "undef")) || !lex(&p, true, &name) || !ident_start(name.s[0]))
        return true;
    /* the measure does not evaluate #if: inside one, a definition never shrinks what a name expands to
     * (an #undef or a redefinition there is passed over), so both sides count at their largest */
    int known = lookup(c, name);
    if (is(kw, "undef")) {
        if (known >= 0 && c->cond == 0)
            c->m[known].removed = true;
        return true;
    }
    if (known >= 0 && c->cond > 0)
        return true;
    if (c->nm == c->cap) {
        int cap = c->cap ? 2 * c->cap : 256;
        macro *n = realloc(c->m, (size_t)cap * sizeof *n);
        if (!n)
            return fail(c, "%s: %s (%zu)", "out of memory measuring the source", 0);
        c->m = n, c->cap = cap;
    }
    macro *m = &c->m[c->nm];
    *m = (macro){.name = name, .nparams = -1};
    if (*p == '(') { /* a function-like macro: '(' right after the name */
        p++;
        m->nparams = 0;
        tok t;
        while (lex(&p, true, &t) && !is(t, ")"))
            if (!is(t, ",") && m->nparams++ < PARAMS_MAX)
                m->params[m->nparams - 1] = t;
        if (m->nparams > PARAMS_MAX)
            return fail(c, "%s: %s more than %zu parameters: simplify it", "a macro has", (size_t)PARAMS_MAX);
    }
    tokens body = {0};
    for (tok t; lex(&p, true, &t);) {
        if (is(t, "##")) {
            free(body.t);
            return fail(c, "%s: %s (%zu): write the names out", "a macro pastes tokens with ##", 0);
        }
        for (int k = 0; k < m->nparams; k++)
            if (same(t, m->params[k]))
                t.param = k;
        if (!push_tok(c, &body, t)) {
            free(body.t);
            return false;
        }
    }
    m->body = body.t, m->nbody = (int)body.n;
    unsigned b = bucket(name);
    m->next = c->head[b];
    c->head[b] = c->nm++;
    return true;
}

/* ---- expansion ---------------------------------------------------------------------------------------- */

static void pop(ctx *c, stream *st)
{
    src *s = &st->stack[--st->sp];
    if (s->macro >= 0)
        c->m[s->macro].disabled = false;
    if (s->owned)
        free(s->t);
}

static bool next(ctx *c, stream *st, tok *t)
{
    while (st->sp > 0) {
        src *s = &st->stack[st->sp - 1];
        if (s->i < s->n)
            return *t = s->t[s->i++], true;
        pop(c, st);
    }
    while (st->bi < st->nbase) {
        tok b = st->base[st->bi++];
        if (b.param != DIRECTIVE)
            return *t = b, true;
        if (st->text && !c->collecting && !directive(c, b.s + 1))
            return false;
    }
    return false;
}

/* Is the next token '(' (looking past sources that are used up, without leaving them)? */
static bool next_is_paren(const stream *st)
{
    for (int k = st->sp - 1; k >= 0; k--)
        if (st->stack[k].i < st->stack[k].n)
            return is(st->stack[k].t[st->stack[k].i], "(");
    for (size_t i = st->bi; i < st->nbase; i++)
        if (st->base[i].param != DIRECTIVE)
            return is(st->base[i], "(");
    return false;
}

static bool push_src(ctx *c, stream *st, tok *t, size_t n, int m, bool owned)
{
    if (st->sp == SOURCES_MAX) {
        if (owned)
            free(t);
        return fail(c, "%s: %s deeper than %zu: simplify the macros", "macros nest", (size_t)SOURCES_MAX);
    }
    st->stack[st->sp++] = (src){t, n, 0, m, owned};
    if (m >= 0)
        c->m[m].disabled = true;
    return spend(c, 1);
}

typedef bool (*sink)(ctx *c, void *to, tok t);
static bool expand(ctx *c, stream *st, sink emit, void *to, int level);

static bool materialize(ctx *c, void *to, tok t) { return push_tok(c, to, t); }

/* A function-like macro's call, its '(' next: the arguments read, each expanded alone, substituted. */
static bool call(ctx *c, stream *st, int mi, int level)
{
    tokens args[PARAMS_MAX] = {{0}}, sub = {0};
    tok t;
    next(c, st, &t); /* the '(' */
    int depth = 1, k = 0;
    bool ok = true;
    c->collecting++;
    while (ok && depth > 0 && next(c, st, &t)) {
        depth += is(t, "(") - is(t, ")");
        if (depth == 0)
            break;
        if (depth == 1 && is(t, ","))
            k += k < PARAMS_MAX - 1;
        else
            ok = push_tok(c, &args[k], t);
    }
    c->collecting--;
    tokens expanded[PARAMS_MAX] = {{0}};
    for (int a = 0; ok && a < c->m[mi].nparams && a < PARAMS_MAX; a++) {
        stream inner = {.base = args[a].t, .nbase = args[a].n};
        ok = expand(c, &inner, materialize, &expanded[a], level + 1);
        while (inner.sp)
            pop(c, &inner);
    }
    const macro *m = &c->m[mi]; /* read after the arguments: their expansion defines nothing */
    for (int i = 0; ok && i < m->nbody; i++) {
        const tok *b = &m->body[i];
        if (b->param < 0)
            ok = push_tok(c, &sub, *b);
        for (size_t j = 0; ok && b->param >= 0 && j < expanded[b->param].n; j++)
            ok = push_tok(c, &sub, expanded[b->param].t[j]);
    }
    for (int a = 0; a < PARAMS_MAX; a++)
        free(args[a].t), free(expanded[a].t);
    if (!ok) {
        free(sub.t);
        return false;
    }
    return push_src(c, st, sub.t, sub.n, mi, true);
}

static bool expand(ctx *c, stream *st, sink emit, void *to, int level)
{
    if (level > GLSL_MACRO_DEPTH_MAX)
        return fail(c, "%s: %s deeper than %zu: simplify the macros", "macro arguments nest",
                    (size_t)GLSL_MACRO_DEPTH_MAX);
    for (tok t; !c->failed && next(c, st, &t);) {
        int mi = lookup(c, t);
        bool ok;
        if (mi < 0 || c->m[mi].disabled)
            ok = emit(c, to, t);
        else if (c->m[mi].nparams < 0)
            ok = push_src(c, st, c->m[mi].body, (size_t)c->m[mi].nbody, mi, false);
        else if (next_is_paren(st))
            ok = call(c, st, mi, level);
        else
            ok = emit(c, to, t);
        if (!ok)
            return false;
    }
    return !c->failed;
}

/* The compiler's view, token by token: how many, brackets open, tokens since a statement began. */
static bool measure(ctx *c, void *to, tok t)
{
    (void)to;
    glsl_measure *o = &c->out;
    o->tokens++;
    c->statement++;
    if (is(t, "(") || is(t, "[") || is(t, "{"))
        c->depth++;
    if ((is(t, ")") || is(t, "]") || is(t, "}")) && c->depth > 0)
        c->depth--;
    if (is(t, ";") || is(t, "{") || is(t, "}"))
        c->statement = 0;
    o->depth_max = c->depth > o->depth_max ? c->depth : o->depth_max;
    o->statement_max = c->statement > o->statement_max ? c->statement : o->statement_max;
    if (o->tokens > GLSL_TOKENS_MAX)
        return fail(c, "%s: %s past %zu tokens: the GL compiler could crash or run for minutes on it; shorten it",
                    "the program expands", (size_t)GLSL_TOKENS_MAX);
    if (c->depth > GLSL_DEPTH_MAX)
        return fail(c, "%s: %s deeper than %zu: the GL compiler could crash on it; flatten them", "brackets nest",
                    (size_t)GLSL_DEPTH_MAX);
    if (c->statement > GLSL_STATEMENT_MAX)
        return fail(c, "%s: %s %zu tokens: the GL compiler could crash on it; split the expression",
                    "a statement (its macros expanded) is longer than", (size_t)GLSL_STATEMENT_MAX);
    return spend(c, 1);
}

/* The text's tokens, a directive kept as one token at its '#' (read when the stream passes it). */
static bool tokenize(ctx *c, const char *source, tokens *v)
{
    const char *p = source, *prev_end = source;
    tok t;
    while (lex(&p, false, &t)) {
        bool line_start = prev_end == source || memchr(prev_end, '\n', (size_t)(t.s - prev_end)) != NULL;
        if (is(t, "##"))
            return fail(c, "%s: %s (%zu): write the names out", "the text pastes tokens with ##", 0);
        bool directive_start = is(t, "#") && line_start;
        if (directive_start)
            t.param = DIRECTIVE;
        if (!push_tok(c, v, t))
            return false;
        if (directive_start) /* the directive's line is read as the stream reaches it */
            for (tok skip; lex(&p, true, &skip);)
                ;
        prev_end = p;
    }
    return true;
}

/* The text with every line continuation (a '\\' before a newline) spliced out, as the preprocessor does
 * before anything else: a name or a directive cut by one is read whole. */
static char *spliced(const char *source)
{
    size_t n = strlen(source), k = 0;
    char *out = malloc(n + 1);
    for (size_t i = 0; out && i < n; i++) {
        if (source[i] == '\\' && source[i + 1] == '\n')
            i++;
        else if (source[i] == '\\' && source[i + 1] == '\r' && source[i + 2] == '\n')
            i += 2;
        else
            out[k++] = source[i];
    }
    if (out)
        out[k] = '\0';
    return out;
}

bool glsl_budget_check(const char *original, const char *file, glsl_measure *m, err_t *err)
{
    ctx *c = calloc(1, sizeof *c);
    char *source = c ? spliced(original) : NULL;
    if (!source) {
        free(c);
        return err_set(err, "%s: out of memory measuring the source", file);
    }
    memset(c->head, -1, sizeof c->head);
    c->file = file, c->err = err;
    for (const char *line = source; *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        c->out.line_max = (int)len > c->out.line_max ? (int)len : c->out.line_max;
        if (len > GLSL_LINE_MAX) {
            fail(c, "%s: %s longer than %zu bytes: the GL compiler could crash on it; break it up", "a line is",
                 (size_t)GLSL_LINE_MAX);
            break;
        }
        line = end ? end + 1 : line + len;
    }
    tokens text = {0};
    stream *st = calloc(1, sizeof *st);
    bool ok = !c->failed && st && tokenize(c, source, &text);
    if (ok) {
        c->work = 0; /* the text itself is not the macros' work */
        *st = (stream){.base = text.t, .nbase = text.n, .text = true};
        ok = expand(c, st, measure, NULL, 0);
    }
    while (st && st->sp)
        pop(c, st);
    if (m)
        *m = c->out;
    for (int i = 0; i < c->nm; i++)
        free(c->m[i].body);
    free(c->m);
    free(text.t);
    free(st);
    free(source);
    ok = ok && !c->failed;
    free(c);
    return ok;
}
