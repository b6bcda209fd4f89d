/* analytic.c — the analytic curves and surfaces of CAD files as exact NURBS
 * (analytic.h): arcs as rational quadratics, planes, revolution (the
 * cylinders, cones, spheres and tori of IGES and STEP are revolved lines
 * and arcs), extrusion and ruled surfaces; and closed surfaces whose trims
 * run across the seam. */
#include "analytic.h"
#include "nurbs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { MAX_ARC_PIECES = 4 };

/* A unit arc from a0 to a1: pieces of at most 90°, 2·pieces+1 points
 * (cos, sin) scaled by 1/w at the middle points, homogeneous weights w. */
typedef struct unit_arc {
    int pieces, n;
    double xy[2 * MAX_ARC_PIECES + 1][2], w[2 * MAX_ARC_PIECES + 1];
} unit_arc;

static void unit_arc_make(double a0, double a1, unit_arc *a)
{
    double sweep = a1 - a0;
    if (sweep > 2 * M_PI)
        sweep = 2 * M_PI;
    int pieces = (int)ceil(sweep / (M_PI / 2) - 1e-9);
    pieces = pieces < 1 ? 1 : pieces > MAX_ARC_PIECES ? MAX_ARC_PIECES : pieces;
    double half = sweep / pieces / 2, wm = cos(half);
    a->pieces = pieces;
    a->n = 2 * pieces + 1;
    for (int i = 0; i < a->n; i++) {
        double angle = a0 + i * half, reach = i % 2 ? 1 / wm : 1;
        a->xy[i][0] = reach * cos(angle);
        a->xy[i][1] = reach * sin(angle);
        a->w[i] = i % 2 ? wm : 1;
    }
}

/* Knots 0,0,0,1,1,...,pieces,pieces,pieces of a quadratic arc. */
static void arc_knots(int pieces, double *k)
{
    for (int i = 0; i < 3; i++) {
        k[i] = 0;
        k[2 * pieces + 1 + i] = pieces;
    }
    for (int i = 1; i < pieces; i++)
        k[2 * i + 1] = k[2 * i + 2] = i;
}

int sc_line3(const double p0[3], const double p1[3], sc_curve *out)
{
    if (sc_curve_try_alloc(out, 3, 1, 2))
        return SC_FAIL;
    out->knots[0] = out->knots[1] = 0;
    out->knots[2] = out->knots[3] = 1;
    for (int d = 0; d < 3; d++) {
        out->cp[d] = p0[d];
        out->cp[4 + d] = p1[d];
    }
    out->cp[3] = out->cp[7] = 1;
    return SC_OK;
}

int sc_ellipse_arc(int dim, const double c[3], const double x[3], const double y[3], double rx,
                   double ry, double a0, double a1, sc_curve *out)
{
    unit_arc a;
    unit_arc_make(a0, a1, &a);
    if (sc_curve_try_alloc(out, dim, 2, a.n))
        return SC_FAIL;
    arc_knots(a.pieces, out->knots);
    for (int i = 0; i < a.n; i++) {
        double *q = out->cp + (size_t)(dim + 1) * i, w = a.w[i];
        for (int d = 0; d < dim; d++)
            q[d] = (c[d] + rx * a.xy[i][0] * x[d] + ry * a.xy[i][1] * y[d]) * w;
        q[dim] = w;
    }
    return SC_OK;
}

int sc_plane_patch(const double o[3], const double x[3], const double y[3], double u0,
                   double u1, double v0, double v1, sc_surface *out)
{
    memset(out, 0, sizeof *out);
    if (sc_surface_try_alloc(out, 1, 1, 2, 2))
        return SC_FAIL;
    out->knots_u[0] = out->knots_u[1] = u0;
    out->knots_u[2] = out->knots_u[3] = u1;
    out->knots_v[0] = out->knots_v[1] = v0;
    out->knots_v[2] = out->knots_v[3] = v1;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            double *q = out->cp + 4 * (2 * j + i), u = i ? u1 : u0, v = j ? v1 : v0;
            for (int d = 0; d < 3; d++)
                q[d] = o[d] + u * x[d] + v * y[d];
            q[3] = 1;
        }
    sc_surface_update_rational(out);
    return SC_OK;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int sc_revolve(const sc_curve *gen, const double o[3], const double axis[3], double a0,
               double a1, sc_surface *out)
{
    unit_arc a;
    unit_arc_make(a0, a1, &a);
    memset(out, 0, sizeof *out);
    if (sc_surface_try_alloc(out, gen->degree, 2, gen->ncp, a.n))
        return SC_FAIL;
    memcpy(out->knots_u, gen->knots, sizeof(double) * (size_t)(gen->ncp + gen->degree + 1));
    arc_knots(a.pieces, out->knots_v);
    for (int i = 0; i < gen->ncp; i++) {
        const double *g = gen->cp + 4 * i;
        double wg = g[3], p[3], rel[3], foot[3], X[3], Y[3];
        for (int d = 0; d < 3; d++)
            p[d] = g[d] / wg;
        for (int d = 0; d < 3; d++)
            rel[d] = p[d] - o[d];
        double h = dot3(rel, axis);
        for (int d = 0; d < 3; d++) {
            foot[d] = o[d] + h * axis[d];
            X[d] = p[d] - foot[d];
        }
        double r = sqrt(dot3(X, X));
        if (r > 0)
            for (int d = 0; d < 3; d++)
                X[d] /= r;
        Y[0] = axis[1] * X[2] - axis[2] * X[1];
        Y[1] = axis[2] * X[0] - axis[0] * X[2];
        Y[2] = axis[0] * X[1] - axis[1] * X[0];
        for (int j = 0; j < a.n; j++) {
            double *q = out->cp + 4 * ((size_t)j * gen->ncp + i), w = wg * a.w[j];
            for (int d = 0; d < 3; d++)
                q[d] = (foot[d] + r * (a.xy[j][0] * X[d] + a.xy[j][1] * Y[d])) * w;
            q[3] = w;
        }
    }
    sc_surface_update_rational(out);
    return SC_OK;
}

int sc_extrude(const sc_curve *c, const double dvec[3], sc_surface *out)
{
    memset(out, 0, sizeof *out);
    if (sc_surface_try_alloc(out, c->degree, 1, c->ncp, 2))
        return SC_FAIL;
    memcpy(out->knots_u, c->knots, sizeof(double) * (size_t)(c->ncp + c->degree + 1));
    out->knots_v[0] = out->knots_v[1] = 0;
    out->knots_v[2] = out->knots_v[3] = 1;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < c->ncp; i++) {
            const double *g = c->cp + 4 * i;
            double *q = out->cp + 4 * ((size_t)j * c->ncp + i);
            for (int d = 0; d < 3; d++)
                q[d] = g[d] + j * dvec[d] * g[3];
            q[3] = g[3];
        }
    sc_surface_update_rational(out);
    return SC_OK;
}

void sc_curve_reparam(sc_curve *c, double t0, double t1)
{
    int nk = c->ncp + c->degree + 1;
    double a = c->knots[0], b = c->knots[nk - 1];
    for (int i = 0; i < nk; i++)
        c->knots[i] = i == nk - 1 ? t1 : t0 + (c->knots[i] - a) * (t1 - t0) / (b - a);
}

int sc_curve_join(const sc_curve *curves, int n, sc_curve *out)
{
    int p = 0, dim = curves[0].dim, st = dim + 1, total = 1;
    for (int k = 0; k < n; k++)
        p = curves[k].degree > p ? curves[k].degree : p;
    memset(out, 0, sizeof *out);
    sc_curve *c = sc_try_alloc((size_t)n, sizeof(sc_curve));
    if (!c)
        return SC_FAIL;
    double size = 0;
    int status = SC_OK, made = 0;
    for (; made < n && status == SC_OK; made++) {
        int k = made;
        status = curves[k].degree < p ? sc_curve_elevate(&curves[k], p - curves[k].degree, &c[k])
                                      : sc_curve_try_copy(&c[k], &curves[k]);
        if (status)
            break;
        sc_curve_reparam(&c[k], k, k + 1);
        total += c[k].ncp - 1;
        for (int i = 0; i < c[k].ncp * st; i++)
            size = fmax(size, fabs(c[k].cp[i] / c[k].cp[(i / st) * st + dim]));
    }
    for (int k = 1; k < n && status == SC_OK; k++) {
        const double *e = c[k - 1].cp + (size_t)st * (c[k - 1].ncp - 1);
        double *s = c[k].cp, scale = e[dim] / s[dim];
        for (int i = 0; i < c[k].ncp * st; i++)
            c[k].cp[i] *= scale;
        for (int d = 0; d < dim; d++)
            if (fabs(e[d] / e[dim] - s[d] / s[dim]) > 1e-6 * (size + 1e-300))
                status = SC_JOIN_APART;
    }
    if (status == SC_OK)
        status = sc_curve_try_alloc(out, dim, p, total);
    if (status == SC_OK) {
        int at = 0, kn = 0;
        for (int k = 0; k < n; k++) {
            int first = k ? 1 : 0;
            memcpy(out->cp + (size_t)st * at, c[k].cp + (size_t)st * first,
                   sizeof(double) * (size_t)st * (c[k].ncp - first));
            at += c[k].ncp - first;
            int nk = c[k].ncp + p + 1, from = k ? p + 1 : 0, to = k < n - 1 ? nk - 1 : nk;
            for (int i = from; i < to; i++)
                out->knots[kn++] = c[k].knots[i];
        }
    }
    for (int k = 0; k < made; k++)
        sc_curve_free(&c[k]);
    free(c);
    return status;
}

/* Knots of `from` (interior, with multiplicity) that `to` lacks. */
static int missing_knots(const sc_curve *to, const sc_curve *from, double *x)
{
    int n = 0, nkf = from->ncp + from->degree + 1, nkt = to->ncp + to->degree + 1;
    for (int i = from->degree + 1; i < nkf - from->degree - 1;) {
        double k = from->knots[i];
        int mf = 0, mt = 0;
        while (i < nkf - from->degree - 1 && fabs(from->knots[i] - k) < 1e-12) {
            mf++;
            i++;
        }
        for (int j = 0; j < nkt; j++)
            mt += fabs(to->knots[j] - k) < 1e-12;
        for (int m = mt; m < mf; m++)
            x[n++] = k;
    }
    return n;
}

int sc_ruled(const sc_curve *a, const sc_curve *b, sc_surface *out)
{
    sc_curve c[2] = {{0}}, tmp;
    const sc_curve *in[2] = {a, b};
    int p = a->degree > b->degree ? a->degree : b->degree, status = SC_OK;
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 2 && status == SC_OK; k++) {
        status = in[k]->degree < p ? sc_curve_elevate(in[k], p - in[k]->degree, &c[k])
                                   : sc_curve_try_copy(&c[k], in[k]);
        if (status == SC_OK)
            sc_curve_reparam(&c[k], 0, 1);
    }
    for (int k = 0; k < 2 && status == SC_OK; k++) {
        int nk = c[!k].ncp + c[!k].degree + 1;
        double *x = sc_try_alloc((size_t)nk, sizeof(double));
        if (!x) {
            status = SC_FAIL;
            break;
        }
        int nx = missing_knots(&c[k], &c[!k], x);
        if (nx) {
            status = sc_curve_refine(&c[k], x, nx, &tmp);
            if (status == SC_OK) {
                sc_curve_free(&c[k]);
                c[k] = tmp;
            }
        }
        free(x);
    }
    if (status == SC_OK)
        status = sc_surface_try_alloc(out, p, 1, c[0].ncp, 2);
    if (status == SC_OK) {
        memcpy(out->knots_u, c[0].knots, sizeof(double) * (size_t)(c[0].ncp + p + 1));
        out->knots_v[0] = out->knots_v[1] = 0;
        out->knots_v[2] = out->knots_v[3] = 1;
        for (int j = 0; j < 2; j++)
            memcpy(out->cp + 4 * (size_t)j * c[0].ncp, c[j].cp,
                   sizeof(double) * 4 * (size_t)c[0].ncp);
        sc_surface_update_rational(out);
    }
    sc_curve_free(&c[0]);
    sc_curve_free(&c[1]);
    return status;
}


/* Range along dir of the trim curves' control points (a bound of the
 * curves themselves). */
static void trims_range(const sc_surface *s, int dir, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int l = 0; l < s->nloops; l++)
        for (int c = 0; c < s->loops[l].ncurves; c++) {
            const sc_curve *k = &s->loops[l].curves[c];
            for (int i = 0; i < k->ncp; i++) {
                double x = k->cp[3 * i + dir] / k->cp[3 * i + 2];
                *lo = fmin(*lo, x);
                *hi = fmax(*hi, x);
            }
        }
}

static const double *row_point(const sc_surface *s, int dir, int along, int across)
{
    return s->cp + 4 * (dir ? (size_t)along * s->nu + across : (size_t)across * s->nu + along);
}

/* Closed along dir: the first and last rows of control points coincide
 * (homogeneous, so that a copy can share them). */
int sc_surface_closed(const sc_surface *s, int dir)
{
    int n = dir ? s->nv : s->nu, m = dir ? s->nu : s->nv;
    double scale = 0;
    for (size_t k = 0; k < 4 * (size_t)s->nu * s->nv; k++)
        scale = fmax(scale, fabs(s->cp[k]));
    for (int j = 0; j < m; j++) {
        const double *a = row_point(s, dir, 0, j), *b = row_point(s, dir, n - 1, j);
        for (int d = 0; d < 4; d++)
            if (fabs(a[d] - b[d]) > 1e-9 * scale)
                return 0;
    }
    return 1;
}

/* Joins a copy of the (clamped, closed) surface shifted by one period
 * before (left) or after it along dir: the seam becomes an interior knot of
 * multiplicity degree, the shape is unchanged. */
static int join_period(sc_surface *s, int dir, int left)
{
    int p = dir ? s->deg_v : s->deg_u, n = dir ? s->nv : s->nu, nk = n + p + 1;
    const double *k = dir ? s->knots_v : s->knots_u;
    double period = k[nk - 1] - k[0], shift = left ? -period : period;
    sc_surface out = *s;
    out.loops = NULL;
    out.nloops = 0;
    if (sc_surface_try_alloc(&out, s->deg_u, s->deg_v, dir ? s->nu : 2 * n - 1,
                             dir ? 2 * n - 1 : s->nv))
        return SC_FAIL;
    memcpy(dir ? out.knots_u : out.knots_v, dir ? s->knots_u : s->knots_v,
           sizeof(double) * (size_t)(dir ? s->nu + s->deg_u + 1 : s->nv + s->deg_v + 1));
    double *ko = dir ? out.knots_v : out.knots_u;
    /* first copy without its last knot, second without its first p+1 */
    const double first_shift = left ? shift : 0, second_shift = left ? 0 : shift;
    for (int i = 0; i < nk - 1; i++)
        ko[i] = k[i] + first_shift;
    for (int i = p + 1; i < nk; i++)
        ko[nk - 1 + i - (p + 1)] = k[i] + second_shift;
    int m = dir ? s->nu : s->nv;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < 2 * n - 1; i++) {
            int src = i < n ? i : i - n + 1;
            double *dst = (double *)row_point(&out, dir, i, j);
            memcpy(dst, row_point(s, dir, src, j), 4 * sizeof(double));
        }
    sc_surface_free(s);
    *s = out;
    return SC_OK;
}

/* Trims of a closed surface may run across its seam (a torus trimmed at
 * u in [-pi/2, pi/2] on a [0, 2pi] domain). The surface is then extended by
 * whole periods and restricted to the trims' range, so that every trimmed
 * point has its own parameters. */
int sc_surface_unwrap_seams(sc_surface *s)
{
    if (s->nloops == 0)
        return SC_OK;
    /* Restriction and joining rebuild the surface without its loops. */
    sc_loop *loops = s->loops;
    int nloops = s->nloops, status = SC_OK;
    for (int dir = 0; dir < 2 && status == SC_OK; dir++) {
        double lo, hi, a, b, c, d;
        sc_surface_domain(s, &a, &b, &c, &d);
        if (dir) {
            a = c;
            b = d;
        }
        double period = b - a, slack = 1e-6 * period;
        trims_range(s, dir, &lo, &hi);
        if (!(lo < a - slack || hi > b + slack) || hi - lo > period + slack ||
            !sc_surface_closed(s, dir))
            continue;
        s->loops = NULL;
        s->nloops = 0;
        if (lo < a - slack)
            status = join_period(s, dir, 1);
        if (status == SC_OK && hi > b + slack)
            status = join_period(s, dir, 0);
        if (status == SC_OK)
            status = sc_surface_try_restrict(s, dir, lo, hi);
        s->loops = loops;
        s->nloops = nloops;
    }
    return status;
}
