/* fuzz_key.c — libFuzzer target for the variant-key parser (scg_key_parse,
 * gen/key.h): any text is a key or an error. A parsed key must print back
 * to text that parses to the same key. `make fuzz` builds it. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "key.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    memcpy(text, data, size);
    text[size] = 0;
    scg_key key, again;
    sc_error err;
    if (scg_key_parse(text, &key, &err) == SC_OK) {
        char a[1024], b[1024];
        scg_key_format(&key, a, sizeof a);
        if (scg_key_parse(a, &again, &err) != SC_OK)
            abort();
        scg_key_format(&again, b, sizeof b);
        if (strcmp(a, b) != 0)
            abort();
    }
    free(text);
    return 0;
}
