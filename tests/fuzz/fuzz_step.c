/* fuzz_step.c — libFuzzer target for sc_read_step (runtime/io/step.h): our
 * pre-scan of the exchange structure and, in a build with Open CASCADE,
 * the library's transfer and our conversion behind it. Any bytes must end
 * in a scene or an error, clean under AddressSanitizer and UBSan. Open
 * CASCADE itself is not instrumented: what it does inside is seen only
 * through crashes, hangs and what it hands back. `make fuzz` builds it. */
#include "fuzz_reader.h"
#include "step.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_reader(sc_read_step, data, size);
}
