/* lazy — modules loaded on first use (lazy.h). pread, lstat and O_CLOEXEC are POSIX.1-2008. */
#define _XOPEN_SOURCE 700
#include "data/lazy/lazy.h"

#include <dlfcn.h>
#include <elf.h>
#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

typedef struct module {
    const char *file, *what; /* the module's file name; what it brings, for messages */
    bool tried;
    void *handle;
    err_t why; /* why it could not be loaded */
} module;

static module modules[LAZY_COUNT] = {
    [LAZY_IMAGE] = {.file = "fathom_image.so", .what = "which reads and writes images through OpenImageIO"},
    [LAZY_DEM] = {.file = "fathom_dem.so", .what = "which reads DEMs through GDAL"},
    [LAZY_VIDEO] = {.file = "fathom_video.so", .what = "which writes and reads videos through libavcodec"},
    [LAZY_MESH] = {.file = "fathom_mesh.so", .what = "which writes and reads meshes through assimp and meshoptimizer"},
};

/* Whether the open file fd of size bytes is a whole ELF object: every segment the loader maps and the
 * tables it reads lie inside the file (a module cut short would be mapped past its end, and touching
 * that page kills the process with SIGBUS before dlopen can say anything). */
static bool whole_elf(int fd, off_t size, char *why, size_t n)
{
    Elf64_Ehdr eh;
    if (pread(fd, &eh, sizeof eh, 0) != (ssize_t)sizeof eh || memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0 ||
        eh.e_ident[EI_CLASS] != ELFCLASS64 || eh.e_phentsize != sizeof(Elf64_Phdr))
        return snprintf(why, n, "not a 64-bit ELF module") < 0;
    uint64_t end = (uint64_t)eh.e_phoff + (uint64_t)eh.e_phnum * sizeof(Elf64_Phdr);
    uint64_t sh_end = (uint64_t)eh.e_shoff + (uint64_t)eh.e_shnum * eh.e_shentsize;
    if (end > (uint64_t)size || sh_end > (uint64_t)size)
        return snprintf(why, n, "cut short (%lld bytes)", (long long)size) < 0;
    for (int i = 0; i < eh.e_phnum; i++) {
        Elf64_Phdr ph;
        if (pread(fd, &ph, sizeof ph, (off_t)(eh.e_phoff + (uint64_t)i * sizeof ph)) != (ssize_t)sizeof ph)
            return snprintf(why, n, "unreadable") < 0;
        if (ph.p_offset + ph.p_filesz > (uint64_t)size || ph.p_offset + ph.p_filesz < ph.p_offset)
            return snprintf(why, n, "cut short (%lld bytes; a segment ends at %llu)", (long long)size,
                            (unsigned long long)(ph.p_offset + ph.p_filesz)) < 0;
    }
    return true;
}

/* A module fathom may run: a regular file (a FIFO or device is refused without waiting on it), owned
 * by root or by this user, writable by nobody else, and a whole ELF object. fd is kept open so that
 * what was checked is what dlopen maps (through /proc/self/fd). -1 with why. */
static int open_trusted(const char *path, char *why, size_t n)
{
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    if (fd < 0) {
        snprintf(why, n, "%s", strerror(errno));
        return -1;
    }
    bool ok = fstat(fd, &st) == 0;
    if (ok && !S_ISREG(st.st_mode))
        ok = snprintf(why, n, "not a regular file") < 0;
    else if (ok && st.st_uid != 0 && st.st_uid != geteuid())
        ok = snprintf(why, n, "owned by another user (uid %u)", (unsigned)st.st_uid) < 0;
    else if (ok && (st.st_mode & (S_IWGRP | S_IWOTH)))
        ok = snprintf(why, n, "writable by its group or others (mode %03o): chmod go-w it", (unsigned)st.st_mode & 0777) < 0;
    else if (ok)
        ok = whole_elf(fd, st.st_size, why, n);
    if (!ok) {
        close(fd);
        return -1;
    }
    return fd;
}

/* Two places only: beside the binary (a build folder; the tests get copies beside theirs), and the
 * installed <prefix>/lib/fathom. Never a folder above or beside those: a binary copied to /tmp/x must
 * not run another user's /tmp/fathom_image.so. The first file that exists is checked and loaded. */
static void load(module *m)
{
    m->tried = true;
    char exe[PATH_MAX_LEN], dir[PATH_MAX_LEN], path[PATH_MAX_LEN + 64], why[160];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n <= 0) {
        err_set(&m->why, "cannot find the running binary (/proc/self/exe) to load %s beside it", m->file);
        return;
    }
    exe[n] = '\0';
    util_dirname(exe, dir, sizeof dir);
    static const char *const places[] = {"", "/../lib/fathom"};
    for (size_t i = 0; i < sizeof places / sizeof places[0]; i++) {
        snprintf(path, sizeof path, "%s%s/%s", dir, places[i], m->file);
        struct stat st;
        if (lstat(path, &st) != 0)
            continue;
        int fd = open_trusted(path, why, sizeof why);
        if (fd < 0) {
            err_set(&m->why, "refusing to load %s, %s: %s; reinstall fathom (cmake --install BUILD)", path, m->what,
                    why);
            return;
        }
        char self[64];
        snprintf(self, sizeof self, "/proc/self/fd/%d", fd);
        m->handle = dlopen(self, RTLD_NOW | RTLD_LOCAL);
        if (!m->handle) {
            err_set(&m->why, "cannot load %s, %s: %s", path, m->what, dlerror());
            close(fd);
        } /* else fd stays open: the loader knows the module by "/proc/self/fd/N", and a second module
           * opened on a reused N would be taken for the first */
        return;
    }
    err_set(&m->why, "%s, %s, is not beside %s nor in ../lib/fathom: reinstall fathom (cmake --install BUILD)",
            m->file, m->what, exe);
}

void *lazy_symbol(lazy_module id, const char *name, err_t *err)
{
    module *m = &modules[id];
    if (!m->tried)
        load(m);
    void *sym = m->handle ? dlsym(m->handle, name) : NULL;
    if (!sym && m->handle)
        err_set(&m->why, "%s lacks %s: it is not this fathom's; reinstall fathom", m->file, name);
    if (!sym && err)
        *err = m->why;
    return sym;
}

bool lazy_loaded(lazy_module id) { return modules[id].handle != NULL; }
