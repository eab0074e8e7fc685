/* Videos (data/media/video.h) decoded back with libavformat and compared with the frames they were made
 * from: frame count, size, rate, codec, the 360° and stereo tags, and every frame's PSNR (at least
 * 40.5 dB on the worst frame at the default quality) for H.264 in MP4, VP9 in WebM and AV1 in MP4; the option errors.
 * With arguments, `test_video VIDEO FRAMES_PATTERN N` checks a video fathom wrote against its N frames
 * on disk (tests/capture/video_resume.sh: a flight killed and resumed). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "data/media/image_io.h"
#include "data/media/video.h"
#include "view/path.h"

enum { VW = 192, VH = 128, FRAMES = 12, FPS = 24 };

/* Frame f: a render-like picture (a sky gradient, a shaded ball with a soft edge moving across it, a
 * ground of smooth waves fading with distance), 8-bit sRGB. */
static void synth(int f, uint8_t *rgb)
{
    for (int y = 0; y < VH; y++)
        for (int x = 0; x < VW; x++) {
            double r, g, b, dx = x - (50 + 8.0 * f), dy = y - 50.0, d = sqrt(dx * dx + dy * dy);
            if (y < 80) {
                r = 110 + y * 1.2, g = 150 + y * 0.8, b = 230 - y * 0.3;
            } else {
                double fade = (y - 80) / 48.0;
                r = 120 + 40 * fade * sin(x * 0.15 + f * 0.2), g = 105 + 25 * fade * cos(y * 0.3 + x * 0.05), b = 75;
            }
            double a = fmin(fmax(24 - d, 0), 1.5) / 1.5, shade = 0.55 + 0.45 * fmax(0, (-dx - dy) / 34 + 0.3);
            r = r * (1 - a) + 200 * shade * a, g = g * (1 - a) + 90 * shade * a, b = b * (1 - a) + 60 * shade * a;
            uint8_t *p = rgb + 3 * (y * VW + x);
            p[0] = (uint8_t)lround(fmin(r, 255)), p[1] = (uint8_t)lround(fmin(g, 255)), p[2] = (uint8_t)lround(fmin(b, 255));
        }
}

static double psnr(const uint8_t *a, const uint8_t *b, size_t n)
{
    double se = 0;
    for (size_t i = 0; i < n; i++)
        se += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
    return se > 0 ? 10 * log10(255.0 * 255.0 * (double)n / se) : 99;
}

/* Writes FRAMES synthetic frames to path and reads them back; the worst frame's PSNR. */
static double round_trip(const char *file, const char *options, const video_view *view, video_info *info)
{
    video_options o;
    err_t e = {{0}};
    if (!video_options_parse(options, file, &o, &e))
        fail_msg("options '%s': %s", options ? options : "(defaults)", e.msg);
    static uint8_t frames[FRAMES][VW * VH * 3];
    video_writer *v = video_open(file, VW, VH, FPS, &o, view, &e);
    if (!v)
        fail_msg("video_open: %s", e.msg);
    for (int f = 0; f < FRAMES; f++) {
        synth(f, frames[f]);
        if (!video_frame(v, frames[f], &e))
            fail_msg("frame %d: %s", f, e.msg);
    }
    if (!video_finish(v, &e))
        fail_msg("video_finish: %s", e.msg);
    uint8_t *rgb;
    if (!video_decode(file, info, &rgb, &e))
        fail_msg("video_decode: %s", e.msg);
    assert_int_equal(info->frames, FRAMES);
    assert_int_equal(info->width, VW);
    assert_int_equal(info->height, VH);
    double worst = 99;
    for (int f = 0; f < FRAMES; f++)
        worst = fmin(worst, psnr(frames[f], rgb + (size_t)f * VW * VH * 3, (size_t)VW * VH * 3));
    free(rgb);
    unlink(file);
    return worst;
}

static void codecs_round_trip(void **st)
{
    (void)st;
    static const struct {
        const char *file, *options, *codec;
        double min_db;
    } cases[] = {
        {"fathom-test-video.mp4", NULL, "h264", 40.5},
        {"fathom-test-video.webm", NULL, "vp9", 40.5},
        {"fathom-test-video-av1.mp4", "codec=av1", "av1", 40.5},
        {"fathom-test-video-444.mkv", "pix_fmt=yuv444p,crf=10", "h264", 44},
        {"fathom-test-video-low.mp4", "crf=40", "h264", 20}, /* lower quality, still a picture */
    };
    double low = 99, good = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        video_info info;
        double db = round_trip(cases[i].file, cases[i].options, &(video_view){0}, &info);
        print_message("%s (%s): %s, %d frames at %.0f fps, worst frame %.1f dB\n", cases[i].file,
                      cases[i].options ? cases[i].options : "defaults", info.codec, info.frames, info.fps, db);
        assert_string_equal(info.codec, cases[i].codec);
        assert_true(fabs(info.fps - FPS) < 0.01);
        assert_true(db >= cases[i].min_db);
        if (i == 0)
            good = db;
        if (i == 4)
            low = db;
    }
    assert_true(low < good - 3); /* crf changes the quality: the check sees it */
}

/* A 360° video and a stereo one carry the tags players read, in MP4 and in WebM. */
static void view_tags(void **st)
{
    (void)st;
    const char *files[] = {"fathom-test-tags.mp4", "fathom-test-tags.webm"};
    for (int i = 0; i < 2; i++)
        for (int stereo = 0; stereo <= 2; stereo++) {
            video_info info;
            video_view view = {.equirectangular = stereo != 1, .stereo = stereo};
            round_trip(files[i], NULL, &view, &info);
            print_message("%s: 360 %d stereo %d -> read back 360 %d stereo %d\n", files[i], view.equirectangular,
                          view.stereo, info.view.equirectangular, info.view.stereo);
            assert_int_equal(info.view.equirectangular, view.equirectangular);
            assert_int_equal(info.view.stereo, view.stereo);
        }
}

static void bad_options(void **st)
{
    (void)st;
    static const struct {
        const char *text, *path, *want;
    } bad[] = {
        {"crf=64", "a.mp4", "expected a whole number from 0 (best) to 63"},
        {"crf=52", "a.mp4", "h264's scale ends at 51"},
        {"codec=h265", "a.mp4", "expected h264, av1 or vp9"},
        {"codec=h264", "a.webm", "a WebM file holds vp9 or av1"},
        {"pix_fmt=rgb24", "a.mp4", "expected yuv420p"},
        {"speed=3", "a.mp4", "bad --video 'speed'"},
        {"crf=", "a.mp4", "expected a whole number"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        video_options o;
        err_t e = {{0}};
        if (video_options_parse(bad[i].text, bad[i].path, &o, &e) || !strstr(e.msg, bad[i].want))
            fail_msg("'%s': got '%s', expected '%s'", bad[i].text, e.msg, bad[i].want);
    }
    video_options o;
    err_t e = {{0}};
    assert_true(video_options_parse(NULL, "a.webm", &o, &e));
    assert_int_equal(o.codec, VIDEO_VP9);
    assert_int_equal(o.crf, 3);
    /* an odd size cannot be yuv420p: one clear line, nothing written */
    assert_null(video_open("fathom-test-odd.mp4", 95, 64, FPS, &o, &(video_view){0}, &e));
    assert_non_null(strstr(e.msg, "needs an even width and height"));
    assert_false(access("fathom-test-odd.mp4", F_OK) == 0);
}

/* test_video VIDEO PATTERN N: the video holds the N frames on disk, each at 40.5 dB or better (the guide's
 * promise for the default quality, cameras.md: the worst frame, not the mean). */
static int check_video(const char *video, const char *pattern, int n)
{
    video_info info;
    uint8_t *rgb;
    err_t e = {{0}};
    if (!video_decode(video, &info, &rgb, &e)) {
        fprintf(stderr, "%s\n", e.msg);
        return 1;
    }
    int bad = info.frames != n;
    double worst = 99;
    for (int f = 0; f < n && !bad; f++) {
        char name[PATH_MAX_LEN];
        uint8_t *px;
        int w, h;
        if (!path_frame_name(pattern, f, name, sizeof name, &e) || !image_read_u8(name, 3, 16384, &w, &h, &px, &e)) {
            fprintf(stderr, "%s\n", e.msg);
            return 1;
        }
        bad = w != info.width || h != info.height;
        worst = bad ? worst : fmin(worst, psnr(px, rgb + (size_t)f * (size_t)w * (size_t)h * 3, (size_t)w * (size_t)h * 3));
        free(px);
    }
    free(rgb);
    printf("%s: %d frames (%d on disk), %dx%d, %s, worst frame %.1f dB\n", video, info.frames, n, info.width,
           info.height, info.codec, worst);
    return bad || worst < 40.5;
}

int main(int argc, char **argv)
{
    if (argc == 4)
        return check_video(argv[1], argv[2], atoi(argv[3]));
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(codecs_round_trip),
        cmocka_unit_test(view_tags),
        cmocka_unit_test(bad_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
