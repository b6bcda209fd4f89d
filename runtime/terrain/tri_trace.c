/* tri_trace.c — exact ray casting of triangular Bézier height patches and
 * meshes of them in double precision (tri_trace.h): the reference for the
 * GPU program of `tri` keys. */
#include "tri_trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Subdivision of the polynomial along the ray stops at intervals this
 * short (in its parameter s, [0, 1] over the clipped segment). */
#define ROOT_WIDTH 1e-14
#define MAX_DEPTH 64

/* Barycentric coordinates of the origin (a) and their rates along dir. */
static void ray_barycentric(const double tri[6], const double o[3], const double d[3],
                            double a[3], double rate[3])
{
    double e1x = tri[2] - tri[0], e1y = tri[3] - tri[1];
    double e2x = tri[4] - tri[0], e2y = tri[5] - tri[1];
    double area = e1x * e2y - e1y * e2x;
    double px = o[0] - tri[0], py = o[1] - tri[1];
    a[1] = (px * e2y - py * e2x) / area;
    a[2] = (e1x * py - e1y * px) / area;
    a[0] = 1 - a[1] - a[2];
    rate[1] = (d[0] * e2y - d[1] * e2x) / area;
    rate[2] = (e1x * d[1] - e1y * d[0]) / area;
    rate[0] = -rate[1] - rate[2];
}

/* {t : a + b t >= 0} intersected into [*lo, *hi]. */
static void clip(double a, double b, double *lo, double *hi)
{
    if (b > 0)
        *lo = fmax(*lo, -a / b);
    else if (b < 0)
        *hi = fmin(*hi, -a / b);
    else if (a < 0)
        *lo = INFINITY;
}

/* One de Casteljau step of a scalar net of degree m with weights l. */
static void casteljau_step(int m, const double *net, const double l[3], double *out)
{
    for (int i = m - 1; i >= 0; i--)
        for (int j = m - 1 - i; j >= 0; j--)
            out[sc_tri_index(m - 1, i, j)] = l[0] * net[sc_tri_index(m, i + 1, j)] +
                                             l[1] * net[sc_tri_index(m, i, j + 1)] +
                                             l[2] * net[sc_tri_index(m, i, j)];
}

/* The blossom b[u1^(n-i), u2^i] of the heights: the BB-coefficients of the
 * patch along the segment from u1 to u2. */
static void blossom(int n, const double *coef, const double u1[3], const double u2[3],
                    double *c)
{
    for (int i = 0; i <= n; i++) {
        double net[SC_TRI_MAX_COEF], next[SC_TRI_MAX_COEF];
        memcpy(net, coef, (size_t)sc_tri_ncoef(n) * sizeof *net);
        for (int m = n; m >= 1; m--) {
            casteljau_step(m, net, m > n - i ? u2 : u1, next);
            memcpy(net, next, (size_t)sc_tri_ncoef(m - 1) * sizeof *net);
        }
        c[i] = net[0];
    }
}

/* The smallest root in [lo, hi] of the polynomial with BB-coefficients g
 * over that interval, by subdivision at the middle, left half first; a
 * NaN when there is none. */
static double first_root(int n, const double *g, double lo, double hi, int depth)
{
    int pos = 0, neg = 0;
    for (int i = 0; i <= n; i++) {
        pos += g[i] > 0;
        neg += g[i] < 0;
    }
    if (pos == n + 1 || neg == n + 1)
        return NAN;
    if (hi - lo < ROOT_WIDTH || depth == MAX_DEPTH) {
        /* The interval is a hair wide: where g changes sign, or its middle
         * (a touching root). */
        if (g[0] == 0)
            return lo;
        return 0.5 * (lo + hi);
    }
    double left[SC_TRI_MAX_DEGREE + 1], right[SC_TRI_MAX_DEGREE + 1], d[SC_TRI_MAX_DEGREE + 1];
    memcpy(d, g, (size_t)(n + 1) * sizeof *d);
    for (int r = 0; r <= n; r++) {
        left[r] = d[0];
        right[n - r] = d[n - r];
        for (int i = 0; i < n - r; i++)
            d[i] = 0.5 * (d[i] + d[i + 1]);
    }
    double mid = 0.5 * (lo + hi);
    double s = first_root(n, left, lo, mid, depth + 1);
    return isnan(s) ? first_root(n, right, mid, hi, depth + 1) : s;
}

int sc_tri_patch_trace(int n, const double *coef, const double tri[6], const double origin[3],
                       const double dir[3], double t_min, sc_tri_hit *hit)
{
    hit->patch = -1;
    double a[3], rate[3];
    ray_barycentric(tri, origin, dir, a, rate);
    double lo = t_min, hi = INFINITY;
    for (int k = 0; k < 3; k++)
        clip(a[k], rate[k], &lo, &hi);
    double zmin = coef[0], zmax = coef[0];
    for (int k = 1; k < sc_tri_ncoef(n); k++) {
        zmin = fmin(zmin, coef[k]);
        zmax = fmax(zmax, coef[k]);
    }
    clip(origin[2] - zmin, dir[2], &lo, &hi);
    clip(zmax - origin[2], -dir[2], &lo, &hi);
    if (!(lo <= hi) || isinf(hi))
        return SC_FAIL;
    double u1[3], u2[3], c[SC_TRI_MAX_DEGREE + 1];
    for (int k = 0; k < 3; k++) {
        u1[k] = a[k] + rate[k] * lo;
        u2[k] = a[k] + rate[k] * hi;
    }
    blossom(n, coef, u1, u2, c);
    for (int i = 0; i <= n; i++)
        c[i] -= origin[2] + dir[2] * (lo + (hi - lo) * i / n);
    double s = first_root(n, c, 0, 1, 0);
    if (isnan(s))
        return SC_FAIL;
    double t = lo + (hi - lo) * s;
    if (!(t > t_min))
        return SC_FAIL;
    sc_tri_point p;
    double x = origin[0] + t * dir[0], y = origin[1] + t * dir[1];
    sc_tri_eval(n, coef, tri, x, y, &p);
    double len = sqrt(p.grad[0] * p.grad[0] + p.grad[1] * p.grad[1] + 1);
    *hit = (sc_tri_hit){.patch = 0, .t = t, .point = {x, y, p.value},
                        .normal = {-p.grad[0] / len, -p.grad[1] / len, 1 / len}};
    return SC_OK;
}

void sc_tri_tracer_init(sc_tri_tracer *tr, const sc_tri_mesh *m)
{
    tr->mesh = m;
    int squares = m->nx * m->ny;
    tr->square_range = sc_alloc((size_t)(squares ? 2 * squares : 1), sizeof(double));
    tr->zmin = INFINITY;
    tr->zmax = -INFINITY;
    for (int q = 0; q < squares; q++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int k = 0; k < 2 * m->ncoef; k++) {
            double z = m->coef[(size_t)(2 * q) * (size_t)m->ncoef + (size_t)k];
            lo = fmin(lo, z);
            hi = fmax(hi, z);
        }
        tr->square_range[2 * q] = lo;
        tr->square_range[2 * q + 1] = hi;
        tr->zmin = fmin(tr->zmin, lo);
        tr->zmax = fmax(tr->zmax, hi);
    }
}

void sc_tri_tracer_free(sc_tri_tracer *tr)
{
    free(tr->square_range);
    tr->square_range = NULL;
}

/* The nearer of the two patches' hits in square (i, j). */
static int trace_square(const sc_tri_tracer *tr, int i, int j, const double o[3],
                        const double d[3], double t_min, sc_tri_hit *best)
{
    const sc_tri_mesh *m = tr->mesh;
    best->patch = -1;
    int q = j * m->nx + i;
    for (int k = 0; k < 2; k++) {
        int p = 2 * q + k;
        double tri[6];
        sc_tri_hit h;
        sc_tri_mesh_domain(m, p, tri);
        if (sc_tri_patch_trace(m->degree, m->coef + (size_t)p * (size_t)m->ncoef, tri, o, d,
                               t_min, &h) == SC_OK &&
            (best->patch < 0 || h.t < best->t)) {
            *best = h;
            best->patch = p;
        }
    }
    return best->patch >= 0 ? SC_OK : SC_FAIL;
}

int sc_tri_tracer_trace(const sc_tri_tracer *tr, const double o[3], const double d[3],
                        double t_min, sc_tri_hit *hit)
{
    const sc_tri_mesh *m = tr->mesh;
    hit->patch = -1;
    double x1 = m->x0 + m->nx * m->hx, y1 = m->y0 + m->ny * m->hy;
    /* The ray's interval in the mesh's box (slabs), a hair wider. */
    double lo = t_min, hi = INFINITY;
    double eps_x = 1e-9 * m->hx, eps_y = 1e-9 * m->hy;
    double eps_z = 1e-9 * (tr->zmax - tr->zmin) + 1e-300;
    clip(o[0] - (m->x0 - eps_x), d[0], &lo, &hi);
    clip(x1 + eps_x - o[0], -d[0], &lo, &hi);
    clip(o[1] - (m->y0 - eps_y), d[1], &lo, &hi);
    clip(y1 + eps_y - o[1], -d[1], &lo, &hi);
    clip(o[2] - (tr->zmin - eps_z), d[2], &lo, &hi);
    clip(tr->zmax + eps_z - o[2], -d[2], &lo, &hi);
    if (!(lo <= hi))
        return SC_FAIL;
    /* Walk the squares from the entry point (Amanatides and Woo). */
    double px = o[0] + lo * d[0], py = o[1] + lo * d[1];
    int i = (int)floor((px - m->x0) / m->hx), j = (int)floor((py - m->y0) / m->hy);
    i = i < 0 ? 0 : i >= m->nx ? m->nx - 1 : i;
    j = j < 0 ? 0 : j >= m->ny ? m->ny - 1 : j;
    int step_i = d[0] > 0 ? 1 : -1, step_j = d[1] > 0 ? 1 : -1;
    double next_x = m->x0 + (i + (step_i > 0)) * m->hx;
    double next_y = m->y0 + (j + (step_j > 0)) * m->hy;
    double t_x = d[0] != 0 ? (next_x - o[0]) / d[0] : INFINITY;
    double t_y = d[1] != 0 ? (next_y - o[1]) / d[1] : INFINITY;
    double dt_x = d[0] != 0 ? m->hx / fabs(d[0]) : INFINITY;
    double dt_y = d[1] != 0 ? m->hy / fabs(d[1]) : INFINITY;
    for (;;) {
        if (trace_square(tr, i, j, o, d, t_min, hit) == SC_OK)
            return SC_OK;
        if (fmin(t_x, t_y) > hi)
            return SC_FAIL;
        if (t_x < t_y) {
            i += step_i;
            t_x += dt_x;
        } else {
            j += step_j;
            t_y += dt_y;
        }
        if (i < 0 || j < 0 || i >= m->nx || j >= m->ny)
            return SC_FAIL;
    }
}
