/* analytic.h — exact NURBS forms of the analytic curves and surfaces that
 * CAD files name (circle and ellipse arcs as rational quadratics, planes,
 * surfaces of revolution — cylinders, cones, spheres, tori —, extrusions,
 * ruled surfaces), closed surfaces whose trims cross their seam, and the
 * projection of model-space (3D) trim loops into a surface's parameter
 * space (project.c). Any reader can use them: they know no file format. */
#ifndef SC_ANALYTIC_H
#define SC_ANALYTIC_H

#include "scene.h"

/* The constructions allocate what a file's numbers ask for: each returns
 * SC_OK, or SC_FAIL when memory runs out, with its output zeroed and
 * nothing left allocated (sc_alloc_failed_bytes says how much was asked
 * for); the codes below are their other outcomes. */
enum {
    SC_JOIN_APART = 1,   /* sc_curve_join: an end misses the next start */
    SC_OFFSET_LOOSE = 1, /* sc_offset_fit: the best fit misses the tolerance */
    SC_PROJECT_OFF = 1   /* sc_project_loop: the curves do not lie on the surface */
};

/* 3D line from p0 (t = 0) to p1 (t = 1), degree 1. */
int sc_line3(const double p0[3], const double p1[3], sc_curve *out);
/* The arc c + rx·cos(a)·x + ry·sin(a)·y for a from a0 to a1 (a1 > a0,
 * at most 2π apart; x and y orthonormal) in `dim` 2 or 3 (dim 2 uses the
 * first two coordinates): rational quadratic pieces of at most 90°, middle
 * weights cos(half the piece), parameter 0..pieces. A circle has rx = ry. */
int sc_ellipse_arc(int dim, const double c[3], const double x[3], const double y[3], double rx,
                   double ry, double a0, double a1, sc_curve *out);
/* The plane o + u·x + v·y over [u0, u1] × [v0, v1] (bilinear). */
int sc_plane_patch(const double o[3], const double x[3], const double y[3], double u0,
                   double u1, double v0, double v1, sc_surface *out);
/* The 3D curve `gen` turned about the axis through o along the unit
 * vector `axis` from angle a0 to a1 (right-handed, the curve at angle 0):
 * u is the curve's parameter, v the arc's (as sc_ellipse_arc). */
int sc_revolve(const sc_curve *gen, const double o[3], const double axis[3], double a0,
               double a1, sc_surface *out);
/* c(u) + v·d, v in [0, 1]: a tabulated cylinder. */
int sc_extrude(const sc_curve *c, const double d[3], sc_surface *out);
/* (1 − v)·a(s) + v·b(s), both curves taken on [0, 1] (their own domains
 * mapped linearly), made compatible by degree elevation and knot merging:
 * exact. */
int sc_ruled(const sc_curve *a, const sc_curve *b, sc_surface *out);
/* Curves joined end to end into one (C0 at the joints, degree raised to
 * the highest, each on [k, k + 1], each later curve's homogeneous
 * coordinates scaled so that the weights agree where it meets the one
 * before). Returns SC_JOIN_APART when an end misses the next start by
 * more than 1e-6 of the curves' size. */
int sc_curve_join(const sc_curve *curves, int n, sc_curve *out);
/* The curve's knots mapped linearly onto [t0, t1] (the shape unchanged). */
void sc_curve_reparam(sc_curve *c, double t0, double t1);

/* The offset surface base + d·N (N the unit normal su × sv) fitted as a
 * piecewise bicubic (the one construction here that is not exact):
 * refined until the fit is within tol of the offset at every check; *dev
 * the largest distance measured. SC_OFFSET_LOOSE (with the best fit in
 * *out and its *dev) when 128 x 128 cells do not reach tol. */
int sc_offset_fit(const sc_surface *base, double d, double tol, sc_surface *out, double *dev);

/* Whether the surface closes on itself along dir (0 = u): the first and
 * last rows of control points coincide. */
int sc_surface_closed(const sc_surface *s, int dir);
/* Trims of a closed surface may run across its seam (a torus trimmed at
 * u in [-π/2, π/2] on a [0, 2π] domain): the surface is then extended by
 * whole periods and restricted to the trims' range, so that every trimmed
 * point has its own parameters. The shape is unchanged. */
int sc_surface_unwrap_seams(sc_surface *s);

/* ---- model-space trim loops (project.c) ---- */
/* Projects a closed chain of 3D curves lying on the surface (object space,
 * in chain order, each starting where the previous ends) into its
 * parameter space: closest points along each curve, refined until the
 * surface at the fitted parameter-space curve is within `tol` of the 3D
 * curve at every check, then fitted as piecewise cubic B-splines (one 2D
 * curve per 3D curve, on the 3D curve's parameter). Across a closed
 * surface's seam the parameters run on (sc_surface_unwrap_seams then
 * extends the surface); where consecutive curves meet in 3D but not in
 * (u, v) (a pole, a seam), a straight segment joins them. *out gets *nout
 * curves (free each, then the array); *dev the largest deviation measured.
 * Work and memory are bounded (at most 4096 pieces per curve). The
 * distance a curve keeps from the surface (an edge a file gives slightly
 * off its face) is not refined away but counted in *dev. Returns SC_OK,
 * or SC_PROJECT_OFF (*out empty) when *dev passes off_limit: the curves do
 * not lie on the surface. */
int sc_project_loop(const sc_surface *s, const sc_curve *curves, int n, double tol,
                    double off_limit, sc_curve **out, int *nout, double *dev);

#endif
