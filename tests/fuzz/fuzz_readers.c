/* libFuzzer harness for the small text readers a shared file reaches: a camera path (path_parse), a
 * shot's record in an image (shot_parse), a tile's record (offline_tile_record), a fractal formula's
 * declarations with its @bound and @require expressions (formula_parse, formula_eval) and a
 * Fragmentarium fragment's translation and presets (frag_load, frag_preset_shot: the text in a file of
 * its own). The first input byte picks the reader; the rest is its text. Each must return true or false, never crash, hang,
 * leak or trip a sanitizer. Build and run: tests/fuzz/run.sh MINUTES readers. */
/* mkstemps */
#define _DEFAULT_SOURCE
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "jobs/capture/offline.h"
#include "scene/formula/formula.h"
#include "scene/formula/frag.h"
#include "view/path.h"
#include "view/shot.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char frag_path[] = "/tmp/fathom-fuzz-frag-XXXXXX.frag"; /* the fragment reader's file, removed at exit */
static void remove_frag(void) { unlink(frag_path); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    char *text = malloc(size);
    if (!text)
        return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    err_t err;
    switch (data[0] % 5) {
    case 0: {
        path p;
        if (path_parse(text, "fuzz.json", &p, &err)) {
            path_sample smp;
            path_eval(&p, p.keys[0].time + 0.5 * path_duration(&p), &smp);
            path_free(&p);
        }
        break;
    }
    case 1: {
        static shot_desc d;
        shot_parse(text, "fuzz.png", &d, &err);
        break;
    }
    case 3: {
        static formula f;
        if (formula_parse(text, "fuzz.glsl", &f, &err)) {
            static float v[FORMULA_MAX_PARAMS][4];
            double out;
            for (int i = 0; i < f.param_count; i++)
                memcpy(v[i], f.params[i].def, sizeof v[i]);
            formula_eval(&f, f.bound, v, f.iterations, &out, &err);
            for (int i = 0; i < f.require_count; i++)
                formula_eval(&f, f.requires[i].lhs, v, f.iterations, &out, &err);
        }
        break;
    }
    case 4: { /* a fragment: read from a file, as fathom reads one */
        static int fd = -1;
        if (fd < 0 && ((fd = mkstemps(frag_path, 5)) < 0 || atexit(remove_frag)))
            break;
        const char *path = frag_path;
        FILE *f = fopen(path, "w");
        if (!f)
            break;
        fwrite(text, 1, strlen(text), f);
        fclose(f);
        static formula fr;
        if (frag_load(path, &fr, &err)) {
            strbuf shot = {0};
            char *ignored = NULL;
            frag_preset_shot(path, NULL, &shot, &ignored, &err);
            free(ignored);
            sb_free(&shot);
        }
        break;
    }
    default: {
        tile_record r;
        offline_tile_record(text, data[0] & 4, &r);
        break;
    }
    }
    free(text);
    return 0;
}
