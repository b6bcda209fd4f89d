/* step.h — STEP (ISO 10303-21) files: our own pre-scan of the exchange
 * structure, which every file passes before a library sees it, and the C
 * face of the Open CASCADE part that turns a checked file into the scene
 * model (step_occt.cpp; built only where Open CASCADE is installed,
 * SC_HAVE_OCCT). docs/step.md says what is read and how. */
#ifndef SC_STEP_H
#define SC_STEP_H

#include <stddef.h>

#include "scene.h"

/* Bytes of a STEP file handed to Open CASCADE: its in-memory model takes
 * about 10 to 20 times the file's size, so this cap is lower than the
 * other readers' (docs/limits.md). */
#define SC_STEP_MAX_FILE_BYTES ((size_t)128 << 20)
/* Seconds a STEP read may take (transfer and conversion; the parse itself
 * is linear in the pre-scanned file); past it the read fails. */
#define SC_STEP_MAX_SECONDS 60.0
/* Nesting of parentheses in one instance: real files use 4 or 5 levels. */
#define SC_STEP_MAX_NESTING 32

/* What the pre-scan learns: the instances of the DATA sections by name
 * (#id) and line, and how many faces the file holds. */
typedef struct sc_step_scan {
    int ninstances;
    int *ids;            /* sorted ascending */
    int *lines;          /* line of the instance ids[k] */
    int faces;           /* ADVANCED_FACE and FACE_SURFACE instances */
} sc_step_scan;

/* Checks the exchange structure of `text` (ISO-10303-21; header, DATA
 * sections, END-ISO-10303-21;): every instance `#id = RECORD(...);` with
 * balanced parentheses (at most SC_STEP_MAX_NESTING deep), closed strings
 * and comments, unique ids, and every reference naming an instance of the
 * file. Fails with "name:line: what is wrong" at the first problem. */
int sc_step_scan_text(const char *text, size_t size, const char *name, sc_step_scan *scan,
                      sc_error *err);
void sc_step_scan_free(sc_step_scan *scan);
/* Line of instance #id, 0 when there is none. */
int sc_step_line_of(const sc_step_scan *scan, int id);

/* Reads a STEP file's text. The size cap and the pre-scan first; then, in
 * a build with Open CASCADE, its reader: every face converted to a NURBS
 * surface with parameter-space trim loops, placed by its assembly, with
 * its colour. Without Open CASCADE it fails with "built without STEP
 * support". */
int sc_read_step(const char *text, size_t size, const char *name, sc_scene *scene,
                 sc_error *err);

/* sc_occt_read_step in a child process (step_isolate.c): a crash of the
 * library, its memory and the time cap end the child, not the caller,
 * and become errors "name: ...". */
int sc_step_read_isolated(const char *text, size_t size, const char *name,
                          const sc_step_scan *scan, double max_seconds, sc_scene *scene,
                          sc_error *err);

/* ---- the Open CASCADE part (step_occt.cpp) ---- */
#ifdef __cplusplus
extern "C" {
#endif

/* Transfers the pre-scanned `text` with Open CASCADE and appends one
 * surface per face to `scene` (skipped faces are counted with
 * sc_scene_skip and warned about). Exceptions of the library are caught
 * and become "name: message" errors; past `max_seconds` the read fails. */
int sc_occt_read_step(const char *text, size_t size, const char *name,
                      const sc_step_scan *scan, double max_seconds, sc_scene *scene,
                      sc_error *err);

/* One face as Open CASCADE computes it on the original geometry, for the
 * independent check of our conversion and trimming (tests). */
typedef struct sc_occt_face {
    int bspline;         /* the face lies on a B-spline surface */
    int deg_u, deg_v;    /* its degrees (0 for other surfaces) */
    double area;         /* BRepGProp::SurfaceProperties, trimmed, world space */
    double centroid[3];  /* centre of that area, world space */
} sc_occt_face;

/* Reads a STEP (.stp/.step) or IGES (.igs/.iges) file with Open CASCADE's
 * own readers and lists its faces, in the order sc_occt_read_step gives
 * them for STEP. *faces is malloc'ed (free it). */
int sc_occt_face_props(const char *path, sc_occt_face **faces, int *nfaces, sc_error *err);

#ifdef __cplusplus
}
#endif

#endif
