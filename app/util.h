/* util — errors, files, paths, clocks shared by every module.
 *
 * Errors: functions that can fail on bad data or environment return false and fill an err_t with
 * one line (what, where, what to do). Only main() prints it and exits. Programmer mistakes assert.
 */
#ifndef FATHOM_UTIL_H
#define FATHOM_UTIL_H

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { ERR_MSG_MAX = 2048, PATH_MAX_LEN = 1024 };

/* The image (and window) size when none is given: --size's default. */
enum { FATHOM_DEFAULT_WIDTH = 1280, FATHOM_DEFAULT_HEIGHT = 720 };

typedef struct err_t {
    char msg[ERR_MSG_MAX];
} err_t;

/* Sets err->msg (printf format). Returns false so callers can `return err_set(...)`. */
bool err_set(err_t *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The same, keeping line breaks: for a message that is many lines by nature (a shader compiler's log). */
bool err_set_lines(err_t *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Allocation that cannot come back empty-handed: on failure it prints "fathom: out of memory: WHAT
 * (N MB)" and exits with 1 (an output being written is removed first: image_io's exit handler). For
 * the many small allocations whose failure leaves nothing sensible to do; big ones whose size comes
 * from input (images, heightmaps, bands) check their own and say what to change. */
void *util_alloc(size_t bytes, const char *what);
void *util_calloc(size_t count, size_t size, const char *what);
void *util_realloc(void *p, size_t bytes, const char *what);
char *util_strdup(const char *s);

/* Reads a whole file, NUL-terminated. *out is malloc'd; the caller frees it. A file over max bytes is
 * refused by its size before a byte is read ("larger than N KB"); util_read_file's max is the largest
 * text file fathom reads (scenes, presets, flights, formulas). */
enum { UTIL_TEXT_FILE_MAX = 64 << 20, UTIL_SOURCE_FILE_MAX = 512 << 10 /* a formula's or shader's GLSL */ };
bool util_read_file_max(const char *path, size_t max, char **out, size_t *len, err_t *err);
bool util_read_file(const char *path, char **out, size_t *len, err_t *err);

/* A decimal number as users write one ("12", "-0.5", "1e3"), the whole string: strtod alone also takes
 * "0x10" (16), "inf" and "nan", which no option means. */
bool util_parse_decimal(const char *s, double *out);

/* Writes text to path atomically (util_atomic below). False with "cannot save WHAT to 'path': reason". */
bool util_write_text_atomic(const char *path, const char *text, const char *what, err_t *err);

/* The one name every writer's temporary file has, beside path: ".BASE.tmpPID-SERIAL.EXT" (the same
 * folder, so the rename is atomic; the target's extension, for libraries that choose a format by it).
 * False when out is too small. */
bool util_temp_path(const char *path, char *out, size_t n);
/* Removes, in path's folder, every temporary file of that form whose writer is gone (a run killed
 * mid-write): called by every writer before it writes. Returns how many it removed. */
int util_remove_stale_temps(const char *path);

/* A file written whole or not at all. open makes a new temporary file beside path (util_temp_path,
 * O_EXCL|O_NOFOLLOW: nothing planted there, a symbolic link included, is followed or overwritten);
 * commit checks every write, flushes it to the disk and renames it over path (rename replaces a link
 * at path, it never writes through one); on any failure, and in abort, the temporary file is removed
 * and path is left as it was. */
/* fsync of a file opened with flags (its bytes on the disk, not in a cache: a failure here, EIO or
 * ENOSPC on some file systems, is the last chance to hear of it), and of the folder that holds path (a
 * rename in it made durable); false with errno on failure. */
bool util_fsync_path(const char *path, int flags);
bool util_sync_folder_of(const char *path);

typedef struct util_atomic {
    void *f; /* FILE *, for fprintf */
    char tmp[PATH_MAX_LEN + 64], path[PATH_MAX_LEN];
} util_atomic;
bool util_atomic_open(util_atomic *a, const char *path, err_t *err);
bool util_atomic_commit(util_atomic *a, err_t *err); /* "cannot write 'path': reason (is the disk full?)" */
void util_atomic_abort(util_atomic *a);

/* Every byte fathom prints passes one guard: stdout and stderr are replaced by streams that show a control
 * byte (C0 but tab, newline and carriage return; DEL; C1 in UTF-8 or alone) as a visible escape such as
 * \x1b, so that no text from a file (a fragment's #info, a parameter's help, a preset's name, a path) can
 * drive the terminal (change its title, clear it, move the cursor). Once, first thing in main. */
void util_guard_terminal(void);
/* The guard's escaping of n bytes into out (at most 6 bytes a byte in); returns the bytes written. */
size_t util_escape_controls(const char *s, size_t n, char *out);

/* s with every control byte (below 0x20, 0x7f: ESC, BEL, a newline) as '?', into out: text from a
 * file that goes to a terminal, a CSV cell or a one-line message. Returns out. */
const char *util_printable(const char *s, char *out, size_t n);

/* Directory part of path ("." if none), and a path resolved against a directory (absolute paths
 * are kept). Both truncate nothing silently: they return false when out is too small. */
bool util_dirname(const char *path, char *out, size_t n);
bool util_join(const char *dir, const char *rel, char *out, size_t n);
bool util_file_exists(const char *path);
/* FNV-1a 64 of a file's bytes (not a cryptographic hash: it tells fathom's own file from another one). */
bool util_file_digest(const char *path, unsigned long long *digest);

/* The machine's physical memory in bytes (INFINITY when it cannot be told): what a file's claimed size is
 * weighed against before anything is allocated. */
double util_physical_memory(void);
/* Removes a folder of files that fathom made: each entry is unlinked (a link goes, what it points to
 * stays; a subfolder stays, and with it the folder), then the folder. */
void util_remove_folder(const char *dir);
/* Removes a folder fathom made and everything under it, subfolders too (links are removed, never followed). */
void util_remove_tree(const char *dir);

/* <cache>/fathom/SUB/LEAF ($XDG_CACHE_HOME, else ~/.cache; leaf may be NULL) into out, each folder made where
 * missing, only this user may write them. False with errno set (ENAMETOOLONG when out is too small); out
 * then holds the folder that could not be made. */
bool util_cache_folder(const char *sub, const char *leaf, char *out, size_t n);

/* Where shaders/, scenes/, textures/ and terrains/ live: $FATHOM_DATA_DIR, else found beside the
 * binary (installed: <prefix>/bin/../share/fathom), else the source tree it was built from. */
const char *util_data_dir(void);

/* Monotonic wall clock in seconds. */
double util_now(void);

/* Growable string. */
typedef struct strbuf {
    char *data;
    size_t len, cap;
} strbuf;
void sb_append(strbuf *sb, const char *s);
void sb_appendn(strbuf *sb, const char *s, size_t n);
void sb_printf(strbuf *sb, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void sb_free(strbuf *sb);

/* Sorts n doubles in place, ascending. */
void util_sort(double *v, int n);
/* Median of n doubles (sorts a copy). */
double util_median(const double *v, int n);

/* Calendar dates (proleptic Gregorian, UTC): days from 1970-01-01 to y-m-d, and seconds since the epoch
 * back to the date and time of day. */
long util_days_from_civil(int y, int m, int d);
void util_civil_from_seconds(double t, int *y, int *mo, int *d, int *h, int *mi, double *s);

#ifdef __cplusplus
}
#endif

#endif
