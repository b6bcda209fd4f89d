/* iges_surfaces.c — IGES surfaces as NURBS: 128 as it is, and the others
 * converted exactly with the constructions of runtime/model/analytic.h
 * (108/190 planes, 192–198 cylinders, cones, spheres, tori, 118 ruled,
 * 120 revolution, 122 tabulated cylinder, 114 parametric splines), 140
 * offset surfaces fitted within a stated tolerance. */
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
    sc_surface_alloc(s, m1, m2, (int)nu, (int)nv);
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
    if (p->ntok - 1 >= at + 3) {
        for (int i = 0; i < 4; i++)
            if (iges_real(r, p, at + i, &range[i]))
                return SC_FAIL;
        if (range[0] < range[1])
            sc_surface_restrict(s, 0, range[0], range[1]);
        if (range[2] < range[3])
            sc_surface_restrict(s, 1, range[2], range[3]);
    } else {
        sc_surface_restrict(s, 0, s->knots_u[m1], s->knots_u[s->nu]);
        sc_surface_restrict(s, 1, s->knots_v[m2], s->knots_v[s->nv]);
    }
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
