/* libFuzzer harness for droplet files: any bytes as a CSV of droplets, then the grid and the BVH over
 * what was read. The reader must return true or false with one line of error and never crash, hang,
 * leak or trip a sanitizer. Build and run: tests/fuzz/run.sh MINUTES droplets. */
#include <stddef.h>
#include <stdint.h>

#include "data/droplets/droplets.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    droplets d;
    err_t err;
    if (!droplets_read_text((const char *)data, size, "fuzz.csv", 1, &d, &err))
        return 0;
    if (droplets_build_grid(&d, &err))
        droplets_build_bvh(&d);
    droplets_free(&d);
    return 0;
}
