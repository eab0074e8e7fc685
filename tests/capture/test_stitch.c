/* fathom stitch against forged tiles (no GL needed): every class of bad record found by the hostile
 * campaign is refused with one message and no poster, a good set is stitched. Each case fails without
 * its guard in offline_stitch (a 2^31-1 count grew memory toward 20 GB; EXR tiles claiming AOVs they do
 * not carry stitched with Z filled from R; --output naming a tile replaced it). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <cmocka.h>

#include "check.h"
#include "data/media/image_io.h"
#include "jobs/capture/offline.h"
#include "view/shot.h"

static char dir[] = "/tmp/fathom-stitch-XXXXXX";

static int setup(void **st)
{
    (void)st;
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **st)
{
    (void)st;
    return remove_tree(dir);
}

/* A W × rows tile (PNG, or EXR with `channels` channels) whose record is `record`. */
static const char *tile(const char *name, int w, int rows, int channels, const char *record)
{
    static char path[8][256];
    static int k;
    char *p = path[k++ % 8];
    snprintf(p, 256, "%s/%s", dir, name);
    const char *texts[] = {TILE_KEY, record, SHOT_KEY, "{}", NULL};
    bool png = strstr(name, ".png") != NULL;
    static const char *const names[] = {"R", "G", "B", "A", "Z"};
    err_t e;
    image_writer *wr = image_writer_open_text(p, w, rows, png ? 3 : channels, !png, png ? NULL : names, texts, &e);
    if (!wr)
        fail_msg("%s", e.msg);
    size_t n = (size_t)w * (size_t)rows * (size_t)(png ? 3 : channels);
    void *px = calloc(n, png ? 1 : sizeof(float));
    assert_true(image_writer_rows(wr, rows, px, &e));
    assert_true(image_writer_finish(wr, &e));
    free(px);
    return p;
}

static void refused_with(const char *const *tiles, int n, const char *out, const char *needle)
{
    err_t e = {{0}};
    char poster[256];
    snprintf(poster, sizeof poster, "%s/%s", dir, out);
    struct stat before, after;
    bool existed = stat(poster, &before) == 0;
    if (offline_stitch(poster, tiles, n, true, &e))
        fail_msg("stitched, expected '%s'", needle);
    if (!strstr(e.msg, needle))
        fail_msg("'%s' lacks '%s'", e.msg, needle);
    assert_null(strchr(e.msg, '\n'));
    if (existed) { /* an input named as the output is left as it was */
        assert_int_equal(stat(poster, &after), 0);
        assert_int_equal(after.st_size, before.st_size);
    } else {
        assert_int_not_equal(stat(poster, &after), 0);
    }
}

static void forged_records(void **st)
{
    (void)st;
    /* tiles of an 8x4 poster cut in 2: rows 0-1 and 2-3 */
    const char *good[2] = {tile("a.tile-1-of-2.png", 8, 2, 3, "1 2 8 4 0 0"), tile("a.tile-2-of-2.png", 8, 2, 3, "2 2 8 4 2 0")};
    char poster[256];
    snprintf(poster, sizeof poster, "%s/a.png", dir);
    err_t e;
    if (!offline_stitch(poster, good, 2, true, &e))
        fail_msg("a good set: %s", e.msg);
    const char *huge[1] = {tile("huge.png", 8, 2, 3, "1 2147483647 8 4 0 0")};
    refused_with(huge, 1, "h.png", "its record is damaged");
    const char *mask[1] = {tile("mask.exr", 8, 2, 4, "1 2 8 4 0 4294967295")};
    refused_with(mask, 1, "m.exr", "its record is damaged");
    const char *png_aov[1] = {tile("pngaov.png", 8, 2, 3, "1 2 8 4 0 1")};
    refused_with(png_aov, 1, "p.png", "its record is damaged");
    /* an EXR that claims depth (5 channels: RGBA + Z) but carries RGBA only */
    const char *claims[2] = {tile("c.tile-1-of-2.exr", 8, 2, 4, "1 2 8 4 0 1"), tile("c.tile-2-of-2.exr", 8, 2, 4, "2 2 8 4 2 1")};
    refused_with(claims, 2, "c.exr", "has 4 channels; its record's AOVs make 5");
    /* the poster named as one of its tiles: refused, the tile kept */
    refused_with(good, 2, "a.tile-1-of-2.png", "is one of the tiles");
    /* a tile file that is not there */
    char missing[256];
    snprintf(missing, sizeof missing, "%s/nosuch.tile-2-of-2.png", dir);
    const char *gone[2] = {good[0], missing};
    refused_with(gone, 2, "g.png", "not found");
    /* a newline in a record stays out of the message */
    const char *nl[1] = {tile("nl.png", 8, 2, 3, "1 2 8 4 0 0\nforged")};
    refused_with(nl, 1, "n.png", "its record is damaged");
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(forged_records)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
