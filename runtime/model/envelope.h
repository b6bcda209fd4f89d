/* envelope.h — the envelope of what a scene file may ask for (docs/limits.md).
 * Scene files come from other people's CAD systems and from the internet,
 * so every reader bounds the work and memory a file can cause: counts are
 * checked against the data present, and geometry that a file expands into
 * (a curve referenced many times, composites listing composites) is charged
 * to a per-file budget as it grows, so a hostile file stops early with a
 * "file:line: ..." error instead of filling memory. Each value is set well
 * above what real models need (the 25 MB, 100,000-patch OBJ of the tests
 * uses a third of the geometry budget). */
#ifndef SC_ENVELOPE_H
#define SC_ENVELOPE_H

#include <stddef.h>

#include "scene.h"

/* Degree of a surface (either direction) or trim curve a reader accepts:
 * CAD systems stay below 30; the cost of evaluation grows with its square. */
#define SC_READ_MAX_DEGREE 64
/* Bytes of a scene file (and of a material library, which is only colours). */
#define SC_MAX_FILE_BYTES ((size_t)1 << 30)
#define SC_MAX_MTL_BYTES ((size_t)16 << 20)
/* Bytes of geometry (knots, control points, curve and surface records) one
 * file may expand into. */
#define SC_GEOMETRY_BUDGET ((size_t)256 << 20)
/* Curves in one trim loop, after composites are expanded. */
#define SC_MAX_LOOP_PIECES (1 << 16)
/* Samples of a height grid (seed 004's terrains): 4096 x 4096, whose
 * triangular patches already exceed what a frame draws interactively; and
 * the bytes of a height file, a CSV of that many samples at 16 bytes each. */
#define SC_MAX_HEIGHT_SAMPLES (1 << 24)
#define SC_MAX_HEIGHT_FILE_BYTES ((size_t)256 << 20)
/* Pixels of an image file (AOV): 16384 x 16384. */
#define SC_MAX_IMAGE_PIXELS ((long long)1 << 28)

/* Geometry charged so far against `limit` (0: SC_GEOMETRY_BUDGET). */
typedef struct sc_budget {
    size_t used, limit;
} sc_budget;

/* Charges `bytes`; past the limit fails with "name:line: ..." naming
 * `what` and the limit. */
int sc_budget_charge(sc_budget *b, size_t bytes, const char *what, const char *name, int line,
                     sc_error *err);
/* What a curve or surface of these sizes holds, in bytes. */
size_t sc_curve_bytes(int dim, int degree, int ncp);
size_t sc_surface_bytes(int deg_u, int deg_v, int nu, int nv);

#endif
