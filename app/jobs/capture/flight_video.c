/* flight_video — frames on disk to a video, atomically (flight_video.h). */
#include "jobs/capture/flight_video.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "data/media/image_io.h"
#include "view/path.h"

bool flight_video_prepare(const char *output, const char *options, char *pattern, size_t n, video_options *o,
                          err_t *err)
{
    if (!video_options_parse(options, output, o, err))
        return false;
    char folder[PATH_MAX_LEN];
    if (snprintf(folder, sizeof folder, "%s.frames", output) >= (int)sizeof folder ||
        snprintf(pattern, n, "%s/%%05d.png", folder) >= (int)n)
        return err_set(err, "--output '%s': the name is too long", output);
    if (mkdir(folder, 0775) != 0 && errno != EEXIST) /* never writable by all, whatever the umask */
        return err_set(err, "cannot make the frames' folder '%s': %s", folder, strerror(errno));
    /* a folder someone else put there (a link to another folder, another user's) is not fathom's to write into */
    struct stat st;
    if (lstat(folder, &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != geteuid() || (st.st_mode & S_IWOTH))
        return err_set(err, "the frames' folder '%s' is %s: fathom writes frames only into a folder it made; remove "
                            "it (or render to another name)", folder,
                       S_ISLNK(st.st_mode) ? "a link" : !S_ISDIR(st.st_mode) ? "not a folder"
                                                      : st.st_uid != geteuid() ? "another user's" : "writable by everyone");
    return true;
}

/* The frames' manifest: "INDEX DIGEST" a line, appended as fathom writes each frame (several processes
 * of a farm append to one, a line a write). A frame is fathom's when its last line's digest matches. */
static bool manifest_path(const char *pattern, char *out, size_t n)
{
    char folder[PATH_MAX_LEN];
    return util_dirname(pattern, folder, sizeof folder) && snprintf(out, n, "%s/%s", folder, FRAMES_MANIFEST) < (int)n;
}

bool flight_video_frame_trusted(const char *pattern, int f, const char *name)
{
    char list[PATH_MAX_LEN + 32];
    unsigned long long want = 0, d;
    bool listed = false;
    FILE *m = manifest_path(pattern, list, sizeof list) ? fopen(list, "r") : NULL;
    for (int i; m && fscanf(m, "%d %llx", &i, &d) == 2;)
        if (i == f)
            want = d, listed = true;
    if (m)
        fclose(m);
    return listed && util_file_digest(name, &d) && d == want;
}

bool flight_video_frame_record(const char *pattern, int f, const char *name, err_t *err)
{
    char list[PATH_MAX_LEN + 32], line[64];
    unsigned long long d;
    if (!manifest_path(pattern, list, sizeof list) || !util_file_digest(name, &d))
        return err_set(err, "cannot read back the frame '%s' just written: %s", name, strerror(errno));
    int fd = open(list, O_WRONLY | O_CREAT | O_APPEND | O_NOFOLLOW | O_CLOEXEC, 0666);
    int k = snprintf(line, sizeof line, "%d %016llx\n", f, d);
    bool ok = fd >= 0 && write(fd, line, (size_t)k) == k;
    int saved = errno;
    if (fd >= 0)
        close(fd);
    return ok || err_set(err, "cannot write the frames' manifest '%s': %s", list, strerror(saved));
}

/* Encodes frames 0 … last into tmp. */
static bool encode(const char *tmp, const char *pattern, int last, int fps, const video_options *o,
                   const video_view *view, err_t *err)
{
    video_writer *v = NULL;
    int w0 = 0, h0 = 0;
    bool ok = true;
    for (int f = 0; ok && f <= last; f++) {
        char name[PATH_MAX_LEN];
        uint8_t *rgb = NULL;
        int w, h;
        ok = path_frame_name(pattern, f, name, sizeof name, err) && image_read_u8(name, 3, VIDEO_MAX_SIDE, &w, &h, &rgb, err);
        if (ok && !v) {
            w0 = w, h0 = h;
            ok = (v = video_open(tmp, w, h, fps, o, view, err)) != NULL;
        } else if (ok && (w != w0 || h != h0)) {
            ok = err_set(err, "%s is %dx%d, frame 0 is %dx%d: a video's frames are one size (remove the odd ones and "
                              "render them again)", name, w, h, w0, h0);
        }
        ok = ok && video_frame(v, rgb, err);
        free(rgb);
    }
    if (!ok) {
        video_abort(v);
        return false;
    }
    return video_finish(v, err);
}

bool flight_video_assemble(const char *output, const char *pattern, int last, int fps, const video_options *o,
                           const video_view *view, bool quiet, err_t *err)
{
    int missing = 0, first_missing = -1;
    for (int f = 0; f <= last; f++) {
        char name[PATH_MAX_LEN];
        if (!path_frame_name(pattern, f, name, sizeof name, err))
            return false;
        if (!util_file_exists(name) && missing++ == 0)
            first_missing = f;
        else if (util_file_exists(name) && !flight_video_frame_trusted(pattern, f, name))
            return err_set(err, "%s is not the frame fathom wrote (not in the frames' manifest, or changed since): "
                                "remove it and render the path again", name);
    }
    if (missing) {
        if (!quiet)
            fprintf(stderr, "%s: %d of %d frames are not rendered yet (the first: %d); the video is made when all "
                            "are there (render the path again without --frames)\n", output, missing, last + 1, first_missing);
        return true;
    }
    char tmp[PATH_MAX_LEN + 64];
    util_remove_stale_temps(output); /* what an encoding killed mid-way left */
    if (!util_temp_path(output, tmp, sizeof tmp))
        return err_set(err, "--output '%s': the name is too long", output);
    /* made here, new (O_EXCL) and no link followed: libavformat then writes into this file */
    int fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0)
        return err_set(err, "cannot write '%s': %s", tmp, strerror(errno));
    close(fd);
    double t0 = util_now();
    bool ok = encode(tmp, pattern, last, fps, o, view, err);
    if (ok && !(util_fsync_path(tmp, O_RDONLY) && rename(tmp, output) == 0 && util_sync_folder_of(output)))
        ok = err_set(err, "cannot write '%s': %s (is the disk full?)", output, strerror(errno));
    if (!ok) {
        unlink(tmp);
        return false;
    }
    if (!quiet) {
        char desc[64];
        video_options_describe(o, desc, sizeof desc);
        fprintf(stderr, "wrote %s (%d frames at %d fps, %s%s%s, %.1f s; the frames stay in %.*s)\n", output, last + 1,
                fps, desc, view->equirectangular ? ", 360" : "", view->stereo ? ", stereo" : "", util_now() - t0,
                (int)(strrchr(pattern, '/') - pattern), pattern);
    }
    return true;
}
