/* iges_surfaces.c — IGES surfaces as NURBS: 128 as it is, and the others
 * converted exactly with the constructions of runtime/model/analytic.h
 * (108/190 planes, 192–198 cylinders, cones, spheres, tori, 118 ruled,
 * 120 revolution, 122 tabulated cylinder, 114 parametric splines), 140
 * offset surfaces fitted within a stated tolerance. */
#include "analytic.h"
#include "iges_local.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ */
/* Entity 128: rational B-spline surface                                */
/* ------------------------------------------------------------------ */

static int read_128_into(reader *r, const params *p, sc_surface *s)
{
    int e = p->entity, k1, k2, m1, m2, prop[5];
    if (iges_need(r, p, 9) || iges_int(r, p, 1, &k1) || iges_int(r, p, 2, &k2) ||
        iges_int(r, p, 3, &m1) || iges_int(r, p, 4, &m2))
        return SC_FAIL;
    for (int i = 0; i < 5; i++)
        if (iges_int(r, p, 5 + i, &prop[i]))
            return SC_FAIL;
    if (m1 < 1 || m2 < 1)
        return iges_fail(r, e, iges_line(r, p, 3), "degree %d x %d: a surface needs degree 1 "
                           "or more in both directions", m1, m2);
    if (m1 > SC_READ_MAX_DEGREE || m2 > SC_READ_MAX_DEGREE)
        return iges_fail(r, e, iges_line(r, p, 3), "degree %d x %d: above the %d this reader "
                           "accepts (docs/limits.md)", m1, m2, SC_READ_MAX_DEGREE);
    if (k1 < m1 || k2 < m2)
        return iges_fail(r, e, iges_line(r, p, 1), "degree %d x %d needs at least %d x %d "
                           "control points, has %d x %d", m1, m2, m1 + 1, m2 + 1, k1 + 1, k2 + 1);
    long long nu = (long long)k1 + 1, nv = (long long)k2 + 1;
    if (nu > p->ntok || nv > p->ntok || nu * nv > p->ntok)
        return iges_fail(r, e, iges_line(r, p, 1), "%lld x %lld control points: more than "
                           "the %d parameters present (counts larger than the data)", nu, nv,
                           p->ntok - 1);
    long long nku = nu + m1 + 1, nkv = nv + m2 + 1;
    if (iges_need(r, p, 9 + nku + nkv + 4 * nu * nv) ||
        sc_budget_charge(&r->budget, sc_surface_bytes(m1, m2, (int)nu, (int)nv), "surface",
                         r->name, iges_line(r, p, 1), r->err))
        return SC_FAIL;
    if (sc_surface_try_alloc(s, m1, m2, (int)nu, (int)nv))
        return iges_fail_oom(r, e, sc_surface_bytes(m1, m2, (int)nu, (int)nv), "the surface");
    int at = 10;
    if (iges_read_knots(r, p, at, s->knots_u, (int)nku, m1, "u"))
        return SC_FAIL;
    at += (int)nku;
    if (iges_read_knots(r, p, at, s->knots_v, (int)nkv, m2, "v"))
        return SC_FAIL;
    at += (int)nkv;
    int npts = (int)(nu * nv), polynomial = prop[2] == 1, bad_weight = -1;
    for (int i = 0; i < npts; i++) {
        if (iges_real(r, p, at + i, &s->cp[4 * i + 3]))
            return SC_FAIL;
        if (!(s->cp[4 * i + 3] > 0) && bad_weight < 0)
            bad_weight = i;
    }
    /* A polynomial surface's weights carry no information; some writers
     * leave them zero. */
    if (bad_weight >= 0 && !polynomial)
        return iges_fail(r, e, iges_line(r, p, at + bad_weight), "weight %d is %.17g (weights "
                           "of a rational surface must be > 0)", bad_weight,
                           s->cp[4 * bad_weight + 3]);
    at += npts;
    for (int i = 0; i < npts; i++) {
        double w = bad_weight >= 0 ? 1.0 : s->cp[4 * i + 3];
        s->cp[4 * i + 3] = w;
        for (int d = 0; d < 3; d++) {
            double x;
            if (iges_real(r, p, at + 3 * i + d, &x))
                return SC_FAIL;
            s->cp[4 * i + d] = x * w;
        }
    }
    at += 3 * npts;
    /* U(0), U(1), V(0), V(1): the used part of the domain. */
    double range[4];
    int restricted = SC_OK;
    if (p->ntok - 1 >= at + 3) {
        for (int i = 0; i < 4; i++)
            if (iges_real(r, p, at + i, &range[i]))
                return SC_FAIL;
        if (range[0] < range[1])
            restricted = sc_surface_try_restrict(s, 0, range[0], range[1]);
        if (range[2] < range[3] && restricted == SC_OK)
            restricted = sc_surface_try_restrict(s, 1, range[2], range[3]);
    } else {
        restricted = sc_surface_try_restrict(s, 0, s->knots_u[m1], s->knots_u[s->nu]);
        if (restricted == SC_OK)
            restricted = sc_surface_try_restrict(s, 1, s->knots_v[m2], s->knots_v[s->nv]);
    }
    if (restricted)
        return iges_fail_oom(r, e, sc_alloc_failed_bytes(), "restricting the surface");
    sc_surface_update_rational(s);
    sc_error check;
    if (sc_surface_check(s, &check))
        return iges_fail(r, e, iges_line(r, p, 1), "%s", check.message);
    return SC_OK;
}

int iges_read_128(reader *r, int e, sc_surface *s)
{
    memset(s, 0, sizeof *s);
    params p;
    int status = iges_params(r, e, &p);
    if (status == SC_OK)
        status = read_128_into(r, &p, s);
    if (status)
        sc_surface_free(s);
    return status;
}

/* ------------------------------------------------------------------ */
/* Points, directions and curves the analytic surfaces name             */
/* ------------------------------------------------------------------ */

/* A 116 point or 123 direction entity, its transformation chain applied
 * (only the linear part to a direction). Directions come out unit. */
static int read_vector(reader *r, const params *owner, int i, int type, double out[3])
{
    int e;
    if (iges_pointer(r, owner, i, &e))
        return SC_FAIL;
    if (e < 0 || r->ent[e].type != type)
        return iges_fail(r, owner->entity, iges_line(r, owner, i), "parameter %d: expected a "
                         "pointer to a %d %s", i, type, type == 116 ? "point" : "direction");
    params p;
    double v[3], m[12];
    if (iges_params(r, e, &p) || iges_leading_reals(r, &p, 3, v) || iges_xform(r, e, m))
        return SC_FAIL;
    double t = type == 116 ? 1 : 0;
    for (int d = 0; d < 3; d++)
        out[d] = m[4 * d] * v[0] + m[4 * d + 1] * v[1] + m[4 * d + 2] * v[2] + t * m[4 * d + 3];
    if (type == 123) {
        double len = sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
        if (!(len > 0))
            return iges_fail(r, e, 0, "direction of length 0");
        for (int d = 0; d < 3; d++)
            out[d] /= len;
    }
    return SC_OK;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    memcpy(out, c, sizeof c);
}

/* A unit vector perpendicular to the unit `axis`: `ref` made perpendicular
 * when given (form 1), else any. */
static void frame_x(const double axis[3], const double *ref, double x[3])
{
    double t[3] = {1, 0, 0};
    if (ref)
        memcpy(t, ref, sizeof t);
    for (int pass = 0; pass < 2; pass++) {
        double h = t[0] * axis[0] + t[1] * axis[1] + t[2] * axis[2];
        for (int d = 0; d < 3; d++)
            x[d] = t[d] - h * axis[d];
        double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (len > 1e-9) {
            for (int d = 0; d < 3; d++)
                x[d] /= len;
            return;
        }
        t[0] = fabs(axis[0]) < 0.9 ? 1 : 0;
        t[1] = fabs(axis[0]) < 0.9 ? 0 : 1;
        t[2] = 0;
    }
}

/* One 3D curve entity (a generatrix, a directrix, a rail) as a single
 * NURBS curve: a composite's members are joined end to end. */
static int one_curve(reader *r, const params *owner, int i, sc_curve *out)
{
    int e;
    if (iges_pointer(r, owner, i, &e))
        return SC_FAIL;
    if (e < 0)
        return iges_fail(r, owner->entity, iges_line(r, owner, i), "parameter %d: null curve "
                         "pointer", i);
    curve_list l = {.dim = 3};
    int status = iges_trim_curves(r, e, iges_identity, 0, &l, 0);
    if (status == SC_OK && l.n == 0)
        status = iges_fail(r, e, 0, "curve without pieces");
    if (status == SC_OK) {
        iges_orient_chain(&l);
        int joined = sc_curve_join(l.items, l.n, out);
        if (joined == SC_FAIL)
            status = iges_fail_oom(r, e, sc_alloc_failed_bytes(), "the joined curve");
        else if (joined)
            status = iges_fail(r, e, 0, "composite curve whose members do not meet");
    }
    iges_list_free(&l);
    return status == SC_OK ? SC_OK : status == SC_FAIL ? SC_FAIL : 0;
}

/* ------------------------------------------------------------------ */
/* Surfaces                                                             */
/* ------------------------------------------------------------------ */

static int analytic_frame(reader *r, const params *p, int loc, int axis, int ref,
                          iges_surface *sf)
{
    double refd[3];
    int form = r->ent[p->entity].form;
    if (read_vector(r, p, loc, 116, sf->o) || read_vector(r, p, axis, 123, sf->z))
        return SC_FAIL;
    int has_ref = form == 1 && p->ntok - 1 >= ref;
    if (has_ref) {
        int e;
        if (iges_pointer(r, p, ref, &e))
            return SC_FAIL;
        has_ref = e >= 0;
    }
    if (has_ref && read_vector(r, p, ref, 123, refd))
        return SC_FAIL;
    frame_x(sf->z, has_ref ? refd : NULL, sf->x);
    cross(sf->z, sf->x, sf->y);
    return SC_OK;
}

/* 120: L (axis line), C (generatrix), SA, TA: the generatrix turned from
 * SA to TA (radians) about the line. */
static int read_120(reader *r, const params *p, iges_surface *sf)
{
    double sa, ta;
    int axis;
    if (iges_need(r, p, 4) || iges_real(r, p, 3, &sa) || iges_real(r, p, 4, &ta) ||
        iges_pointer(r, p, 1, &axis))
        return SC_FAIL;
    if (axis < 0 || r->ent[axis].type != 110)
        return iges_fail(r, p->entity, iges_line(r, p, 1), "its axis (parameter 1) is not a "
                         "110 line");
    sc_curve line, gen;
    int status = one_curve(r, p, 1, &line);
    if (status != SC_OK)
        return status;
    double a[3], b[3], dir[3];
    for (int d = 0; d < 3; d++) {
        a[d] = line.cp[d] / line.cp[3];
        b[d] = line.cp[4 + d] / line.cp[7];
        dir[d] = b[d] - a[d];
    }
    sc_curve_free(&line);
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(len > 0))
        return iges_fail(r, p->entity, 0, "its axis has length 0");
    for (int d = 0; d < 3; d++)
        dir[d] /= len;
    /* Writers give periodic ranges longer than a turn: a whole turn is the
     * most a surface holds. */
    if (!(ta > sa))
        return iges_fail(r, p->entity, iges_line(r, p, 3), "rotation from %g to %g: needs "
                         "TA > SA", sa, ta);
    status = one_curve(r, p, 2, &gen);
    if (status != SC_OK)
        return status;
    status = sc_revolve(&gen, a, dir, sa, fmin(ta, sa + 2 * M_PI), &sf->nurbs);
    sc_curve_free(&gen);
    if (status)
        return iges_fail_oom(r, p->entity, sc_alloc_failed_bytes(), "the surface");
    return 1;
}

/* 122: DE (directrix), LX, LY, LZ (where its start is moved to). */
static int read_122(reader *r, const params *p, iges_surface *sf)
{
    double l[3], start[3], d[3];
    if (iges_need(r, p, 4))
        return SC_FAIL;
    for (int i = 0; i < 3; i++)
        if (iges_real(r, p, 2 + i, &l[i]))
            return SC_FAIL;
    sc_curve c;
    int status = one_curve(r, p, 1, &c);
    if (status != SC_OK)
        return status;
    for (int i = 0; i < 3; i++) {
        start[i] = c.cp[i] / c.cp[3];
        d[i] = l[i] - start[i];
    }
    status = sc_extrude(&c, d, &sf->nurbs);
    sc_curve_free(&c);
    if (status)
        return iges_fail_oom(r, p->entity, sc_alloc_failed_bytes(), "the surface");
    return 1;
}

/* 118: DE1, DE2, DIRFLG (1: the first end of one meets the last of the
 * other), DEVFLG. */
static int read_118(reader *r, const params *p, iges_surface *sf)
{
    int dirflg;
    if (iges_need(r, p, 3) || iges_int(r, p, 3, &dirflg))
        return SC_FAIL;
    sc_curve a, b;
    int status = one_curve(r, p, 1, &a);
    if (status != SC_OK)
        return status;
    status = one_curve(r, p, 2, &b);
    if (status != SC_OK) {
        sc_curve_free(&a);
        return status;
    }
    if (dirflg == 1)
        sc_curve_reverse(&b);
    status = sc_ruled(&a, &b, &sf->nurbs);
    sc_curve_free(&a);
    sc_curve_free(&b);
    if (status)
        return iges_fail_oom(r, p->entity, sc_alloc_failed_bytes(), "the surface");
    return 1;
}

/* A half circle of radius rr about c in the plane of x and z, from −z
 * up to +z through +x (a sphere's generatrix), or a full circle of radius
 * rr about c + R·x (a torus's). */
static int circle_in(const double c[3], const double x[3], const double z[3], double R,
                     double rr, double a0, double a1, sc_curve *out)
{
    double ctr[3];
    for (int d = 0; d < 3; d++)
        ctr[d] = c[d] + R * x[d];
    return sc_ellipse_arc(3, ctr, x, z, rr, rr, a0, a1, out);
}

/* A circle turned about the frame's axis: a sphere or a torus. */
static int revolved_circle(reader *r, int e, iges_surface *sf, double R, double rr, double a0,
                           double a1)
{
    sc_curve gen;
    int status = circle_in(sf->o, sf->x, sf->z, R, rr, a0, a1, &gen);
    if (status == SC_OK) {
        status = sc_revolve(&gen, sf->o, sf->z, 0, 2 * M_PI, &sf->nurbs);
        sc_curve_free(&gen);
    }
    if (status)
        return iges_fail_oom(r, e, sc_alloc_failed_bytes(), "the surface");
    return 1;
}

/* 114 parametric spline surface: CTYPE, PTYPE, M, N, TU(M+1), TV(N+1),
 * then per patch (i over u, j over v, j fastest) 16 coefficients of x,
 * 16 of y, 16 of z, the one of s^a t^b (s = u − TU(i), t = v − TV(j)) at
 * 4b + a, and after each row of patches 48 values that are not used.
 * Exactly a bicubic B-spline with triple knots at the breakpoints. */
static int read_114(reader *r, const params *p, iges_surface *sf)
{
    int m, n, e = p->entity;
    if (iges_need(r, p, 4) || iges_count(r, p, 3, 49, &m) || iges_count(r, p, 4, 49, &n))
        return SC_FAIL;
    if (m < 1 || n < 1)
        return iges_fail(r, e, iges_line(r, p, 3), "%d x %d patches", m, n);
    if (iges_need(r, p, 4 + (long long)m + n + 2 + 48LL * m * n) ||
        sc_budget_charge(&r->budget, sc_surface_bytes(3, 3, 3 * m + 1, 3 * n + 1), "surface",
                         r->name, iges_line(r, p, 3), r->err))
        return SC_FAIL;
    double *tu = sc_try_alloc((size_t)m + n + 2, sizeof(double)), *tv = tu + m + 1;
    if (!tu)
        return iges_fail_oom(r, e, ((size_t)m + n + 2) * sizeof(double), "breakpoints");
    int status = SC_OK;
    for (int i = 0; i < m + n + 2 && status == SC_OK; i++)
        status = iges_real(r, p, 5 + i, &tu[i]);
    for (int i = 0; i < m && status == SC_OK; i++)
        if (!(tu[i + 1] > tu[i]))
            status = iges_fail(r, e, iges_line(r, p, 5 + i), "u breakpoints do not increase");
    for (int j = 0; j < n && status == SC_OK; j++)
        if (!(tv[j + 1] > tv[j]))
            status = iges_fail(r, e, iges_line(r, p, 6 + m + j), "v breakpoints do not increase");
    if (status) {
        free(tu);
        return SC_FAIL;
    }
    sc_surface *s = &sf->nurbs;
    if (sc_surface_try_alloc(s, 3, 3, 3 * m + 1, 3 * n + 1)) {
        free(tu);
        return iges_fail_oom(r, e, sc_surface_bytes(3, 3, 3 * m + 1, 3 * n + 1), "the surface");
    }
    for (int k = 0; k < 4; k++) {
        s->knots_u[k] = tu[0];
        s->knots_u[3 * m + 1 + k] = tu[m];
        s->knots_v[k] = tv[0];
        s->knots_v[3 * n + 1 + k] = tv[n];
    }
    for (int i = 1; i < m; i++)
        for (int k = 0; k < 3; k++)
            s->knots_u[3 * i + 1 + k] = tu[i];
    for (int j = 1; j < n; j++)
        for (int k = 0; k < 3; k++)
            s->knots_v[3 * j + 1 + k] = tv[j];
    int at = 7 + m + n;
    for (int i = 0; i < m && status == SC_OK; i++) {
        for (int j = 0; j < n && status == SC_OK; j++, at += 48) {
            double hu = tu[i + 1] - tu[i], hv = tv[j + 1] - tv[j];
            for (int d = 0; d < 3 && status == SC_OK; d++) {
                double c[16], rows[4][4], b[4][4];
                for (int k = 0; k < 16 && status == SC_OK; k++)
                    status = iges_real(r, p, at + 16 * d + k, &c[k]);
                /* along s for each power of t, then along t */
                for (int pb = 0; pb < 4; pb++)
                    iges_power_to_bezier(c + 4 * pb, hu, rows[pb]);
                for (int a = 0; a < 4; a++) {
                    double col[4] = {rows[0][a], rows[1][a], rows[2][a], rows[3][a]}, out[4];
                    iges_power_to_bezier(col, hv, out);
                    for (int bb = 0; bb < 4; bb++)
                        b[a][bb] = out[bb];
                }
                for (int a = 0; a < 4; a++)
                    for (int bb = 0; bb < 4; bb++) {
                        double *q = s->cp + 4 * ((size_t)(3 * j + bb) * s->nu + 3 * i + a);
                        q[d] = b[a][bb];
                        q[3] = 1;
                    }
            }
        }
        at += 48; /* the row's unused values */
    }
    free(tu);
    if (status)
        return SC_FAIL;
    sc_surface_update_rational(s);
    return 1;
}

/* Relative to the base surface's size: how close the fitted offset
 * surface is made to the true offset. */
#define OFFSET_TOL 1e-5

static double box_size(const sc_surface *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < (size_t)s->nu * s->nv; k++)
        for (int d = 0; d < 3; d++) {
            double x = s->cp[4 * k + d] / s->cp[4 * k + 3];
            lo[d] = fmin(lo[d], x);
            hi[d] = fmax(hi[d], x);
        }
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* 140: NDX, NDY, NDZ, D, DE: the surface DE moved by D along its unit
 * normal, fitted (sc_offset_fit) within OFFSET_TOL of its size. The base
 * is taken in the 140's space (its own transformation applied). */
static int read_140(reader *r, const params *p, iges_surface *sf)
{
    double d, m[12];
    int base, e = p->entity;
    if (iges_need(r, p, 5) || iges_real(r, p, 4, &d) || iges_pointer(r, p, 5, &base))
        return SC_FAIL;
    if (base < 0)
        return iges_fail(r, e, iges_line(r, p, 5), "its surface pointer is null");
    if (r->ent[base].busy)
        return iges_fail(r, e, 0, "reference cycle: the offset surface is its own base");
    iges_surface b;
    r->ent[e].busy = 1;
    int status = iges_read_surface(r, base, &b);
    r->ent[e].busy = 0;
    if (status != 1 || b.need_bounds) {
        sc_surface_free(&b.nurbs);
        return status == SC_FAIL ? SC_FAIL : 0;
    }
    if (iges_xform(r, base, m)) {
        sc_surface_free(&b.nurbs);
        return SC_FAIL;
    }
    memcpy(b.nurbs.xform, m, sizeof m);
    sc_surface_bake_xform(&b.nurbs);
    double dev, tol = OFFSET_TOL * box_size(&b.nurbs);
    status = sc_offset_fit(&b.nurbs, d, tol, &sf->nurbs, &dev);
    sc_surface_free(&b.nurbs);
    if (status == SC_FAIL)
        return iges_fail_oom(r, e, sc_alloc_failed_bytes(), "the fitted offset surface");
    r->scene->offset_surfaces++;
    r->scene->offset_dev = fmax(r->scene->offset_dev, dev);
    if (status)
        sc_log(SC_LOG_WARN, "%s:%d: entity 140 (D %d): the offset surface is fitted within "
               "%.3g, not the %.3g asked for", r->name, r->ent[e].line, 2 * e + 1, dev, tol);
    return 1;
}

int iges_read_surface(reader *r, int e, iges_surface *sf)
{
    memset(sf, 0, sizeof *sf);
    sf->type = r->ent[e].type;
    if (sf->type == 128)
        return iges_read_128(r, e, &sf->nurbs) ? SC_FAIL : 1;
    params p;
    double rad[2];
    int status = 0;
    switch (sf->type) {
    case 108: /* A, B, C, D: the plane A x + B y + C z = D (unbounded form 0) */
    {
        double v[4];
        if (iges_params(r, e, &p) || iges_leading_reals(r, &p, 4, v))
            return SC_FAIL;
        double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]), m[12];
        if (!(len > 0))
            return iges_fail(r, e, iges_line(r, &p, 1), "plane with normal of length 0");
        for (int d = 0; d < 3; d++) {
            sf->z[d] = v[d] / len;
            sf->o[d] = sf->z[d] * v[3] / len;
        }
        (void)m;
        frame_x(sf->z, NULL, sf->x);
        cross(sf->z, sf->x, sf->y);
        sf->need_bounds = IGES_BOUND_PLANE;
        return 1;
    }
    case 190:
        if (iges_params(r, e, &p) || iges_need(r, &p, 2) || analytic_frame(r, &p, 1, 2, 3, sf))
            return SC_FAIL;
        sf->need_bounds = IGES_BOUND_PLANE;
        return 1;
    case 192:
    case 194:
        if (iges_params(r, e, &p) || iges_need(r, &p, sf->type == 192 ? 3 : 4) ||
            iges_real(r, &p, 3, &sf->radius))
            return SC_FAIL;
        if (sf->type == 194) {
            double angle;
            if (iges_real(r, &p, 4, &angle))
                return SC_FAIL;
            if (!(fabs(angle) < 180))
                return iges_fail(r, e, iges_line(r, &p, 4), "cone semi-angle %g degrees", angle);
            sf->slope = tan(angle * M_PI / 180);
            if (fabs(angle) > 89.999) {
                /* a flat cone: the plane through o across the axis */
                if (analytic_frame(r, &p, 1, 2, 5, sf))
                    return SC_FAIL;
                sf->need_bounds = IGES_BOUND_PLANE;
                return 1;
            }
        }
        if (!(sf->radius >= 0))
            return iges_fail(r, e, iges_line(r, &p, 3), "radius %g", sf->radius);
        if (analytic_frame(r, &p, 1, 2, sf->type == 192 ? 4 : 5, sf))
            return SC_FAIL;
        sf->need_bounds = IGES_BOUND_AXIS;
        return 1;
    case 196: /* LOC, RADIUS, AXIS, REFD */
        if (iges_params(r, e, &p) || iges_need(r, &p, 2) || iges_real(r, &p, 2, &rad[0]))
            return SC_FAIL;
        if (!(rad[0] > 0))
            return iges_fail(r, e, iges_line(r, &p, 2), "sphere radius %g", rad[0]);
        if (r->ent[e].form == 1) {
            if (iges_need(r, &p, 3) || analytic_frame(r, &p, 1, 3, 4, sf))
                return SC_FAIL;
        } else {
            double z[3] = {0, 0, 1};
            if (read_vector(r, &p, 1, 116, sf->o))
                return SC_FAIL;
            memcpy(sf->z, z, sizeof z);
            frame_x(sf->z, NULL, sf->x);
            cross(sf->z, sf->x, sf->y);
        }
        return revolved_circle(r, e, sf, 0, rad[0], -M_PI / 2, M_PI / 2);
    case 198: /* LOC, AXIS, MAJRAD, MINRAD, REFD */
        if (iges_params(r, e, &p) || iges_need(r, &p, 4) || iges_real(r, &p, 3, &rad[0]) ||
            iges_real(r, &p, 4, &rad[1]))
            return SC_FAIL;
        if (!(rad[1] > 0) || !(rad[0] > 0))
            return iges_fail(r, e, iges_line(r, &p, 3), "torus radii %g and %g", rad[0], rad[1]);
        if (analytic_frame(r, &p, 1, 2, 5, sf))
            return SC_FAIL;
        return revolved_circle(r, e, sf, rad[0], rad[1], 0, 2 * M_PI);
    case 114:
    case 140:
        if (iges_params(r, e, &p))
            return SC_FAIL;
        status = sf->type == 114 ? read_114(r, &p, sf) : read_140(r, &p, sf);
        if (status != 1)
            sc_surface_free(&sf->nurbs);
        return status;
    case 118:
    case 120:
    case 122:
        if (iges_params(r, e, &p))
            return SC_FAIL;
        r->ent[e].busy = 1;
        status = sf->type == 118 ? read_118(r, &p, sf) : sf->type == 120 ? read_120(r, &p, sf)
                                                                        : read_122(r, &p, sf);
        r->ent[e].busy = 0;
        if (status == 1) {
            sc_error check;
            if (sc_surface_check(&sf->nurbs, &check)) {
                sc_surface_free(&sf->nurbs);
                return iges_fail(r, e, 0, "%s", check.message);
            }
        }
        return status;
    default:
        return 0;
    }
}

/* The control points of the model-space loops, in the frame's coordinates:
 * lo/hi along x, y, z. */
static void loop_box(const iges_surface *sf, const curve_list *loops, int n, double lo[3],
                     double hi[3])
{
    const double *ax[3] = {sf->x, sf->y, sf->z};
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (int l = 0; l < n; l++)
        for (int c = 0; c < loops[l].n; c++) {
            const sc_curve *cv = &loops[l].items[c];
            for (int i = 0; i < cv->ncp; i++) {
                const double *q = cv->cp + 4 * i;
                double rel[3];
                for (int d = 0; d < 3; d++)
                    rel[d] = q[d] / q[3] - sf->o[d];
                for (int k = 0; k < 3; k++) {
                    double t = rel[0] * ax[k][0] + rel[1] * ax[k][1] + rel[2] * ax[k][2];
                    lo[k] = fmin(lo[k], t);
                    hi[k] = fmax(hi[k], t);
                }
            }
        }
}

int iges_bound_surface(iges_surface *sf, const curve_list *loops, int n)
{
    double lo[3], hi[3];
    loop_box(sf, loops, n, lo, hi);
    if (!(lo[0] <= hi[0]))
        return IGES_NO_BOUNDS;
    if (sf->need_bounds == IGES_BOUND_PLANE) {
        double mu = 0.01 * (hi[0] - lo[0]) + 1e-9, mv = 0.01 * (hi[1] - lo[1]) + 1e-9;
        return sc_plane_patch(sf->o, sf->x, sf->y, lo[0] - mu, hi[0] + mu, lo[1] - mv,
                              hi[1] + mv, &sf->nurbs);
    }
    /* cylinder or cone: the axis range of the loops, a little more; a cone
     * stops at its apex */
    double h0 = lo[2], h1 = hi[2], m = 0.01 * (h1 - h0) + 1e-9 * (1 + sf->radius);
    h0 -= m;
    h1 += m;
    if (sf->slope != 0) {
        double apex = -sf->radius / sf->slope;
        if (sf->slope > 0)
            h0 = fmax(h0, apex);
        else
            h1 = fmin(h1, apex);
    }
    if (!(h1 > h0))
        return IGES_NO_BOUNDS;
    double p0[3], p1[3];
    for (int d = 0; d < 3; d++) {
        p0[d] = sf->o[d] + h0 * sf->z[d] + fmax(0, sf->radius + sf->slope * h0) * sf->x[d];
        p1[d] = sf->o[d] + h1 * sf->z[d] + fmax(0, sf->radius + sf->slope * h1) * sf->x[d];
    }
    sc_curve gen;
    if (sc_line3(p0, p1, &gen))
        return SC_FAIL;
    int status = sc_revolve(&gen, sf->o, sf->z, 0, 2 * M_PI, &sf->nurbs);
    sc_curve_free(&gen);
    return status;
}

int iges_plane_curves(const iges_surface *sf, const curve_list *in, curve_list *out)
{
    for (int c = 0; c < in->n; c++) {
        const sc_curve *src = &in->items[c];
        sc_curve *dst = iges_list_push(out);
        if (!dst || sc_curve_try_alloc(dst, 2, src->degree, src->ncp))
            return SC_FAIL;
        memcpy(dst->knots, src->knots, sizeof(double) * (size_t)(src->ncp + src->degree + 1));
        for (int i = 0; i < src->ncp; i++) {
            const double *q = src->cp + 4 * i;
            double rel[3];
            for (int d = 0; d < 3; d++)
                rel[d] = q[d] - sf->o[d] * q[3];
            dst->cp[3 * i] = rel[0] * sf->x[0] + rel[1] * sf->x[1] + rel[2] * sf->x[2];
            dst->cp[3 * i + 1] = rel[0] * sf->y[0] + rel[1] * sf->y[1] + rel[2] * sf->y[2];
            dst->cp[3 * i + 2] = q[3];
        }
    }
    return SC_OK;
}
