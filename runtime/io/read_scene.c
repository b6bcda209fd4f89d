/* read_scene.c — the front door of the readers: a scene by file name (the
 * extension picks the reader) and the embedded default teapot. */
#include "io.h"
#include "envelope.h"
#include "step.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int sc_load_default_scene(sc_scene *scene, sc_error *err)
{
    const sc_embedded_file *f = sc_embedded_find(sc_embedded_scenes, "teapot32.bpt");
    if (!f) {
        sc_scene_init(scene);
        return sc_fail(err, NULL, 0, "the embedded teapot32.bpt is missing from the library");
    }
    return sc_read_bpt((const char *)f->data, f->size, "teapot", scene, err);
}

static int has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && !strcasecmp(path + n - e, ext);
}

int sc_read_scene(const char *path, sc_scene *scene, sc_error *err)
{
    if (!strcmp(path, "teapot"))
        return sc_load_default_scene(scene, err);
    int (*reader)(const char *, size_t, const char *, sc_scene *, sc_error *) = NULL;
    if (has_extension(path, ".bpt"))
        reader = sc_read_bpt;
    else if (has_extension(path, ".obj"))
        reader = sc_read_obj;
    else if (has_extension(path, ".igs") || has_extension(path, ".iges"))
        reader = sc_read_iges;
    else if (has_extension(path, ".stp") || has_extension(path, ".step"))
        reader = sc_read_step;
    if (!reader) {
        sc_scene_init(scene);
        return sc_fail(err, path, 0, "unknown scene type: expected a .bpt, .obj, .igs, .iges, "
                       ".stp or .step file, or `teapot`");
    }
    char *data;
    size_t size;
    /* A STEP file is capped lower (its library's model is large) and
     * before it is read whole. */
    size_t cap = reader == sc_read_step ? SC_STEP_MAX_FILE_BYTES : SC_MAX_FILE_BYTES;
    if (sc_read_file_max(path, cap, 0, &data, &size, err)) {
        sc_scene_init(scene);
        return SC_FAIL;
    }
    int status = reader(data, size, path, scene, err);
    free(data);
    return status;
}
