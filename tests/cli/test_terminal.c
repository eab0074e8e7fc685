/* The terminal guard (util_guard_terminal): what fathom prints reaches the terminal with every control
 * byte escaped and every UTF-8 character whole, also when stdio hands it over a byte at a time (a
 * character cut between two writes: the first version printed '×' cut by a flush as "\x97"). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "util.h"

static const char SENT[] = "a\xc3\x97" "b\xe2\x80\x94" "c\x1b[2J\x07\xc2\x9b" "3\x85\t\n\xc2\xa0\x7f";
static const char SHOWN[] = "a\xc3\x97" "b\xe2\x80\x94" "c\\x1b[2J\\x07\\u009b" "3\\x85\t\n\xc2\xa0\\x7f";

/* SENT through the guard in a child whose stdout is a pipe, stdio's buffer `buffer` bytes; what came out */
static char *through_guard(size_t buffer)
{
    int fd[2];
    assert_int_equal(pipe(fd), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        dup2(fd[1], STDOUT_FILENO);
        close(fd[0]);
        util_guard_terminal();
        setvbuf(stdout, NULL, _IOFBF, buffer);
        fputs(SENT, stdout);
        fflush(stdout);
        _exit(0);
    }
    close(fd[1]);
    static char got[512];
    size_t n = 0;
    for (ssize_t r; (r = read(fd[0], got + n, sizeof got - 1 - n)) > 0;)
        n += (size_t)r;
    got[n] = '\0';
    close(fd[0]);
    int status;
    waitpid(pid, &status, 0);
    return got;
}

static void escapes_controls_keeps_characters(void **state)
{
    (void)state;
    assert_string_equal(through_guard(BUFSIZ), SHOWN);
    char out[6 * sizeof SENT];
    out[util_escape_controls(SENT, strlen(SENT), out)] = '\0';
    assert_string_equal(out, SHOWN);
}

static void a_byte_at_a_time(void **state)
{
    (void)state;
    assert_string_equal(through_guard(1), SHOWN);
    assert_string_equal(through_guard(2), SHOWN);
    assert_string_equal(through_guard(3), SHOWN);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(escapes_controls_keeps_characters),
        cmocka_unit_test(a_byte_at_a_time),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
