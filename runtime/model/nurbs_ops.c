/* nurbs_ops.c — the NURBS operations that build new curves and surfaces
 * (nurbs.h): knot insertion and refinement (A5.1, A5.4), Bézier extraction
 * by refinement, splitting, clamping, restriction to a sub-domain,
 * reversal, and degree elevation by Bézier segments and exact knot removal
 * (A5.8's two-sided recursion). Surfaces run the curve algorithms on each
 * row or column of homogeneous points. Evaluation is in nurbs.c. */
#include "nurbs.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs_local.h"

/* ------------------------------------------------------------------ */
/* Curve algorithms on raw arrays (stride doubles per point), so that    */
/* surfaces can run them on their rows and columns.                      */
/* ------------------------------------------------------------------ */

static size_t knot_count(const sc_curve *c) { return (size_t)(c->ncp + c->degree + 1); }

static void copy_point(double *dst, const double *src, int stride)
{
    memcpy(dst, src, sizeof(double) * (size_t)stride);
}

/* dst = a·x + (1 − a)·y */
static void blend_point(double *dst, double a, const double *x, const double *y, int stride)
{
    for (int k = 0; k < stride; k++)
        dst[k] = a * x[k] + (1.0 - a) * y[k];
}

static int multiplicity(const double *knots, int nknots, double u)
{
    int m = 0;
    for (int i = 0; i < nknots; i++)
        if (knots[i] == u)
            m++;
    return m;
}

/* The k with U[k] <= u < U[k+1] that A5.1 needs, for any u in the closed
 * domain. sc_find_span maps the domain's upper end to the span below it,
 * right for evaluation but not for inserting there: an unclamped vector
 * has knots above the domain, and u must go in before them. */
static int insertion_span(const double *knots, int nknots, double u)
{
    int low = 0, high = nknots; /* first index with knots[i] > u lies in [low, high] */
    while (low < high) {
        int mid = (low + high) / 2;
        if (knots[mid] <= u)
            low = mid + 1;
        else
            high = mid;
    }
    return low - 1;
}

/* Every operation runs in one of two modes: checked, where an allocation
 * that fails makes it return SC_FAIL with its outputs zeroed and nothing
 * left allocated (the public curve operations, which readers apply to what
 * a file gives), or aborting as sc_alloc does (the surface operations of
 * the stages after reading, whose sizes the envelope has bounded). */
static void *op_alloc(int checked, size_t count, size_t size)
{
    return checked ? sc_try_alloc(count, size) : sc_alloc(count, size);
}

static int op_curve_alloc(int checked, sc_curve *c, int dim, int degree, int ncp)
{
    if (checked)
        return sc_curve_try_alloc(c, dim, degree, ncp);
    sc_curve_alloc(c, dim, degree, ncp);
    return SC_OK;
}

static int op_curve_copy(int checked, sc_curve *dst, const sc_curve *src)
{
    if (checked)
        return sc_curve_try_copy(dst, src);
    sc_curve_copy(dst, src);
    return SC_OK;
}

/* A5.1: inserts u `times` times (limited so that the multiplicity does not
 * exceed the degree). u may be a domain end: inserting the ends of an
 * unclamped vector up to the degree is how it is clamped (sc_curve_clamp). */
static int insert_knot(int checked, const sc_curve *c, double u, int times, sc_curve *out)
{
    int p = c->degree, n = c->ncp - 1, stride = c->dim + 1;
    double t0, t1;
    sc_curve_domain(c, &t0, &t1);
    if (!(u >= t0 && u <= t1 && t0 < t1))
        return op_curve_copy(checked, out, c);
    int k = insertion_span(c->knots, (int)knot_count(c), u);
    int s = multiplicity(c->knots, (int)knot_count(c), u);
    int r = times < p - s ? times : p - s;
    if (r <= 0)
        return op_curve_copy(checked, out, c);
    if (op_curve_alloc(checked, out, c->dim, p, c->ncp + r))
        return SC_FAIL;
    const double *U = c->knots;
    double *UQ = out->knots;
    int m = n + p + 1;
    for (int i = 0; i <= k; i++)
        UQ[i] = U[i];
    for (int i = 1; i <= r; i++)
        UQ[k + i] = u;
    for (int i = k + 1; i <= m; i++)
        UQ[i + r] = U[i];
#define PW(i) (c->cp + (size_t)(i) * (size_t)stride)
#define QW(i) (out->cp + (size_t)(i) * (size_t)stride)
    for (int i = 0; i <= k - p; i++)
        copy_point(QW(i), PW(i), stride);
    for (int i = k - s; i <= n; i++)
        copy_point(QW(i + r), PW(i), stride);
    /* Degrees up to SC_READ_MAX_DEGREE: at most a few kilobytes, the
     * documented abort of small allocations. */
    double stack[STACK_ORDER * 4];
    double *R = scratch(stack, STACK_ORDER * 4, (size_t)(p + 1) * (size_t)stride);
    for (int i = 0; i <= p - s; i++)
        copy_point(R + i * stride, PW(k - p + i), stride);
    int L = 0;
    for (int j = 1; j <= r; j++) {
        L = k - p + j;
        for (int i = 0; i <= p - j - s; i++) {
            double alpha = (u - U[L + i]) / (U[i + k + 1] - U[L + i]);
            blend_point(R + i * stride, alpha, R + (i + 1) * stride, R + i * stride, stride);
        }
        copy_point(QW(L), R, stride);
        copy_point(QW(k + r - j - s), R + (p - j - s) * stride, stride);
    }
    for (int i = L + 1; i < k - s; i++)
        copy_point(QW(i), R + (i - L) * stride, stride);
#undef PW
#undef QW
    scratch_release(R, stack);
    return SC_OK;
}

int sc_curve_insert_knot(const sc_curve *c, double u, int times, sc_curve *out)
{
    return insert_knot(1, c, u, times, out);
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A5.4: inserts all of x at once. Values at or outside the domain's ends
 * are ignored (the clamped ends already have full multiplicity), the rest
 * sorted; x need not be ordered. */
static int refine(int checked, const sc_curve *c, const double *x, int nx, sc_curve *out)
{
    double t0, t1;
    sc_curve_domain(c, &t0, &t1);
    memset(out, 0, sizeof *out);
    double *X = op_alloc(checked, (size_t)(nx > 0 ? nx : 1), sizeof(double));
    if (!X)
        return SC_FAIL;
    int r = 0;
    for (int i = 0; i < nx; i++)
        if (x[i] > t0 && x[i] < t1)
            X[r++] = x[i];
    if (r == 0) {
        free(X);
        return op_curve_copy(checked, out, c);
    }
    qsort(X, (size_t)r, sizeof(double), compare_double);
    int p = c->degree, n = c->ncp - 1, m = n + p + 1, stride = c->dim + 1;
    const double *U = c->knots;
    if (op_curve_alloc(checked, out, c->dim, p, c->ncp + r)) {
        free(X);
        return SC_FAIL;
    }
    double *Ubar = out->knots;
#define PW(i) (c->cp + (size_t)(i) * (size_t)stride)
#define QW(i) (out->cp + (size_t)(i) * (size_t)stride)
    int a = sc_find_span(p, U, c->ncp, X[0]);
    int b = sc_find_span(p, U, c->ncp, X[r - 1]) + 1;
    for (int j = 0; j <= a - p; j++)
        copy_point(QW(j), PW(j), stride);
    for (int j = b - 1; j <= n; j++)
        copy_point(QW(j + r), PW(j), stride);
    for (int j = 0; j <= a; j++)
        Ubar[j] = U[j];
    for (int j = b + p; j <= m; j++)
        Ubar[j + r] = U[j];
    /* Sweep from the right: knots of U above the next new knot shift
     * right by the number of new knots still to place; each new knot
     * blends p points. */
    int i = b + p - 1, k = b + p + r - 1;
    for (int j = r - 1; j >= 0; j--) {
        while (X[j] <= U[i] && i > a) {
            copy_point(QW(k - p - 1), PW(i - p - 1), stride);
            Ubar[k] = U[i];
            k--;
            i--;
        }
        copy_point(QW(k - p - 1), QW(k - p), stride);
        for (int l = 1; l <= p; l++) {
            int ind = k - p + l;
            double alpha = Ubar[k + l] - X[j];
            if (alpha == 0.0) {
                copy_point(QW(ind - 1), QW(ind), stride);
            } else {
                alpha /= Ubar[k + l] - U[i - p + l];
                blend_point(QW(ind - 1), alpha, QW(ind - 1), QW(ind), stride);
            }
        }
        Ubar[k] = X[j];
        k--;
    }
#undef PW
#undef QW
    free(X);
    return SC_OK;
}

int sc_curve_refine(const sc_curve *c, const double *x, int nx, sc_curve *out)
{
    return refine(1, c, x, nx, out);
}

/* The knots to insert so that every interior knot has multiplicity at
 * least the degree: the curve is then a chain of Bézier segments. Returns
 * how many were written to x (which holds (ncp − degree − 1)·degree). */
static int bezier_refinement(int degree, const double *knots, int ncp, double *x)
{
    int count = 0;
    int i = degree + 1;
    while (i < ncp) {
        int mult = 1;
        while (i + mult < ncp && knots[i + mult] == knots[i])
            mult++;
        for (int k = mult; k < degree; k++)
            x[count++] = knots[i];
        i += mult;
    }
    return count;
}

static int refine_to_bezier(int checked, const sc_curve *c, sc_curve *out)
{
    memset(out, 0, sizeof *out);
    double *x = op_alloc(checked, (size_t)(c->ncp) * (size_t)c->degree + 1, sizeof(double));
    if (!x)
        return SC_FAIL;
    int nx = bezier_refinement(c->degree, c->knots, c->ncp, x);
    int status = refine(checked, c, x, nx, out);
    free(x);
    return status;
}

/* Spans that are not empty: with every interior multiplicity >= degree,
 * the points of span k are cp[k − degree .. k], in Bernstein form. */
static int nonempty_spans(int degree, const double *knots, int ncp, int *spans)
{
    int count = 0;
    for (int k = degree; k < ncp; k++)
        if (knots[k] < knots[k + 1])
            spans[count++] = k;
    return count;
}

int sc_curve_to_bezier(const sc_curve *c, sc_curve **segments, int *count)
{
    sc_curve refined;
    *segments = NULL;
    *count = 0;
    if (refine_to_bezier(1, c, &refined))
        return SC_FAIL;
    int p = c->degree, stride = c->dim + 1;
    int *spans = sc_try_alloc((size_t)refined.ncp, sizeof(int));
    int nseg = spans ? nonempty_spans(p, refined.knots, refined.ncp, spans) : 0;
    sc_curve *segs = spans ? sc_try_alloc((size_t)nseg, sizeof(sc_curve)) : NULL;
    int made = 0;
    while (segs && made < nseg) {
        int k = spans[made];
        sc_curve *sg = &segs[made];
        if (sc_curve_try_alloc(sg, c->dim, p, p + 1))
            break;
        for (int i = 0; i <= p; i++) {
            sg->knots[i] = refined.knots[k];
            sg->knots[p + 1 + i] = refined.knots[k + 1];
        }
        memcpy(sg->cp, refined.cp + (size_t)(k - p) * (size_t)stride,
               sizeof(double) * (size_t)(p + 1) * (size_t)stride);
        made++;
    }
    free(spans);
    sc_curve_free(&refined);
    if (!segs || made < nseg) {
        for (int s = 0; s < made; s++)
            sc_curve_free(&segs[s]);
        free(segs);
        return SC_FAIL;
    }
    *segments = segs;
    *count = nseg;
    return SC_OK;
}

static int split(int checked, const sc_curve *c, double t, sc_curve *left, sc_curve *right)
{
    double t0, t1;
    sc_curve_domain(c, &t0, &t1);
    assert(t > t0 && t < t1);
    int p = c->degree, stride = c->dim + 1;
    sc_curve full;
    memset(left, 0, sizeof *left);
    memset(right, 0, sizeof *right);
    if (insert_knot(checked, c, t, p, &full))
        return SC_FAIL;
    /* With t of multiplicity p (at least), the curve passes through the
     * control point just before t's first knot: both halves share it. */
    int nk = full.ncp + p + 1, first = 0;
    while (first < nk && full.knots[first] < t)
        first++;
    int last = first;
    while (last + 1 < nk && full.knots[last + 1] == t)
        last++;
    int mult = last - first + 1;
    int left_ncp = first;
    /* A knot already at multiplicity degree+1 separates the halves
     * without a shared point. */
    int right_start = mult > p ? first : first - 1;
    int right_ncp = full.ncp - right_start;
    if (op_curve_alloc(checked, left, c->dim, p, left_ncp) ||
        op_curve_alloc(checked, right, c->dim, p, right_ncp)) {
        sc_curve_free(left);
        sc_curve_free(&full);
        return SC_FAIL;
    }
    memcpy(left->knots, full.knots, sizeof(double) * (size_t)first);
    for (int i = 0; i <= p; i++)
        left->knots[first + i] = t;
    for (int i = 0; i <= p; i++)
        right->knots[i] = t;
    memcpy(right->knots + p + 1, full.knots + last + 1,
           sizeof(double) * (size_t)(nk - last - 1));
    memcpy(left->cp, full.cp, sizeof(double) * (size_t)left_ncp * (size_t)stride);
    memcpy(right->cp, full.cp + (size_t)right_start * (size_t)stride,
           sizeof(double) * (size_t)right_ncp * (size_t)stride);
    sc_curve_free(&full);
    return SC_OK;
}

int sc_curve_split(const sc_curve *c, double t, sc_curve *left, sc_curve *right)
{
    return split(1, c, t, left, right);
}

static int clamp(int checked, const sc_curve *c, sc_curve *out)
{
    int p = c->degree, stride = c->dim + 1;
    double t0, t1;
    sc_curve_domain(c, &t0, &t1);
    if (!(t0 < t1))
        return op_curve_copy(checked, out, c);
    sc_curve front, both;
    memset(out, 0, sizeof *out);
    if (insert_knot(checked, c, t0, p, &front))
        return SC_FAIL;
    int status = insert_knot(checked, &front, t1, p, &both);
    sc_curve_free(&front);
    if (status)
        return SC_FAIL;
    /* Each end now has multiplicity >= p. N_i with i < last_t0 - p ends at
     * or before t0, N_i with i >= first_t1 starts at or after t1: neither
     * reaches into the domain, so their points go. The outermost knots
     * kept, on which no function over the domain depends, become t0 and
     * t1. */
    int nk = both.ncp + p + 1, last_t0 = p, first_t1 = both.ncp;
    while (last_t0 + 1 < nk && both.knots[last_t0 + 1] == t0)
        last_t0++;
    while (both.knots[first_t1 - 1] == t1)
        first_t1--;
    int first = last_t0 - p, count = first_t1 - first;
    if (op_curve_alloc(checked, out, c->dim, p, count)) {
        sc_curve_free(&both);
        return SC_FAIL;
    }
    memcpy(out->knots, both.knots + first, sizeof(double) * (size_t)(count + p + 1));
    out->knots[0] = t0;
    out->knots[count + p] = t1;
    memcpy(out->cp, both.cp + (size_t)first * (size_t)stride,
           sizeof(double) * (size_t)count * (size_t)stride);
    sc_curve_free(&both);
    return SC_OK;
}

int sc_curve_clamp(const sc_curve *c, sc_curve *out) { return clamp(1, c, out); }

/* A requested domain end within rounding of a knot is that knot, so that
 * no sliver span is created. */
static double snap_to_knot(double t, const double *knots, int nk, double scale)
{
    for (int i = 0; i < nk; i++)
        if (fabs(t - knots[i]) <= 1e-10 * scale)
            return knots[i];
    return t;
}

/* The clamped piece of c over [a, b]: ends outside the domain are moved to
 * it, ends within 1e-10 of the domain of a knot snap to it, and an empty
 * range means the whole domain. */
static int curve_restricted(int checked, const sc_curve *c, double a, double b, sc_curve *out)
{
    sc_curve work, lo, hi;
    memset(out, 0, sizeof *out);
    if (clamp(checked, c, &work))
        return SC_FAIL;
    double t0, t1;
    sc_curve_domain(&work, &t0, &t1);
    int nk = (int)knot_count(&work);
    a = snap_to_knot(a < t0 ? t0 : a, work.knots, nk, t1 - t0);
    b = snap_to_knot(b > t1 ? t1 : b, work.knots, nk, t1 - t0);
    if (!(a < b)) {
        a = t0;
        b = t1;
    }
    if (a > t0) {
        int status = split(checked, &work, a, &lo, &hi);
        sc_curve_free(&lo);
        sc_curve_free(&work);
        if (status)
            return SC_FAIL;
        work = hi;
    }
    if (b < t1) {
        int status = split(checked, &work, b, &lo, &hi);
        sc_curve_free(&hi);
        sc_curve_free(&work);
        if (status)
            return SC_FAIL;
        work = lo;
    }
    *out = work;
    return SC_OK;
}

int sc_curve_restrict(sc_curve *c, double a, double b)
{
    sc_curve out;
    if (curve_restricted(1, c, a, b, &out))
        return SC_FAIL;
    sc_curve_free(c);
    *c = out;
    return SC_OK;
}

/* Knots reflected within the domain [a, b]: k -> a + b - k, with the ends
 * exchanged exactly (a + b - b need not round to a) and every knot of the
 * domain kept inside it, so the domain and the order of the knots survive
 * rounding. */
void sc_curve_reverse(sc_curve *c)
{
    int nk = (int)knot_count(c), stride = c->dim + 1;
    double a, b;
    sc_curve_domain(c, &a, &b);
    for (int i = 0; i < nk; i++) {
        double k = c->knots[i], r = a + b - k;
        if (k == a)
            r = b;
        else if (k == b)
            r = a;
        else if (k > a && k < b)
            r = fmin(fmax(r, a), b);
        c->knots[i] = r;
    }
    for (int i = 0, j = nk - 1; i < j; i++, j--) {
        double t = c->knots[i];
        c->knots[i] = c->knots[j];
        c->knots[j] = t;
    }
    for (int i = 0, j = c->ncp - 1; i < j; i++, j--)
        for (int d = 0; d < stride; d++) {
            double t = c->cp[i * stride + d];
            c->cp[i * stride + d] = c->cp[j * stride + d];
            c->cp[j * stride + d] = t;
        }
}

/* Removes one copy of the knot U[r] (multiplicity s, U[r] < U[r+1]) from a
 * curve known not to change by it, e.g. one just assembled from elevated
 * Bézier segments. The p − s new points follow from the knot insertion
 * equations P_i = α_i Q_i + (1 − α_i) Q_{i−1}, solved from the left for the
 * first half and from the right for the second (A5.8), which keeps the
 * divisions by α and 1 − α away from small values. */
static void remove_knot_once(double *U, double *P, int *ncp, int stride, int p, int r, int s)
{
    int n = *ncp - 1, unknowns = p - s;
    double u = U[r];
    double stack[STACK_ORDER * 4];
    double *Q = scratch(stack, STACK_ORDER * 4, (size_t)(unknowns + 2) * (size_t)stride);
    /* Q[k + 1] is the new point of index r − p + k; Q[0] and Q[unknowns+1]
     * are the unchanged neighbours. */
    copy_point(Q, P + (size_t)(r - p - 1) * (size_t)stride, stride);
    copy_point(Q + (size_t)(unknowns + 1) * (size_t)stride,
               P + (size_t)(r - s + 1) * (size_t)stride, stride);
    int from_left = (unknowns + 1) / 2;
    for (int k = 0; k < from_left; k++) {
        int i = r - p + k;
        double alpha = (u - U[i]) / (U[i + p + 1] - U[i]);
        const double *Pi = P + (size_t)i * (size_t)stride;
        double *q = Q + (size_t)(k + 1) * (size_t)stride;
        for (int c = 0; c < stride; c++)
            q[c] = (Pi[c] - (1.0 - alpha) * q[c - stride]) / alpha;
    }
    for (int k = unknowns - 1; k >= from_left; k--) {
        int i = r - p + k + 1;
        double alpha = (u - U[i]) / (U[i + p + 1] - U[i]);
        const double *Pi = P + (size_t)i * (size_t)stride;
        double *q = Q + (size_t)(k + 1) * (size_t)stride;
        for (int c = 0; c < stride; c++)
            q[c] = (Pi[c] - alpha * q[c + stride]) / (1.0 - alpha);
    }
    memcpy(P + (size_t)(r - p) * (size_t)stride, Q + stride,
           sizeof(double) * (size_t)unknowns * (size_t)stride);
    memmove(P + (size_t)(r - s) * (size_t)stride, P + (size_t)(r - s + 1) * (size_t)stride,
            sizeof(double) * (size_t)(n - r + s) * (size_t)stride);
    memmove(U + r, U + r + 1, sizeof(double) * (size_t)(n + p + 1 - r));
    *ncp = n;
    scratch_release(Q, stack);
}

/* Degree elevation: split into Bézier segments, raise each by
 * Q_i = Σ_j C(p,j) C(t,i−j) / C(p+t,i) P_j, chain them with every interior
 * knot at multiplicity p+t, then remove each knot down to its original
 * multiplicity + t (the continuity the original curve had). */
static int elevate(int checked, const sc_curve *c, int times, sc_curve *out)
{
    memset(out, 0, sizeof *out);
    if (times <= 0)
        return op_curve_copy(checked, out, c);
    int p = c->degree, ph = p + times, stride = c->dim + 1;
    sc_curve refined;
    if (refine_to_bezier(checked, c, &refined))
        return SC_FAIL;
    int *spans = op_alloc(checked, (size_t)refined.ncp, sizeof(int));
    int nseg = spans ? nonempty_spans(p, refined.knots, refined.ncp, spans) : 0;

    /* Upper bound: every segment with its own ph+1 points. */
    size_t cap = (size_t)nseg * (size_t)(ph + 1);
    double *P = spans ? op_alloc(checked, cap * (size_t)stride, sizeof(double)) : NULL;
    double *U = P ? op_alloc(checked, cap + (size_t)ph + 1, sizeof(double)) : NULL;
    double *coef = U ? op_alloc(checked, (size_t)(ph + 1) * (size_t)(p + 1), sizeof(double))
                     : NULL;
    int status = coef ? SC_OK : SC_FAIL;
    for (int i = 0; i <= ph && coef; i++)
        for (int j = 0; j <= p; j++)
            if (j <= i && i - j <= times)
                coef[i * (p + 1) + j] = binomial(p, j) * binomial(times, i - j) / binomial(ph, i);

    int ncp = 0, nk = 0;
    for (int i = 0; i <= ph && coef; i++)
        U[nk++] = refined.knots[spans[0]];
    for (int sgi = 0; sgi < nseg && coef; sgi++) {
        int k = spans[sgi];
        const double *B = refined.cp + (size_t)(k - p) * (size_t)stride;
        /* A breakpoint of multiplicity degree+1 (a possible jump) keeps
         * both end points; otherwise consecutive segments share one. */
        int first = 0;
        if (sgi > 0) {
            int mult = multiplicity(refined.knots, refined.ncp + p + 1, refined.knots[k]);
            first = mult > p ? 0 : 1;
            for (int i = 0; i < (mult > p ? ph + 1 : ph); i++)
                U[nk++] = refined.knots[k];
        }
        for (int i = first; i <= ph; i++) {
            double *q = P + (size_t)ncp * (size_t)stride;
            for (int d = 0; d < stride; d++) {
                double sum = 0.0;
                for (int j = 0; j <= p; j++)
                    sum += coef[i * (p + 1) + j] * B[(size_t)j * (size_t)stride + (size_t)d];
                q[d] = sum;
            }
            ncp++;
        }
    }
    for (int i = 0; i <= ph && coef; i++)
        U[nk++] = refined.knots[spans[nseg - 1] + 1];

    /* Knot removal, breakpoint by breakpoint. */
    for (int sgi = 1; sgi < nseg && coef; sgi++) {
        double u = refined.knots[spans[sgi]];
        int target = multiplicity(c->knots, (int)knot_count(c), u) + times;
        for (;;) {
            int r = 0, mult = 0;
            for (int i = 0; i < ncp + ph + 1; i++)
                if (U[i] == u) {
                    r = i;
                    mult++;
                }
            if (mult <= target)
                break;
            remove_knot_once(U, P, &ncp, stride, ph, r, mult);
        }
    }
    if (status == SC_OK)
        status = op_curve_alloc(checked, out, c->dim, ph, ncp);
    if (status == SC_OK) {
        memcpy(out->knots, U, sizeof(double) * (size_t)(ncp + ph + 1));
        memcpy(out->cp, P, sizeof(double) * (size_t)ncp * (size_t)stride);
    }
    free(coef);
    free(U);
    free(P);
    free(spans);
    sc_curve_free(&refined);
    return status;
}

int sc_curve_elevate(const sc_curve *c, int times, sc_curve *out)
{
    return elevate(1, c, times, out);
}

/* ------------------------------------------------------------------ */
/* Surfaces: the curve algorithms run on each row (dir 0, along u) or     */
/* column (dir 1, along v) of homogeneous control points (A5.3, A5.5).   */
/* ------------------------------------------------------------------ */

typedef enum curve_job_kind {
    JOB_INSERT,
    JOB_REFINE,
    JOB_SPLIT,
    JOB_ELEVATE,
    JOB_CLAMP,
    JOB_RESTRICT
} curve_job_kind;

typedef struct curve_job {
    curve_job_kind kind;
    double t, t_end; /* t_end: the upper end of a restriction */
    int times;
    const double *x;
    int nx;
} curve_job;

static int job_outputs(const curve_job *job) { return job->kind == JOB_SPLIT ? 2 : 1; }

static int run_job(int checked, const curve_job *job, const sc_curve *in, sc_curve out[2])
{
    switch (job->kind) {
    case JOB_INSERT: return insert_knot(checked, in, job->t, job->times, &out[0]);
    case JOB_REFINE: return refine(checked, in, job->x, job->nx, &out[0]);
    case JOB_SPLIT: return split(checked, in, job->t, &out[0], &out[1]);
    case JOB_ELEVATE: return elevate(checked, in, job->times, &out[0]);
    case JOB_CLAMP: return clamp(checked, in, &out[0]);
    case JOB_RESTRICT: return curve_restricted(checked, in, job->t, job->t_end, &out[0]);
    }
    return SC_FAIL;
}

/* Index of control point (i along dir, j across) in the surface array. */
static size_t line_index(int dir, int nu, int along, int across)
{
    return dir == 0 ? (size_t)across * (size_t)nu + (size_t)along
                    : (size_t)along * (size_t)nu + (size_t)across;
}

/* With `checked`, fails (out zeroed, nothing kept) when memory runs out,
 * for the surface-sized arrays or a row's curves. Without, aborts as
 * sc_alloc does. */
static int surface_run_job(const sc_surface *s, int dir, const curve_job *job, sc_surface *out,
                           int checked)
{
    int nouts = job_outputs(job);
    int along_n = dir == 0 ? s->nu : s->nv, across_n = dir == 0 ? s->nv : s->nu;
    sc_curve line;
    line.dim = 3;
    line.degree = dir == 0 ? s->deg_u : s->deg_v;
    line.ncp = along_n;
    line.knots = dir == 0 ? s->knots_u : s->knots_v;
    line.cp = op_alloc(checked, (size_t)along_n * 4, sizeof(double));
    memset(out, 0, sizeof *out * (size_t)nouts);
    if (!line.cp)
        return SC_FAIL;
    for (int j = 0; j < across_n; j++) {
        for (int i = 0; i < along_n; i++)
            copy_point(line.cp + 4 * i, s->cp + 4 * line_index(dir, s->nu, i, j), 4);
        sc_curve res[2];
        if (run_job(checked, job, &line, res)) {
            if (j > 0)
                for (int k = 0; k < nouts; k++)
                    sc_surface_free(&out[k]);
            memset(out, 0, sizeof *out * (size_t)nouts);
            free(line.cp);
            return SC_FAIL;
        }
        for (int o = 0; o < nouts; o++) {
            sc_surface *dst = &out[o];
            if (j == 0) {
                *dst = *s;
                dst->nloops = 0;
                dst->loops = NULL;
                int nu = dir == 0 ? res[o].ncp : s->nu, nv = dir == 0 ? s->nv : res[o].ncp;
                int du = dir == 0 ? res[o].degree : s->deg_u;
                int dv = dir == 0 ? s->deg_v : res[o].degree;
                if (!checked)
                    sc_surface_alloc(dst, du, dv, nu, nv);
                else if (sc_surface_try_alloc(dst, du, dv, nu, nv)) {
                    for (int k = 0; k < nouts; k++)
                        sc_curve_free(&res[k]);
                    for (int k = 0; k < o; k++)
                        sc_surface_free(&out[k]);
                    memset(out, 0, sizeof *out * (size_t)nouts);
                    free(line.cp);
                    return SC_FAIL;
                }
                double *kn = dir == 0 ? dst->knots_u : dst->knots_v;
                memcpy(kn, res[o].knots, sizeof(double) * knot_count(&res[o]));
                if (dir == 0)
                    memcpy(dst->knots_v, s->knots_v, sizeof(double) * (size_t)(s->nv + s->deg_v + 1));
                else
                    memcpy(dst->knots_u, s->knots_u, sizeof(double) * (size_t)(s->nu + s->deg_u + 1));
            }
            for (int i = 0; i < res[o].ncp; i++)
                copy_point(dst->cp + 4 * line_index(dir, dst->nu, i, j), res[o].cp + 4 * i, 4);
            sc_curve_free(&res[o]);
        }
    }
    free(line.cp);
    return SC_OK;
}


void sc_surface_insert_knot(const sc_surface *s, int dir, double t, int times, sc_surface *out)
{
    curve_job job = {.kind = JOB_INSERT, .t = t, .times = times};
    surface_run_job(s, dir, &job, out, 0);
}

void sc_surface_refine(const sc_surface *s, int dir, const double *x, int nx, sc_surface *out)
{
    curve_job job = {.kind = JOB_REFINE, .x = x, .nx = nx};
    surface_run_job(s, dir, &job, out, 0);
}

void sc_surface_split(const sc_surface *s, int dir, double t, sc_surface *lo, sc_surface *hi)
{
    sc_surface halves[2];
    curve_job job = {.kind = JOB_SPLIT, .t = t};
    surface_run_job(s, dir, &job, halves, 0);
    *lo = halves[0];
    *hi = halves[1];
}

void sc_surface_elevate(const sc_surface *s, int dir, int times, sc_surface *out)
{
    curve_job job = {.kind = JOB_ELEVATE, .times = times};
    surface_run_job(s, dir, &job, out, 0);
}

static int surface_clamp(const sc_surface *s, sc_surface *out, int checked)
{
    curve_job job = {.kind = JOB_CLAMP};
    sc_surface clamped_u;
    memset(out, 0, sizeof *out);
    if (surface_run_job(s, 0, &job, &clamped_u, checked))
        return SC_FAIL;
    int status = surface_run_job(&clamped_u, 1, &job, out, checked);
    sc_surface_free(&clamped_u);
    return status;
}

int sc_surface_try_clamp(const sc_surface *s, sc_surface *out) { return surface_clamp(s, out, 1); }

void sc_surface_clamp(const sc_surface *s, sc_surface *out) { surface_clamp(s, out, 0); }

/* Clamped in both directions first, so that every row holds the same
 * clamped knots and restricting each row is restricting the surface. */
static int surface_restrict(sc_surface *s, int dir, double a, double b, int checked)
{
    sc_surface clamped, out;
    if (surface_clamp(s, &clamped, checked))
        return SC_FAIL;
    curve_job job = {.kind = JOB_RESTRICT, .t = a, .t_end = b};
    int status = surface_run_job(&clamped, dir, &job, &out, checked);
    sc_surface_free(&clamped);
    if (status != SC_OK)
        return SC_FAIL;
    out.loops = s->loops;
    out.nloops = s->nloops;
    s->loops = NULL;
    s->nloops = 0;
    sc_surface_free(s);
    *s = out;
    return SC_OK;
}

int sc_surface_try_restrict(sc_surface *s, int dir, double a, double b)
{
    return surface_restrict(s, dir, a, b, 1);
}

/* For the stages after reading (patches for hulls, GPU data and the
 * reference): aborting. */
static void surface_refine_to_bezier(const sc_surface *s, int dir, sc_surface *out)
{
    int deg = dir == 0 ? s->deg_u : s->deg_v, n = dir == 0 ? s->nu : s->nv;
    const double *knots = dir == 0 ? s->knots_u : s->knots_v;
    double *x = sc_alloc((size_t)n * (size_t)deg + 1, sizeof(double));
    int nx = bezier_refinement(deg, knots, n, x);
    sc_surface_refine(s, dir, x, nx, out);
    free(x);
}

void sc_surface_to_bezier(const sc_surface *s, sc_bezier_patch **patches, int *count)
{
    sc_surface ru, ruv;
    surface_refine_to_bezier(s, 0, &ru);
    surface_refine_to_bezier(&ru, 1, &ruv);
    sc_surface_free(&ru);
    int p = s->deg_u, q = s->deg_v;
    int *spans_u = sc_alloc((size_t)ruv.nu, sizeof(int));
    int *spans_v = sc_alloc((size_t)ruv.nv, sizeof(int));
    int nsu = nonempty_spans(p, ruv.knots_u, ruv.nu, spans_u);
    int nsv = nonempty_spans(q, ruv.knots_v, ruv.nv, spans_v);
    sc_bezier_patch *out = sc_alloc((size_t)nsu * (size_t)nsv, sizeof(sc_bezier_patch));
    for (int b = 0; b < nsv; b++)
        for (int a = 0; a < nsu; a++) {
            sc_bezier_patch *bp = &out[b * nsu + a];
            int ku = spans_u[a], kv = spans_v[b];
            bp->surface = -1;
            bp->deg_u = p;
            bp->deg_v = q;
            bp->u0 = ruv.knots_u[ku];
            bp->u1 = ruv.knots_u[ku + 1];
            bp->v0 = ruv.knots_v[kv];
            bp->v1 = ruv.knots_v[kv + 1];
            bp->cp = sc_alloc((size_t)(p + 1) * (size_t)(q + 1) * 4, sizeof(double));
            for (int j = 0; j <= q; j++)
                for (int i = 0; i <= p; i++)
                    copy_point(bp->cp + 4 * (j * (p + 1) + i),
                               ruv.cp + 4 * ((size_t)(kv - q + j) * (size_t)ruv.nu +
                                             (size_t)(ku - p + i)),
                               4);
        }
    free(spans_u);
    free(spans_v);
    sc_surface_free(&ruv);
    *patches = out;
    *count = nsu * nsv;
}

void sc_bezier_patch_free(sc_bezier_patch *p)
{
    free(p->cp);
    p->cp = NULL;
}

void sc_surface_world_patches(const sc_surface *s, int index, sc_patch_list *out)
{
    sc_surface bare = *s, world;
    bare.loops = NULL; /* patches do not need the trim loops */
    bare.nloops = 0;
    sc_surface_copy(&world, &bare);
    sc_surface_bake_xform(&world);
    sc_surface_to_bezier(&world, &out->patches, &out->count);
    for (int p = 0; p < out->count; p++)
        out->patches[p].surface = index;
    sc_surface_free(&world);
}

void sc_patch_list_free(sc_patch_list *list)
{
    for (int p = 0; p < list->count; p++)
        sc_bezier_patch_free(&list->patches[p]);
    free(list->patches);
    list->patches = NULL;
    list->count = 0;
}
