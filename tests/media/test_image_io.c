/* Image files round trip exactly; asymmetric sizes and per-channel values catch flips and swaps;
 * failed writes leave no file behind; OpenImageIO loads only when an image is read or written. */
#include <dirent.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "check.h"

#include "data/media/image_io.h"
#include "data/lazy/lazy.h"

enum { W = 7, H = 5 };
static char dir[64];

static int setup(void **st)
{
    (void)st;
    strcpy(dir, "/tmp/fathom-io-XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **st)
{
    (void)st;
    return remove_tree(dir);
}

/* A value no other pixel or channel shares, so any flip or swap shows. */
static uint8_t u8_at(int x, int y, int c) { return (uint8_t)(y * 50 + x * 7 + c * 2 + 1); }

/* Runs first: checking an output path, writing a PNG and reading the shipped JPEG and PNG files need
 * no OpenImageIO (libpng and libjpeg-turbo do); the first EXR loads it (lazy.h). */
static void loaded_on_first_use(void **st)
{
    (void)st;
    char png[128], exr[128];
    err_t e;
    snprintf(png, sizeof png, "%s/first.png", dir);
    snprintf(exr, sizeof exr, "%s/first.exr", dir);
    assert_false(lazy_loaded(LAZY_IMAGE));
    assert_true(image_can_write(png, &e));
    image_io_install_signal_cleanup();
    uint8_t px[4] = {1, 2, 3, 255};
    assert_true(image_write_u8(png, 1, 1, 4, px, &e));
    assert_false(lazy_loaded(LAZY_IMAGE));
    /* the shipped scenes' textures and heightmaps read without it too */
    char tex[PATH_MAX_LEN], dem[PATH_MAX_LEN];
    snprintf(tex, sizeof tex, "%s/textures/ground_rock.jpg", FATHOM_SOURCE_DIR);
    snprintf(dem, sizeof dem, "%s/terrains/jacksboro.png", FATHOM_SOURCE_DIR);
    int w, h, c;
    uint8_t *t = NULL;
    float *d = NULL;
    assert_true(image_read_u8(tex, 4, IMAGE_MAX_SIDE, &w, &h, &t, &e));
    assert_true(image_read_f32(dem, 1, IMAGE_MAX_SIDE, &w, &h, &c, &d, &e));
    free(t);
    free(d);
    assert_false(lazy_loaded(LAZY_IMAGE));
    float fx[4] = {0.5f, 1, 2, 1};
    assert_true(image_write_f32(exr, 1, 1, 4, NULL, fx, &e));
    assert_true(lazy_loaded(LAZY_IMAGE));
    assert_false(lazy_loaded(LAZY_DEM));
    unlink(png);
    unlink(exr);
}

static void png_round_trip(void **st)
{
    (void)st;
    for (int channels = 3; channels <= 4; channels++) {
        uint8_t px[W * H * 4];
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < channels; c++)
                    px[(y * W + x) * channels + c] = u8_at(x, y, c);
        char path[128];
        snprintf(path, sizeof path, "%s/rt%d.png", dir, channels);
        err_t e;
        if (!image_write_u8(path, W, H, channels, px, &e))
            fail_msg("%s", e.msg);
        int w, h;
        uint8_t *back;
        if (!image_read_u8(path, 4, IMAGE_MAX_SIDE, &w, &h, &back, &e))
            fail_msg("%s", e.msg);
        assert_int_equal(w, W);
        assert_int_equal(h, H);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++)
                for (int c = 0; c < 4; c++) {
                    uint8_t want = c < channels ? u8_at(x, y, c) : 255;
                    if (back[(y * W + x) * 4 + c] != want)
                        fail_msg("%d channels: pixel (%d,%d) channel %d: %d != %d", channels, x, y, c,
                                 back[(y * W + x) * 4 + c], want);
                }
        free(back);
    }
}

static void exr_round_trip(void **st)
{
    (void)st;
    enum { C = 6 };
    const char *names[C] = {"R", "G", "B", "A", "Z", "steps"};
    float px[W * H * C];
    for (int i = 0; i < W * H * C; i++)
        px[i] = (float)(i % 13) * -0.37f + (float)i * 1e-3f;
    px[4] = INFINITY;     /* depth of a miss */
    px[C + 4] = 1e-30f;   /* tiny, stays tiny in 32-bit float */
    px[2 * C + 1] = 3e30f;
    char path[128];
    snprintf(path, sizeof path, "%s/rt.exr", dir);
    err_t e;
    if (!image_write_f32(path, W, H, C, names, px, &e))
        fail_msg("%s", e.msg);
    int w, h, c;
    float *back;
    if (!image_read_f32(path, 0, IMAGE_MAX_SIDE, &w, &h, &c, &back, &e))
        fail_msg("%s", e.msg);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    assert_int_equal(c, C);
    /* R, G, B, A first, the rest by name: the order we wrote */
    for (int i = 0; i < W * H * C; i++)
        if (!(back[i] == px[i] || (isinf(px[i]) && isinf(back[i]) && back[i] > 0)))
            fail_msg("pixel %d channel %s: %g read back as %g", i / C, names[i % C], (double)px[i], (double)back[i]);
    free(back);
}

static int count_files(void)
{
    int n = 0;
    DIR *d = opendir(dir);
    for (struct dirent *e; (e = readdir(d));)
        n += e->d_name[0] != '.' || strstr(e->d_name, ".tmp") != NULL;
    closedir(d);
    return n;
}

static void failed_writes_leave_nothing(void **st)
{
    (void)st;
    int before = count_files();
    uint8_t px[W * H * 3] = {0};
    err_t e;
    char path[128];
    snprintf(path, sizeof path, "%s/no/such/folder/x.png", dir);
    assert_false(image_can_write(path, &e));
    assert_non_null(strstr(e.msg, "does not exist"));
    assert_false(image_write_u8(path, W, H, 3, px, &e));
    snprintf(path, sizeof path, "%s/x.unknownformat", dir);
    assert_false(image_write_u8(path, W, H, 3, px, &e));
    assert_int_equal(count_files(), before);
    assert_false(image_read_u8("/nonexistent.png", 4, IMAGE_MAX_SIDE, &(int){0}, &(int){0}, &(uint8_t *){NULL}, &e));
    assert_non_null(strstr(e.msg, "/nonexistent.png"));
}

/* Streaming writes in bands give the same file as one call; a writer that gets too few rows, or one
 * abandoned half way, leaves nothing. */
static void banded_writes(void **st)
{
    (void)st;
    int before = count_files();
    uint8_t px[W * H * 3];
    for (int i = 0; i < W * H * 3; i++)
        px[i] = (uint8_t)(i * 3 + 1);
    char path[128];
    snprintf(path, sizeof path, "%s/bands.png", dir);
    err_t e;
    image_writer *w = image_writer_open(path, W, H, 3, false, NULL, &e);
    assert_non_null(w);
    assert_true(image_writer_rows(w, 2, px, &e));
    assert_true(image_writer_rows(w, H - 2, px + 2 * W * 3, &e));
    assert_false(image_writer_rows(w, 1, px, &e)); /* past the last row */
    assert_true(image_writer_finish(w, &e));
    int w2, h2;
    uint8_t *back;
    assert_true(image_read_u8(path, 3, IMAGE_MAX_SIDE, &w2, &h2, &back, &e));
    assert_memory_equal(back, px, sizeof px);
    free(back);
    unlink(path);

    w = image_writer_open(path, W, H, 3, false, NULL, &e);
    assert_true(image_writer_rows(w, 2, px, &e));
    assert_false(image_writer_finish(w, &e));
    assert_non_null(strstr(e.msg, "only 2 of 5 rows"));
    w = image_writer_open(path, W, H, 3, false, NULL, &e);
    assert_true(image_writer_rows(w, 2, px, &e));
    image_writer_abort(w);
    assert_int_equal(count_files(), before);
}

/* A header's size is checked before anything is allocated for it. */
static void oversized_images_are_refused(void **st)
{
    (void)st;
    uint8_t px[W * H * 3] = {0};
    char path[128];
    snprintf(path, sizeof path, "%s/wide.png", dir);
    err_t e;
    assert_true(image_write_u8(path, W, H, 3, px, &e));
    int w, h;
    uint8_t *back = NULL;
    assert_false(image_read_u8(path, 4, H - 1, &w, &h, &back, &e));
    assert_non_null(strstr(e.msg, "is 7x5: larger than the 4x4"));
    assert_null(back);
    assert_true(image_read_u8(path, 4, W, &w, &h, &back, &e));
    free(back);
    unlink(path);
}

/* The shipped PNG and JPEG files, read here (libpng, libjpeg-turbo), equal what OpenImageIO reads from
 * them, value for value, as 8-bit and as float, in every channel count fathom asks for. */
static void fast_reads_equal_openimageio(void **st)
{
    (void)st;
    static const char *const files[] = {"textures/ground_rock.jpg", "textures/skybox/irrlicht2_up.jpg",
                                        "terrains/jacksboro.png"};
    LAZY_FN_NAMED(ref_u8, bool (*ref_u8)(const char *, int, int, int *, int *, uint8_t **, err_t *),
                  lazy_symbol(LAZY_IMAGE, "oiio_read_u8", NULL));
    LAZY_FN_NAMED(ref_f32, bool (*ref_f32)(const char *, int, int, int *, int *, int *, float **, err_t *),
                  lazy_symbol(LAZY_IMAGE, "oiio_read_f32", NULL));
    assert_non_null(ref_u8);
    assert_non_null(ref_f32);
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        char path[PATH_MAX_LEN];
        snprintf(path, sizeof path, "%s/%s", FATHOM_SOURCE_DIR, files[i]);
        bool sixteen = strstr(path, ".png") != NULL; /* jacksboro.png: 16-bit grey, read as float only */
        for (int ch = 0; ch <= 4; ch++) {
            err_t e;
            int w, h, w2, h2, c, c2;
            float *f = NULL, *f2 = NULL;
            assert_true(image_read_f32(path, ch, IMAGE_MAX_SIDE, &w, &h, &c, &f, &e));
            assert_true(ref_f32(path, ch, IMAGE_MAX_SIDE, &w2, &h2, &c2, &f2, &e));
            assert_true(w == w2 && h == h2 && c == c2);
            assert_memory_equal(f, f2, sizeof(float) * (size_t)w * (size_t)h * (size_t)c);
            free(f);
            free(f2);
            if (sixteen || ch == 0)
                continue;
            uint8_t *u = NULL, *u2 = NULL;
            assert_true(image_read_u8(path, ch, IMAGE_MAX_SIDE, &w, &h, &u, &e));
            assert_true(ref_u8(path, ch, IMAGE_MAX_SIDE, &w2, &h2, &u2, &e));
            assert_true(w == w2 && h == h2);
            assert_memory_equal(u, u2, (size_t)w * (size_t)h * (size_t)ch);
            free(u);
            free(u2);
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(loaded_on_first_use),
        cmocka_unit_test(png_round_trip),
        cmocka_unit_test(exr_round_trip),
        cmocka_unit_test(failed_writes_leave_nothing),
        cmocka_unit_test(banded_writes),
        cmocka_unit_test(oversized_images_are_refused),
        cmocka_unit_test(fast_reads_equal_openimageio),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
