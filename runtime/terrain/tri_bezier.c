/* tri_bezier.c — evaluation, degree elevation and interpolation of
 * triangular Bézier patches (de Casteljau in barycentric coordinates), and
 * the type-1 mesh of patches that the spline schemes fill. */
#include "tri_bezier.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sc_tri_barycentric(const double tri[6], double x, double y, double bary[3])
{
    double d = (tri[2] - tri[0]) * (tri[5] - tri[1]) - (tri[4] - tri[0]) * (tri[3] - tri[1]);
    bary[0] = ((tri[2] - x) * (tri[5] - y) - (tri[4] - x) * (tri[3] - y)) / d;
    bary[1] = ((tri[4] - x) * (tri[1] - y) - (tri[0] - x) * (tri[5] - y)) / d;
    bary[2] = 1.0 - bary[0] - bary[1];
}

/* Gradients of the three barycentric coordinates (constant on the plane). */
static void bary_gradients(const double tri[6], double g[3][2])
{
    double d = (tri[2] - tri[0]) * (tri[5] - tri[1]) - (tri[4] - tri[0]) * (tri[3] - tri[1]);
    g[0][0] = (tri[3] - tri[5]) / d; g[0][1] = (tri[4] - tri[2]) / d;
    g[1][0] = (tri[5] - tri[1]) / d; g[1][1] = (tri[0] - tri[4]) / d;
    g[2][0] = (tri[1] - tri[3]) / d; g[2][1] = (tri[2] - tri[0]) / d;
}

/* One de Casteljau step: degree r coefficients to degree r-1. */
static void casteljau_step(int r, const double *in, const double l[3], double *out)
{
    for (int i = 0; i < r; i++)
        for (int j = 0; i + j < r; j++)
            out[sc_tri_index(r - 1, i, j)] = l[0] * in[sc_tri_index(r, i + 1, j)]
                                           + l[1] * in[sc_tri_index(r, i, j + 1)]
                                           + l[2] * in[sc_tri_index(r, i, j)];
}

void sc_tri_eval(int n, const double *coef, const double tri[6], double x, double y,
                 sc_tri_point *out)
{
    double l[3], g[3][2], a[SC_TRI_MAX_COEF], b[SC_TRI_MAX_COEF];
    sc_tri_barycentric(tri, x, y, l);
    bary_gradients(tri, g);
    memset(out, 0, sizeof *out);
    memcpy(a, coef, (size_t)sc_tri_ncoef(n) * sizeof *a);
    /* Down to degree 2 (the Hessian's net), then 1 (the gradient's). */
    int r = n;
    for (; r > 2; r--) {
        casteljau_step(r, a, l, b);
        memcpy(a, b, (size_t)sc_tri_ncoef(r - 1) * sizeof *a);
    }
    double lin[3];
    if (n >= 2) {
        /* a holds b^{n-2}: six coefficients of degree 2. */
        double q[3][3];   /* q[e][f] = b^{n-2}_{e+f} */
        for (int e = 0; e < 3; e++)
            for (int f = 0; f < 3; f++) {
                int ii = (e == 0) + (f == 0), jj = (e == 1) + (f == 1);
                q[e][f] = a[sc_tri_index(2, ii, jj)];
            }
        double s = (double)n * (n - 1);
        for (int e = 0; e < 3; e++)
            for (int f = 0; f < 3; f++) {
                out->hess[0] += s * q[e][f] * g[e][0] * g[f][0];
                out->hess[1] += s * q[e][f] * g[e][0] * g[f][1];
                out->hess[2] += s * q[e][f] * g[e][1] * g[f][1];
            }
        casteljau_step(2, a, l, b);
        lin[0] = b[sc_tri_index(1, 1, 0)];
        lin[1] = b[sc_tri_index(1, 0, 1)];
        lin[2] = b[sc_tri_index(1, 0, 0)];
    } else {
        lin[0] = a[sc_tri_index(1, 1, 0)];
        lin[1] = a[sc_tri_index(1, 0, 1)];
        lin[2] = a[sc_tri_index(1, 0, 0)];
    }
    out->value = l[0] * lin[0] + l[1] * lin[1] + l[2] * lin[2];
    for (int e = 0; e < 3; e++) {
        out->grad[0] += n * lin[e] * g[e][0];
        out->grad[1] += n * lin[e] * g[e][1];
    }
}

void sc_tri_elevate(int n, const double *in, double *out)
{
    int m = n + 1;
    for (int i = 0; i <= m; i++)
        for (int j = 0; i + j <= m; j++) {
            int k = m - i - j;
            double s = 0;
            if (i > 0) s += i * in[sc_tri_index(n, i - 1, j)];
            if (j > 0) s += j * in[sc_tri_index(n, i, j - 1)];
            if (k > 0) s += k * in[sc_tri_index(n, i, j)];
            out[sc_tri_index(m, i, j)] = s / m;
        }
}

static double bernstein(int n, int i, int j, const double l[3])
{
    int k = n - i - j;
    double c = 1;   /* n! / (i! j! k!) */
    for (int t = 2; t <= n; t++) c *= t;
    for (int t = 2; t <= i; t++) c /= t;
    for (int t = 2; t <= j; t++) c /= t;
    for (int t = 2; t <= k; t++) c /= t;
    return c * pow(l[0], i) * pow(l[1], j) * pow(l[2], k);
}

/* Inverts the n x n matrix a (destroyed) into inv by Gauss-Jordan with
 * partial pivoting; fails on a (numerically) singular matrix. */
static int invert(int n, double *a, double *inv, sc_error *err)
{
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++) inv[r * n + c] = (r == c);
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(a[r * n + c]) > fabs(a[p * n + c])) p = r;
        if (fabs(a[p * n + c]) < 1e-12)
            return sc_fail(err, NULL, 0, "collocation points are not unisolvent");
        for (int t = 0; t < n; t++) {
            double u = a[c * n + t]; a[c * n + t] = a[p * n + t]; a[p * n + t] = u;
            u = inv[c * n + t]; inv[c * n + t] = inv[p * n + t]; inv[p * n + t] = u;
        }
        double d = a[c * n + c];
        for (int t = 0; t < n; t++) { a[c * n + t] /= d; inv[c * n + t] /= d; }
        for (int r = 0; r < n; r++) {
            if (r == c || a[r * n + c] == 0) continue;
            double f = a[r * n + c];
            for (int t = 0; t < n; t++) {
                a[r * n + t] -= f * a[c * n + t];
                inv[r * n + t] -= f * inv[c * n + t];
            }
        }
    }
    return SC_OK;
}

int sc_tri_collocation_inverse(int n, const double *bary, double *inv, sc_error *err)
{
    if (n < 1 || n > SC_TRI_MAX_DEGREE)
        return sc_fail(err, NULL, 0, "triangular patch degree %d is not in 1..%d", n,
                       SC_TRI_MAX_DEGREE);
    int nc = sc_tri_ncoef(n);
    double *a = sc_alloc((size_t)nc * nc, sizeof *a);
    for (int p = 0; p < nc; p++)
        for (int i = 0; i <= n; i++)
            for (int j = 0; i + j <= n; j++)
                a[p * nc + sc_tri_index(n, i, j)] = bernstein(n, i, j, bary + 3 * p);
    int rc = invert(nc, a, inv, err);
    free(a);
    return rc;
}

int sc_tri_interp_matrix(int n, double *inv, sc_error *err)
{
    if (n < 1 || n > SC_TRI_MAX_DEGREE)
        return sc_fail(err, NULL, 0, "triangular patch degree %d is not in 1..%d", n,
                       SC_TRI_MAX_DEGREE);
    double bary[3 * SC_TRI_MAX_COEF];
    for (int i = 0; i <= n; i++)
        for (int j = 0; i + j <= n; j++) {
            double *b = bary + 3 * sc_tri_index(n, i, j);
            b[0] = (double)i / n; b[1] = (double)j / n; b[2] = (double)(n - i - j) / n;
        }
    return sc_tri_collocation_inverse(n, bary, inv, err);
}

int sc_tri_mesh_init(sc_tri_mesh *m, int degree, int nx, int ny, double x0, double y0,
                     double hx, double hy)
{
    memset(m, 0, sizeof *m);
    m->degree = degree;
    m->ncoef = sc_tri_ncoef(degree);
    m->nx = nx; m->ny = ny;
    m->x0 = x0; m->y0 = y0; m->hx = hx; m->hy = hy;
    m->count = 2 * nx * ny;
    m->coef = sc_try_alloc((size_t)m->count * m->ncoef, sizeof *m->coef);
    if (!m->coef) {
        memset(m, 0, sizeof *m);
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_tri_mesh_free(sc_tri_mesh *m)
{
    free(m->coef);
    memset(m, 0, sizeof *m);
}

void sc_tri_mesh_domain(const sc_tri_mesh *m, int p, double tri[6])
{
    int sq = p / 2, i = sq % m->nx, j = sq / m->nx;
    double xa = m->x0 + i * m->hx, ya = m->y0 + j * m->hy;
    double xb = xa + m->hx, yb = ya + m->hy;
    tri[0] = xa; tri[1] = ya;
    if (p % 2 == 0) { tri[2] = xb; tri[3] = ya; tri[4] = xb; tri[5] = yb; }
    else            { tri[2] = xb; tri[3] = yb; tri[4] = xa; tri[5] = yb; }
}

int sc_tri_mesh_locate(const sc_tri_mesh *m, double x, double y)
{
    double s = (x - m->x0) / m->hx, t = (y - m->y0) / m->hy;
    if (!(s >= 0 && t >= 0 && s <= m->nx && t <= m->ny)) return -1;
    int i = (int)s, j = (int)t;
    if (i == m->nx) i--;
    if (j == m->ny) j--;
    /* Below the diagonal of the square: the lower patch. */
    int upper = (t - j) > (s - i);
    return 2 * (j * m->nx + i) + upper;
}

int sc_tri_mesh_eval(const sc_tri_mesh *m, double x, double y, sc_tri_point *out)
{
    int p = sc_tri_mesh_locate(m, x, y);
    if (p < 0) return SC_FAIL;
    double tri[6];
    sc_tri_mesh_domain(m, p, tri);
    sc_tri_eval(m->degree, m->coef + (size_t)p * m->ncoef, tri, x, y, out);
    return SC_OK;
}
