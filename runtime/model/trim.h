/* trim.h — exact trimming in a surface's parameter space: is (u, v) kept
 * by the surface's trim loops? The parity of the crossings of the ray from
 * (u, v) towards +u with all loops decides. The loops are prepared once per
 * surface into v-monotone rational Bézier pieces with half-open v ranges, so
 * that a ray through a shared end point, a tangency or along a horizontal
 * piece counts right. Used by the CPU reference; the piece list is also the
 * natural input of GPU trim data. */
#ifndef SC_TRIM_H
#define SC_TRIM_H

#include "scene.h"

/* Highest trim-curve degree that trimming handles, in the reference and on
 * the GPU alike: the highest degree a variant key can name (SCG_MAX_DEGREE,
 * gen/key.h). Loop validation drops loops with curves above it, so every
 * loop a reader keeps can be drawn. */
#define SC_TRIM_MAX_DEGREE 16

/* One v-monotone piece of a trim curve: a rational Bézier curve in
 * homogeneous form (u·w, v·w, w), oriented so that v grows with its
 * parameter. It covers v in [v_lo, v_hi) (the end point with the larger v
 * is left out), which makes the crossing count of consecutive pieces right
 * at shared end points, extrema and horizontal runs. A horizontal piece has
 * v_lo == v_hi and so covers no v at all. */
typedef struct sc_trim_piece {
    int degree;
    double cp[3 * (SC_TRIM_MAX_DEGREE + 1)];
    double u_lo, v_lo;        /* end point at the lower v */
    double u_hi, v_hi;        /* end point at the upper v; v_hi >= v_lo */
    double u_min, u_max;      /* bounds of u over the piece (control points) */
    int loop;                 /* index of the loop it came from */
} sc_trim_piece;

typedef struct sc_trim {
    int npieces;
    sc_trim_piece *pieces;
    /* Whether a point with no crossing at all is kept: 0 when the surface
     * has an outer loop, 1 when it has only holes (the domain boundary then
     * acts as the outer loop). */
    int kept_without_crossings;
    /* Buckets over v: bucket k lists the pieces whose [v_lo, v_hi] meets
     * [v0 + k·dv, v0 + (k+1)·dv], so that a query looks at few pieces. */
    double v0, dv;
    int nbuckets;
    int *bucket_start;        /* nbuckets + 1 offsets into bucket_items */
    int *bucket_items;
} sc_trim;

/* Prepares the loops of `s`. For an untrimmed surface *out is NULL (every
 * point is kept). Fails, naming the surface, loop and curve, for a curve
 * that is not 2D, of degree above SC_TRIM_MAX_DEGREE or with non-positive
 * weights: loop validation keeps these from the readers, so only scenes
 * built in code meet it. */
int sc_trim_prepare(const sc_surface *s, sc_trim **out, sc_error *err);
void sc_trim_free(sc_trim *trim);

/* 1 when (u, v) is kept, 0 when it is trimmed away; a NULL trim keeps
 * everything. Safe to call from several threads at once. */
int sc_trim_inside(const sc_trim *trim, double u, double v);

/* Classifies a whole parameter rectangle: 1 when every point of it is
 * kept, 0 when every point is trimmed away, -1 when a trim piece's bounds
 * touch it (undecided). Lets a subdivision drop or stop testing whole
 * sub-patches; a NULL trim gives 1. */
int sc_trim_classify_rect(const sc_trim *trim, double u0, double u1, double v0, double v1);

/* The number of crossings of the ray from (u, v) towards +u with the
 * pieces (for tests and statistics). */
int sc_trim_crossings(const sc_trim *trim, double u, double v);

#endif
