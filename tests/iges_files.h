/* iges_files.h — what the IGES reader's tests share (iges_files.c): small
 * IGES files written from a list of entities, reading them with warnings
 * gathered, and error texts. */
#ifndef SC_TEST_IGES_FILES_H
#define SC_TEST_IGES_FILES_H

#include "io.h"
#include "nurbs.h"

/* Warnings of the last read, one per line. */
extern char iges_warnings[4096];

int iges_read_path(const char *path, sc_scene *scene, sc_error *err);
/* Reads text as the file "t.igs", gathering warnings. */
int iges_read_text(const char *text, sc_scene *scene, sc_error *err);
/* The error as "file:line: message" (static buffer). */
const char *iges_error_text(const sc_error *err);
/* How many entities of `type` the reader skipped for `reason`. */
int iges_skipped_count(const sc_scene *s, const char *type, const char *reason);

typedef struct spec {
    int type;
    const char *params; /* free-format parameters ending with ';' */
    int xform;          /* directory field 7 */
    int color;          /* directory field 13 */
    const char *label;
} spec;

/* A fixed-format file: one S, one G record, two D records per entity, the
 * parameters cut into 64-column P records. Entity k has DE 2k+1; its first
 * P record is at line 3 + 2n + (P records before it). malloc'd. */
char *iges_make_iges(const spec *e, int n);
/* Reads the file iges_make_iges writes for `e`; prints the error on failure. */
int iges_read_specs(const spec *e, int n, sc_scene *scene);
/* "t.igs:N:" for the line of the file holding `needle`. */
const char *iges_position_of(const char *text, const char *needle);
/* The parameters of the plane (u, v, 0) over [0, size]^2, bilinear. */
char *iges_plane_params(double size);
/* A 2-D curve's point at t. */
void iges_eval2(const sc_curve *c, double t, double p[2]);

#endif
