/* read_step.c — the STEP reader's C side: the limits every STEP file
 * passes before a library sees it (size cap, our pre-scan of the exchange
 * structure), then Open CASCADE's transfer and our conversion
 * (step_occt.cpp) in a child process (step_isolate.c) in a build that has
 * it, and the common end of a read. */
#include "io.h"
#include "step.h"

int sc_read_step(const char *text, size_t size, const char *name, sc_scene *scene,
                 sc_error *err)
{
    sc_scene_init(scene);
    if (size > SC_STEP_MAX_FILE_BYTES)
        return sc_finish_read(sc_fail(err, name, 0, "larger than the limit of a STEP file (at "
                                      "most %zu MiB are read; docs/limits.md)",
                                      SC_STEP_MAX_FILE_BYTES >> 20), name, scene, err);
    sc_step_scan scan;
    if (sc_step_scan_text(text, size, name, &scan, err))
        return sc_finish_read(SC_FAIL, name, scene, err);
#ifdef SC_HAVE_OCCT
    int status = sc_step_read_isolated(text, size, name, &scan, SC_STEP_MAX_SECONDS, scene,
                                       err);
#else
    int status = sc_fail(err, name, 0, "built without STEP support (Open CASCADE was not found "
                         "when splinecast was built; docs/step.md)");
#endif
    sc_step_scan_free(&scan);
    return sc_finish_read(status, name, scene, err);
}
