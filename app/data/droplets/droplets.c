/* droplets — see droplets.h. */
#include "data/droplets/droplets.h"

#include "data/droplets/bvh.h"

#include <csv.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum { COL_X, COL_Y, COL_Z, COL_R, COLS, HEADER_MAX_COLUMNS = 4096 };
static const char *const COL_NAME[COLS] = {"x", "y", "z", "radius"};

typedef struct reader {
    const char *path;
    float scale;
    droplets *d;
    err_t *err;
    bool failed;
    long line;            /* the line being parsed */
    bool header_done;     /* the first row decided the columns */
    int col[COLS];        /* column of x, y, z, radius/diameter */
    bool diameter;        /* the size column is a diameter */
    int ncols;            /* columns of the header (or of the first row) */
    char col_label[COLS][64];
    /* the row being read */
    int field;
    char *first[HEADER_MAX_COLUMNS]; /* first row's fields, kept until it is understood */
    char value[COLS][64];
    bool have[COLS];
    int cap;
} reader;

static bool fail(reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static bool fail(reader *r, const char *fmt, ...)
{
    if (r->failed)
        return false;
    char msg[ERR_MSG_MAX - PATH_MAX_LEN - 64];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    err_set(r->err, "droplets file '%s':%ld: %s", r->path, r->line, msg);
    r->failed = true;
    return false;
}

/* A whole field as a number (spaces around it allowed); false if it is not one. */
static bool parse_number(const char *s, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    if (end == s)
        return false;
    while (*end == ' ' || *end == '\t' || *end == '\r')
        end++;
    return *end == '\0';
}

static void trim_copy(char *dst, size_t n, const char *src, size_t len)
{
    while (len > 0 && (*src == ' ' || *src == '\t'))
        src++, len--;
    while (len > 0 && (src[len - 1] == ' ' || src[len - 1] == '\t' || src[len - 1] == '\r'))
        len--;
    if (len >= n)
        len = n - 1;
    memcpy(dst, src, len);
    dst[len] = '\0';
}

static int column_of(reader *r, const char *const *names)
{
    for (int c = 0; c < r->ncols; c++)
        for (const char *const *n = names; *n; n++)
            if (strcasecmp(r->first[c], *n) == 0)
                return c;
    return -1;
}

/* The first row: a header naming the columns, or four numbers (x, y, z, r with no header). */
static bool understand_first_row(reader *r)
{
    bool numeric = r->ncols >= 4;
    for (int c = 0; c < r->ncols && numeric; c++) {
        double v;
        numeric = parse_number(r->first[c], &v);
    }
    if (numeric) {
        for (int k = 0; k < COLS; k++) {
            r->col[k] = k;
            snprintf(r->col_label[k], sizeof r->col_label[k], "%s", COL_NAME[k]);
        }
        return true;
    }
    static const char *const X[] = {"Points:0", "Points_0", "x", NULL}, *const Y[] = {"Points:1", "Points_1", "y", NULL},
                             *const Z[] = {"Points:2", "Points_2", "z", NULL}, *const R[] = {"radius", "r", NULL},
                             *const D[] = {"diameter", "d", NULL};
    const char *const *want[] = {X, Y, Z};
    for (int k = 0; k < 3; k++)
        r->col[k] = column_of(r, want[k]);
    r->col[COL_R] = column_of(r, R);
    if (r->col[COL_R] < 0 && (r->col[COL_R] = column_of(r, D)) >= 0)
        r->diameter = true;
    for (int k = 0; k < COLS; k++)
        if (r->col[k] < 0) { /* the header's names are not repeated: the file may be anyone's */
            fail(r, "no %s column in the first row's %d fields; expected a header with ParaView's Points:0, Points:1, "
                    "Points:2 and radius or diameter, or x, y, z, r",
                 k == COL_R ? "radius or diameter" : COL_NAME[k], r->ncols);
            return false;
        }
    for (int k = 0; k < COLS; k++)
        snprintf(r->col_label[k], sizeof r->col_label[k], "%s", r->first[r->col[k]]);
    return true;
}

static bool add_droplet(reader *r)
{
    double v[COLS];
    for (int k = 0; k < COLS; k++) {
        if (!r->have[k])
            return fail(r, "the row has no column %d (%s): every row needs the header's %d columns", r->col[k] + 1,
                        r->col_label[k], r->ncols);
        if (!parse_number(r->value[k], &v[k]))
            return fail(r, "column %d (%s): '%s' is not a number", r->col[k] + 1, r->col_label[k], r->value[k]);
        if (!isfinite(v[k]))
            return fail(r, "column %d (%s): %s is not a finite number", r->col[k] + 1, r->col_label[k], r->value[k]);
        v[k] *= r->scale;
        if (fabs(v[k]) > DROPLETS_COORD_MAX)
            return fail(r, "column %d (%s): %s is beyond %g m from the origin, which fathom's float grid cannot "
                           "resolve; move the data near the origin or scale it (droplets.scale)",
                        r->col[k] + 1, r->col_label[k], r->value[k], DROPLETS_COORD_MAX);
    }
    if (r->diameter)
        v[COL_R] *= 0.5;
    if (!(v[COL_R] > 0))
        return fail(r, "column %d (%s): %s: a droplet's size must be positive", r->col[COL_R] + 1,
                    r->col_label[COL_R], r->value[COL_R]);
    if (v[COL_R] < DROPLETS_RADIUS_MIN) /* (a float would round it to 0: found by tests/fuzz) */
        return fail(r, "column %d (%s): %s: a droplet smaller than %g m across cannot be drawn; check the "
                       "units (droplets.scale)",
                    r->col[COL_R] + 1, r->col_label[COL_R], r->value[COL_R], 2 * DROPLETS_RADIUS_MIN);
    droplets *d = r->d;
    if (d->count == DROPLETS_MAX)
        return fail(r, "more than %d droplets: fathom holds at most that many; thin the data (ParaView's "
                       "MaskPoints filter) or split it",
                    DROPLETS_MAX);
    if (d->count == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 1024;
        if (r->cap > DROPLETS_MAX)
            r->cap = DROPLETS_MAX;
        d->spheres = util_realloc(d->spheres, sizeof(float) * 4 * (size_t)r->cap, "droplets");
    }
    for (int k = 0; k < COLS; k++)
        d->spheres[4 * (size_t)d->count + (size_t)k] = (float)v[k];
    d->count++;
    return true;
}

static void on_field(void *s, size_t len, void *data)
{
    reader *r = data;
    if (r->failed)
        return;
    int f = r->field++;
    if (s && memchr(s, '\0', len)) { /* a NUL would end the text early: "1\0junk" is no number */
        fail(r, "field %d holds a NUL byte: this is not a text CSV file", f + 1);
        return;
    }
    if (!r->header_done) {
        if (f >= HEADER_MAX_COLUMNS) {
            fail(r, "more than %d columns in the first row", HEADER_MAX_COLUMNS);
            return;
        }
        r->first[f] = util_alloc(len + 1, "droplets header");
        trim_copy(r->first[f], len + 1, s ? s : "", s ? len : 0);
        r->ncols = f + 1;
        return;
    }
    for (int k = 0; k < COLS; k++)
        if (r->col[k] == f) {
            trim_copy(r->value[k], sizeof r->value[k], s ? s : "", s ? len : 0);
            r->have[k] = true;
        }
}

static void on_row(int c, void *data)
{
    (void)c;
    reader *r = data;
    if (r->failed)
        return;
    if (!r->header_done) {
        r->header_done = true;
        if (!understand_first_row(r))
            return;
        bool numeric = r->col[COL_X] == 0 && r->col[COL_R] == 3 && !r->diameter;
        double v;
        if (numeric && parse_number(r->first[0], &v)) { /* no header: the row is a droplet */
            for (int k = 0; k < COLS; k++) {
                trim_copy(r->value[k], sizeof r->value[k], r->first[k], strlen(r->first[k]));
                r->have[k] = true;
            }
            add_droplet(r);
        }
    } else {
        add_droplet(r);
    }
    r->field = 0;
    memset(r->have, 0, sizeof r->have);
}

static void reader_free(reader *r)
{
    for (int c = 0; c < r->ncols; c++)
        free(r->first[c]);
}

static bool finish(reader *r, struct csv_parser *p)
{
    if (!r->failed && csv_fini(p, on_field, on_row, r) != 0)
        fail(r, "%s", csv_strerror(csv_error(p)));
    csv_free(p);
    reader_free(r);
    if (!r->failed && r->d->count == 0) { /* about the whole file: no line */
        err_set(r->err, "droplets file '%s' holds no droplets: it needs a header (ParaView's Points:0, Points:1, "
                        "Points:2 and radius or diameter, or x, y, z, r) and one row per droplet", r->path);
        r->failed = true;
    }
    if (r->failed) {
        droplets_free(r->d);
        return false;
    }
    droplets *d = r->d;
    d->r_min = INFINITY;
    d->r_max = 0;
    for (int i = 0; i < d->count; i++) {
        d->r_min = fminf(d->r_min, d->spheres[4 * (size_t)i + 3]);
        d->r_max = fmaxf(d->r_max, d->spheres[4 * (size_t)i + 3]);
    }
    return true;
}

static bool feed(reader *r, struct csv_parser *p, const char *line, size_t len)
{
    if (r->line == 1 && len >= 3 && memcmp(line, "\xEF\xBB\xBF", 3) == 0) /* a UTF-8 byte-order mark */
        line += 3, len -= 3;
    if (csv_parse(p, line, len, on_field, on_row, r) != len)
        return fail(r, "%s", csv_strerror(csv_error(p)));
    return !r->failed;
}

static void reader_init(reader *r, struct csv_parser *p, const char *path, float scale, droplets *d, err_t *err)
{
    memset(d, 0, sizeof *d);
    memset(r, 0, sizeof *r);
    r->path = path;
    r->scale = scale;
    r->d = d;
    r->err = err;
    csv_init(p, CSV_APPEND_NULL);
}

bool droplets_read_text(const char *text, size_t len, const char *path, float scale, droplets *d, err_t *err)
{
    reader r;
    struct csv_parser p;
    reader_init(&r, &p, path, scale, d, err);
    size_t at = 0;
    while (at < len && !r.failed) {
        const char *nl = memchr(text + at, '\n', len - at);
        size_t n = nl ? (size_t)(nl - (text + at)) + 1 : len - at;
        r.line++;
        feed(&r, &p, text + at, n);
        at += n;
    }
    return finish(&r, &p);
}

bool droplets_read(const char *path, float scale, droplets *d, err_t *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        memset(d, 0, sizeof *d);
        return err_set(err, "droplets file '%s': %s", path, strerror(errno));
    }
    reader r;
    struct csv_parser p;
    reader_init(&r, &p, path, scale, d, err);
    char *line = NULL;
    size_t cap = 0;
    ssize_t n;
    while (!r.failed && (n = getline(&line, &cap, f)) >= 0) {
        r.line++;
        feed(&r, &p, line, (size_t)n);
    }
    if (!r.failed && ferror(f))
        fail(&r, "read error: %s", strerror(errno));
    free(line);
    fclose(f);
    return finish(&r, &p);
}

/* ---- the grid ---- */

size_t droplets_cell_count(const droplets *d)
{
    return (size_t)d->dims[0] * (size_t)d->dims[1] * (size_t)d->dims[2];
}

static int clampi(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* The cells of droplet i's bounding box (inclusive ranges). */
static void cell_range(const droplets *d, const float *s, int lo[3], int hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = clampi((int)floorf((s[k] - s[3] - d->lo[k]) / d->cell[k]), 0, d->dims[k] - 1);
        hi[k] = clampi((int)floorf((s[k] + s[3] - d->lo[k]) / d->cell[k]), 0, d->dims[k] - 1);
    }
}

/* Does the sphere reach into cell (x, y, z)? (Arvo's box–sphere test: squared distance to the box.) */
static bool sphere_meets_cell(const droplets *d, const float *s, int x, int y, int z)
{
    int c[3] = {x, y, z};
    double dist2 = 0;
    for (int k = 0; k < 3; k++) {
        double a = d->lo[k] + (double)d->cell[k] * c[k], b = a + d->cell[k], v = s[k];
        double e = v < a ? a - v : v > b ? v - b : 0;
        dist2 += e * e;
    }
    return dist2 <= (double)s[3] * s[3];
}

/* Pass 1 (counts) or pass 2 (fill): every (droplet, cell) pair the spheres overlap. */
static size_t visit(droplets *d, uint32_t *count, uint32_t *cursor)
{
    size_t refs = 0;
    int nx = d->dims[0], ny = d->dims[1];
    for (int i = 0; i < d->count; i++) {
        const float *s = d->spheres + 4 * (size_t)i;
        int lo[3], hi[3];
        cell_range(d, s, lo, hi);
        for (int z = lo[2]; z <= hi[2]; z++)
            for (int y = lo[1]; y <= hi[1]; y++)
                for (int x = lo[0]; x <= hi[0]; x++) {
                    if (!sphere_meets_cell(d, s, x, y, z))
                        continue;
                    size_t c = (size_t)x + (size_t)nx * ((size_t)y + (size_t)ny * (size_t)z);
                    if (cursor)
                        d->index[cursor[c]++] = (uint32_t)i;
                    else
                        count[c]++;
                    refs++;
                }
        if (!cursor && refs > DROPLET_REFS_MAX)
            return refs;
    }
    return refs;
}

static void free_structure(droplets *d)
{
    free(d->cells);
    free(d->index);
    free(d->nodes);
    d->cells = d->index = NULL;
    d->nodes = NULL;
    d->node_count = 0;
    memset(d->dims, 0, sizeof d->dims);
}

void droplets_build_bvh(droplets *d)
{
    free_structure(d);
    int n = d->count;
    float(*lo)[3] = util_alloc(sizeof *lo * (size_t)n, "droplet BVH"), (*hi)[3] = util_alloc(sizeof *hi * (size_t)n, "droplet BVH");
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            lo[i][k] = d->spheres[4 * (size_t)i + (size_t)k] - d->spheres[4 * (size_t)i + 3];
            hi[i][k] = d->spheres[4 * (size_t)i + (size_t)k] + d->spheres[4 * (size_t)i + 3];
        }
    bvh_node *nodes = util_alloc(sizeof *nodes * (size_t)bvh_max_nodes(n), "droplet BVH");
    int *order = util_alloc(sizeof *order * (size_t)n, "droplet BVH");
    d->node_count = bvh_build(n, (const float(*)[3])lo, (const float(*)[3])hi, nodes, order);
    /* unsigned texels: the ints stay exact past 2^24, and no float channel carries int bits (those
     * would be denormals, which GPUs may flush to zero) */
    d->nodes = util_alloc(sizeof(uint32_t) * 8 * (size_t)d->node_count, "droplet BVH");
    for (int i = 0; i < d->node_count; i++) {
        uint32_t *t = d->nodes + 8 * (size_t)i;
        memcpy(t, nodes[i].lo, sizeof nodes[i].lo);
        t[3] = (uint32_t)nodes[i].first;
        memcpy(t + 4, nodes[i].hi, sizeof nodes[i].hi);
        t[7] = (uint32_t)nodes[i].count;
    }
    memcpy(d->lo, nodes[0].lo, sizeof d->lo);
    memcpy(d->hi, nodes[0].hi, sizeof d->hi);
    d->index = util_alloc(sizeof(uint32_t) * (size_t)n, "droplet BVH");
    for (int i = 0; i < n; i++)
        d->index[i] = (uint32_t)order[i];
    d->refs = (size_t)n;
    free(order);
    free(nodes);
    free(lo);
    free(hi);
}

bool droplets_build_grid(droplets *d, err_t *err)
{
    free_structure(d);
    for (int k = 0; k < 3; k++) {
        d->lo[k] = INFINITY;
        d->hi[k] = -INFINITY;
    }
    for (int i = 0; i < d->count; i++) {
        const float *s = d->spheres + 4 * (size_t)i;
        for (int k = 0; k < 3; k++) {
            d->lo[k] = fminf(d->lo[k], s[k] - s[3]);
            d->hi[k] = fmaxf(d->hi[k], s[k] + s[3]);
        }
    }
    /* Cells about cube-shaped, DROPLET_GRID_DENSITY per droplet; a flat or thin cloud keeps at least
     * one cell across its thin side. */
    double ext[3], largest = 0;
    for (int k = 0; k < 3; k++) {
        ext[k] = (double)d->hi[k] - d->lo[k];
        largest = fmax(largest, ext[k]);
    }
    double vol = 1;
    for (int k = 0; k < 3; k++)
        vol *= fmax(ext[k], largest * 1e-3);
    double side = cbrt(vol / (DROPLET_GRID_DENSITY * d->count));
    /* no finer than the smallest droplets' diameter: finer cells only list big droplets more often */
    side = fmax(side, 2.0 * d->r_min);
    if (!(side > 0 && isfinite(side))) /* one droplet, or all at one point: any positive cell will do */
        side = fmax(largest, 1e-6);
    int dims[3];
    for (;;) { /* within DROPLET_GRID_MAX_CELLS: cells a little bigger until it fits */
        for (int k = 0; k < 3; k++)
            dims[k] = clampi((int)ceil(ext[k] / side), 1, DROPLET_GRID_MAX_SIDE);
        if ((size_t)dims[0] * (size_t)dims[1] * (size_t)dims[2] <= DROPLET_GRID_MAX_CELLS)
            break;
        side *= 1.02;
    }
    for (;;) {
        for (int k = 0; k < 3; k++) {
            d->dims[k] = dims[k];
            /* a pad of one part in 10⁵ keeps the largest coordinates inside the last cell */
            d->cell[k] = (float)(fmax(ext[k], 1e-6) * (1 + 1e-5) / dims[k]);
        }
        size_t cells = droplets_cell_count(d);
        uint32_t *count = util_calloc(cells + 1, sizeof(uint32_t), "droplet grid");
        size_t refs = visit(d, count, NULL);
        if (refs > DROPLET_REFS_MAX) {
            free(count);
            if (dims[0] == 1 && dims[1] == 1 && dims[2] == 1)
                return err_set(err, "droplets: %d droplets list %zu cells, beyond fathom's limit", d->count, refs);
            for (int k = 0; k < 3; k++) /* big droplets against small cells: coarser cells */
                dims[k] = dims[k] > 1 ? (dims[k] + 1) / 2 : 1;
            continue;
        }
        /* exclusive prefix sum: count becomes the cells' first offsets */
        uint32_t sum = 0;
        for (size_t c = 0; c <= cells; c++) {
            uint32_t n = count[c];
            count[c] = sum;
            sum += n;
        }
        d->refs = refs;
        d->index = util_alloc(sizeof(uint32_t) * (refs ? refs : 1), "droplet grid index");
        uint32_t *cursor = util_alloc(sizeof(uint32_t) * cells, "droplet grid");
        memcpy(cursor, count, sizeof(uint32_t) * cells);
        visit(d, count, cursor);
        free(cursor);
        d->cells = count;
        return true;
    }
}

size_t droplets_bytes(const droplets *d)
{
    return sizeof(float) * 4 * (size_t)d->count + (d->cells ? sizeof(uint32_t) * (droplets_cell_count(d) + 1) : 0) +
           sizeof(uint32_t) * d->refs + sizeof(uint32_t) * 8 * (size_t)d->node_count;
}

void droplets_free(droplets *d)
{
    free(d->spheres);
    free_structure(d);
    memset(d, 0, sizeof *d);
}

/* ---- level of detail ---- */

double droplets_fresnel(double cos_i, double eta)
{
    /* Born & Wolf, Principles of Optics, §1.5: the s and p amplitude ratios, averaged in power */
    cos_i = fabs(cos_i);
    double sin2_t = eta * eta * fmax(0.0, 1.0 - cos_i * cos_i);
    if (sin2_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(1.0 - sin2_t);
    double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

void droplets_lod_table(float ior, droplet_lod_table *t)
{
    /* 8-point Gauss–Legendre nodes and weights on [−1, 1] (Abramowitz & Stegun, table 25.4) */
    static const double X[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double W[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    t->reflect = 0;
    for (int k = 0; k < DROPLET_LOD_NODES; k++) {
        double x = k < 4 ? -X[3 - k] : X[k - 4], wt = k < 4 ? W[3 - k] : W[k - 4];
        double w = 0.5 * (x + 1), weight = 0.5 * wt; /* w = sin² of the incidence angle, uniform over the disc */
        double F = droplets_fresnel(sqrt(1 - w), 1.0 / ior);
        t->weight[k] = (float)(weight * (1 - F) * (1 - F));
        t->cos_t[k] = (float)sqrt(1 - w / ((double)ior * ior));
        t->reflect += (float)(weight * F);
    }
}

double droplets_distance(const droplets *d, const float p[3])
{
    double out = 0, wall = INFINITY;
    int c[3];
    for (int k = 0; k < 3; k++) {
        double lo = d->lo[k], h = d->cell[k], x = p[k], o = fmax(lo - x, x - (lo + h * d->dims[k]));
        out += o > 0 ? o * o : 0;
        c[k] = clampi((int)floor((x - lo) / h), 0, d->dims[k] - 1);
        wall = fmin(wall, fmin(x - (lo + h * (c[k] - 1)), lo + h * (c[k] + 2) - x));
    }
    /* a droplet listed in none of the 27 cells around p's lies beyond their block's walls, and every
     * droplet inside the grid's box */
    double best = fmax(sqrt(out), wall);
    for (int z = c[2] - 1; z <= c[2] + 1; z++)
        for (int y = c[1] - 1; y <= c[1] + 1; y++)
            for (int x = c[0] - 1; x <= c[0] + 1; x++) {
                if (x < 0 || y < 0 || z < 0 || x >= d->dims[0] || y >= d->dims[1] || z >= d->dims[2])
                    continue;
                size_t cell = (size_t)x + (size_t)d->dims[0] * ((size_t)y + (size_t)d->dims[1] * (size_t)z);
                for (uint32_t i = d->cells[cell]; i < d->cells[cell + 1]; i++) {
                    const float *s = d->spheres + 4 * (size_t)d->index[i];
                    double dx = (double)p[0] - s[0], dy = (double)p[1] - s[1], dz = (double)p[2] - s[2];
                    best = fmin(best, sqrt(dx * dx + dy * dy + dz * dz) - s[3]);
                }
            }
    return best;
}
