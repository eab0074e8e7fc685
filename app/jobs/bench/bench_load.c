/* bench_load — what every bench file shares (bench_load.h): a scene loaded with the command line's
 * --set, an image's time, a whole process's time. */
#include "jobs/bench/bench_load.h"

#include <epoxy/gl.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli/cli.h"
#include "gpu/render.h"

bool bench_load(const bench_desc *opt, const char *const *extra, int n_extra, scene *s, err_t *err)
{
    const char *sets[2 * CLI_MAX_SETS];
    int n = 0;
    for (int i = 0; i < opt->set_count; i++)
        sets[n++] = opt->sets[i];
    for (int i = 0; i < n_extra && n < 2 * CLI_MAX_SETS; i++)
        sets[n++] = extra[i];
    return scene_load(opt->scene, sets, n, s, err);
}

double bench_image_ms(const scene *s, const camera *cam, int w, int h)
{
    render_resize(w, h);
    render_begin(cam);
    glFinish();
    double t0 = util_now();
    for (int i = 0; i < s->quality.spp; i++)
        render_sample();
    glFinish();
    return (util_now() - t0) * 1000.0;
}

double bench_process_ms(char *const *argv, const char *log)
{
    double t0 = util_now();
    pid_t pid = fork();
    if (pid == 0) {
        int null = open("/dev/null", O_WRONLY);
        int err = log ? open(log, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600) : null;
        if (null >= 0)
            dup2(null, 1);
        if (err >= 0)
            dup2(err, 2);
        execv("/proc/self/exe", argv);
        _exit(127);
    }
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return -1;
    return (util_now() - t0) * 1000.0;
}
