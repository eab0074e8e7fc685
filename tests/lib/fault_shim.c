/* A fault for the write protocol's tests (tests/cli/bad_input.sh), preloaded (LD_PRELOAD): with
 * FATHOM_TEST_FAULT=fsync a file's fsync fails with EIO, =dirfsync a folder's, =rename every rename;
 * anything else passes each call on. Only the tests build it; fathom never loads it. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static bool fault(const char *which)
{
    const char *f = getenv("FATHOM_TEST_FAULT");
    return f && !strcmp(f, which);
}

int fsync(int fd)
{
    struct stat st;
    bool folder = fstat(fd, &st) == 0 && S_ISDIR(st.st_mode);
    if (fault(folder ? "dirfsync" : "fsync")) {
        errno = EIO;
        return -1;
    }
    int (*real)(int) = (int (*)(int))dlsym(RTLD_NEXT, "fsync");
    return real(fd);
}

int rename(const char *from, const char *to)
{
    if (fault("rename")) {
        errno = EIO;
        return -1;
    }
    int (*real)(const char *, const char *) = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    return real(from, to);
}
