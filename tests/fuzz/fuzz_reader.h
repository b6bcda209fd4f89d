/* fuzz_reader.h — what the scene-reader fuzz targets share: run a reader
 * from memory on libFuzzer's bytes with the logger silenced (warnings are
 * expected on junk and would only slow the fuzzer), and check the one
 * promise every reader makes: a failure leaves the scene empty. */
#ifndef SC_FUZZ_READER_H
#define SC_FUZZ_READER_H

#include <stdint.h>
#include <stdlib.h>

#include "io.h"

typedef int (*fuzz_reader_fn)(const char *text, size_t size, const char *name, sc_scene *scene,
                              sc_error *err);

static void fuzz_quiet(sc_log_level level, const char *msg, void *user)
{
    (void)level, (void)msg, (void)user;
}

static inline int fuzz_reader(fuzz_reader_fn read, const uint8_t *data, size_t size)
{
    sc_set_logger(fuzz_quiet, NULL);
    sc_scene scene;
    sc_error err;
    if (read((const char *)data, size, "fuzz", &scene, &err) != SC_OK && scene.nsurfaces != 0)
        abort();
    sc_scene_free(&scene);
    return 0;
}

#endif
