/* fuzz_heights.c — libFuzzer target for the height-grid reader
 * (sc_heights_parse, runtime/terrain/heights.h): any bytes, PGM (P2, P5)
 * or CSV, are a grid or an error, and a header is checked against the data
 * present before anything is allocated from it. `make fuzz` builds it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "heights.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* The parser cuts CSV lines in place and reads a NUL at data[size]. */
    char *text = malloc(size + 1);
    if (!text)
        return 0;
    memcpy(text, data, size);
    text[size] = 0;
    sc_heights h;
    sc_error err;
    if (sc_heights_parse(text, size, "fuzz", 1, 1, &h, &err) == SC_OK) {
        if (h.z == NULL)
            abort();
        sc_heights_free(&h);
    } else if (h.z != NULL) {
        abort();
    }
    free(text);
    return 0;
}
