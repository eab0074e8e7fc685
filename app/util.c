/* realpath() is XSI; fopencookie is GNU */
#define _GNU_SOURCE
#include "util.h"

#include <assert.h>
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdarg.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
#include <time.h>

/* Formats into err; newline_ok keeps '\n' (a compiler's log), every other control character is '?'. */
static void err_vset(err_t *err, bool newline_ok, const char *fmt, va_list ap)
{
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    for (char *c = err->msg; *c; c++)
        if (((unsigned char)*c < 0x20 && !(newline_ok && *c == '\n')) || *c == 0x7f)
            *c = '?';
}

/* The guard's state across writes: a UTF-8 character or a C1 pair may be cut between two of them. */
typedef struct guard {
    int fd;
    unsigned char prev; /* the byte before: a byte 0x80-0x9f after ASCII is an 8-bit terminal's C1 */
    bool held_c2;       /* a 0xc2 waiting for the next byte: with 0x80-0x9f it is a C1 control in UTF-8 */
} guard;

static size_t escape_byte(guard *g, unsigned char c, char *out)
{
    size_t k = 0;
    if (g->held_c2) {
        g->held_c2 = false;
        if (c >= 0x80 && c <= 0x9f)
            return g->prev = c, (size_t)sprintf(out, "\\u%04x", c);
        out[k++] = (char)0xc2;
    }
    bool c1_alone = c >= 0x80 && c <= 0x9f && g->prev < 0x80;
    if (c == 0xc2)
        g->held_c2 = true;
    else if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f || c1_alone)
        k += (size_t)sprintf(out + k, "\\x%02x", c);
    else
        out[k++] = (char)c;
    g->prev = c;
    return k;
}

size_t util_escape_controls(const char *s, size_t n, char *out)
{
    guard g = {0};
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        k += escape_byte(&g, (unsigned char)s[i], out + k);
    if (g.held_c2)
        out[k++] = (char)0xc2;
    return k;
}

static bool write_all(int fd, const char *b, size_t k)
{
    for (size_t w = 0; w < k;) {
        ssize_t r = write(fd, b + w, k - w);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return false;
        w += (size_t)r;
    }
    return true;
}

static ssize_t guarded_write(void *cookie, const char *buf, size_t n)
{
    guard *g = cookie;
    char out[8192];
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        k += escape_byte(g, (unsigned char)buf[i], out + k);
        if (k > sizeof out - 16) {
            if (!write_all(g->fd, out, k))
                return i ? (ssize_t)i : -1;
            k = 0;
        }
    }
    return write_all(g->fd, out, k) ? (ssize_t)n : -1;
}

static int guarded_close(void *cookie)
{
    guard *g = cookie;
    if (g->held_c2)
        write_all(g->fd, "\xc2", 1);
    return 0;
}

void util_guard_terminal(void)
{
    static guard out_guard = {.fd = STDOUT_FILENO}, err_guard = {.fd = STDERR_FILENO};
    cookie_io_functions_t io = {.write = guarded_write, .close = guarded_close};
    fflush(stdout);
    fflush(stderr);
    FILE *out = fopencookie(&out_guard, "w", io);
    FILE *err = fopencookie(&err_guard, "w", io);
    if (out) {
        setvbuf(out, NULL, isatty(STDOUT_FILENO) ? _IOLBF : _IOFBF, BUFSIZ);
        stdout = out;
    }
    if (err) {
        setvbuf(err, NULL, _IONBF, 0);
        stderr = err;
    }
}

const char *util_printable(const char *s, char *out, size_t n)
{
    size_t k = 0;
    for (; *s && k + 1 < n; s++)
        out[k++] = ((unsigned char)*s < 0x20 || *s == 0x7f) ? '?' : *s;
    if (n)
        out[k] = '\0';
    return out;
}

bool err_set(err_t *err, const char *fmt, ...)
{
    if (err) { /* one line, whatever a file name, key or field brought in */
        va_list ap;
        va_start(ap, fmt);
        err_vset(err, false, fmt, ap);
        va_end(ap);
    }
    return false;
}

bool err_set_lines(err_t *err, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        err_vset(err, true, fmt, ap);
        va_end(ap);
    }
    return false;
}

bool util_cache_folder(const char *sub, const char *leaf, char *out, size_t n)
{
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    int len = xdg && *xdg ? snprintf(out, n, "%s", xdg) : snprintf(out, n, "%s/.cache", home ? home : ".");
    const char *const parts[] = {"", "/fathom", "/", sub, leaf ? "/" : NULL, leaf}; /* a folder made after each name */
    for (int i = 0; i < 6 && parts[i] && len < (int)n; i++) {
        len += snprintf(out + len, n - (size_t)len, "%s", parts[i]);
        if ((i == 0 || i % 2 == 1) && len < (int)n && mkdir(out, 0700) != 0 && errno != EEXIST)
            return false; /* out: the folder that could not be made */
    }
    return len < (int)n || (errno = ENAMETOOLONG, false);
}

static void remove_entries(const char *dir, bool deep) /* util_remove_folder (deep: util_remove_tree) */
{
    DIR *d = opendir(dir);
    for (struct dirent *e; d && (e = readdir(d));) {
        char path[PATH_MAX_LEN + 256];
        struct stat st;
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") ||
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= (int)sizeof path || lstat(path, &st) != 0)
            continue;
        if (deep && S_ISDIR(st.st_mode))
            remove_entries(path, true);
        else
            unlink(path);
    }
    if (d)
        closedir(d);
    rmdir(dir);
}

void util_remove_folder(const char *dir) { remove_entries(dir, false); }
void util_remove_tree(const char *dir) { remove_entries(dir, true); }

bool util_temp_path(const char *path, char *out, size_t n)
{
    static unsigned serial;
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path, *dot = strrchr(base, '.');
    int k = snprintf(out, n, "%.*s.%s.tmp%ld-%u%s", (int)(base - path), path, base, (long)getpid(), serial++,
                     dot && dot != base ? dot : "");
    return k > 0 && (size_t)k < n;
}

/* Is name one of fathom's temporary names, ".BASE.tmpPID-N.EXT" (util_temp_path), ".BASE.tmpPID.EXT" (the
 * image writer's before it) or ".BASE.tmpPID-N" (util_atomic's before it)? Its PID, else 0. EXT must be
 * BASE's own extension: a user's ".notes.tmp12.md" is not fathom's. */
static long temp_writer(const char *name)
{
    const char *t = name[0] == '.' ? strstr(name, ".tmp") : NULL;
    while (t && strstr(t + 1, ".tmp"))
        t = strstr(t + 1, ".tmp");
    if (!t || t == name)
        return 0;
    char *end;
    long pid = strtol(t + 4, &end, 10);
    if (end == t + 4 || pid <= 0 || !isdigit((unsigned char)t[4]))
        return 0;
    bool serial = *end == '-';
    if (serial) {
        const char *s = end + 1;
        strtoul(s, &end, 10);
        if (end == s || !isdigit((unsigned char)*s))
            return 0;
    }
    if (*end == '\0')
        return serial ? pid : 0;
    const char *base_ext = memrchr(name + 1, '.', (size_t)(t - name - 1)); /* BASE's extension, if any */
    size_t ext_len = strlen(end);
    return *end == '.' && !strchr(end + 1, '.') && base_ext && (size_t)(t - base_ext) == ext_len &&
                   !strncmp(base_ext, end, ext_len)
               ? pid
               : 0;
}

int util_remove_stale_temps(const char *path)
{
    const char *slash = strrchr(path, '/');
    char dir[PATH_MAX_LEN], file[PATH_MAX_LEN * 2];
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) + 1 : 2, slash ? path : "./");
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int removed = 0;
    for (struct dirent *e; (e = readdir(d));) {
        long pid = temp_writer(e->d_name);
        if (pid <= 0 || pid == (long)getpid() || kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue; /* not a temporary file, or its writer is alive (or not ours to ask): leave it */
        snprintf(file, sizeof file, "%s%s", dir, e->d_name);
        struct stat st;
        if (lstat(file, &st) == 0 && (S_ISREG(st.st_mode) || S_ISLNK(st.st_mode)))
            removed += unlink(file) == 0;
    }
    closedir(d);
    return removed;
}

bool util_atomic_open(util_atomic *a, const char *path, err_t *err)
{
    *a = (util_atomic){0};
    if (snprintf(a->path, sizeof a->path, "%s", path) >= (int)sizeof a->path)
        return err_set(err, "cannot write '%.200s...': the path is too long", path);
    util_remove_stale_temps(path);
    for (int tries = 0; tries < 100; tries++) {
        if (!util_temp_path(path, a->tmp, sizeof a->tmp))
            return err_set(err, "cannot write '%.200s...': the path is too long", path);
        int fd = open(a->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd < 0 && errno == EEXIST)
            continue;
        if (fd < 0)
            return err_set(err, "cannot write '%s': %s", path, strerror(errno));
        a->f = fdopen(fd, "w");
        if (!a->f) {
            close(fd);
            unlink(a->tmp);
            return err_set(err, "cannot write '%s': %s", path, strerror(errno));
        }
        return true;
    }
    return err_set(err, "cannot write '%s': no free temporary name beside it", path);
}

bool util_fsync_path(const char *path, int flags)
{
    int fd = open(path, flags | O_CLOEXEC);
    if (fd < 0)
        return false;
    bool ok = fsync(fd) == 0 || errno == EINVAL; /* EINVAL: a file system without fsync */
    int saved = errno;
    close(fd);
    errno = saved;
    return ok;
}

bool util_sync_folder_of(const char *path)
{
    char dir[PATH_MAX_LEN];
    const char *slash = strrchr(path, '/');
    snprintf(dir, sizeof dir, "%.*s", slash ? (int)(slash - path) + 1 : 1, slash ? path : ".");
    return util_fsync_path(dir, O_RDONLY | O_DIRECTORY);
}

bool util_atomic_commit(util_atomic *a, err_t *err)
{
    FILE *f = a->f;
    a->f = NULL;
    errno = 0;
    bool ok = fflush(f) == 0 && !ferror(f);
    ok = (fsync(fileno(f)) == 0 || errno == EINVAL) && ok; /* EINVAL: a file system without fsync */
    int saved = errno;
    ok = fclose(f) == 0 && ok;
    if (!ok || rename(a->tmp, a->path) != 0) {
        if (ok)
            saved = errno;
        unlink(a->tmp);
        return err_set(err, "cannot write '%s': %s (is the disk full?)", a->path,
                       strerror(saved ? saved : EIO));
    }
    if (!util_sync_folder_of(a->path)) { /* the new name may not outlive a crash: no file, not a maybe */
        saved = errno;
        unlink(a->path);
        return err_set(err, "cannot write '%s': its folder could not be synced to the disk: %s", a->path, strerror(saved));
    }
    return true;
}

void util_atomic_abort(util_atomic *a)
{
    if (a->f)
        fclose(a->f);
    a->f = NULL;
    unlink(a->tmp);
}

bool util_write_text_atomic(const char *path, const char *text, const char *what, err_t *err)
{
    util_atomic a;
    err_t e;
    if (!util_atomic_open(&a, path, &e))
        return err_set(err, "cannot save %s: %s", what, e.msg);
    fputs(text, a.f);
    if (!util_atomic_commit(&a, &e))
        return err_set(err, "cannot save %s: %s", what, e.msg);
    return true;
}

bool util_parse_decimal(const char *s, double *out)
{
    char *end;
    if (!*s || s[strspn(s, "0123456789+-.eE")] != '\0')
        return false;
    *out = strtod(s, &end);
    return *end == '\0' && end != s && isfinite(*out);
}

bool util_read_file(const char *path, char **out, size_t *len, err_t *err)
{
    return util_read_file_max(path, UTIL_TEXT_FILE_MAX, out, len, err);
}

bool util_read_file_max(const char *path, size_t max, char **out, size_t *len, err_t *err)
{
    /* O_NONBLOCK: opening a FIFO for reading would wait for a writer forever; it is refused below */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return err_set(err, "cannot open '%s': %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return err_set(err, "'%s' is not a regular file", path);
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return err_set(err, "cannot open '%s': %s", path, strerror(errno));
    }
    size_t size = (size_t)st.st_size;
    if (size > max) { /* by the size the file system gives: a sparse 2 GB file is not read to find out */
        fclose(f);
        return err_set(err, "'%s' is larger than %zu KB: not a file fathom reads", path, max / 1024);
    }
    char *buf = util_alloc(size + 1, path);
    size_t got = fread(buf, 1, size, f);
    fclose(f);
    if (got != size) {
        free(buf);
        return err_set(err, "cannot read '%s': short read", path);
    }
    buf[size] = '\0';
    *out = buf;
    if (len)
        *len = size;
    return true;
}

bool util_dirname(const char *path, char *out, size_t n)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return (size_t)snprintf(out, n, ".") < n;
    size_t len = (size_t)(slash - path);
    if (len == 0)
        len = 1; /* "/file" -> "/" */
    if (len + 1 > n)
        return false;
    memcpy(out, path, len);
    out[len] = '\0';
    return true;
}

bool util_join(const char *dir, const char *rel, char *out, size_t n)
{
    int w = (rel[0] == '/') ? snprintf(out, n, "%s", rel) : snprintf(out, n, "%s/%s", dir, rel);
    return w >= 0 && (size_t)w < n;
}

bool util_file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

bool util_file_digest(const char *path, unsigned long long *digest)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return false;
    unsigned long long h = 14695981039346656037ull; /* FNV-1a 64's offset basis and prime (Fowler, Noll, Vo) */
    unsigned char buf[65536];
    for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;)
        for (size_t i = 0; i < n; i++)
            h = (h ^ buf[i]) * 1099511628211ull;
    bool ok = !ferror(f);
    fclose(f);
    *digest = h;
    return ok;
}

/* A folder holds fathom's data when it has shaders/common/contract.glsl. */
static bool is_data_dir(const char *dir)
{
    char probe[PATH_MAX_LEN];
    return snprintf(probe, sizeof probe, "%s/shaders/common/contract.glsl", dir) < (int)sizeof probe &&
           util_file_exists(probe);
}

/* $FATHOM_DATA_DIR; else beside the binary: <bin>/../share/fathom (installed), <bin>/.. (a build folder
 * inside the source tree), <bin> itself; else the source tree the binary was built from. */
const char *util_data_dir(void)
{
    static char found[PATH_MAX_LEN];
    const char *env = getenv("FATHOM_DATA_DIR");
    if (env && env[0])
        return env;
    if (found[0])
        return found;
    char exe[PATH_MAX_LEN], dir[PATH_MAX_LEN];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = '\0';
        util_dirname(exe, dir, sizeof dir);
        const char *const rel[] = {("/../" FATHOM_DATA_SUBDIR), "/..", ""};
        for (size_t i = 0; i < sizeof rel / sizeof rel[0]; i++)
            if (snprintf(found, sizeof found, "%s%s", dir, rel[i]) < (int)sizeof found && is_data_dir(found)) {
                char clean[PATH_MAX]; /* messages name the scene file: without "bin/.." */
                if (realpath(found, clean) && strlen(clean) < sizeof found)
                    strcpy(found, clean);
                return found;
            }
    }
    snprintf(found, sizeof found, "%s", FATHOM_SOURCE_DIR);
    return found;
}

double util_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void out_of_memory(size_t bytes, const char *what)
{
    fprintf(stderr, "fathom: out of memory: %s needs %.1f MB more than this machine or its limits (ulimit -v) "
                    "give\n", what, (double)bytes / (1 << 20));
    exit(1);
}

void *util_alloc(size_t bytes, const char *what)
{
    void *p = malloc(bytes ? bytes : 1);
    if (!p)
        out_of_memory(bytes, what);
    return p;
}

void *util_calloc(size_t count, size_t size, const char *what)
{
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p)
        out_of_memory(count * size, what);
    return p;
}

void *util_realloc(void *old, size_t bytes, const char *what)
{
    void *p = realloc(old, bytes ? bytes : 1);
    if (!p)
        out_of_memory(bytes, what);
    return p;
}

char *util_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    return memcpy(util_alloc(n, "text"), s, n);
}

void sb_appendn(strbuf *sb, const char *s, size_t n)
{
    if (sb->len + n + 1 > sb->cap) {
        size_t cap = sb->cap ? sb->cap : 256;
        while (cap < sb->len + n + 1)
            cap *= 2;
        sb->data = util_realloc(sb->data, cap, "text");
        sb->cap = cap;
    }
    memcpy(sb->data + sb->len, s, n);
    sb->len += n;
    sb->data[sb->len] = '\0';
}

void sb_append(strbuf *sb, const char *s) { sb_appendn(sb, s, strlen(s)); }

void sb_printf(strbuf *sb, const char *fmt, ...)
{
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    assert(n >= 0);
    char *tmp = util_alloc((size_t)n + 1, "text");
    vsnprintf(tmp, (size_t)n + 1, fmt, ap2);
    va_end(ap2);
    sb_appendn(sb, tmp, (size_t)n);
    free(tmp);
}

void sb_free(strbuf *sb)
{
    free(sb->data);
    *sb = (strbuf){0};
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void util_sort(double *v, int n) { qsort(v, (size_t)n, sizeof *v, cmp_double); }

double util_median(const double *v, int n)
{
    assert(n > 0);
    double *c = util_alloc(sizeof *c * (size_t)n, "a median");
    memcpy(c, v, sizeof *c * (size_t)n);
    util_sort(c, n);
    double m = (n % 2) ? c[n / 2] : 0.5 * (c[n / 2 - 1] + c[n / 2]);
    free(c);
    return m;
}
/* Days from 1970-01-01 to a proleptic Gregorian date (the era arithmetic of H. Hinnant's
 * "chrono-Compatible Low-Level Date Algorithms"). */
long util_days_from_civil(int y, int m, int d)
{
    y -= m <= 2;
    long era = (y >= 0 ? y : y - 399) / 400;
    long yoe = y - era * 400, mp = (m + 9) % 12;
    long doy = (153 * mp + 2) / 5 + d - 1, doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    return era * 146097 + doe - 719468;
}

void util_civil_from_seconds(double t, int *y, int *mo, int *d, int *h, int *mi, double *s)
{
    long days = (long)floor(t / 86400);
    double rest = t - (double)days * 86400;
    long z = days + 719468, era = (z >= 0 ? z : z - 146096) / 146097, doe = z - era * 146097;
    long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365, doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    long mp = (5 * doy + 2) / 153;
    *d = (int)(doy - (153 * mp + 2) / 5 + 1);
    *mo = (int)(mp < 10 ? mp + 3 : mp - 9);
    *y = (int)(yoe + era * 400 + (*mo <= 2));
    *h = (int)(rest / 3600);
    *mi = (int)((rest - *h * 3600) / 60);
    *s = rest - *h * 3600 - *mi * 60;
}


double util_physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? (double)pages * (double)page : INFINITY;
}
