/* gnuplot — the bench's plots drawn by gnuplot, with no shell between fathom and it.
 *
 * Every string that goes into a script (a title, a label, a file name) is written by gnuplot_string:
 * a single-quoted gnuplot string, in which gnuplot substitutes nothing (no `command`, no @macro, no
 * backslash escape). A scene's name or a sweep's value from a stranger's preset is text on a plot,
 * never a command. gnuplot_run starts gnuplot by posix_spawn (no /bin/sh) in a folder of its own,
 * with the script's constant name as its one argument.
 */
#ifndef FATHOM_GNUPLOT_H
#define FATHOM_GNUPLOT_H

#include <stdbool.h>
#include <stdio.h>

#include "util.h"

/* Writes s as one gnuplot string expression: 'text' with ' doubled; a newline becomes '."\n".'
 * (a line break in a title); any other control byte (below 0x20, 0x7f) becomes '?'. */
void gnuplot_string(FILE *f, const char *s);

/* Runs `gnuplot SCRIPT` with dir as its working folder, stdout to /dev/null and stderr to dir/LOG_NAME.
 * False, with gnuplot's first complaint, when it cannot start or does not exit 0. */
#define GNUPLOT_LOG_NAME "gnuplot.log"
bool gnuplot_run(const char *dir, const char *script, err_t *err);

#endif
