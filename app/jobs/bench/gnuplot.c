/* gnuplot — see gnuplot.h. posix_spawn_file_actions_addchdir_np is a GNU extension (glibc 2.29). */
#define _GNU_SOURCE
#include "jobs/bench/gnuplot.h"

#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

void gnuplot_string(FILE *f, const char *s)
{
    fputc('\'', f);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        if (*c == '\'')
            fputs("''", f);
        else if (*c == '\n')
            fputs("'.\"\\n\".'", f);
        else if (*c < 0x20 || *c == 0x7f)
            fputc('?', f);
        else
            fputc(*c, f);
    }
    fputc('\'', f);
}

/* The first line of gnuplot's complaint, or "" */
static void first_complaint(const char *dir, char *out, size_t n)
{
    char path[PATH_MAX_LEN], *text = NULL;
    err_t e;
    out[0] = '\0';
    if (snprintf(path, sizeof path, "%s/%s", dir, GNUPLOT_LOG_NAME) >= (int)sizeof path ||
        !util_read_file(path, &text, NULL, &e))
        return;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n"))
        if (strspn(line, " ^\t") < strlen(line)) { /* gnuplot marks the column with a line of '^' */
            snprintf(out, n, ": %s", line);
            break;
        }
    for (char *c = out; *c; c++)
        if ((unsigned char)*c < 0x20)
            *c = ' ';
    free(text);
}

bool gnuplot_run(const char *dir, const char *script, err_t *err)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addchdir_np(&fa, dir);
    posix_spawn_file_actions_addopen(&fa, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, GNUPLOT_LOG_NAME, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    char *argv[] = {"gnuplot", (char *)script, NULL};
    pid_t pid;
    int rc = posix_spawnp(&pid, "gnuplot", &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0)
        return err_set(err, "cannot run gnuplot (%s): install it (apt-get install gnuplot-nox)", strerror(rc));
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR)
        ;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        char why[256];
        first_complaint(dir, why, sizeof why);
        return err_set(err, "gnuplot failed%s%s", why,
                       WIFEXITED(status) && WEXITSTATUS(status) == 127 ? " (is gnuplot installed? apt-get install "
                                                                          "gnuplot-nox)" : "");
    }
    return true;
}
