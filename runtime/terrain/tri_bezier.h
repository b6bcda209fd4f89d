/* tri_bezier.h — triangular Bézier patches in double precision, and meshes
 * of them over a type-1 triangulation of a rectangle: the form in which the
 * spline schemes of splines.h (seed 004, sections III–IV) hand height fields
 * to the rest of splinecast. Heights are along z; a patch is its domain
 * triangle in the xy plane and its BB-coefficients, so that the renderer can
 * later pack "domain triangle + 15 coefficients" per quartic patch. */
#ifndef SC_TRI_BEZIER_H
#define SC_TRI_BEZIER_H

#include "sc_base.h"

/* Degrees up to this work everywhere (fixed-size scratch arrays). */
#define SC_TRI_MAX_DEGREE 8
#define SC_TRI_MAX_COEF ((SC_TRI_MAX_DEGREE + 1) * (SC_TRI_MAX_DEGREE + 2) / 2)

/* Number of BB-coefficients of degree n: (n+1)(n+2)/2 (15 for quartics). */
static inline int sc_tri_ncoef(int n) { return (n + 1) * (n + 2) / 2; }

/* Index of b_ijk (k = n - i - j) in a coefficient array. Rows run by
 * falling i (row r = n - i), and within a row by rising k, so the first
 * coefficient is b_n00 (at vertex 0), the last b_00n (at vertex 2). The
 * domain point of b_ijk is (i v0 + j v1 + k v2) / n. */
static inline int sc_tri_index(int n, int i, int j)
{
    int r = n - i, k = n - i - j;
    return r * (r + 1) / 2 + k;
}

/* Barycentric coordinates of (x, y) in the triangle tri = {x0,y0,x1,y1,x2,y2}. */
void sc_tri_barycentric(const double tri[6], double x, double y, double bary[3]);

/* Value, gradient and Hessian of a patch at a point of the plane. */
typedef struct sc_tri_point {
    double value;
    double grad[2];       /* d/dx, d/dy */
    double hess[3];       /* d2/dx2, d2/dxdy, d2/dy2 */
} sc_tri_point;

/* Evaluates the patch of degree n (1..SC_TRI_MAX_DEGREE) with coefficients
 * coef over tri at (x, y) by de Casteljau's algorithm (points outside the
 * triangle extrapolate the polynomial). The gradient comes from the last
 * step (n b^{n-1}_e grad(lambda_e)), the Hessian from the step before. */
void sc_tri_eval(int n, const double *coef, const double tri[6], double x, double y,
                 sc_tri_point *out);

/* Degree elevation n -> n+1 (the same polynomial): out has
 * sc_tri_ncoef(n + 1) entries. */
void sc_tri_elevate(int n, const double *in, double *out);

/* The matrix that turns the values of a degree-n polynomial at the
 * domain points (ordered as the coefficients) into its BB-coefficients: the
 * inverse of the Bernstein collocation matrix, which does not depend on
 * the triangle. inv holds sc_tri_ncoef(n)^2 entries, row-major. */
int sc_tri_interp_matrix(int n, double *inv, sc_error *err);

/* The same for values at arbitrary points given by barycentric coordinates
 * (bary: 3 per point, sc_tri_ncoef(n) points): fails when they are not
 * unisolvent. */
int sc_tri_collocation_inverse(int n, const double *bary, double *inv, sc_error *err);

/* A mesh of triangular patches on the type-1 triangulation of an nx x ny
 * grid of squares (each cut by the diagonal from its lower-left to its
 * upper-right corner). Square (i, j) has its lower-left corner at
 * (x0 + i hx, y0 + j hy); its patches are 2 (j nx + i) (lower, vertices
 * lower-left, lower-right, upper-right) and that + 1 (upper, vertices
 * lower-left, upper-right, upper-left), both counter-clockwise. */
typedef struct sc_tri_mesh {
    int degree, ncoef;
    int nx, ny;
    double x0, y0, hx, hy;
    int count;            /* 2 nx ny */
    double *coef;         /* count * ncoef */
} sc_tri_mesh;

/* Allocates coefficients (zeroed) for the given layout; SC_FAIL (m empty)
 * when memory runs out. */
int sc_tri_mesh_init(sc_tri_mesh *m, int degree, int nx, int ny, double x0, double y0,
                      double hx, double hy);
void sc_tri_mesh_free(sc_tri_mesh *m);
/* The domain triangle of patch p. */
void sc_tri_mesh_domain(const sc_tri_mesh *m, int p, double tri[6]);
/* The patch whose closed domain holds (x, y), or -1 outside the mesh
 * (points on a shared edge go to one of the patches). */
int sc_tri_mesh_locate(const sc_tri_mesh *m, double x, double y);
/* Evaluates the mesh at (x, y); SC_FAIL (no error record: a query, not
 * an input error) outside. */
int sc_tri_mesh_eval(const sc_tri_mesh *m, double x, double y, sc_tri_point *out);

#endif
