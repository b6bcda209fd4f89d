/* nurbs.h — the NURBS core in double precision: knot spans, basis functions
 * and derivatives, curve and surface evaluation (rational by the quotient
 * rule), knot insertion and refinement, Bézier extraction, splitting, degree
 * elevation, restriction and reversal, and a normal that survives collapsed
 * edges. Algorithms follow Piegl & Tiller, The NURBS Book (A2.1–A2.3, A4.x,
 * A5.x). Evaluation is in nurbs.c, the operations in nurbs_ops.c, the
 * de Casteljau split of Bézier pieces in bezier.h. */
#ifndef SC_NURBS_H
#define SC_NURBS_H

#include "scene.h"

/* Index of the knot span holding u for a curve with n+1 = ncp control
 * points: knots[span] <= u < knots[span+1], with u at the domain's upper end
 * mapped to the last non-empty span. u is clamped into the domain. */
int sc_find_span(int degree, const double *knots, int ncp, double u);

/* The degree+1 non-zero basis functions at u in `span`. */
void sc_basis(int span, double u, int degree, const double *knots, double *N);

/* Basis functions and their derivatives up to order n (n <= degree
 * allowed; higher orders are zero): ders[k * (degree + 1) + j] is the k-th
 * derivative of N_{span-degree+j}. */
void sc_basis_ders(int span, double u, int degree, const double *knots, int n,
                   double *ders);

/* Curve point (dim coordinates, Euclidean) and, if d1 != NULL, the first
 * derivative. */
void sc_curve_eval(const sc_curve *c, double u, double *point, double *d1);
/* The curve's domain [knots[degree], knots[ncp]]. */
void sc_curve_domain(const sc_curve *c, double *t0, double *t1);

/* Surface point and first partials in object space (transform not applied);
 * su / sv may be NULL. */
void sc_surface_eval(const sc_surface *s, double u, double v, double p[3],
                     double su[3], double sv[3]);
/* Same with the surface's transform applied to point and partials. */
void sc_surface_eval_world(const sc_surface *s, double u, double v, double p[3],
                           double su[3], double sv[3]);
/* Unit object-space normal su × sv. Where that vanishes (a collapsed edge,
 * like the teapot's lid and bottom poles) the limit normal is taken from the
 * derivatives a small step inside the domain, so the result is always a unit
 * vector for a non-degenerate surface. Returns 0 on success, -1 when no
 * direction can be found (the whole surface is degenerate). */
int sc_surface_normal(const sc_surface *s, double u, double v, double n[3]);
void sc_surface_domain(const sc_surface *s, double *u0, double *u1, double *v0,
                       double *v1);

/* ---- curves: new curves written to *out (allocated; free with
 * sc_curve_free). `out` must not alias the input. Each returns SC_OK, or
 * SC_FAIL when memory runs out (a curve of a file can be as large as the
 * envelope allows): the outputs are then zeroed and nothing is left
 * allocated (sc_alloc_failed_bytes says how much was asked for). ---- */
/* Inserts u (in the closed domain, ends included) up to multiplicity
 * degree; more, or u outside the domain, leaves the curve as it is. */
int sc_curve_insert_knot(const sc_curve *c, double u, int times, sc_curve *out);
int sc_curve_refine(const sc_curve *c, const double *x, int nx, sc_curve *out);
/* Splits at t strictly inside the domain into [t0, t] and [t, t1]. */
int sc_curve_split(const sc_curve *c, double t, sc_curve *left, sc_curve *right);
int sc_curve_elevate(const sc_curve *c, int times, sc_curve *out);
/* The same curve on its domain [knots[degree], knots[ncp]] with clamped
 * knots: for an unclamped (uniform, periodic, ...) vector, both domain ends
 * inserted to multiplicity degree and the control points outside dropped;
 * a clamped curve (or one with an empty domain) is copied as it is. */
int sc_curve_clamp(const sc_curve *c, sc_curve *out);
/* ---- in place: these replace their argument (readers apply them to what
 * they have just built); on SC_FAIL the argument is as it was. ---- */
/* The clamped piece of the curve over [a, b]: an end outside the domain is
 * moved onto it, an end within 1e-10 of the domain's size of a knot is
 * that knot (no sliver spans), and an empty range keeps the whole domain
 * (the curve is then only clamped). */
int sc_curve_restrict(sc_curve *c, double a, double b);
/* The same curve run backwards on the same domain [a, b]: knots reflected
 * within it (k -> a + b - k, the ends exchanged exactly), control points in
 * reverse order. Allocates nothing. */
void sc_curve_reverse(sc_curve *c);
/* sc_curve_restrict along dir for every row (dir 0) or column (dir 1); the
 * result is clamped in both directions and keeps the trim loops, which
 * restriction does not move. SC_FAIL (s unchanged) when memory runs out. */
int sc_surface_try_restrict(sc_surface *s, int dir, double a, double b);

/* Bézier segments: *count segments written to a new array of curves, each
 * with degree+1 control points and knots [a..a b..b] keeping its original
 * parameter interval. */
int sc_curve_to_bezier(const sc_curve *c, sc_curve **segments, int *count);

/* ---- surfaces: dir 0 = u, 1 = v. New surfaces keep name, colour,
 * transform and rational flag; trim loops are not copied. These abort when
 * memory runs out (the stages after reading use them, on surfaces the
 * envelope has bounded), except the _try_ forms. ---- */
void sc_surface_insert_knot(const sc_surface *s, int dir, double t, int times,
                            sc_surface *out);
void sc_surface_refine(const sc_surface *s, int dir, const double *x, int nx,
                       sc_surface *out);
void sc_surface_split(const sc_surface *s, int dir, double t, sc_surface *lo,
                      sc_surface *hi);
void sc_surface_elevate(const sc_surface *s, int dir, int times, sc_surface *out);
/* sc_curve_clamp in both directions. */
void sc_surface_clamp(const sc_surface *s, sc_surface *out);
/* The same, failing (out zeroed) when memory runs out. */
int sc_surface_try_clamp(const sc_surface *s, sc_surface *out);

/* One Bézier patch of a surface, with its parameter rectangle in the
 * surface's own domain. cp layout as sc_surface: 4 doubles per point,
 * (deg_u+1)×(deg_v+1) points, u fastest. */
typedef struct sc_bezier_patch {
    int surface;              /* index of the surface in its scene */
    int deg_u, deg_v;
    double u0, u1, v0, v1;
    double *cp;
} sc_bezier_patch;

/* Extracts all Bézier patches of a surface (patches in u fastest order). */
void sc_surface_to_bezier(const sc_surface *s, sc_bezier_patch **patches,
                          int *count);
void sc_bezier_patch_free(sc_bezier_patch *p);

/* The Bézier patches of one surface in world space: sc_surface_to_bezier of
 * the surface with its transform baked in, `surface` set to its index. A
 * renderer decomposes each surface once this way and builds both the hulls
 * and the GPU records from the same list, so that patch p of a surface is
 * one thing to both. */
typedef struct sc_patch_list {
    int count;
    sc_bezier_patch *patches;
} sc_patch_list;

void sc_surface_world_patches(const sc_surface *s, int index, sc_patch_list *out);
void sc_patch_list_free(sc_patch_list *list);

#endif
