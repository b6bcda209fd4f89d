/* trim_probe.h — what the GPU trimming tests share (trim_probe.c): trimmed
 * patches of known shapes, the distance of a point from their curves, and
 * the probe, which runs the generated trim stage alone in the IR
 * interpreter and compares it with the reference's exact classification. */
#ifndef SC_TEST_TRIM_PROBE_H
#define SC_TEST_TRIM_PROBE_H

#include <float.h>
#include <stdbool.h>

#include "ir.h"
#include "nurbs.h"
#include "trim.h"
#include "trim_gen.h"
#include "trim_pack.h"

/* 64 float ulps of 1.0 (2^-23 each): the largest ulp in [0, 1]. */
#define NEAR_CURVE (64.0 * FLT_EPSILON)

/* Doubles of a homogeneous 2D Bézier curve of the highest trim degree. */
#define CURVE_DOUBLES (3 * (SC_TRIM_MAX_DEGREE + 1))

typedef enum shape {
    SHAPE_CIRCLE, SHAPE_NINE, SHAPE_NESTED, SHAPE_STAR, SHAPE_TOUCH, SHAPE_HOLES_ONLY,
    SHAPE_POLY100, SHAPE_POLY1000, SHAPE_TWO, SHAPE_EIGHT, SHAPE_COUNT
} shape;

/* The trim curves as Bézier segments, normalised to the domain: the
 * horizontal ones too, which the pieces leave out. */
typedef struct curves {
    int count;
    int *degree;
    double (*cp)[CURVE_DOUBLES];
} curves;

typedef struct probe {
    scg_program *prog;
    scg_interp *it;
    sc_trim_block block;
    float *texels;          /* record 0, then the block */
    int ntexels;
    scg_interp_env env;
} probe;

typedef struct agreement {
    int tested, skipped_near, wrong;
    long long steps;
    int iters;
} agreement;

extern const double outer_square[4][2];
extern const char *const shape_names[SHAPE_COUNT];
/* Texel of the trim block in the probe's records (after record 0). */
extern const int BLOCK_AT;

/* A flat bicubic patch over the domain [u0, u1] × [v0, v1]: x = u, y = v. */
sc_surface *add_patch(sc_scene *scene, double u0, double u1, double v0, double v1);

/* A new loop of ncurves (allocated, empty) on s. */
sc_loop *add_loop(sc_surface *s, int is_hole, int ncurves);

/* Domain coordinates from normalised ones. */
void to_domain(const sc_surface *s, double un, double vn, double *u, double *v);

/* A closed polygon (normalised coordinates) as one degree-1 B-spline. */
void add_polygon(sc_surface *s, int is_hole, const double (*pts)[2], int n);

/* A circle of four rational quadratic quarter arcs (weights 1, √2/2). */
void add_circle(sc_surface *s, int is_hole, double cu, double cv, double r);

/* Builds the shape on a patch of the given domain. */
sc_surface *make_shape(sc_scene *scene, shape which, double u0, double u1, double v0,
                       double v1);

/* The trim curves of s as Bézier pieces (normalised coordinates). */
void curves_of(const sc_surface *s, curves *out);

/* Whether (un, vn) lies within NEAR_CURVE of a curve: such points are
 * skipped, since float rounding may put them on either side. */
bool near_curves(const curves *c, double un, double vn);

/* Texel offsets in a block (gpu_layout.h): header, cells, loops, pieces. */
int loops_at(const sc_trim_block *block);

int piece_at(const sc_trim_block *block, int k);

/* Record 0 then the block, as the programs read them (malloc'd). */
void fill_records(const sc_trim_block *block, float **texels, int *ntexels);

/* The trim stage of the key with this trim field, for surface s. */
int probe_open(probe *p, const char *trim_field, const sc_surface *s, sc_error *err);

void probe_close(probe *p);

/* Kept (1) or not (0) for the surface point (u, v) given in float; -1 on
 * an interpreter error. */
int probe_run(probe *p, float u, float v, long long *steps, int *iters);

/* Random points, then points level with every piece end point (the v of
 * the block's pieces, exact in float for the unit domain). */
bool check_surface(const char *trim_field, const sc_surface *s, int npoints, agreement *a);

/* check_surface on the shape built on a patch of the given domain. */
bool check_shape(const char *trim_field, shape which, double u0, double u1, double v0,
                 double v1, int npoints, agreement *a);

#endif
