/* offset.c — an offset surface S + d·N as a NURBS (sc_offset_fit,
 * analytic.h). The offset of a NURBS surface is not a NURBS in general, so
 * it is fitted: bicubic Hermite patches from the offset's points and
 * derivatives on a grid that starts at the base surface's knot lines (each
 * cell inside one polynomial piece) and is refined until the fit is within
 * the tolerance of the offset at every cell's centre and edge midpoints. */
#include "analytic.h"
#include "nurbs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_CELLS = 128 }; /* per direction: 385 x 385 control points at most */

typedef struct offset {
    const sc_surface *s;
    double d, dom[4];
} offset;

static void offset_point(const offset *o, double u, double v, double out[3])
{
    double p[3], n[3];
    sc_surface_eval(o->s, u, v, p, NULL, NULL);
    if (sc_surface_normal(o->s, u, v, n))
        n[0] = n[1] = n[2] = 0;
    for (int k = 0; k < 3; k++)
        out[k] = p[k] + o->d * n[k];
}

/* Point, partials and twist of the offset by central differences, one
 * sided at the domain's ends. */
static void offset_jet(const offset *o, double u, double v, double jet[4][3])
{
    double hu = 1e-5 * (o->dom[1] - o->dom[0]), hv = 1e-5 * (o->dom[3] - o->dom[2]);
    double ua = fmax(u - hu, o->dom[0]), ub = fmin(u + hu, o->dom[1]);
    double va = fmax(v - hv, o->dom[2]), vb = fmin(v + hv, o->dom[3]);
    double p[2][2][3];
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++)
            offset_point(o, i ? ub : ua, j ? vb : va, p[j][i]);
    double pu0[3], pu1[3], pv0[3], pv1[3];
    offset_point(o, u, v, jet[0]);
    offset_point(o, ua, v, pu0);
    offset_point(o, ub, v, pu1);
    offset_point(o, u, va, pv0);
    offset_point(o, u, vb, pv1);
    for (int k = 0; k < 3; k++) {
        jet[1][k] = (pu1[k] - pu0[k]) / (ub - ua);
        jet[2][k] = (pv1[k] - pv0[k]) / (vb - va);
        jet[3][k] = (p[1][1][k] - p[1][0][k] - p[0][1][k] + p[0][0][k]) / ((ub - ua) * (vb - va));
    }
}

/* Distinct knots of one direction inside the domain, each cell cut into
 * `split` equal parts; at most MAX_CELLS cells (uniform beyond). */
static int grid_lines(const double *knots, int nk, double a, double b, int split, double *out)
{
    int n = 0;
    out[n++] = a;
    for (int i = 1; i < nk; i++) {
        double k = knots[i];
        if (k > out[n - 1] + 1e-12 * (b - a) && k < b - 1e-12 * (b - a)) {
            if (n * split >= MAX_CELLS)
                break;
            out[n++] = k;
        }
    }
    out[n++] = b;
    if ((n - 1) * split > MAX_CELLS) {
        int cells = MAX_CELLS;
        for (int i = 0; i <= cells; i++)
            out[i] = a + (b - a) * i / cells;
        return cells + 1;
    }
    double tmp[MAX_CELLS + 2];
    memcpy(tmp, out, sizeof(double) * (size_t)n);
    int m = 0;
    for (int i = 0; i + 1 < n; i++)
        for (int k = 0; k < split; k++)
            out[m++] = tmp[i] + (tmp[i + 1] - tmp[i]) * k / split;
    out[m++] = tmp[n - 1];
    return m;
}

/* The bicubic Hermite fit on the grid gu x gv; SC_FAIL when memory runs
 * out (up to 385 x 385 control points). */
static int hermite_fit(const offset *o, const double *gu, int nu, const double *gv, int nv,
                       sc_surface *out)
{
    memset(out, 0, sizeof *out);
    int cu = nu - 1, cv = nv - 1;
    if (sc_surface_try_alloc(out, 3, 3, 3 * cu + 1, 3 * cv + 1))
        return SC_FAIL;
    for (int k = 0; k < 4; k++) {
        out->knots_u[k] = gu[0];
        out->knots_u[3 * cu + 1 + k] = gu[cu];
        out->knots_v[k] = gv[0];
        out->knots_v[3 * cv + 1 + k] = gv[cv];
    }
    for (int i = 1; i < cu; i++)
        for (int k = 0; k < 3; k++)
            out->knots_u[3 * i + 1 + k] = gu[i];
    for (int j = 1; j < cv; j++)
        for (int k = 0; k < 3; k++)
            out->knots_v[3 * j + 1 + k] = gv[j];
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            double jet[4][3];
            offset_jet(o, gu[i], gv[j], jet);
            /* the four Bézier points around this corner, towards each
             * neighbouring cell */
            for (int su = -1; su <= 1; su += 2)
                for (int sv = -1; sv <= 1; sv += 2) {
                    int ci = su < 0 ? i - 1 : i, cj = sv < 0 ? j - 1 : j;
                    if (ci < 0 || ci >= cu || cj < 0 || cj >= cv)
                        continue;
                    /* a third of the cell, signed towards it */
                    double hu = (gu[ci + 1] - gu[ci]) / 3 * su, hv = (gv[cj + 1] - gv[cj]) / 3 * sv;
                    int ai = 3 * i, bj = 3 * j, ai1 = ai + su, bj1 = bj + sv;
                    double *q00 = out->cp + 4 * ((size_t)bj * out->nu + ai);
                    double *q10 = out->cp + 4 * ((size_t)bj * out->nu + ai1);
                    double *q01 = out->cp + 4 * ((size_t)bj1 * out->nu + ai);
                    double *q11 = out->cp + 4 * ((size_t)bj1 * out->nu + ai1);
                    for (int k = 0; k < 3; k++) {
                        q00[k] = jet[0][k];
                        q10[k] = jet[0][k] + hu * jet[1][k];
                        q01[k] = jet[0][k] + hv * jet[2][k];
                        q11[k] = jet[0][k] + hu * jet[1][k] + hv * jet[2][k] +
                                 hu * hv * jet[3][k];
                    }
                    q00[3] = q10[3] = q01[3] = q11[3] = 1;
                }
        }
    sc_surface_update_rational(out);
    return SC_OK;
}

static double fit_error(const offset *o, const sc_surface *fit, const double *gu, int nu,
                        const double *gv, int nv)
{
    static const double at[5][2] = {{0.5, 0.5}, {0.5, 0}, {0, 0.5}, {0.25, 0.75}, {0.75, 0.25}};
    double worst = 0;
    for (int j = 0; j + 1 < nv; j++)
        for (int i = 0; i + 1 < nu; i++)
            for (int k = 0; k < 5; k++) {
                double u = gu[i] + at[k][0] * (gu[i + 1] - gu[i]);
                double v = gv[j] + at[k][1] * (gv[j + 1] - gv[j]), a[3], b[3];
                offset_point(o, u, v, a);
                sc_surface_eval(fit, u, v, b, NULL, NULL);
                worst = fmax(worst, sqrt((a[0] - b[0]) * (a[0] - b[0]) +
                                         (a[1] - b[1]) * (a[1] - b[1]) +
                                         (a[2] - b[2]) * (a[2] - b[2])));
            }
    return worst;
}

int sc_offset_fit(const sc_surface *base, double d, double tol, sc_surface *out, double *dev)
{
    offset o = {.s = base, .d = d};
    sc_surface_domain(base, &o.dom[0], &o.dom[1], &o.dom[2], &o.dom[3]);
    double gu[MAX_CELLS + 2], gv[MAX_CELLS + 2];
    int status = SC_OFFSET_LOOSE;
    memset(out, 0, sizeof *out);
    *dev = 0;
    for (int split = 1; split <= MAX_CELLS; split *= 2) {
        int nu = grid_lines(base->knots_u, base->nu + base->deg_u + 1, o.dom[0], o.dom[1], split,
                            gu);
        int nv = grid_lines(base->knots_v, base->nv + base->deg_v + 1, o.dom[2], o.dom[3], split,
                            gv);
        sc_surface fit;
        if (hermite_fit(&o, gu, nu, gv, nv, &fit)) {
            status = SC_FAIL;
            break;
        }
        double err = fit_error(&o, &fit, gu, nu, gv, nv);
        int last = err <= tol || ((nu - 1) * 2 > MAX_CELLS && (nv - 1) * 2 > MAX_CELLS) ||
                   split == MAX_CELLS;
        if (last) {
            *out = fit;
            *dev = err;
            status = err <= tol ? SC_OK : SC_OFFSET_LOOSE;
            break;
        }
        sc_surface_free(&fit);
    }
    return status;
}
