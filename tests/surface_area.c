/* surface_area.c — the trimmed area of a surface, integrated over our
 * scene model with our trim data: Gauss-Legendre in v between breaks at
 * the knots and at the ends of the v-monotone trim pieces of sc_trim (so
 * that the kept length along u varies smoothly between breaks), and along
 * each v line Gauss-Legendre over the intervals between the knots and the
 * pieces' crossings, each kept or not as our exact trim test
 * (sc_trim_inside) says at its middle. The integrand |Su x Sv| is smooth
 * inside a knot span, so the result is accurate to far below the 1e-3 of
 * the check. */
#include "surface_area.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs.h"
#include "trim.h"

#define GAUSS_N 8
/* Pieces of each interval between v breaks: a surface's derivatives can
 * vary a lot over one long knot span (OCC131-2.igs needs 8 for 1e-6). */
#define V_CUTS 8

static const double gx[GAUSS_N] = {-0.9602898564975363, -0.7966664774136267,
                                   -0.5255324099163290, -0.1834346424956498,
                                   0.1834346424956498,  0.5255324099163290,
                                   0.7966664774136267,  0.9602898564975363};
static const double gw[GAUSS_N] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                   0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};

/* Distinct knots inside [lo, hi], ends included. */
static int breakpoints(const double *k, int n, double lo, double hi, double *out)
{
    int m = 0;
    for (int i = 0; i < n; i++)
        if (k[i] >= lo && k[i] <= hi && (m == 0 || k[i] > out[m - 1]))
            out[m++] = k[i];
    return m;
}

/* Adds the integral over u in [a, b] at v of |Su x Sv| (and of P times
 * it) with Gauss nodes, weighted by wv. */
static void add_u_interval(const sc_surface *s, double v, double wv, double a, double b,
                           double *area, double c[3])
{
    double h = 0.5 * (b - a), m = 0.5 * (a + b);
    for (int k = 0; k < GAUSS_N; k++) {
        double p[3], su[3], sv[3];
        sc_surface_eval_world(s, m + h * gx[k], v, p, su, sv);
        double n[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2],
                       su[0] * sv[1] - su[1] * sv[0]};
        double da = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) * h * gw[k] * wv;
        *area += da;
        for (int d = 0; d < 3; d++)
            c[d] += p[d] * da;
    }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Sorted, with values closer than tol merged. Returns the new count. */
static int sort_unique(double *x, int n, double tol)
{
    qsort(x, (size_t)n, sizeof *x, cmp_double);
    int m = 0;
    for (int i = 0; i < n; i++)
        if (m == 0 || x[i] - x[m - 1] > tol)
            x[m++] = x[i];
    return m;
}

/* A v-monotone piece's point at t (de Casteljau on the homogeneous
 * control points), as (u, v). */
static void piece_eval(const sc_trim_piece *p, double t, double *u, double *v)
{
    double q[3 * (SC_TRIM_MAX_DEGREE + 1)];
    memcpy(q, p->cp, sizeof(double) * 3 * (size_t)(p->degree + 1));
    for (int r = 1; r <= p->degree; r++)
        for (int i = 0; i <= p->degree - r; i++)
            for (int d = 0; d < 3; d++)
                q[3 * i + d] = (1 - t) * q[3 * i + d] + t * q[3 * (i + 1) + d];
    *u = q[0] / q[2];
    *v = q[1] / q[2];
}

/* The u where piece p crosses the line v (v_lo <= v < v_hi): v grows with
 * the piece's parameter, so bisection finds it. */
static double piece_crossing(const sc_trim_piece *p, double v)
{
    double lo = 0, hi = 1, u, pv;
    for (int it = 0; it < 60; it++) {
        double mid = 0.5 * (lo + hi);
        piece_eval(p, mid, &u, &pv);
        if (pv < v)
            lo = mid;
        else
            hi = mid;
    }
    piece_eval(p, 0.5 * (lo + hi), &u, &pv);
    return u;
}

int surface_trimmed_area(const sc_surface *s, double *area, double centroid[3])
{
    sc_trim *trim = NULL;
    sc_error err;
    if (sc_trim_prepare(s, &trim, &err))
        return SC_FAIL;
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    int npieces = trim ? trim->npieces : 0;
    double *ub = malloc(sizeof(double) * (size_t)(s->nu + s->deg_u + 1));
    double *vb = malloc(sizeof(double) * (size_t)(s->nv + s->deg_v + 1 + 2 * npieces));
    double *us = malloc(sizeof(double) * (size_t)(s->nu + s->deg_u + 1 + npieces));
    int nub = breakpoints(s->knots_u, s->nu + s->deg_u + 1, u0, u1, ub);
    /* v breaks: the knots and the ends of every v-monotone trim piece, so
     * that between two breaks the same pieces cross each v line, each at
     * a u that moves smoothly with v */
    int nvb = breakpoints(s->knots_v, s->nv + s->deg_v + 1, v0, v1, vb);
    for (int k = 0; k < npieces; k++) {
        const sc_trim_piece *p = &trim->pieces[k];
        if (p->v_lo > v0 && p->v_lo < v1)
            vb[nvb++] = p->v_lo;
        if (p->v_hi > v0 && p->v_hi < v1)
            vb[nvb++] = p->v_hi;
    }
    nvb = sort_unique(vb, nvb, 1e-12 * (v1 - v0));
    double a = 0, c[3] = {0, 0, 0};
    for (int j = 0; j + 1 < nvb; j++)
        for (int cut = 0; cut < V_CUTS; cut++) {
            double va = vb[j] + (vb[j + 1] - vb[j]) * cut / V_CUTS;
            double vl = (vb[j + 1] - vb[j]) / V_CUTS;
            for (int g = 0; g < GAUSS_N; g++) {
                /* v = va + vl (3t^2 - 2t^3): where a trim curve turns at a
                 * break, the kept length goes like the square root of the
                 * distance in v; this substitution makes it smooth */
                double t = 0.5 * (1 + gx[g]);
                double v = va + vl * t * t * (3 - 2 * t);
                double wv = 0.5 * gw[g] * vl * 6 * t * (1 - t);
                /* the line's cuts: knots and trim crossings; each piece
                 * between two cuts is kept or not as a whole, which our
                 * trim test tells at its middle */
                int nus = 0;
                for (int i = 0; i < nub; i++)
                    us[nus++] = ub[i];
                for (int k = 0; k < npieces; k++) {
                    const sc_trim_piece *p = &trim->pieces[k];
                    if (!(v >= p->v_lo && v < p->v_hi))
                        continue;
                    double u = piece_crossing(p, v);
                    if (u > u0 && u < u1)
                        us[nus++] = u;
                }
                nus = sort_unique(us, nus, 1e-13 * (u1 - u0));
                for (int i = 0; i + 1 < nus; i++)
                    if (sc_trim_inside(trim, 0.5 * (us[i] + us[i + 1]), v))
                        add_u_interval(s, v, wv, us[i], us[i + 1], &a, c);
            }
        }
    free(ub);
    free(vb);
    free(us);
    sc_trim_free(trim);
    *area = a;
    for (int d = 0; d < 3; d++)
        centroid[d] = a > 0 ? c[d] / a : 0;
    return SC_OK;
}
