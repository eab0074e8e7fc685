/* video's functions in the binary (data/media/video.h): the options are parsed here; encoding and decoding
 * load fathom_video.so (video.c, video_decode.c and libavcodec) on first use (data/lazy/lazy.h), so a run
 * that writes no video never maps libavcodec's libraries. */
#include "data/media/video.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "data/lazy/lazy.h"

static const char *const CODECS[VIDEO_CODEC_COUNT] = {"h264", "av1", "vp9"};

static const char *extension(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
}

bool video_is_file(const char *path)
{
    const char *e = extension(path);
    return !strcmp(e, ".mp4") || !strcmp(e, ".webm") || !strcmp(e, ".mkv");
}

/* One KEY=VALUE of --video. */
static bool option(const char *kv, bool webm, video_options *o, bool *has_crf, err_t *err)
{
    const char *eq = strchr(kv, '=');
    size_t klen = eq ? (size_t)(eq - kv) : strlen(kv);
    const char *v = eq ? eq + 1 : "";
    if (klen == 5 && !strncmp(kv, "codec", 5)) {
        for (int c = 0; c < VIDEO_CODEC_COUNT; c++)
            if (!strcmp(v, CODECS[c])) {
                o->codec = (video_codec)c;
                return !(webm && c == VIDEO_H264) ||
                       err_set(err, "bad --video codec=h264: a WebM file holds vp9 or av1 (or write an .mp4)");
            }
        return err_set(err, "bad --video codec='%s': expected h264, av1 or vp9", v);
    }
    if (klen == 3 && !strncmp(kv, "crf", 3)) {
        char *end;
        long n = strtol(v, &end, 10);
        if (!*v || *end || n < 0 || n > 63)
            return err_set(err, "bad --video crf='%s': expected a whole number from 0 (best) to 63", v);
        o->crf = (int)n;
        *has_crf = true;
        return true;
    }
    if (klen == 7 && !strncmp(kv, "pix_fmt", 7)) {
        if (strcmp(v, "yuv420p") && strcmp(v, "yuv444p"))
            return err_set(err, "bad --video pix_fmt='%s': expected yuv420p (plays everywhere) or yuv444p", v);
        o->yuv444 = !strcmp(v, "yuv444p");
        return true;
    }
    return err_set(err, "bad --video '%.*s': expected codec=h264|av1|vp9, crf=N or pix_fmt=yuv420p|yuv444p", (int)klen, kv);
}

bool video_options_parse(const char *text, const char *path, video_options *o, err_t *err)
{
    bool webm = !strcmp(extension(path), ".webm"), has_crf = false;
    *o = (video_options){.codec = webm ? VIDEO_VP9 : VIDEO_H264};
    char buf[256];
    if (text && snprintf(buf, sizeof buf, "%s", text) >= (int)sizeof buf)
        return err_set(err, "bad --video: too long");
    for (char *save = NULL, *kv = text ? strtok_r(buf, ",", &save) : NULL; kv; kv = strtok_r(NULL, ",", &save))
        if (!option(kv, webm, o, &has_crf, err))
            return false;
    if (!has_crf)
        /* each keeps the worst frame of the csg flight at 640x360 over 40.5 dB, at 1 and 3 frames a second (crf 18,
         * 6 and 3 kept the mean there, the worst at 39.4-40.3 dB) */
        o->crf = o->codec == VIDEO_H264 ? 12 : o->codec == VIDEO_VP9 ? 3 : 1;
    if (o->codec == VIDEO_H264 && o->crf > 51)
        return err_set(err, "bad --video crf=%d: h264's scale ends at 51", o->crf);
    return true;
}

void video_options_describe(const video_options *o, char *out, size_t n)
{
    snprintf(out, n, "codec=%s,crf=%d,pix_fmt=%s", CODECS[o->codec], o->crf, o->yuv444 ? "yuv444p" : "yuv420p");
}

video_writer *video_open(const char *path, int width, int height, int fps, const video_options *o,
                         const video_view *view, err_t *err)
{
    LAZY_FN(video_writer * (*f)(const char *, int, int, int, const video_options *, const video_view *, err_t *),
            lazy_symbol(LAZY_VIDEO, "video_open", err));
    return f ? f(path, width, height, fps, o, view, err) : NULL;
}

bool video_frame(video_writer *v, const uint8_t *rgb, err_t *err)
{
    LAZY_FN(bool (*f)(video_writer *, const uint8_t *, err_t *), lazy_symbol(LAZY_VIDEO, "video_frame", err));
    return f && f(v, rgb, err);
}

bool video_finish(video_writer *v, err_t *err)
{
    LAZY_FN(bool (*f)(video_writer *, err_t *), lazy_symbol(LAZY_VIDEO, "video_finish", err));
    return f && f(v, err);
}

void video_abort(video_writer *v)
{
    LAZY_FN(void (*f)(video_writer *), lazy_symbol(LAZY_VIDEO, "video_abort", NULL));
    if (f)
        f(v);
}

bool video_decode(const char *path, video_info *info, uint8_t **rgb, err_t *err)
{
    LAZY_FN(bool (*f)(const char *, video_info *, uint8_t **, err_t *), lazy_symbol(LAZY_VIDEO, "video_decode", err));
    return f && f(path, info, rgb, err);
}
