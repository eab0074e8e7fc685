/* libFuzzer harness for the scene parser: any bytes as a scene file, then the same with --set
 * overrides taken from the input's last line. The parser must return true or false with one line of
 * error and never crash, hang, leak or trip a sanitizer. Build and run: tests/fuzz/run.sh MINUTES. */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    /* a path in scenes/, so relative texture and heightmap paths resolve as the shipped scenes' do */
    static const char PATH[] = FATHOM_SOURCE_DIR "/scenes/fuzz.json";
    scene s;
    err_t err;
    if (scene_load_text(text, PATH, NULL, 0, &s, &err))
        scene_free(&s);
    /* the last line as an override "key=value" applied to the rest */
    char *nl = strrchr(text, '\n');
    if (nl && strchr(nl + 1, '=') && nl[1] != '=') {
        *nl = '\0';
        const char *sets[] = {nl + 1};
        if (scene_load_text(text, PATH, sets, 1, &s, &err))
            scene_free(&s);
    }
    free(text);
    return 0;
}
