/* nurbs.c — the NURBS core's evaluation (nurbs.h) in double precision:
 * span search (A2.1), basis functions and derivatives (A2.2/A2.3), curve and
 * surface points and partials, and normals at collapsed edges. Evaluation
 * is the hot path of the CPU reference ray caster: it works in stack
 * buffers for degrees up to MAX_STACK_DEGREE and only allocates beyond.
 * Rational geometry is evaluated in homogeneous form (x·w, y·w, z·w, w)
 * and divided at the end (quotient rule for derivatives). The operations
 * that build new curves and surfaces are in nurbs_ops.c. */
#include "nurbs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs_local.h"

/* Clamps into [lo, hi]; NaN goes to lo, so evaluation never reads outside
 * the control net. */
static double clamp_to(double x, double lo, double hi)
{
    return x >= lo ? (x <= hi ? x : hi) : lo;
}

/* ------------------------------------------------------------------ */
/* Knot spans and basis functions                                       */
/* ------------------------------------------------------------------ */

int sc_find_span(int degree, const double *knots, int ncp, double u)
{
    int n = ncp - 1;
    double lo = knots[degree], hi = knots[n + 1];
    if (!(u > lo)) /* also catches NaN */
        u = lo;
    if (u >= hi) {
        /* The domain's closed upper end belongs to the last span that is
         * not empty (interior knots may repeat up to degree+1 times). */
        int span = n;
        while (span > degree && !(knots[span] < knots[span + 1]))
            span--;
        return span;
    }
    int low = degree, high = n + 1;
    /* Invariant: knots[low] <= u < knots[high]. */
    while (high - low > 1) {
        int mid = (low + high) / 2;
        if (u < knots[mid])
            high = mid;
        else
            low = mid;
    }
    return low;
}

/* Cox–de Boor triangle: the degree+1 functions non-zero on the span, built
 * without divisions by zero since the span is not empty. */
static void basis_in(int span, double u, int degree, const double *knots, double *N,
                     double *left, double *right)
{
    N[0] = 1.0;
    for (int j = 1; j <= degree; j++) {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            double temp = N[r] / (right[r + 1] + left[j - r]);
            N[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        N[j] = saved;
    }
}

void sc_basis(int span, double u, int degree, const double *knots, double *N)
{
    double stack[2 * STACK_ORDER];
    double *buf = scratch(stack, 2 * STACK_ORDER, 2 * (size_t)(degree + 1));
    basis_in(span, u, degree, knots, N, buf, buf + degree + 1);
    scratch_release(buf, stack);
}

/* A2.3: the table ndu holds the basis functions of every degree up to
 * `degree` (upper triangle) and the knot differences (lower triangle); the
 * derivatives are combinations of its columns with coefficients a[][]. */
static void basis_ders_in(int span, double u, int degree, const double *knots, int n,
                          double *ders, double *work)
{
    int p = degree, order = p + 1;
    double *ndu = work;                    /* order × order */
    double *left = ndu + order * order;    /* order */
    double *right = left + order;          /* order */
    double *a = right + order;             /* 2 × order */
#define NDU(i, j) ndu[(i) * order + (j)]
    NDU(0, 0) = 1.0;
    for (int j = 1; j <= p; j++) {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        double saved = 0.0;
        for (int r = 0; r < j; r++) {
            NDU(j, r) = right[r + 1] + left[j - r];
            double temp = NDU(r, j - 1) / NDU(j, r);
            NDU(r, j) = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        NDU(j, j) = saved;
    }
    for (int j = 0; j <= p; j++)
        ders[j] = NDU(j, p);
    int nmax = n < p ? n : p;
    for (int r = 0; r <= p; r++) {
        double *a_prev = a, *a_next = a + order;
        a_prev[0] = 1.0;
        for (int k = 1; k <= nmax; k++) {
            double d = 0.0;
            int rk = r - k, pk = p - k;
            if (r >= k) {
                a_next[0] = a_prev[0] / NDU(pk + 1, rk);
                d = a_next[0] * NDU(rk, pk);
            }
            int j1 = rk >= -1 ? 1 : -rk;
            int j2 = r - 1 <= pk ? k - 1 : p - r;
            for (int j = j1; j <= j2; j++) {
                a_next[j] = (a_prev[j] - a_prev[j - 1]) / NDU(pk + 1, rk + j);
                d += a_next[j] * NDU(rk + j, pk);
            }
            if (r <= pk) {
                a_next[k] = -a_prev[k - 1] / NDU(pk + 1, r);
                d += a_next[k] * NDU(r, pk);
            }
            ders[k * order + r] = d;
            double *swap = a_prev;
            a_prev = a_next;
            a_next = swap;
        }
    }
#undef NDU
    double factor = p;
    for (int k = 1; k <= nmax; k++) {
        for (int j = 0; j <= p; j++)
            ders[k * order + j] *= factor;
        factor *= p - k;
    }
    for (int k = nmax + 1; k <= n; k++)
        for (int j = 0; j <= p; j++)
            ders[k * order + j] = 0.0;
}

static size_t basis_ders_work(int degree)
{
    size_t order = (size_t)degree + 1;
    return order * order + 4 * order;
}

void sc_basis_ders(int span, double u, int degree, const double *knots, int n, double *ders)
{
    enum { STACK_WORK = STACK_ORDER * STACK_ORDER + 4 * STACK_ORDER };
    double stack[STACK_WORK];
    double *work = scratch(stack, STACK_WORK, basis_ders_work(degree));
    basis_ders_in(span, u, degree, knots, n, ders, work);
    scratch_release(work, stack);
}

/* The basis functions and their first derivatives, cheaper than A2.3 for
 * the evaluation hot path: from the degree p−1 functions, with
 * T_j = N_{j−1,p−1} / (U[span+j] − U[span+j−p]) (zero outside 1..p),
 *   N_j = (u − U[span−p+j]) T_j + (U[span+j+1] − u) T_{j+1},
 *   N'_j = p (T_j − T_{j+1}).
 * `work` holds 3 (p + 1) + 1 doubles. */
static void basis_with_d1(int span, double u, int p, const double *knots, double *N, double *dN,
                          double *work)
{
    if (p == 0) {
        N[0] = 1.0;
        dN[0] = 0.0;
        return;
    }
    double *lower = work, *left = work + (p + 1), *right = left + (p + 1);
    basis_in(span, u, p - 1, knots, lower, left, right);
    double t_next = 0.0;
    for (int j = p; j >= 0; j--) {
        double t_j = j >= 1 ? lower[j - 1] / (knots[span + j] - knots[span + j - p]) : 0.0;
        N[j] = (u - knots[span - p + j]) * t_j + (knots[span + j + 1] - u) * t_next;
        dN[j] = p * (t_j - t_next);
        t_next = t_j;
    }
}

/* ------------------------------------------------------------------ */
/* Evaluation                                                           */
/* ------------------------------------------------------------------ */

void sc_curve_domain(const sc_curve *c, double *t0, double *t1)
{
    *t0 = c->knots[c->degree];
    *t1 = c->knots[c->ncp];
}

void sc_surface_domain(const sc_surface *s, double *u0, double *u1, double *v0, double *v1)
{
    *u0 = s->knots_u[s->deg_u];
    *u1 = s->knots_u[s->nu];
    *v0 = s->knots_v[s->deg_v];
    *v1 = s->knots_v[s->nv];
}

void sc_curve_eval(const sc_curve *c, double u, double *point, double *d1)
{
    enum { STACK_WORK = 5 * STACK_ORDER + 1 };
    double stack[STACK_WORK];
    int p = c->degree, order = p + 1, stride = c->dim + 1;
    double *buf = scratch(stack, STACK_WORK, 5 * (size_t)order + 1);
    double *ders = buf, *work = buf + 2 * order;
    u = clamp_to(u, c->knots[p], c->knots[c->ncp]);
    int span = sc_find_span(p, c->knots, c->ncp, u);
    if (d1)
        basis_with_d1(span, u, p, c->knots, ders, ders + order, work);
    else
        basis_in(span, u, p, c->knots, ders, work, work + order);
    double A[4] = {0}, dA[4] = {0};
    for (int j = 0; j <= p; j++) {
        const double *P = c->cp + (size_t)(span - p + j) * (size_t)stride;
        for (int k = 0; k < stride; k++) {
            A[k] += ders[j] * P[k];
            if (d1)
                dA[k] += ders[order + j] * P[k];
        }
    }
    double w = A[c->dim], dw = dA[c->dim];
    for (int k = 0; k < c->dim; k++) {
        point[k] = A[k] / w;
        if (d1)
            d1[k] = (dA[k] - dw * point[k]) / w;
    }
    scratch_release(buf, stack);
}

/* Homogeneous sums of a surface at (u, v): the point and, when `order_needed`
 * is 1, the partials and the mixed partial. */
typedef struct homog_ders {
    double S[4], Su[4], Sv[4], Suv[4];
} homog_ders;

static void surface_homog(const sc_surface *s, double u, double v, int order_needed,
                          homog_ders *h)
{
    int p = s->deg_u, q = s->deg_v;
    size_t work_u = 5 * (size_t)(p + 1) + 1, work_v = 5 * (size_t)(q + 1) + 1;
    enum { STACK_WORK = 2 * (5 * STACK_ORDER + 1) };
    double stack[STACK_WORK];
    double *buf = scratch(stack, STACK_WORK, work_u + work_v);
    double *Nu = buf, *Nv = buf + work_u;
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    u = clamp_to(u, u0, u1);
    v = clamp_to(v, v0, v1);
    int span_u = sc_find_span(p, s->knots_u, s->nu, u);
    int span_v = sc_find_span(q, s->knots_v, s->nv, v);
    double *work_pu = Nu + 2 * (p + 1), *work_pv = Nv + 2 * (q + 1);
    if (order_needed) {
        basis_with_d1(span_u, u, p, s->knots_u, Nu, Nu + p + 1, work_pu);
        basis_with_d1(span_v, v, q, s->knots_v, Nv, Nv + q + 1, work_pv);
    } else {
        basis_in(span_u, u, p, s->knots_u, Nu, work_pu, work_pu + p + 1);
        basis_in(span_v, v, q, s->knots_v, Nv, work_pv, work_pv + q + 1);
    }
    memset(h, 0, sizeof *h);
    for (int l = 0; l <= q; l++) {
        const double *row = s->cp + 4 * ((size_t)(span_v - q + l) * (size_t)s->nu +
                                         (size_t)(span_u - p));
        double t0[4] = {0}, t1[4] = {0};
        for (int k = 0; k <= p; k++) {
            const double *P = row + 4 * k;
            for (int c = 0; c < 4; c++)
                t0[c] += Nu[k] * P[c];
            if (order_needed)
                for (int c = 0; c < 4; c++)
                    t1[c] += Nu[p + 1 + k] * P[c];
        }
        for (int c = 0; c < 4; c++)
            h->S[c] += Nv[l] * t0[c];
        if (order_needed) {
            double dv = Nv[q + 1 + l];
            for (int c = 0; c < 4; c++) {
                h->Su[c] += Nv[l] * t1[c];
                h->Sv[c] += dv * t0[c];
                h->Suv[c] += dv * t1[c];
            }
        }
    }
    scratch_release(buf, stack);
}

/* Euclidean point, partials and mixed partial from the homogeneous sums by
 * the quotient rule. */
static void surface_euclid(const homog_ders *h, double p[3], double su[3], double sv[3],
                           double suv[3])
{
    double w = h->S[3];
    for (int c = 0; c < 3; c++)
        p[c] = h->S[c] / w;
    if (!su)
        return;
    for (int c = 0; c < 3; c++) {
        su[c] = (h->Su[c] - h->Su[3] * p[c]) / w;
        sv[c] = (h->Sv[c] - h->Sv[3] * p[c]) / w;
    }
    if (!suv)
        return;
    for (int c = 0; c < 3; c++)
        suv[c] = (h->Suv[c] - h->Suv[3] * p[c] - h->Su[3] * sv[c] - h->Sv[3] * su[c]) / w;
}

void sc_surface_eval(const sc_surface *s, double u, double v, double p[3], double su[3],
                     double sv[3])
{
    homog_ders h;
    int want = su || sv;
    surface_homog(s, u, v, want, &h);
    double su_buf[3], sv_buf[3];
    surface_euclid(&h, p, want ? (su ? su : su_buf) : NULL, sv ? sv : sv_buf, NULL);
}

void sc_surface_eval_world(const sc_surface *s, double u, double v, double p[3], double su[3],
                           double sv[3])
{
    sc_surface_eval(s, u, v, p, su, sv);
    sc_xform_point(s->xform, p, p);
    if (su)
        sc_xform_vector(s->xform, su, su);
    if (sv)
        sc_xform_vector(s->xform, sv, sv);
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm3(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* su × sv counts as a normal when its sine-weighted length is not lost in
 * the rounding of the larger partial: below this ratio the partials are
 * (nearly) parallel or one of them has (nearly) vanished. The threshold
 * balances the cancellation error of a tiny partial (~1e-16 / |partial|)
 * against the O(distance) error of the limit normal used instead. */
static const double NORMAL_SINE_MIN = 1e-8;

/* A partial this much shorter than the other counts as vanished (the
 * surface collapses along an edge through this point). */
static const double COLLAPSED_RATIO = 1e-6;

static int unit_if_clear(const double n[3], double scale, double out[3])
{
    double len = norm3(n);
    if (!(len > NORMAL_SINE_MIN * scale) || !isfinite(len))
        return -1;
    for (int c = 0; c < 3; c++)
        out[c] = n[c] / len;
    return 0;
}

int sc_surface_normal(const sc_surface *s, double u, double v, double n[3])
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    u = clamp_to(u, u0, u1);
    v = clamp_to(v, v0, v1);
    homog_ders h;
    double p[3], su[3], sv[3], suv[3], c[3];
    surface_homog(s, u, v, 1, &h);
    surface_euclid(&h, p, su, sv, suv);
    double lu = norm3(su), lv = norm3(sv), big = lu > lv ? lu : lv;
    cross3(su, sv, c);
    if (unit_if_clear(c, big * big, n) == 0)
        return 0;

    /* A collapsed edge: along v = v* the partial su vanishes, so near it
     * su ≈ (v − v*) suv and su × sv ≈ (v − v*) suv × sv; the factor's sign
     * is + on the lower edge and − on the upper one (and symmetrically for
     * a vanishing sv). This is the exact limit at the pole. */
    double lm = norm3(suv), small = lu < lv ? lu : lv;
    int collapsed = small <= COLLAPSED_RATIO * big;
    if (collapsed) {
        int su_vanishes = lu < lv;
        double sign = su_vanishes ? (v - v0 <= v1 - v ? 1.0 : -1.0)
                                  : (u - u0 <= u1 - u ? 1.0 : -1.0);
        if (su_vanishes)
            cross3(suv, sv, c);
        else
            cross3(su, suv, c);
        for (int k = 0; k < 3; k++)
            c[k] *= sign;
        if (unit_if_clear(c, su_vanishes ? lm * lv : lu * lm, n) == 0)
            return 0;
    }

    /* Corners where both partials vanish, parallel partials, or vanishing
     * second derivatives: step towards the domain's centre until the
     * normal is well defined. */
    double uc = 0.5 * (u0 + u1), vc = 0.5 * (v0 + v1);
    double f = 1e-7;
    for (int step = 0; step < 7; step++, f *= 10) {
        double ui = u + f * (uc - u), vi = v + f * (vc - v);
        surface_homog(s, ui, vi, 1, &h);
        surface_euclid(&h, p, su, sv, NULL);
        lu = norm3(su);
        lv = norm3(sv);
        big = lu > lv ? lu : lv;
        cross3(su, sv, c);
        if (unit_if_clear(c, big * big, n) == 0)
            return 0;
    }
    n[0] = n[1] = 0;
    n[2] = 1;
    return -1;
}
