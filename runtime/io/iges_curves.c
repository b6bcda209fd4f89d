/* iges_curves.c — IGES curves as NURBS: the parameter-space trim curves of
 * a loop (110 lines, 100 arcs as rational quadratics, 126 B-splines, 102
 * composites, and through iges_curve3 the 104 conics and 112 parametric
 * splines), charged to the geometry budget, and the same entities in model
 * space (3D) for loops that have no parameter-space curves. */
#include "analytic.h"
#include "iges_local.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int list_dim(const curve_list *l)
{
    return l->dim ? l->dim : 2;
}

/* A new curve of the list, its arrays allocated; NULL (the error recorded)
 * when memory runs out. */
static sc_curve *new_curve(reader *r, const params *p, curve_list *out, int degree, int ncp)
{
    sc_curve *c = iges_list_push(out);
    if (!c) {
        iges_fail_oom(r, p->entity, sc_alloc_failed_bytes(), "the list of curves");
        return NULL;
    }
    if (sc_curve_try_alloc(c, list_dim(out), degree, ncp)) {
        iges_fail_oom(r, p->entity, sc_curve_bytes(list_dim(out), degree, ncp), "the curve");
        return NULL;
    }
    return c;
}

static int read_110(reader *r, const params *p, const double m[12], curve_list *out)
{
    double v[6];
    if (iges_leading_reals(r, p, 6, v))
        return SC_FAIL;
    sc_curve *c = new_curve(r, p, out, 1, 2);
    if (!c)
        return SC_FAIL;
    c->knots[0] = c->knots[1] = 0;
    c->knots[2] = c->knots[3] = 1;
    iges_put_point(c, 0, m, v[0], v[1], v[2], 1);
    iges_put_point(c, 1, m, v[3], v[4], v[5], 1);
    return SC_OK;
}

/* A circular arc, counter-clockwise from start to end about the centre in
 * the plane z = ZT of its definition space, as rational quadratic pieces
 * of at most 90° (middle weight cos(half the piece's angle)). */
static int read_100(reader *r, const params *p, const double m[12], curve_list *out)
{
    double v[7];
    if (iges_leading_reals(r, p, 7, v))
        return SC_FAIL;
    double zt = v[0], cx = v[1], cy = v[2];
    double radius = hypot(v[3] - cx, v[4] - cy);
    if (!(radius > 0) || !isfinite(radius))
        return iges_fail(r, p->entity, iges_line(r, p, 2), "circular arc of radius %g",
                           radius);
    double a0 = atan2(v[4] - cy, v[3] - cx), a1 = atan2(v[6] - cy, v[5] - cx);
    double sweep = a1 - a0;
    if (hypot(v[5] - v[3], v[6] - v[4]) <= 1e-12 * radius)
        sweep = 2 * M_PI;
    while (sweep <= 0)
        sweep += 2 * M_PI;
    int pieces = (int)ceil(sweep / (M_PI / 2) - 1e-9);
    if (pieces < 1)
        pieces = 1;
    double half = sweep / pieces / 2, w = cos(half);
    sc_curve *c = new_curve(r, p, out, 2, 2 * pieces + 1);
    if (!c)
        return SC_FAIL;
    for (int i = 0; i < 3; i++) {
        c->knots[i] = 0;
        c->knots[2 * pieces + 1 + i] = pieces;
    }
    for (int i = 1; i < pieces; i++)
        c->knots[2 * i + 1] = c->knots[2 * i + 2] = i;
    for (int i = 0; i <= 2 * pieces; i++) {
        double angle = a0 + i * half;
        double reach = i % 2 ? radius / w : radius;
        iges_put_point(c, i, m, cx + reach * cos(angle), cy + reach * sin(angle), zt, i % 2 ? w : 1);
    }
    return SC_OK;
}

/* 104 conic arc: A x² + B xy + C y² + D x + E y + F = 0 in the plane
 * z = ZT, from (X1, Y1) to (X2, Y2). An ellipse (form 1) is an affine image
 * of a circle: centre and axes from the quadratic form, counter-clockwise
 * from start to end (start = end: the whole ellipse). A parabola (form 3)
 * arc is a quadratic Bézier whose middle point is where the end tangents
 * meet. A hyperbola (form 2) arc is made of rational quadratic pieces
 * (below). */
static int read_104(reader *r, const params *p, const double m[12], curve_list *out)
{
    double v[11];
    if (iges_leading_reals(r, p, 11, v))
        return SC_FAIL;
    double A = v[0], B = v[1], C = v[2], D = v[3], E = v[4], F = v[5], zt = v[6];
    double xs = v[7], ys = v[8], xe = v[9], ye = v[10];
    double disc = B * B - 4 * A * C, scale = fabs(A) + fabs(B) + fabs(C);
    if (!(scale > 0))
        return iges_fail(r, p->entity, iges_line(r, p, 1), "conic with no quadratic terms");
    if (disc < -1e-12 * scale * scale) {
        /* centre: gradient zero */
        double det = 4 * A * C - B * B;
        double x0 = (B * E - 2 * C * D) / det, y0 = (B * D - 2 * A * E) / det;
        double f = F + 0.5 * (D * x0 + E * y0);
        double th = 0.5 * atan2(B, A - C), c = cos(th), s = sin(th);
        double l1 = A * c * c + B * c * s + C * s * s, l2 = A * s * s - B * c * s + C * c * c;
        if (!(-f / l1 > 0) || !(-f / l2 > 0))
            return iges_fail(r, p->entity, iges_line(r, p, 1), "ellipse with no real points");
        double rx = sqrt(-f / l1), ry = sqrt(-f / l2);
        double ex[3] = {c, s, 0}, ey[3] = {-s, c, 0}, ctr[3] = {x0, y0, zt};
        double a0 = atan2(((xs - x0) * ey[0] + (ys - y0) * ey[1]) / ry,
                          ((xs - x0) * ex[0] + (ys - y0) * ex[1]) / rx);
        double a1 = atan2(((xe - x0) * ey[0] + (ye - y0) * ey[1]) / ry,
                          ((xe - x0) * ex[0] + (ye - y0) * ex[1]) / rx);
        double sweep = a1 - a0;
        if (hypot(xe - xs, ye - ys) <= 1e-12 * fmax(rx, ry))
            sweep = 2 * M_PI;
        while (sweep <= 0)
            sweep += 2 * M_PI;
        sc_curve e3, *dst;
        if (sc_ellipse_arc(3, ctr, ex, ey, rx, ry, a0, a0 + sweep, &e3))
            return iges_fail_oom(r, p->entity, sc_alloc_failed_bytes(), "the ellipse");
        if (!(dst = new_curve(r, p, out, 2, e3.ncp))) {
            sc_curve_free(&e3);
            return SC_FAIL;
        }
        memcpy(dst->knots, e3.knots, sizeof(double) * (size_t)(e3.ncp + 3));
        for (int i = 0; i < e3.ncp; i++) {
            const double *q = e3.cp + 4 * i;
            iges_put_point(dst, i, m, q[0] / q[3], q[1] / q[3], zt, q[3]);
        }
        sc_curve_free(&e3);
        return SC_OK;
    }
    if (fabs(disc) <= 1e-12 * scale * scale) {
        /* tangents: perpendicular to the gradient at each end */
        double gs[2] = {2 * A * xs + B * ys + D, B * xs + 2 * C * ys + E};
        double ge[2] = {2 * A * xe + B * ye + D, B * xe + 2 * C * ye + E};
        double ts[2] = {-gs[1], gs[0]}, te[2] = {-ge[1], ge[0]};
        double den = ts[0] * te[1] - ts[1] * te[0];
        if (!(fabs(den) > 1e-14 * hypot(ts[0], ts[1]) * hypot(te[0], te[1])))
            return iges_fail(r, p->entity, iges_line(r, p, 8), "parabola arc with parallel end "
                             "tangents");
        double k = ((xe - xs) * te[1] - (ye - ys) * te[0]) / den;
        sc_curve *c = new_curve(r, p, out, 2, 3);
        if (!c)
            return SC_FAIL;
        c->knots[0] = c->knots[1] = c->knots[2] = 0;
        c->knots[3] = c->knots[4] = c->knots[5] = 1;
        iges_put_point(c, 0, m, xs, ys, zt, 1);
        iges_put_point(c, 1, m, xs + k * ts[0], ys + k * ts[1], zt, 1);
        iges_put_point(c, 2, m, xe, ye, zt, 1);
        return SC_OK;
    }
    /* hyperbola: about its centre, l1 X^2 + l2 Y^2 = -f with l1, l2 of
     * opposite signs; X = ±a cosh s, Y = b sinh s on the branch of the
     * ends. A piece from s0 to s1 is a rational quadratic with middle
     * point (a cosh m, b sinh m) / cosh h and weight cosh h (m the middle,
     * h half the span): the hyperbolic counterpart of a circle's arc. */
    double det = 4 * A * C - B * B;
    double x0 = (B * E - 2 * C * D) / det, y0 = (B * D - 2 * A * E) / det;
    double f = F + 0.5 * (D * x0 + E * y0);
    double th = 0.5 * atan2(B, A - C), c = cos(th), s = sin(th);
    double l1 = A * c * c + B * c * s + C * s * s, l2 = A * s * s - B * c * s + C * c * c;
    if (-f / l1 < 0) { /* make X the transverse axis */
        double tmp = l1;
        l1 = l2;
        l2 = tmp;
        double nc = -s, ns = c;
        c = nc;
        s = ns;
    }
    if (!(-f / l1 > 0) || !(f / l2 > 0))
        return iges_fail(r, p->entity, iges_line(r, p, 1), "degenerate hyperbola");
    double a = sqrt(-f / l1), b = sqrt(f / l2);
    double xs_ = (xs - x0) * c + (ys - y0) * s, ys_ = -(xs - x0) * s + (ys - y0) * c;
    double xe_ = (xe - x0) * c + (ye - y0) * s, ye_ = -(xe - x0) * s + (ye - y0) * c;
    if (xs_ * xe_ < 0)
        return iges_fail(r, p->entity, iges_line(r, p, 8), "hyperbola arc with its ends on "
                         "two branches");
    double sign = xs_ < 0 ? -1 : 1, s0 = asinh(ys_ / b), s1 = asinh(ye_ / b);
    int pieces = (int)ceil(fabs(s1 - s0) / 2);
    pieces = pieces < 1 ? 1 : pieces > 64 ? 64 : pieces;
    sc_curve *k = new_curve(r, p, out, 2, 2 * pieces + 1);
    if (!k)
        return SC_FAIL;
    for (int i = 0; i < 3; i++) {
        k->knots[i] = 0;
        k->knots[2 * pieces + 1 + i] = pieces;
    }
    for (int i = 1; i < pieces; i++)
        k->knots[2 * i + 1] = k->knots[2 * i + 2] = i;
    double half = (s1 - s0) / pieces / 2, w = cosh(half);
    for (int i = 0; i <= 2 * pieces; i++) {
        double at = s0 + i * half, reach = i % 2 ? 1 / w : 1;
        double X = sign * a * cosh(at) * reach, Y = b * sinh(at) * reach;
        iges_put_point(k, i, m, x0 + X * c - Y * s, y0 + X * s + Y * c, zt, i % 2 ? w : 1);
    }
    return SC_OK;
}

/* Cubic power-basis coefficients c0 + c1 s + c2 s² + c3 s³ on [0, h] as
 * the four Bézier points of the same cubic: b_k = sum over j <= k of
 * C(k, j) / C(3, j) · c_j h^j. */
void iges_power_to_bezier(const double c[4], double h, double b[4])
{
    double a[4] = {c[0], c[1] * h, c[2] * h * h, c[3] * h * h * h};
    b[0] = a[0];
    b[1] = a[0] + a[1] / 3;
    b[2] = a[0] + 2 * a[1] / 3 + a[2] / 3;
    b[3] = a[0] + a[1] + a[2] + a[3];
}

/* 112 parametric spline curve: CTYPE, H, NDIM, N, T(1..N+1), then per
 * segment AX BX CX DX AY … DZ (x = AX + BX s + CX s² + DX s³ with
 * s = t − T(i)): exactly a cubic B-spline with triple knots at the
 * breakpoints. */
static int read_112(reader *r, const params *p, const double m[12], curve_list *out)
{
    int n;
    if (iges_need(r, p, 4) || iges_count(r, p, 4, 13, &n))
        return SC_FAIL;
    if (n < 1)
        return iges_fail(r, p->entity, iges_line(r, p, 4), "no segments");
    double *bp = sc_try_alloc((size_t)n + 1, sizeof(double));
    if (!bp)
        return iges_fail_oom(r, p->entity, ((size_t)n + 1) * sizeof(double), "breakpoints");
    for (int i = 0; i <= n; i++)
        if (iges_real(r, p, 5 + i, &bp[i])) {
            free(bp);
            return SC_FAIL;
        }
    for (int i = 0; i < n; i++)
        if (!(bp[i + 1] > bp[i])) {
            free(bp);
            return iges_fail(r, p->entity, iges_line(r, p, 5 + i), "breakpoints do not "
                             "increase (%.17g, %.17g)", bp[i], bp[i + 1]);
        }
    sc_curve *c = new_curve(r, p, out, 3, 3 * n + 1);
    if (!c) {
        free(bp);
        return SC_FAIL;
    }
    for (int k = 0; k < 4; k++) {
        c->knots[k] = bp[0];
        c->knots[3 * n + 1 + k] = bp[n];
    }
    for (int i = 1; i < n; i++)
        for (int k = 0; k < 3; k++)
            c->knots[3 * i + 1 + k] = bp[i];
    int at = 6 + n;
    for (int i = 0; i < n; i++, at += 12) {
        double b[3][4];
        for (int d = 0; d < 3; d++) {
            double coef[4];
            for (int k = 0; k < 4; k++)
                if (iges_real(r, p, at + 4 * d + k, &coef[k])) {
                    free(bp);
                    return SC_FAIL;
                }
            iges_power_to_bezier(coef, bp[i + 1] - bp[i], b[d]);
        }
        for (int k = i ? 1 : 0; k < 4; k++)
            iges_put_point(c, 3 * i + k, m, b[0][k], b[1][k], b[2][k], 1);
    }
    free(bp);
    return SC_OK;
}

static int read_126(reader *r, const params *p, const double m[12], curve_list *out)
{
    int e = p->entity, k, deg, prop[4];
    if (iges_need(r, p, 6) || iges_int(r, p, 1, &k) || iges_int(r, p, 2, &deg))
        return SC_FAIL;
    for (int i = 0; i < 4; i++)
        if (iges_int(r, p, 3 + i, &prop[i]))
            return SC_FAIL;
    if (deg < 1)
        return iges_fail(r, e, iges_line(r, p, 2), "degree %d: a curve needs degree 1 or more",
                           deg);
    if (deg > SC_READ_MAX_DEGREE)
        return iges_fail(r, e, iges_line(r, p, 2), "degree %d: above the %d this reader "
                           "accepts (docs/limits.md)", deg, SC_READ_MAX_DEGREE);
    if (k < deg)
        return iges_fail(r, e, iges_line(r, p, 1), "degree %d needs at least %d control "
                           "points, has %d", deg, deg + 1, k + 1);
    long long n = (long long)k + 1, nk = n + deg + 1;
    if (iges_need(r, p, 6 + nk + 4 * n))
        return SC_FAIL;
    sc_curve *c = new_curve(r, p, out, deg, (int)n);
    if (!c)
        return SC_FAIL;
    int wi = c->dim, st = c->dim + 1;
    int at = 7;
    if (iges_read_knots(r, p, at, c->knots, (int)nk, deg, "curve"))
        return SC_FAIL;
    at += (int)nk;
    int bad_weight = -1;
    for (int i = 0; i < n; i++) {
        if (iges_real(r, p, at + i, &c->cp[st * i + wi]))
            return SC_FAIL;
        if (!(c->cp[st * i + wi] > 0) && bad_weight < 0)
            bad_weight = i;
    }
    if (bad_weight >= 0 && prop[2] != 1)
        return iges_fail(r, e, iges_line(r, p, at + bad_weight), "weight %d is %.17g (weights "
                           "of a rational curve must be > 0)", bad_weight,
                           c->cp[st * bad_weight + wi]);
    at += (int)n;
    for (int i = 0; i < n; i++) {
        double x[3];
        for (int d = 0; d < 3; d++)
            if (iges_real(r, p, at + 3 * i + d, &x[d]))
                return SC_FAIL;
        iges_put_point(c, i, m, x[0], x[1], x[2], bad_weight >= 0 ? 1.0 : c->cp[st * i + wi]);
    }
    at += 3 * (int)n;
    /* V(0), V(1): the used part of the parameter range. */
    double range[2] = {c->knots[deg], c->knots[n]};
    if (p->ntok - 1 >= at + 1) {
        double v[2];
        if (iges_real(r, p, at, &v[0]) || iges_real(r, p, at + 1, &v[1]))
            return SC_FAIL;
        if (v[0] < v[1])
            memcpy(range, v, sizeof range);
    }
    if (sc_curve_restrict(c, range[0], range[1]))
        return iges_fail_oom(r, e, sc_alloc_failed_bytes(), "restricting the curve");
    return SC_OK;
}

/* Charges the curves [first, n) just read from entity e to the budget. */
int iges_charge_curves(reader *r, int e, const curve_list *l, int first)
{
    if (l->n > SC_MAX_LOOP_PIECES)
        return iges_fail(r, e, 0, "a trim loop of more than %d curves (docs/limits.md)",
                           SC_MAX_LOOP_PIECES);
    size_t bytes = 0;
    char what[64];
    for (int i = first; i < l->n; i++)
        bytes += sc_curve_bytes(2, l->items[i].degree, l->items[i].ncp);
    snprintf(what, sizeof what, "entity %d (D %d) in a trim loop", r->ent[e].type, 2 * e + 1);
    return sc_budget_charge(&r->budget, bytes, what, r->name, r->ent[e].line, r->err);
}

/* How many curves entity e expands into as a trim curve, at most
 * SC_MAX_LOOP_PIECES + 1, remembered per entity so that a composite listing
 * another many times is counted in time linear in the entities. Anything
 * that is not a composite is one curve; errors (cycles, bad pointers) count
 * as one here and are reported when the loop is built. */
static int count_pieces(reader *r, int e, int depth)
{
    entity *en = &r->ent[e];
    if (en->pieces)
        return en->pieces;
    if (en->type != 102 || en->counting || depth > MAX_NESTING)
        return 1;
    params p; /* the cache's: nothing to free */
    int count = 0, member;
    long long total = 0;
    sc_error *err = r->err;
    r->err = NULL;
    if (!iges_params(r, e, &p) && !iges_need(r, &p, 1) && !iges_count(r, &p, 1, 1, &count)) {
        en->counting = 1;
        for (int i = 0; i < count && total <= SC_MAX_LOOP_PIECES; i++)
            if (iges_pointer(r, &p, 2 + i, &member) == SC_OK && member >= 0)
                total += count_pieces(r, member, depth + 1);
        en->counting = 0;
    }
    r->err = err;
    en->pieces = total > SC_MAX_LOOP_PIECES ? SC_MAX_LOOP_PIECES + 1 : total < 1 ? 1 : (int)total;
    return en->pieces;
}

/* Curves [first, n) of the list run backwards: last first, each reversed. */
void iges_reverse_chain(curve_list *l, int first)
{
    for (int i = first, j = l->n - 1; i < j; i++, j--) {
        sc_curve t = l->items[i];
        l->items[i] = l->items[j];
        l->items[j] = t;
    }
    for (int i = first; i < l->n; i++)
        sc_curve_reverse(&l->items[i]);
}

/* Appends the 2D curves of a parameter-space curve entity to `out`, in the
 * entity's own order or reversed. `parent` is the transformation of the
 * referring composite. Returns SC_OK, SC_FAIL, or LOOP_UNSUPPORTED for a
 * curve type this reader does not convert (r->unsupported_entity). */
int iges_trim_curves(reader *r, int e, const double parent[12], int reversed, curve_list *out,
                       int depth)
{
    entity *en = &r->ent[e];
    if (en->busy)
        return iges_fail(r, e, 0, "reference cycle: the entity contains itself");
    if (depth > MAX_NESTING)
        return iges_fail(r, e, 0, "composite curves nested more than %d deep", MAX_NESTING);
    if (en->type != 100 && en->type != 102 && en->type != 104 && en->type != 110 &&
        en->type != 112 && en->type != 126) {
        r->unsupported_entity = e;
        return LOOP_UNSUPPORTED;
    }
    double own[12], m[12];
    if (iges_xform(r, e, own))
        return SC_FAIL;
    iges_compose(parent, own, m);
    params p;
    if (iges_params(r, e, &p))
        return SC_FAIL;
    int first = out->n, status = SC_OK;
    en->busy = 1;
    switch (en->type) {
    case 100: status = read_100(r, &p, m, out); break;
    case 110: status = read_110(r, &p, m, out); break;
    case 126: status = read_126(r, &p, m, out); break;
    case 104: status = read_104(r, &p, m, out); break;
    case 112: status = read_112(r, &p, m, out); break;
    case 102: {
        int count = 0;
        /* Members may repeat: the expansion is counted before it is built. */
        if (count_pieces(r, e, depth) > SC_MAX_LOOP_PIECES - out->n) {
            en->busy = 0;
            return iges_fail(r, e, 0, "composite curve expands to more than %d curves in one "
                               "trim loop (members listed repeatedly; docs/limits.md)",
                               SC_MAX_LOOP_PIECES);
        }
        status = iges_need(r, &p, 1);
        if (status == SC_OK)
            status = iges_count(r, &p, 1, 1, &count);
        for (int i = 0; i < count && status == SC_OK; i++) {
            int member;
            status = iges_pointer(r, &p, 2 + i, &member);
            if (status == SC_OK && member < 0)
                status = iges_fail(r, e, iges_line(r, &p, 2 + i), "member %d is a null "
                                     "pointer", i + 1);
            if (status == SC_OK)
                status = iges_trim_curves(r, member, m, 0, out, depth + 1);
        }
        break;
    }
    }
    en->busy = 0;
    if (status == SC_OK && en->type != 102)
        status = iges_charge_curves(r, e, out, first);
    if (status == SC_OK && reversed)
        iges_reverse_chain(out, first);
    return status;
}

static double point_distance(const sc_curve *a, int ia, const sc_curve *b, int ib)
{
    const double *p = a->cp + 3 * ia, *q = b->cp + 3 * ib;
    return hypot(p[0] / p[2] - q[0] / q[2], p[1] / p[2] - q[1] / q[2]);
}

/* Members of a composite are sometimes written against the direction of
 * the chain: a curve whose end, not its start, meets the previous curve's
 * end is turned around. */
void iges_orient_chain(curve_list *l)
{
    if (l->n < 2)
        return;
    sc_curve *c = l->items;
    int last1 = c[1].ncp - 1, last0 = c[0].ncp - 1;
    double fwd = fmin(point_distance(&c[0], last0, &c[1], 0), point_distance(&c[0], last0, &c[1], last1));
    double rev = fmin(point_distance(&c[0], 0, &c[1], 0), point_distance(&c[0], 0, &c[1], last1));
    if (rev < fwd)
        sc_curve_reverse(&c[0]);
    for (int i = 1; i < l->n; i++) {
        int prev_end = c[i - 1].ncp - 1;
        if (point_distance(&c[i - 1], prev_end, &c[i], c[i].ncp - 1) <
            point_distance(&c[i - 1], prev_end, &c[i], 0))
            sc_curve_reverse(&c[i]);
    }
}
