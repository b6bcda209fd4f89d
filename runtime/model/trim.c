/* trim.c — point classification against trim loops (trim.h).
 *
 * Preparation cuts every trim curve into Bézier segments and every segment
 * at the roots of v'(t) into v-monotone pieces; the roots come from the
 * Bernstein coefficients of the numerator of v'(t) = (V'W - VW')/W², which
 * by the variation-diminishing property can only change sign where its
 * coefficients do. End points of consecutive pieces are made bit-identical,
 * so the half-open rule [v_lo, v_hi) counts a shared end point once on a
 * monotone run, twice at a minimum and never at a maximum or along a
 * horizontal piece. A query finds the crossing's u on a monotone piece by
 * bisection of the curve itself (de Casteljau at 0.5) until its u bounds lie
 * on one side of the point. */
#include "trim.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bezier.h"
#include "nurbs.h"
#include "nurbs_local.h"

static int sign_changes(const double *c, int n)
{
    int changes = 0, last = 0;
    for (int i = 0; i <= n; i++) {
        int s = (c[i] > 0) - (c[i] < 0);
        if (s && last && s != last)
            changes++;
        if (s)
            last = s;
    }
    return changes;
}

/* Root isolation of a Bernstein polynomial on [a, b] (its coefficients
 * relative to that interval): subdivide while the coefficients change sign
 * more than once; a single change with opposite end values is a simple
 * root, found by bisection. */
static void bernstein_roots(const double *c, int n, double a, double b, int depth, double *roots,
                            int *nroots, int max_roots)
{
    if (*nroots >= max_roots || sign_changes(c, n) == 0)
        return;
    if (depth > 60 || b - a < 1e-13) {
        roots[(*nroots)++] = 0.5 * (a + b);
        return;
    }
    if (sign_changes(c, n) == 1 && ((c[0] < 0 && c[n] > 0) || (c[0] > 0 && c[n] < 0))) {
        double lo = 0.0, hi = 1.0, flo = c[0];
        for (int it = 0; it < 200 && hi - lo > 0; it++) {
            double mid = 0.5 * (lo + hi);
            if (mid <= lo || mid >= hi)
                break;
            double fm;
            sc_bezier_point(c, n, 1, 1, mid, &fm);
            if ((fm < 0) == (flo < 0) && fm != 0) {
                lo = mid;
                flo = fm;
            } else {
                hi = mid;
            }
        }
        roots[(*nroots)++] = a + (b - a) * 0.5 * (lo + hi);
        return;
    }
    double left[2 * SC_TRIM_MAX_DEGREE + 1], right[2 * SC_TRIM_MAX_DEGREE + 1];
    sc_bezier_split(c, n, 1, 1, 0.5, left, right);
    double m = 0.5 * (a + b);
    bernstein_roots(left, n, a, m, depth + 1, roots, nroots, max_roots);
    bernstein_roots(right, n, m, b, depth + 1, roots, nroots, max_roots);
}

static int compare_doubles(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Parameters in (0, 1), ascending, where v(t) of the segment turns. */
static int v_turning_points(const double *cp, int p, double *roots, int max_roots)
{
    if (p < 2)
        return 0; /* a rational line is monotone */
    int n = 2 * p - 1;
    double num[2 * SC_TRIM_MAX_DEGREE + 1] = {0};
    for (int i = 0; i < p; i++) {
        double dv = p * (cp[3 * (i + 1) + 1] - cp[3 * i + 1]);
        double dw = p * (cp[3 * (i + 1) + 2] - cp[3 * i + 2]);
        for (int j = 0; j <= p; j++) {
            double weight = binomial(p - 1, i) * binomial(p, j) / binomial(n, i + j);
            num[i + j] += weight * (dv * cp[3 * j + 2] - dw * cp[3 * j + 1]);
        }
    }
    double found[4 * SC_TRIM_MAX_DEGREE];
    int nfound = 0;
    bernstein_roots(num, n, 0.0, 1.0, 0, found, &nfound, 4 * SC_TRIM_MAX_DEGREE);
    qsort(found, (size_t)nfound, sizeof(double), compare_doubles);
    int count = 0;
    for (int k = 0; k < nfound && count < max_roots; k++) {
        double t = found[k];
        if (t <= 1e-12 || t >= 1.0 - 1e-12)
            continue;
        if (count && t - roots[count - 1] <= 1e-12)
            continue;
        roots[count++] = t;
    }
    return count;
}

/* A piece before orientation: control points in curve order and its end
 * points (which may be moved to match the neighbours). */
typedef struct raw_piece {
    int degree;
    double cp[3 * (SC_TRIM_MAX_DEGREE + 1)];
    double start[2], end[2];
    int loop;
} raw_piece;

typedef struct piece_list {
    raw_piece *items;
    int count, cap;
    size_t failed; /* bytes that could not be allocated: the list stops growing */
} piece_list;

static raw_piece *piece_append(piece_list *list)
{
    if (list->count == list->cap) {
        int cap = list->cap ? 2 * list->cap : 64;
        raw_piece *grown = list->failed ? NULL
                                        : sc_try_realloc(list->items, (size_t)cap, sizeof(raw_piece));
        if (!grown) {
            list->failed = (size_t)cap * sizeof(raw_piece);
            return NULL;
        }
        list->items = grown;
        list->cap = cap;
    }
    raw_piece *p = &list->items[list->count++];
    memset(p, 0, sizeof *p);
    return p;
}

/* Appends the monotone pieces of one Bézier segment. */
static void add_segment_pieces(piece_list *list, const double *cp, int p, int loop)
{
    double roots[4 * SC_TRIM_MAX_DEGREE];
    int nroots = v_turning_points(cp, p, roots, 4 * SC_TRIM_MAX_DEGREE);
    double rest[3 * (SC_TRIM_MAX_DEGREE + 1)];
    memcpy(rest, cp, sizeof(double) * 3 * (size_t)(p + 1));
    double consumed = 0.0; /* rest covers [consumed, 1] of the segment */
    for (int k = 0; k <= nroots; k++) {
        raw_piece *piece = piece_append(list);
        if (!piece)
            return;
        piece->degree = p;
        piece->loop = loop;
        if (k < nroots) {
            double local = (roots[k] - consumed) / (1.0 - consumed);
            double right[3 * (SC_TRIM_MAX_DEGREE + 1)];
            sc_bezier_split(rest, p, 3, 3, local, piece->cp, right);
            memcpy(rest, right, sizeof right);
            consumed = roots[k];
        } else {
            memcpy(piece->cp, rest, sizeof(double) * 3 * (size_t)(p + 1));
        }
        piece->start[0] = piece->cp[0] / piece->cp[2];
        piece->start[1] = piece->cp[1] / piece->cp[2];
        piece->end[0] = piece->cp[3 * p] / piece->cp[3 * p + 2];
        piece->end[1] = piece->cp[3 * p + 1] / piece->cp[3 * p + 2];
    }
}

static int prepare_loop(const sc_surface *s, int loop_index, piece_list *list, double tolerance,
                        sc_error *err)
{
    const sc_loop *loop = &s->loops[loop_index];
    int first = list->count;
    for (int c = 0; c < loop->ncurves; c++) {
        const sc_curve *curve = &loop->curves[c];
        if (curve->dim != 2 || curve->degree < 1 || curve->degree > SC_TRIM_MAX_DEGREE)
            return sc_fail(err, NULL, 0,
                           "surface '%s', trim loop %d (%s), curve %d: a %dD curve of degree %d; "
                           "trimming takes 2D curves of degree 1..%d",
                           s->name, loop_index, loop->is_hole ? "a hole" : "the outer loop", c,
                           curve->dim, curve->degree, SC_TRIM_MAX_DEGREE);
        for (int i = 0; i < curve->ncp; i++)
            if (!(curve->cp[3 * i + 2] > 0.0))
                return sc_fail(err, NULL, 0,
                               "surface '%s', trim loop %d (%s), curve %d: control point %d has "
                               "weight %g; trim curves need positive weights",
                               s->name, loop_index, loop->is_hole ? "a hole" : "the outer loop",
                               c, i, curve->cp[3 * i + 2]);
        sc_curve *segments = NULL;
        int nseg = 0;
        if (sc_curve_to_bezier(curve, &segments, &nseg)) {
            list->failed = sc_alloc_failed_bytes();
            break;
        }
        for (int k = 0; k < nseg; k++) {
            add_segment_pieces(list, segments[k].cp, segments[k].degree, loop_index);
            sc_curve_free(&segments[k]);
        }
        free(segments);
    }
    if (list->failed) {
        char what[160];
        snprintf(what, sizeof what, "the trim pieces of surface '%s'", s->name);
        return sc_fail_oom(err, NULL, 0, list->failed, 1, what);
    }
    /* Consecutive pieces (cyclically) share their end point exactly. */
    int n = list->count - first;
    for (int k = 0; k < n; k++) {
        raw_piece *a = &list->items[first + k];
        raw_piece *b = &list->items[first + (k + 1) % n];
        if (fabs(a->end[0] - b->start[0]) <= tolerance && fabs(a->end[1] - b->start[1]) <= tolerance) {
            b->start[0] = a->end[0];
            b->start[1] = a->end[1];
        }
    }
    return SC_OK;
}

static int bucket_of(const sc_trim *trim, double v)
{
    double k = floor((v - trim->v0) / trim->dv);
    if (k < 0)
        return 0;
    if (k > trim->nbuckets - 1)
        return trim->nbuckets - 1;
    return (int)k;
}

static int build_buckets(sc_trim *trim)
{
    double v0 = INFINITY, v1 = -INFINITY;
    for (int k = 0; k < trim->npieces; k++) {
        v0 = fmin(v0, trim->pieces[k].v_lo);
        v1 = fmax(v1, trim->pieces[k].v_hi);
    }
    trim->nbuckets = trim->npieces < 1 ? 1 : trim->npieces > 1024 ? 1024 : trim->npieces;
    trim->v0 = trim->npieces ? v0 : 0.0;
    trim->dv = trim->npieces && v1 > v0 ? (v1 - v0) / trim->nbuckets : 1.0;
    if (!(trim->bucket_start = sc_try_alloc((size_t)trim->nbuckets + 1, sizeof(int))))
        return SC_FAIL;
    for (int pass = 0; pass < 2; pass++) {
        int *fill = pass ? sc_try_alloc((size_t)trim->nbuckets, sizeof(int)) : NULL;
        if (pass && !fill)
            return SC_FAIL;
        for (int k = 0; k < trim->npieces; k++) {
            int b0 = bucket_of(trim, trim->pieces[k].v_lo);
            int b1 = bucket_of(trim, trim->pieces[k].v_hi);
            for (int b = b0; b <= b1; b++) {
                if (pass)
                    trim->bucket_items[trim->bucket_start[b] + fill[b]++] = k;
                else
                    trim->bucket_start[b + 1]++;
            }
        }
        if (!pass) {
            for (int b = 0; b < trim->nbuckets; b++)
                trim->bucket_start[b + 1] += trim->bucket_start[b];
            trim->bucket_items =
                sc_try_alloc((size_t)trim->bucket_start[trim->nbuckets] + 1, sizeof(int));
            if (!trim->bucket_items)
                return SC_FAIL;
        }
        free(fill);
    }
    return SC_OK;
}

int sc_trim_prepare(const sc_surface *s, sc_trim **out, sc_error *err)
{
    *out = NULL;
    if (s->nloops == 0)
        return SC_OK;
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    double tolerance = 1e-9 * fmax(u1 - u0, v1 - v0);
    piece_list list = {0};
    int has_outer = 0;
    for (int l = 0; l < s->nloops; l++) {
        has_outer |= !s->loops[l].is_hole;
        if (prepare_loop(s, l, &list, tolerance, err) != SC_OK) {
            free(list.items);
            return SC_FAIL;
        }
    }
    sc_trim *trim = sc_alloc(1, sizeof *trim);
    trim->kept_without_crossings = !has_outer;
    trim->pieces = sc_try_alloc((size_t)list.count, sizeof(sc_trim_piece));
    if (!trim->pieces) {
        free(list.items);
        free(trim);
        return sc_fail_oom(err, NULL, 0, (size_t)list.count, sizeof(sc_trim_piece),
                           "trim pieces");
    }
    for (int k = 0; k < list.count; k++) {
        /* A horizontal piece keeps v_lo == v_hi, so its half-open range
         * holds no v and a ray along it never counts it; it stays in the
         * list as a boundary for sc_trim_classify_rect. */
        const raw_piece *raw = &list.items[k];
        sc_trim_piece *piece = &trim->pieces[trim->npieces++];
        int p = raw->degree;
        int reverse = raw->start[1] > raw->end[1];
        piece->degree = p;
        piece->loop = raw->loop;
        for (int i = 0; i <= p; i++)
            memcpy(&piece->cp[3 * i], &raw->cp[3 * (reverse ? p - i : i)], 3 * sizeof(double));
        const double *lo = reverse ? raw->end : raw->start;
        const double *hi = reverse ? raw->start : raw->end;
        piece->u_lo = lo[0];
        piece->v_lo = lo[1];
        piece->u_hi = hi[0];
        piece->v_hi = hi[1];
        piece->u_min = fmin(lo[0], hi[0]);
        piece->u_max = fmax(lo[0], hi[0]);
        for (int i = 0; i <= p; i++) {
            double u = piece->cp[3 * i] / piece->cp[3 * i + 2];
            piece->u_min = fmin(piece->u_min, u);
            piece->u_max = fmax(piece->u_max, u);
        }
    }
    free(list.items);
    if (build_buckets(trim)) {
        size_t pieces = (size_t)trim->npieces;
        sc_trim_free(trim);
        return sc_fail_oom(err, NULL, 0, pieces + 1024, 2 * sizeof(int), "trim buckets");
    }
    *out = trim;
    return SC_OK;
}

void sc_trim_free(sc_trim *trim)
{
    if (trim) {
        free(trim->pieces);
        free(trim->bucket_start);
        free(trim->bucket_items);
    }
    free(trim);
}

/* Whether the monotone piece crosses the ray from (u, v) towards +u, given
 * v_lo <= v < v_hi. */
static int piece_crosses(const sc_trim_piece *piece, double u, double v)
{
    if (piece->u_max <= u)
        return 0;
    if (piece->u_min > u)
        return 1;
    if (v == piece->v_lo)
        return piece->u_lo > u;
    int p = piece->degree;
    double cp[3 * (SC_TRIM_MAX_DEGREE + 1)], left[3 * (SC_TRIM_MAX_DEGREE + 1)];
    memcpy(cp, piece->cp, sizeof(double) * 3 * (size_t)(p + 1));
    for (int depth = 0; depth < 80; depth++) {
        double umin = INFINITY, umax = -INFINITY;
        for (int i = 0; i <= p; i++) {
            double ui = cp[3 * i] / cp[3 * i + 2];
            umin = fmin(umin, ui);
            umax = fmax(umax, ui);
        }
        if (umax <= u)
            return 0;
        if (umin > u)
            return 1;
        sc_bezier_split(cp, p, 3, 3, 0.5, left, cp);
        /* The split point is the last control point of the left half. */
        double v_mid = left[3 * p + 1] / left[3 * p + 2];
        if (v < v_mid)
            memcpy(cp, left, sizeof(double) * 3 * (size_t)(p + 1));
    }
    double u_mid = 0.5 * (cp[0] / cp[2] + cp[3 * p] / cp[3 * p + 2]);
    return u_mid > u;
}

int sc_trim_crossings(const sc_trim *trim, double u, double v)
{
    if (!trim || trim->npieces == 0 || !(v >= trim->v0))
        return 0;
    int b = bucket_of(trim, v);
    int crossings = 0;
    for (int k = trim->bucket_start[b]; k < trim->bucket_start[b + 1]; k++) {
        const sc_trim_piece *piece = &trim->pieces[trim->bucket_items[k]];
        if (piece->v_lo <= v && v < piece->v_hi)
            crossings += piece_crosses(piece, u, v);
    }
    return crossings;
}

int sc_trim_inside(const sc_trim *trim, double u, double v)
{
    if (!trim)
        return 1;
    int odd = sc_trim_crossings(trim, u, v) & 1;
    return trim->kept_without_crossings ? !odd : odd;
}

int sc_trim_classify_rect(const sc_trim *trim, double u0, double u1, double v0, double v1)
{
    if (!trim)
        return 1;
    if (trim->npieces) {
        int b0 = bucket_of(trim, v0), b1 = bucket_of(trim, v1);
        for (int b = b0; b <= b1; b++)
            for (int k = trim->bucket_start[b]; k < trim->bucket_start[b + 1]; k++) {
                const sc_trim_piece *piece = &trim->pieces[trim->bucket_items[k]];
                if (piece->v_lo <= v1 && piece->v_hi >= v0 && piece->u_min <= u1 &&
                    piece->u_max >= u0)
                    return -1;
            }
    }
    /* No piece comes near: the rectangle is on one side of every loop. */
    return sc_trim_inside(trim, 0.5 * (u0 + u1), 0.5 * (v0 + v1));
}
