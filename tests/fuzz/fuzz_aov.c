/* fuzz_aov.c — libFuzzer target for the AOV reader (sc_aov_read_mem,
 * runtime/io/aov.h): any bytes are an image or an error, and the header's
 * size is checked against the data before anything is allocated. `make
 * fuzz` builds it. */
#include <stdint.h>

#include "aov.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sc_aov aov;
    sc_error err;
    if (sc_aov_read_mem(data, size, "fuzz", &aov, &err) == SC_OK)
        sc_aov_free(&aov);
    return 0;
}
