/* io.h — scene readers and writers. Every reader either fills the whole
 * scene or fails with "file:line: what is wrong" in the error record and
 * leaves the scene empty: never a silently partial scene. Readers call
 * sc_scene_validate_loops before returning. */
#ifndef SC_IO_H
#define SC_IO_H

#include "embedded.h"
#include "scene.h"

/* The default scene files (examples/scenes/teapot32.bpt), embedded by the
 * Makefile. */
extern const sc_embedded_file sc_embedded_scenes[];

/* Reads by extension: .bpt, .obj, .igs/.iges (case-insensitive). The
 * special name "teapot" (no file) is the embedded 32-patch teapot. */
int sc_read_scene(const char *path, sc_scene *scene, sc_error *err);

/* Readers from memory; `name` is used in messages. `text` need not be
 * NUL-terminated. */
int sc_read_bpt(const char *text, size_t size, const char *name, sc_scene *scene,
                sc_error *err);
int sc_read_obj(const char *text, size_t size, const char *name, sc_scene *scene,
                sc_error *err);
int sc_read_iges(const char *text, size_t size, const char *name, sc_scene *scene,
                 sc_error *err);

/* The embedded default scene: Newell's 32-patch teapot. */
int sc_load_default_scene(sc_scene *scene, sc_error *err);

/* Wavefront OBJ free-form writer: geometry written with %.17g so it reads
 * back bit-exact, names as `o`, transforms baked in, colours through a
 * .mtl beside it (same base name). Written to a temporary file and renamed,
 * so a failure leaves nothing half-written. */
int sc_write_obj(const char *path, const sc_scene *scene, sc_error *err);

/* Whole file into memory (NUL-terminated); fails with a message naming the
 * file. At most SC_MAX_FILE_BYTES (envelope.h). */
int sc_read_file(const char *path, char **data, size_t *size, sc_error *err);
/* (sc_read_file_max, with a cap of its own, is in sc_base.h.) */

/* Fails with "name:line: ..." when `text` is not a text file: a NUL byte, a
 * control character other than tab, CR, LF, FF, VT, or invalid UTF-8.
 * Readers call it first, so that binary junk is refused before parsing. */
int sc_check_text(const char *text, size_t size, const char *name, sc_error *err);

/* The end every reader shares: on failure (status not SC_OK) the scene is
 * freed and left empty; on success it is named after `name` and its loops
 * are validated (which fails, filling `err`, only when memory runs out).
 * Returns the status. */
int sc_finish_read(int status, const char *name, sc_scene *scene, sc_error *err);

#endif
