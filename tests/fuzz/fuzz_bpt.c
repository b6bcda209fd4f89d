/* fuzz_bpt.c — libFuzzer target for sc_read_bpt (runtime/io/io.h): any bytes
 * must end in a scene or an error, within the envelope of docs/limits.md,
 * clean under AddressSanitizer and UBSan. `make fuzz` builds it. */
#include "fuzz_reader.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_reader(sc_read_bpt, data, size);
}
