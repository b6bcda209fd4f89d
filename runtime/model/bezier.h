/* bezier.h — de Casteljau subdivision of Bézier curves and patches, the one
 * split every part of the runtime uses: trim preparation and queries, trim
 * packing, loop flattening, hull refinement and the CPU reference's patch
 * subdivision. Points are homogeneous (rational curves split exactly) and
 * any number of doubles wide. */
#ifndef SC_BEZIER_H
#define SC_BEZIER_H

/* Splits the Bézier curve of `degree` in cp (points of `dim` doubles,
 * `stride` doubles apart) at t in [0, 1]: left receives the points of
 * [0, t], right those of [t, 1], with the same stride. Either may be NULL,
 * and either may be cp itself (the input is copied first). Every new point
 * is (1 − t)·a + t·b, so at t = ½ the halves are exact means: callers
 * relying on bit-identical results between runs get them. */
void sc_bezier_split(const double *cp, int degree, int dim, int stride, double t,
                     double *left, double *right);

/* The point at t of the same curve (dim doubles, homogeneous as given). */
void sc_bezier_point(const double *cp, int degree, int dim, int stride, double t,
                     double *out);

/* Splits a patch of (deg_u+1)×(deg_v+1) homogeneous points (4 doubles each,
 * u fastest) along dir (0: u, 1: v) at t: every row (or column) is split
 * by sc_bezier_split. lo gets [0, t] in that direction, hi [t, 1]; either
 * may be NULL; neither may alias cp. */
void sc_bezier_grid_split(const double *cp, int deg_u, int deg_v, int dir, double t,
                          double *lo, double *hi);

#endif
