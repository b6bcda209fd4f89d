/* small_hull.h — the convex hull of a sub-patch's few control points
 * (16 for a bicubic piece), without qhull: an incremental hull in double
 * precision whose result is checked before it is used, so that a hull it
 * returns bounds every point. qhull's set-up costs tens of microseconds a
 * call; this costs a few, which is what lets sc_update_surface rebuild the
 * hulls of every surface each frame (docs/speed.md, "Updating surfaces").
 * Points it cannot decide (flat or nearly flat sets, or a horizon that is
 * not one loop) are refused, and hulls.c gives them to qhull. */
#ifndef SC_SMALL_HULL_H
#define SC_SMALL_HULL_H

/* The hull of n points (xyz, relative to their middle; size: the diagonal
 * of their box). On success stores its triangles, 3 point numbers each,
 * counter-clockwise seen from outside, in *tris (allocated; the caller
 * frees it) and returns their count; -1 when refused. */
int sc_small_hull(const double *coords, int n, double size, int **tris);

/* Whether the ntris triangles bound the n points: every point on or behind
 * the plane of every triangle, to 1e-9 of size (far below the float
 * precision the GPU draws hulls in), and the surface enclosing a positive
 * volume (not turned inside out). */
int sc_small_hull_bounds(const double *coords, int n, const int *tris, int ntris, double size);

#endif
