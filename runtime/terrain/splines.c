/* splines.c — the four schemes of seed 004 section IV (C0, C1, C2 and the
 * piecewise linear comparison) as BB-coefficient masks over a grid of
 * heights, and the Table I error protocol. Every coefficient is a fixed
 * weighted sum of a few nearby heights (the paper's equation (4)), so a
 * build is one pass over the patches. Derivations: docs/splines.md. */
#include "splines.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *scheme_names[SC_SPLINE_SCHEME_COUNT] = {"c0", "c1", "c2", "linear"};

const char *sc_spline_scheme_name(sc_spline_scheme s)
{
    return (unsigned)s < SC_SPLINE_SCHEME_COUNT ? scheme_names[s] : "?";
}

int sc_spline_scheme_parse(const char *name, sc_spline_scheme *out)
{
    for (int s = 0; s < SC_SPLINE_SCHEME_COUNT; s++)
        if (strcmp(name, scheme_names[s]) == 0) {
            *out = (sc_spline_scheme)s;
            return SC_OK;
        }
    return SC_FAIL;
}

int sc_spline_samples_per_square(sc_spline_scheme s)
{
    return s == SC_SPLINE_C0 ? 4 : s == SC_SPLINE_C1 ? 3 : 1;
}

int sc_spline_pad(sc_spline_scheme s)
{
    return s == SC_SPLINE_C1 ? 3 : s == SC_SPLINE_C2 ? 1 : 0;
}

/* Corners of triangle `up` of square (i, j) in square units, counter-
 * clockwise as in sc_tri_mesh_domain. */
static void tri_corners(int i, int j, int up, int v[3][2])
{
    v[0][0] = i; v[0][1] = j;
    v[1][0] = i + 1; v[1][1] = j + up;
    v[2][0] = i + !up; v[2][1] = j + 1;
}

/* The heights at the degree-k domain points of a triangle (k samples per
 * square side), in coefficient order: the point (a v0 + b v1 + c v2) / k in
 * square units is sample a v0 + b v1 + c v2. */
static void domain_values(const sc_heights *h, int k, int i, int j, int up, double *val)
{
    int v[3][2];
    tri_corners(i, j, up, v);
    for (int a = 0; a <= k; a++)
        for (int b = 0; a + b <= k; b++) {
            int c = k - a - b;
            val[sc_tri_index(k, a, b)] = sc_heights_at(h, a * v[0][0] + b * v[1][0] + c * v[2][0],
                                                       a * v[0][1] + b * v[1][1] + c * v[2][1]);
        }
}

static void matvec(int n, const double *m, const double *x, double *y)
{
    for (int r = 0; r < n; r++) {
        double s = 0;
        for (int c = 0; c < n; c++) s += m[r * n + c] * x[c];
        y[r] = s;
    }
}

/* C0: the quartic interpolant of the 15 heights at the domain points of
 * each triangle (the paper's inverted 15 x 15 interpolation matrix). */
static int build_c0(const sc_heights *h, sc_tri_mesh *m, sc_error *err)
{
    double inv[15 * 15], val[15];
    if (sc_tri_interp_matrix(4, inv, err) != SC_OK) return SC_FAIL;
    for (int p = 0; p < m->count; p++) {
        int sq = p / 2;
        domain_values(h, 4, sq % m->nx, sq / m->nx, p % 2, val);
        matvec(15, inv, val, m->coef + (size_t)p * 15);
    }
    return SC_OK;
}

static void build_linear(const sc_heights *h, sc_tri_mesh *m)
{
    double b1[3], b2[6], b3[10];
    for (int p = 0; p < m->count; p++) {
        int sq = p / 2;
        domain_values(h, 1, sq % m->nx, sq / m->nx, p % 2, b1);
        sc_tri_elevate(1, b1, b2);
        sc_tri_elevate(2, b2, b3);
        sc_tri_elevate(3, b3, m->coef + (size_t)p * 15);
    }
}

/* C2: s = sum_k f_k M(x/h - k), the quartic box spline with the heights as
 * its coefficients (the paper's non-negative masks: the data are control
 * points). On square (i, j) the shifts -1..2 reach it. */
static void build_c2(const sc_heights *h, sc_tri_mesh *m)
{
    for (int p = 0; p < m->count; p++) {
        int sq = p / 2, i = sq % m->nx, j = sq / m->nx, up = p % 2;
        double *out = m->coef + (size_t)p * 15;
        for (int di = -1; di <= 2; di++)
            for (int dj = -1; dj <= 2; dj++) {
                const double *net = sc_box_spline_net(up, di, dj);
                double f = sc_heights_at(h, i + di, j + dj);
                for (int r = 0; r < 15; r++) out[r] += f * net[r];
            }
    }
}

/* ---- C1 ----
 * Data at the cubic domain points (3 samples per square side). Per vertex
 * V: the value (interpolated) and a fourth-order central difference
 * gradient give the v- and u-coefficients (all on one plane, so the C1
 * conditions at V hold). Per triangle T: phi_T, a mask of its 10 samples
 * (symmetric about the perpendicular bisector of its diagonal); each edge's
 * e-coefficient is phi_T + phi_T' of its two triangles, which makes the alternating sum of the six e-coefficients
 * around every vertex vanish, the condition for the z-coefficients around
 * V to satisfy the C1 conditions z_T + z_T' = u + e across each edge. Of
 * that one-parameter family of z, the one nearest (least squares) to the
 * z-coefficients of the cubic interpolants of the six triangles is taken.
 * Every step is exact for cubics, so the spline reproduces cubics. */

/* The six triangles around vertex (i, j), counter-clockwise from the
 * direction (1,0): square offset, lower/upper, and the local indices of V,
 * of the vertex along the edge before T (directions (1,0), (1,1), (0,1),
 * (-1,0), (-1,-1), (0,-1)) and of the vertex along the edge after T. */
static const struct { int di, dj, up, lv, la, lb; } ring[6] = {
    {0, 0, 0, 0, 1, 2}, {0, 0, 1, 0, 1, 2}, {-1, 0, 0, 1, 2, 0},
    {-1, -1, 1, 1, 2, 0}, {-1, -1, 0, 2, 0, 1}, {0, -1, 1, 2, 0, 1},
};
static const int ring_dir[6][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 0}, {-1, -1}, {0, -1}};

static int idx3(int n, const int e[3]) { (void)n; return sc_tri_index(n, e[0], e[1]); }

typedef struct c1_tri {
    double phi;            /* this triangle's share of its edges' e-coefficients */
    double cubic[10];      /* BB-coefficients of the cubic interpolant */
} c1_tri;

static void c1_triangle(const sc_heights *h, const double *inv3, int i, int j, int up,
                        c1_tri *t)
{
    double val[10];
    domain_values(h, 3, i, j, up, val);
    matvec(10, inv3, val, t->cubic);
    /* Over 160 (docs/splines.md): by the right-angle corner r of the
     * triangle (v1 of a lower, v2 of an upper one), 2 at r and 24 at the
     * two other vertices, -45 at the points of the diagonal edge, on the
     * legs -23 next to r and -67 next to the other vertex, 300 at the
     * centroid. Exact for cubics; of that family, the symmetric mask
     * nearest the least-squares optimum on quartics. */
    int r = up ? 2 : 1;
    double s = 0;
    for (int a = 0; a <= 3; a++)
        for (int b = 0; a + b <= 3; b++) {
            int e[3] = {a, b, 3 - a - b}, w;
            if (a == 3 || b == 3 || e[2] == 3) w = e[r] == 3 ? 2 : 24;
            else if (e[r] == 0) w = -45;
            else if (a == 0 || b == 0 || e[2] == 0) w = e[r] == 2 ? -23 : -67;
            else w = 300;
            s += w * val[sc_tri_index(3, a, b)];
        }
    t->phi = s / 160;
}

/* The quartic coefficient with exponents e of the degree-raised cubic. */
static double raised(const double *cubic, const int e[3])
{
    double s = 0;
    for (int q = 0; q < 3; q++) {
        if (!e[q]) continue;
        int f[3] = {e[0], e[1], e[2]};
        f[q]--;
        s += e[q] * cubic[idx3(3, f)];
    }
    return s / 4;
}

static int build_c1(const sc_heights *h, sc_tri_mesh *m, sc_error *err)
{
    double inv3[100];
    if (sc_tri_interp_matrix(3, inv3, err) != SC_OK) return SC_FAIL;
    for (int j = 0; j <= m->ny; j++)
        for (int i = 0; i <= m->nx; i++) {
            int I = 3 * i, J = 3 * j;
            double f = sc_heights_at(h, I, J);
            /* Gradient per sample step, exact for quartics. */
            double gx = (sc_heights_at(h, I - 2, J) - 8 * sc_heights_at(h, I - 1, J)
                         + 8 * sc_heights_at(h, I + 1, J) - sc_heights_at(h, I + 2, J)) / 12;
            double gy = (sc_heights_at(h, I, J - 2) - 8 * sc_heights_at(h, I, J - 1)
                         + 8 * sc_heights_at(h, I, J + 1) - sc_heights_at(h, I, J + 2)) / 12;
            c1_tri t[6];
            double u[6], e[6], s[6], zt[6], z[6];
            for (int a = 0; a < 6; a++)
                c1_triangle(h, inv3, i + ring[a].di, j + ring[a].dj, ring[a].up, &t[a]);
            for (int a = 0; a < 6; a++) {
                /* Edge a lies between triangles a-1 and a; a square side
                 * is 3 sample steps, the u-point a quarter of it. */
                u[a] = f + 0.75 * (gx * ring_dir[a][0] + gy * ring_dir[a][1]);
                e[a] = t[(a + 5) % 6].phi + t[a].phi;
                s[a] = u[a] + e[a];
                int ez[3] = {1, 1, 1};
                ez[ring[a].lv] = 2;
                zt[a] = raised(t[a].cubic, ez);
            }
            /* z[a-1] + z[a] = s[a] around V: a particular solution, then
             * the alternating null vector fitted to the cubics' z. */
            z[0] = 0;
            for (int a = 1; a < 6; a++) z[a] = s[a] - z[a - 1];
            double tfit = 0;
            for (int a = 0; a < 6; a++) tfit += (a % 2 ? -1 : 1) * (zt[a] - z[a]);
            tfit /= 6;
            for (int a = 0; a < 6; a++) z[a] += (a % 2 ? -1 : 1) * tfit;
            for (int a = 0; a < 6; a++) {
                int si = i + ring[a].di, sj = j + ring[a].dj;
                if (si < 0 || sj < 0 || si >= m->nx || sj >= m->ny) continue;
                double *c = m->coef + (size_t)(2 * (sj * m->nx + si) + ring[a].up) * 15;
                int lv = ring[a].lv, la = ring[a].la, lb = ring[a].lb;
                int ev[3] = {0, 0, 0}, ua[3] = {0, 0, 0}, ub[3] = {0, 0, 0};
                int ea[3] = {0, 0, 0}, eb[3] = {0, 0, 0}, ez[3] = {1, 1, 1};
                ev[lv] = 4;
                ua[lv] = 3; ua[la] = 1;
                ub[lv] = 3; ub[lb] = 1;
                ea[lv] = 2; ea[la] = 2;
                eb[lv] = 2; eb[lb] = 2;
                ez[lv] = 2;
                c[idx3(4, ev)] = f;
                c[idx3(4, ua)] = u[a];
                c[idx3(4, ub)] = u[(a + 1) % 6];
                c[idx3(4, ea)] = e[a];
                c[idx3(4, eb)] = e[(a + 1) % 6];
                c[idx3(4, ez)] = z[a];
            }
        }
    return SC_OK;
}

int sc_spline_build(const sc_heights *h, sc_spline_scheme s, sc_tri_mesh *out, sc_error *err)
{
    if ((unsigned)s >= SC_SPLINE_SCHEME_COUNT)
        return sc_fail(err, NULL, 0, "unknown spline scheme %d", (int)s);
    int k = sc_spline_samples_per_square(s), pad = sc_spline_pad(s);
    int mx = (h->nx - 1) / k, my = (h->ny - 1) / k;
    if (mx < 1 || my < 1)
        return sc_fail(err, NULL, 0, "%d x %d heights: scheme %s needs at least %d x %d",
                       h->nx, h->ny, sc_spline_scheme_name(s), k + 1, k + 1);
    if (mx * k + 1 != h->nx || my * k + 1 != h->ny)
        sc_log(SC_LOG_WARN, "scheme %s uses %d x %d of the %d x %d heights (%d samples per "
               "triangle side)", sc_spline_scheme_name(s), mx * k + 1, my * k + 1, h->nx, h->ny, k);
    sc_heights padded;
    const sc_heights *g = h;
    int own = 0;
    if (h->pad < pad) {
        if (sc_heights_padded(h, pad, &padded))
            return sc_fail_oom(err, NULL, 0, sc_alloc_failed_bytes(), 1, "the padded heights");
        g = &padded;
        own = 1;
    }
    sc_tri_mesh m;
    if (sc_tri_mesh_init(&m, 4, mx, my, h->x0, h->y0, k * h->dx, k * h->dy)) {
        if (own)
            sc_heights_free(&padded);
        return sc_fail_oom(err, NULL, 0, sc_alloc_failed_bytes(), 1, "the spline's patches");
    }
    int rc = SC_OK;
    switch (s) {
    case SC_SPLINE_C0: rc = build_c0(g, &m, err); break;
    case SC_SPLINE_C1: rc = build_c1(g, &m, err); break;
    case SC_SPLINE_C2: build_c2(g, &m); break;
    default: build_linear(g, &m); break;
    }
    if (own) sc_heights_free(&padded);
    if (rc != SC_OK) {
        sc_tri_mesh_free(&m);
        return rc;
    }
    *out = m;
    return SC_OK;
}
