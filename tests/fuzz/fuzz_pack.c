/* fuzz_pack.c — libFuzzer target for the pack reader (sc_pack_parse,
 * runtime/io/pack_file.h): any bytes are a pack or an error, and no
 * section is read or allocated past the file. The checksum is made right
 * first (when there is room for it), so that mutations reach the sections
 * behind it instead of stopping at the checksum test. `make fuzz` builds
 * it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "pack_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    unsigned char *copy = malloc(size ? size : 1);
    if (!copy)
        return 0;
    memcpy(copy, data, size);
    if (size >= 32) {
        uint64_t h = 14695981039346656037u;
        for (size_t i = 32; i < size; i++)
            h = (h ^ copy[i]) * 1099511628211u;
        memcpy(copy + 24, &h, 8);
    }
    sc_pack pack;
    sc_error err;
    if (sc_pack_parse(copy, size, "fuzz", &pack, &err) == SC_OK)
        sc_pack_free(&pack);
    free(copy);
    return 0;
}
