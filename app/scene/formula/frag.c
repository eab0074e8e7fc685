/* frag — a Fragmentarium fragment read as data and translated line for line (frag.h). */
/* realpath() is XSI */
#define _XOPEN_SOURCE 700
#include "scene/formula/frag.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "scene/formula/frag_internal.h"

/* A fragment file (and each of its own includes) is read up to FRAG_FILE_MAX bytes; what a program
 * takes from a stranger's files is bounded like a formula's (gpu/shader.h: Mesa's compiler dies on
 * ~10,000 dependent statements; 2,000 compile), the include set's files aside. */
enum { FRAG_FILE_MAX = 512 * 1024, FRAG_STATEMENTS_MAX = 2000, FRAG_DEPTH_MAX = 8, FRAG_TABLE_MAX = 48 };

/* Fathom's compatible include set: the name a fragment includes -> fathom's file under shaders/frag/.
 * Every DE renderer of the public collections maps to the one DE renderer contract; `far` is the
 * renderer's MaxDistance (rays past it are background: DE-Raytracer.frag's trace(); Syntopia's
 * DE-Raytracer and DE-RaytracerX 100000, FragM's DE-Kn2 family a slider at 20, the others 100). Every one
 * of them has Detail -2.3, FudgeFactor 1 and MaxRaySteps 56 by default (frag_presets.c). `light`: how the
 * renderer lights (its lighting(), read from its source; shaders/frag/look.glsl), which makes its own look a
 * fragment's default: DE-Raytracer's (FRAG_LIGHT_DE), or Fast-Raytracer's and DE-Raytracer 0.9.1's (Phong's
 * highlight, the light toward -SpotLightDir; 0.9.1 with shadows). The others light otherwise (Soft-
 * Raytracer's point light, IBL's image, 0.9.10's and the Slicer's own spot, the DE-Kn renderers' lights and
 * clouds, the Sky path tracer) and their fragments start in fathom's look. */
static const struct { const char *name, *file; float far; frag_light light; } COMPAT[] = {
    {"MathUtils.frag", "math_utils.frag", 0, FRAG_LIGHT_NONE},
    {"Complex.frag", "complex.frag", 0, FRAG_LIGHT_NONE},
    {"DE-Raytracer.frag", "raytracer.frag", 100000, FRAG_LIGHT_DE},
    {"DE-Raytracer-v0.9.1.frag", "raytracer_v091.frag", 100, FRAG_LIGHT_PHONG_SHADOWS},
    {"DE-Raytracer-Slicer.frag", "raytracer_slicer.frag", 100, FRAG_LIGHT_NONE},
    {"De-Raytracer-Slicer.frag", "raytracer_slicer.frag", 100, FRAG_LIGHT_NONE},
    {"DE-Raytracer-v0.9.10.frag", "raytracer.frag", 100, FRAG_LIGHT_NONE},
    {"DE-RaytracerX.frag", "raytracer.frag", 100000, FRAG_LIGHT_DE},
    {"Fast-Raytracer.frag", "raytracer.frag", 100, FRAG_LIGHT_PHONG},
    {"Fast-Raytracerexp.frag", "raytracer.frag", 100, FRAG_LIGHT_PHONG},
    {"Fast-Raytracer-with-Palette.frag", "raytracer.frag", 100, FRAG_LIGHT_PHONG},
    {"Soft-Raytracer.frag", "raytracer.frag", 100, FRAG_LIGHT_NONE},
    {"Sky-Pathtracer.frag", "raytracer.frag", 100, FRAG_LIGHT_NONE},
    {"DE-Kn2.frag", "raytracer.frag", 20, FRAG_LIGHT_NONE},
    {"DE-Kn2cr11.frag", "raytracer.frag", 20, FRAG_LIGHT_NONE},
    {"DE-Kn2exp.frag", "raytracer.frag", 20, FRAG_LIGHT_NONE},
    {"DE-Kn9.frag", "raytracer.frag", 20, FRAG_LIGHT_NONE},
    {"DE-PK-1.1.9.frag", "raytracer.frag", 20, FRAG_LIGHT_NONE},
    {"DE-Kn2ColorandHeightmap.frag", "raytracer.frag", 20, FRAG_LIGHT_NONE},
    {"IBL-Raytracer.frag", "raytracer.frag", 100, FRAG_LIGHT_NONE},
    {"QuilezLib.frag", "quilez.frag", 0, FRAG_LIGHT_NONE},
    {"Classic-Noise.frag", "classic_noise.frag", 0, FRAG_LIGHT_NONE},
};

/* The macros Fragmentarium's includes give every fragment (3D.frag's PI, MathUtils' FLT_MAX): defined
 * before the fragment (its prelude) unless it defines them itself (GLSL refuses a different redefinition). */
static const char *const HOST_MACROS[][2] = {
    {"PI", "3.14159265358979323846264"}, {"FLT_MAX", "3.402823466e+38"}, {"FLT_MIN", "1.175494351e-38"}};

/* Includes that mark a fragment fathom does not open, and why. */
static const struct { const char *name, *why; } REFUSED[] = {
    {"2D.frag", "a 2D fragment"},
    {"2D-HP.frag", "a 2D fragment"},
    {"2DJulia.frag", "a 2D fragment"},
    {"Progressive2D.frag", "a 2D fragment"},
    {"Progressive2D-4.frag", "a 2D fragment"},
    {"Progressive2DJulia.frag", "a 2D fragment"},
    {"Progressive2DColoring.frag", "a 2D fragment"},
    {"Brute-Raytracer.frag", "a Brute-Raytracer fragment: it tests inside(), it has no distance estimate"},
    {"Brute-RaytracerExp.frag", "a Brute-Raytracer fragment: it tests inside(), it has no distance estimate"},
    {"Brute3D.frag", "a Brute-Raytracer fragment: it tests inside(), it has no distance estimate"},
    {"3D.frag", "a fragment on 3D.frag alone: it brings its own renderer (color())"},
    {"3DKn-1.0.1.frag", "a fragment on 3D.frag alone: it brings its own renderer (color())"},
};

/* ---- the translations, kept for the shader compiler (frag_text) ------------------------------- */

static struct {
    char path[FRAG_TABLE_MAX][PATH_MAX_LEN];
    char *text[FRAG_TABLE_MAX];
    unsigned long long digest[FRAG_TABLE_MAX]; /* a fragment's: its text and its includes' (frag_digest) */
    int count;
} table;

/* Keeps a translation as the newest entry (a file translated again moves up: the oldest entries go
 * first, never one of the fragment being translated: its files are at most FRAG_SEEN_MAX + 2). */
static void keep(const char *path, char *text)
{
    for (int i = 0; i < table.count; i++)
        if (!strcmp(table.path[i], path)) {
            free(table.text[i]);
            memmove(&table.path[i], &table.path[i + 1], sizeof table.path[0] * (size_t)(table.count - i - 1));
            memmove(&table.text[i], &table.text[i + 1], sizeof table.text[0] * (size_t)(table.count - i - 1));
            memmove(&table.digest[i], &table.digest[i + 1], sizeof table.digest[0] * (size_t)(table.count - i - 1));
            table.count--;
            break;
        }
    if (table.count == FRAG_TABLE_MAX) { /* the oldest goes */
        free(table.text[0]);
        memmove(&table.path[0], &table.path[1], sizeof table.path[0] * (FRAG_TABLE_MAX - 1));
        memmove(&table.text[0], &table.text[1], sizeof table.text[0] * (FRAG_TABLE_MAX - 1));
        memmove(&table.digest[0], &table.digest[1], sizeof table.digest[0] * (FRAG_TABLE_MAX - 1));
        table.count--;
    }
    snprintf(table.path[table.count], PATH_MAX_LEN, "%s", path);
    table.digest[table.count] = 0;
    table.text[table.count++] = text;
}

static int entry(const char *path)
{
    for (int i = 0; i < table.count; i++)
        if (!strcmp(table.path[i], path))
            return i;
    return -1;
}

unsigned long long frag_digest(const char *path)
{
    int i = entry(path);
    return i < 0 ? 0 : table.digest[i];
}

/* PATH:prelude renames the fragment's functions while it compiles (#define NAME frag_NAME);
 * PATH:postlude takes the renames and the fragment's own macros (#define PI) away again after the glue,
 * before fathom's code goes on (its brdf.glsl has a const PI). */
static void keep_wrappers(const frag_ctx *x, const char *path)
{
    strbuf pre = {0}, post = {0};
    sb_append(&pre, "// the fragment's names, renamed while it compiles, and the host's macros (app/scene/formula/frag.c)\n");
    sb_append(&post, "// the fragment's renames and macros, undefined (app/scene/formula/frag.c)\n");
    for (size_t i = 0; i < sizeof HOST_MACROS / sizeof *HOST_MACROS; i++) {
        char entry[64];
        snprintf(entry, sizeof entry, "\n%s\n", HOST_MACROS[i][0]);
        if (!x->macros.data || !strstr(x->macros.data, entry))
            sb_printf(&pre, "#define %s %s\n", HOST_MACROS[i][0], HOST_MACROS[i][1]),
                sb_printf(&post, "#undef %s\n", HOST_MACROS[i][0]);
    }
    for (const char *c = x->functions.data; c && *c; c += strcspn(c, "\n"), c += *c == '\n') {
        int n = (int)strcspn(c, "\n");
        if (n)
            sb_printf(&pre, "#define %.*s frag_%.*s\n", n, c, n, c), sb_printf(&post, "#undef %.*s\n", n, c);
    }
    for (const char *c = x->macros.data; c && *c; c += strcspn(c, "\n"), c += *c == '\n')
        if (strcspn(c, "\n"))
            sb_printf(&post, "#undef %.*s\n", (int)strcspn(c, "\n"), c);
    char name[PATH_MAX_LEN + 16];
    snprintf(name, sizeof name, "%s:prelude", path);
    keep(name, pre.data);
    snprintf(name, sizeof name, "%s:postlude", path);
    keep(name, post.data);
}

/* FNV-1a 64 over the texts of the files a load translated, into the fragment's entry. */
static void digest(const frag_ctx *x, const char *path)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (int k = 0; k < x->seen_count; k++)
        for (const char *c = frag_text(x->seen[k]); c && *c; c++)
            h = (h ^ (unsigned char)*c) * 0x100000001b3ull;
    int i = entry(path);
    if (i >= 0)
        table.digest[i] = h;
}

const char *frag_text(const char *path)
{
    int i = entry(path);
    return i < 0 ? NULL : table.text[i];
}

bool frag_is_fragment(const char *path)
{
    size_t n = strlen(path);
    return n > 5 && !strcmp(path + n - 5, ".frag");
}

/* ---- reading a file ------------------------------------------------------------------------------ */

bool frag_read(const char *path, const char *shown, char **text, err_t *err)
{
    size_t len = 0;
    if (!util_read_file_max(path, FRAG_FILE_MAX, text, &len, err))
        return err_set(err, "%s: %s", shown, err->msg);
    int line = 1;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)(*text)[i];
        line += c == '\n';
        if ((c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f') || c == 0x7f) {
            free(*text);
            return err_set(err, "%s:%d: a control character (0x%02x): a fragment is plain text", shown, line, c);
        }
    }
    return true;
}

/* The code of a line: comments blanked (block comments carry over lines through *in_comment). */
static void code_of(const char *line, bool *in_comment, char *code, size_t n)
{
    size_t k = 0;
    for (const char *c = line; *c && k + 1 < n; c++) {
        if (*in_comment) {
            if (c[0] == '*' && c[1] == '/')
                *in_comment = false, c++;
            code[k++] = ' ';
        } else if (c[0] == '/' && c[1] == '*') {
            *in_comment = true, c++;
            code[k++] = ' ';
        } else if (c[0] == '/' && c[1] == '/') {
            break;
        } else {
            code[k++] = *c;
        }
    }
    code[k] = '\0';
}

/* ---- includes -------------------------------------------------------------------------------------- */

/* Resolves include `inc` of the file in folder `home` into path (absolute): fathom's set, else a plain
 * relative name under home whose real path stays inside the fragment's folder. */
static bool resolve(frag_ctx *x, const char *inc, const char *home, char *path, size_t n, bool *ours,
                    const char **why)
{
    for (size_t i = 0; i < sizeof REFUSED / sizeof *REFUSED; i++)
        if (!strcmp(inc, REFUSED[i].name))
            return *why = REFUSED[i].why, false;
    *ours = false;
    for (size_t i = 0; i < sizeof COMPAT / sizeof *COMPAT; i++)
        if (!strcasecmp(inc, COMPAT[i].name)) { /* Fragmentarium on Windows reads "De-Raytracer.frag" too */
            *ours = true;
            if (COMPAT[i].far > 0)
                x->f->frag_max_distance = COMPAT[i].far, x->f->frag_light = COMPAT[i].light;
            if (snprintf(path, n, "%s/shaders/frag/%s", util_data_dir(), COMPAT[i].file) >= (int)n)
                return *why = "the path is too long", false;
            char real[PATH_MAX];
            if (!realpath(path, real) || strlen(real) >= n)
                return *why = "fathom's include set is missing from its data folder", false;
            memcpy(path, real, strlen(real) + 1);
            return true;
        }
    size_t len = strlen(inc);
    if (inc[0] != '/' && (len < 6 || strcmp(inc + len - 5, ".frag"))) /* never a token file's lines in an error */
        return *why = "not a .frag file", false;
    if (frag_find_file(x, inc, home, path, n, why))
        return true;
    if (strcmp(*why, "no such file"))
        return false;
    return *why = "no such file in the fragment's folder or its collection's Include folder, and not one of "
                  "fathom's include set (MathUtils.frag, Complex.frag, QuilezLib.frag, Classic-Noise.frag, "
                  "DE-Raytracer.frag and the other DE renderers)", false;
}

static bool is_dir(const char *path)
{
    struct stat st;
    return !stat(path, &st) && S_ISDIR(st.st_mode);
}

/* The collection's Include folder (Fragmentarium's include path: Examples/Include beside the group
 * folders, Examples/GROUP/X.frag): a folder named Include in the fragment's folder or the one above it,
 * into x->include_dir (real path), or "". Higher up is a stranger's folder, not the collection's. */
static void include_dir(frag_ctx *x)
{
    char dir[PATH_MAX_LEN], probe[PATH_MAX_LEN], real[PATH_MAX];
    struct stat own, st;
    snprintf(dir, sizeof dir, "%s", x->root);
    if (stat(dir, &own) != 0)
        return;
    for (int up = 0; up < 2; up++) {
        /* the folder itself, not a link to one elsewhere (a planted Include -> /etc), and the fragment's
         * owner's, not writable by everyone (planted by another user on a shared machine) */
        if (util_join(dir, "Include", probe, sizeof probe) && realpath(probe, real) && strlen(real) < PATH_MAX_LEN &&
            !strcmp(real, probe) && is_dir(real) && stat(real, &st) == 0 && st.st_uid == own.st_uid &&
            !(st.st_mode & S_IWOTH)) {
            snprintf(x->include_dir, sizeof x->include_dir, "%s", real);
            return;
        }
        char parent[PATH_MAX_LEN];
        if (!util_dirname(dir, parent, sizeof parent) || !strcmp(parent, dir))
            return;
        memcpy(dir, parent, sizeof dir);
    }
}

/* Whether the collection is Syntopia's Fragmentarium's, not FragM's: its own DE-Raytracer takes the camera light
 * away in shadow (its lighting(): "ambient = mix(ambient,0.0,HardShadow*shadowStrength);"; FragM's has the
 * line commented out: shaders/frag/look.glsl). Syntopia's host also takes a preset's value past a slider's range
 * as it is (its ComboSlider keeps the value it was given; FragM's spin box clamps it): frag_widen_to_presets.
 * Where no collection says, FragM's ways. */
static bool syntopia_collection(const frag_ctx *x)
{
    static const char LINE[] = "ambient = mix(ambient,0.0,HardShadow*shadowStrength)";
    char path[PATH_MAX_LEN], real[PATH_MAX], *text;
    err_t e;
    size_t r = strlen(x->include_dir);
    if (!r || !util_join(x->include_dir, "DE-Raytracer.frag", path, sizeof path) || !realpath(path, real) ||
        strncmp(real, x->include_dir, r) || real[r] != '/' || !frag_read(real, real, &text, &e))
        return false;
    bool yes = false;
    for (const char *c = strstr(text, LINE); c && !yes; c = strstr(c + 1, LINE)) {
        const char *start = c;
        while (start > text && start[-1] != '\n')
            start--;
        yes = strspn(start, " \t") == (size_t)(c - start); /* not commented out */
    }
    free(text);
    return yes;
}

/* "#include "X"" in file `shown` (folder home): translates X (once) and writes its include line. */
static bool include_line(frag_ctx *x, const char *code, const char *home, const char *shown, int line, int depth,
                         strbuf *out)
{
    const char *a = strchr(code, '"'), *b = a ? strchr(a + 1, '"') : NULL;
    if (!a || !b)
        return err_set(x->err, "%s:%d: malformed #include, expected #include \"file.frag\"%s", shown, line, x->chain);
    char inc[PATH_MAX_LEN], path[PATH_MAX_LEN];
    snprintf(inc, sizeof inc, "%.*s", (int)(b - a - 1), a + 1);
    const char *why = "";
    bool ours;
    if (!resolve(x, inc, home, path, sizeof path, &ours, &why))
        return err_set(x->err, "%s:%d: #include \"%s\": %s%s", shown, line, inc, why, x->chain);
    if (ours)
        x->has_renderer |= strstr(path, "raytracer") != NULL;
    size_t chain = strlen(x->chain);
    snprintf(x->chain + chain, sizeof x->chain - chain, " (included from %s:%d)", shown, line);
    char group[sizeof x->group];
    memcpy(group, x->group, sizeof group);
    bool ok = frag_translate(x, path, inc, ours, depth + 1);
    memcpy(x->group, group, sizeof group); /* the includer's #group goes on (its braces are at 0 here) */
    x->depth = 0;
    x->in_vertex = x->in_preset = false;
    x->chain[chain] = '\0';
    if (ok)
        sb_printf(out, "#include \"%s\"\n", path);
    return ok;
}

/* ---- one file ---------------------------------------------------------------------------------------- */

/* The host's directives (Fragmentarium reads them by their start: "#infoText" is an #info). */
static const char *const HOST[] = {"info", "group", "preset", "endpreset", "vertex", "endvertex", "camera",
                                   "donotrun", "buffershader", "buffer", "TexParameter", "frontbuffer", "version",
                                   "replace"};

/* A '#' directive line: true when handled (written to out), else it is GLSL's own. */
static bool directive(frag_ctx *x, const char *code, const char *home, const char *shown, int line, int depth,
                      strbuf *out, bool *ok)
{
    const char *p = frag_skip(code);
    if (*p != '#')
        return false;
    p = frag_skip(p + 1);
    if (!strncmp(p, "include", 7)) {
        *ok = include_line(x, p, home, shown, line, depth, out);
        return true;
    }
    if (!strncmp(p, "define", 6) && isspace((unsigned char)p[6])) { /* undefined again after the fragment */
        const char *name = frag_skip(p + 6);
        frag_add_name(&x->macros, name, strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"));
        return false;
    }
    if (!strncmp(p, "TexParameter", 12)) /* a texture's filter or wrap: kept for the GPU (blanked here) */
        frag_texparameter(x, p + 12);
    size_t k = 0;
    while (k < sizeof HOST / sizeof *HOST && strncmp(p, HOST[k], strlen(HOST[k])))
        k++;
    if (k == sizeof HOST / sizeof *HOST)
        return false;
    const char *arg = frag_skip(p + strlen(HOST[k]));
    if (!strcmp(HOST[k], "info") && !x->f->summary[0] && depth == 0)
        snprintf(x->f->summary, sizeof x->f->summary, "%s", arg);
    else if (!strcmp(HOST[k], "group"))
        snprintf(x->group, sizeof x->group, "%s", arg);
    else if (!strcmp(HOST[k], "vertex"))
        x->in_vertex = true;
    else if (!strcmp(HOST[k], "preset"))
        x->in_preset = true;
    else if (!strcmp(HOST[k], "replace"))
        *ok = err_set(x->err, "%s:%d: #replace (Fragmentarium's text substitution) is not read: edit the line it "
                              "changes instead%s", shown, line, x->chain);
    sb_append(out, "\n"); /* the host's business: a blank line keeps the numbering */
    return true;
}

/* GLSL words that start a top-level line without declaring a name of the fragment's own. */
static bool not_a_type(const char *w, size_t n)
{
    static const char *const WORDS[] = {"return", "precision", "layout", "uniform", "varying", "attribute", "in", "out",
                                        "else", "if", "for", "while"};
    for (size_t i = 0; i < sizeof WORDS / sizeof *WORDS; i++)
        if (strlen(WORDS[i]) == n && !strncmp(WORDS[i], w, n))
            return true;
    return false;
}

#define WORD_CHARS "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_"

/* The names a top-level line declares ("TYPE NAME(" a function, "TYPE A = 1, B;" variables, "struct S"),
 * into x->functions: renamed while the fragment compiles (prelude), so a helper named like one of
 * fathom's (boxFold) or a global that hides a built-in (bool floor) stays the fragment's own; then the
 * braces of the line. */
static void top_level(frag_ctx *x, const char *code)
{
    const char *p = frag_skip(code);
    if (x->depth == 0 && *p != '#' && *p != '{' && *p != '}') {
        while (!strncmp(p, "const", 5) || !strncmp(p, "highp", 5) || !strncmp(p, "lowp", 4) || !strncmp(p, "mediump", 7))
            p = frag_skip(p + strspn(p, WORD_CHARS));
        bool is_struct = !strncmp(p, "struct", 6) && isspace((unsigned char)p[6]);
        size_t t = strspn(p, WORD_CHARS);
        const char *name = frag_skip(p + t);
        size_t n = strspn(name, WORD_CHARS);
        if (t && !not_a_type(p, t) && (is_struct || (n && !isdigit((unsigned char)*name)))) {
            if (is_struct || *frag_skip(name + n) == '(') {
                if (n)
                    frag_add_name(&x->functions, name, n);
            } else { /* variables: NAME [= ...] {, NAME [= ...]} ; at parenthesis depth 0 */
                for (int paren = 0;;) {
                    frag_add_name(&x->functions, name, n);
                    const char *c = name + n;
                    for (; *c && !(paren == 0 && (*c == ',' || *c == ';')); c++)
                        paren += *c == '(' || *c == '[' ? 1 : *c == ')' || *c == ']' ? -1 : 0;
                    if (*c != ',')
                        break;
                    name = frag_skip(c + 1);
                    n = strspn(name, WORD_CHARS);
                    if (!n || isdigit((unsigned char)*name))
                        break;
                }
            }
        }
    }
    for (const char *c = code; *c; c++)
        x->depth += *c == '{' ? 1 : *c == '}' ? -1 : 0;
}

/* Whether code defines the function `name` of return type `type` ("float DE(...)" at any spacing, not
 * followed by ';': a declaration). */
static bool defines(const char *code, const char *type, const char *name)
{
    const char *p = frag_skip(code);
    size_t t = strlen(type), n = strlen(name);
    if (strncmp(p, type, t) || !isspace((unsigned char)p[t]))
        return false;
    p = frag_skip(p + t);
    if (strncmp(p, name, n) || *(p = frag_skip(p + n)) != '(')
        return false;
    const char *close = strchr(p, ')');
    return !close || *frag_skip(close + 1) != ';';
}

bool frag_translate(frag_ctx *x, const char *path, const char *shown, bool ours, int depth)
{
    for (int i = 0; i < x->seen_count; i++)
        if (!strcmp(x->seen[i], path))
            return true; /* included once (the include guard every host gives) */
    if (depth > FRAG_DEPTH_MAX || x->seen_count == FRAG_SEEN_MAX)
        return err_set(x->err, "%s: includes nest deeper than %d or name more than %d files%s", shown, FRAG_DEPTH_MAX,
                       FRAG_SEEN_MAX, x->chain);
    snprintf(x->seen[x->seen_count++], PATH_MAX_LEN, "%s", path);
    char *text, home[PATH_MAX_LEN], line[1024], code[1024];
    if (!frag_read(path, shown, &text, x->err))
        return false;
    util_dirname(path, home, sizeof home);
    strbuf out = {0};
    bool ok = true, in_comment = false;
    x->in_vertex = x->in_preset = false;
    x->group[0] = '\0';
    x->comment[0] = '\0';
    x->depth = 0;
    const char *p = text;
    for (int n = 1; ok && frag_next_line(&p, line, sizeof line); n++) {
        bool was_comment = in_comment;
        code_of(line, &in_comment, code, sizeof code);
        const char *c = frag_skip(code);
        if (!ours && !was_comment)
            x->statements += (size_t)(strchr(c, ';') != NULL);
        bool end = *c == '#' && (strstr(c, "endvertex") || strstr(c, "endpreset"));
        if (x->in_preset || (x->in_vertex && (ours || end))) {
            bool vertex_init = end && x->in_vertex && x->vertex_init; /* glue.glsl runs it once a pixel */
            sb_append(&out, vertex_init ? "#define FRAG_VERTEX_INIT 1\n" : "\n");
            if (end)
                x->in_vertex = x->in_preset = false;
        } else if ((x->in_vertex && frag_vertex_line(x, line, sizeof line, code, sizeof code)) ||
                   (!x->in_vertex && frag_repeated_declaration(x, c))) {
            sb_append(&out, "\n");
        } else if (directive(x, code, home, shown, n, depth, &out, &ok)) {
        } else if (!strncmp(c, "uniform", 7) && isspace((unsigned char)c[7])) {
            ok = frag_uniform(x, line, c, shown, n, &out);
        } else {
            if (defines(c, "void", "main"))
                ok = err_set(x->err, "%s:%d: the fragment brings its own main(), a whole renderer: fathom opens "
                                     "fragments that give DE() to a DE renderer%s", shown, n, x->chain);
            x->has_de |= !ours && defines(c, "float", "DE");
            top_level(x, code);
            sb_printf(&out, "%s\n", line);
        }
        const char *cm = strstr(line, "//");
        if (*c == '\0' && cm) /* a comment line: the next parameter's description */
            snprintf(x->comment, sizeof x->comment, "%s", frag_skip(cm + 2));
        else if (*c)
            x->comment[0] = '\0';
    }
    if (ok && depth == 0 && x->f->frag_syntopia) /* every parameter is declared by now (includes inline) */
        frag_widen_to_presets(text, x->f);
    free(text);
    if (ok && x->statements > FRAG_STATEMENTS_MAX)
        ok = err_set(x->err, "%s: the fragment and its own includes have more than %d statements: the GL compiler "
                             "could crash on it", shown, FRAG_STATEMENTS_MAX);
    if (ok)
        keep(path, out.data ? out.data : util_strdup(""));
    else
        sb_free(&out);
    return ok;
}

/* ---- the whole fragment ------------------------------------------------------------------------------ */

bool frag_load(const char *path, formula *f, err_t *err)
{
    frag_ctx *x = calloc(1, sizeof *x);
    if (!x)
        return err_set(err, "out of memory");
    *f = (formula){.iterations = 1, .iterations_lo = 1, .iterations_hi = 1, .fragment = true, .frag_detail = -2.3f,
                   .frag_max_distance = 100000};
    x->f = f, x->err = err;
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(f->name, sizeof f->name, "%.*s", (int)(strlen(base) - 5), base);
    snprintf(f->file, sizeof f->file, "%s", path);
    snprintf(f->bound, sizeof f->bound, "%s", FRAG_BOUND);
    snprintf(f->trap[0], sizeof f->trap[0], "0");
    snprintf(f->trap[1], sizeof f->trap[1], "1");
    snprintf(f->loops, sizeof f->loops, "iterations + 1");
    char dir[PATH_MAX_LEN];
    util_dirname(path, dir, sizeof dir);
    bool ok = realpath(dir, x->root) != NULL || err_set(err, "%s: its folder cannot be read", path);
    if (ok)
        include_dir(x), f->frag_syntopia = syntopia_collection(x);
    ok = ok && frag_translate(x, path, base, false, 0);
    if (ok && !x->has_de)
        ok = err_set(err, "%s: no float DE(vec3 p): fathom opens distance-estimated fragments", base);
    if (ok && !x->has_renderer)
        ok = err_set(err, "%s: it includes no DE renderer (DE-Raytracer.frag or another): fathom opens fragments "
                          "that give DE() to one", base);
    if (ok && !f->summary[0])
        snprintf(f->summary, sizeof f->summary, "Fragmentarium fragment %s", base);
    if (ok)
        keep_wrappers(x, path), digest(x, path);
    sb_free(&x->functions);
    sb_free(&x->macros);
    sb_free(&x->varyings);
    free(x);
    return ok;
}

void frag_literal(const formula_param *q, const float *v, char *out, size_t n)
{
    static const char *const TYPE[] = {[FORMULA_FLOAT] = "float", [FORMULA_INT] = "int", [FORMULA_VEC3] = "vec3",
                                       [FORMULA_COLOR] = "vec3", [FORMULA_VEC2] = "vec2", [FORMULA_VEC4] = "vec4",
                                       [FORMULA_COLOR4] = "vec4"};
    if (q->type == FORMULA_BOOL) {
        snprintf(out, n, "%s", v[0] != 0 ? "true" : "false");
        return;
    }
    if (q->type == FORMULA_INT) {
        snprintf(out, n, "%d", (int)v[0]);
        return;
    }
    int at = snprintf(out, n, "%s(", TYPE[q->type]);
    for (int i = 0; i < formula_components(q->type) && at > 0 && (size_t)at < n; i++)
        at += snprintf(out + at, n - (size_t)at, "%s%.9g", i ? ", " : "", (double)v[i]);
    if (at > 0 && (size_t)at < n)
        snprintf(out + at, n - (size_t)at, ")");
}
