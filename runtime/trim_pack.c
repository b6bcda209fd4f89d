/* trim_pack.c — trim blocks for the GPU (trim_pack.h). The pieces come from
 * the reference's preparation (sc_trim_prepare), so the GPU and the CPU
 * reference count crossings of the same curves under the same half-open
 * rule. Rounding to float is where care is needed:
 *  - end points shared by consecutive pieces are bit-identical doubles,
 *    normalised by the same operations, so they stay identical floats and
 *    the half-open rule still counts a shared end point once;
 *  - a piece whose v range collapses in float is left out, which is what
 *    the rule does with a horizontal piece;
 *  - u bounds are taken from the float control points, widened by a few
 *    float steps and rounded outwards, so that a verdict from the bounds
 *    agrees with the clipping of the same float curve.
 * Slabs cut the v range at every piece end point; within a slab the pieces
 * span it completely and do not cross, so they are ordered by u at the
 * slab's middle, and each carries the bounds of its part inside the slab,
 * which are much tighter than the piece's. */
#include "trim_pack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_layout.h"
#include "key.h"
#include "nurbs.h"
#include "trim.h"

/* Widening of u bounds, in normalised units (2^-21: four float steps at
 * 1.0). */
#define BOUND_MARGIN (1.0 / 2097152.0)

enum { MAX_POINTS = SCG_MAX_DEGREE + 1 };

int sc_surface_trim_degree(const sc_surface *s)
{
    int degree = 0;
    for (int l = 0; l < s->nloops; l++)
        for (int c = 0; c < s->loops[l].ncurves; c++)
            if (s->loops[l].curves[c].degree > degree)
                degree = s->loops[l].curves[c].degree;
    return degree;
}

/* A piece as packed: float control points (u·w, v·w, w), normalised. */
typedef struct packed_piece {
    float cp[3 * MAX_POINTS];
    float v_lo, v_hi, u_lo, u_min, u_max;
} packed_piece;

static float float_down(double x)
{
    float f = (float)x;
    return (double)f > x ? nextafterf(f, -INFINITY) : f;
}

static float float_up(double x)
{
    float f = (float)x;
    return (double)f < x ? nextafterf(f, INFINITY) : f;
}

/* Degree elevation of a homogeneous 2D Bézier curve from p to n. */
static void elevate(const double *cp, int p, int n, double *out)
{
    double work[3 * MAX_POINTS];
    memcpy(work, cp, sizeof(double) * 3 * (size_t)(p + 1));
    for (int q = p; q < n; q++) {
        double next[3 * MAX_POINTS];
        for (int i = 0; i <= q + 1; i++) {
            double a = (double)i / (q + 1);
            for (int c = 0; c < 3; c++) {
                double left = i > 0 ? work[3 * (i - 1) + c] : 0.0;
                double right = i <= q ? work[3 * i + c] : 0.0;
                next[3 * i + c] = a * left + (1.0 - a) * right;
            }
        }
        memcpy(work, next, sizeof(double) * 3 * (size_t)(q + 2));
    }
    memcpy(out, work, sizeof(double) * 3 * (size_t)(n + 1));
}

/* The float control points of a packed piece, in double. */
static void piece_points(const packed_piece *pc, int n, double *cp)
{
    for (int i = 0; i < 3 * (n + 1); i++)
        cp[i] = pc->cp[i];
}

/* De Casteljau at t: the point (homogeneous) and, when wanted, the control
 * points of [0, t] and [t, 1]. */
static void split_at(const double *cp, int n, double t, double *point, double *left, double *right)
{
    double work[3 * MAX_POINTS];
    memcpy(work, cp, sizeof(double) * 3 * (size_t)(n + 1));
    for (int c = 0; c < 3; c++) {
        if (left)
            left[c] = work[c];
        if (right)
            right[3 * n + c] = work[3 * n + c];
    }
    for (int r = 1; r <= n; r++) {
        for (int i = 0; i <= n - r; i++)
            for (int c = 0; c < 3; c++)
                work[3 * i + c] = (1.0 - t) * work[3 * i + c] + t * work[3 * (i + 1) + c];
        for (int c = 0; c < 3; c++) {
            if (left)
                left[3 * r + c] = work[c];
            if (right)
                right[3 * (n - r) + c] = work[3 * (n - r) + c];
        }
    }
    if (point)
        memcpy(point, work, 3 * sizeof(double));
}

/* The parameter where the (v-increasing) curve reaches v = y, by
 * bisection; 0 below its start, 1 above its end. */
static double param_at_v(const double *cp, int n, double y)
{
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 64; it++) {
        double mid = 0.5 * (lo + hi), pt[3];
        split_at(cp, n, mid, pt, NULL, NULL);
        if (pt[1] / pt[2] < y)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* Bounds of u over the control points of the curve's part on [t0, t1]. */
static void part_bounds(const double *cp, int n, double t0, double t1, double *u_min,
                        double *u_max)
{
    double head[3 * MAX_POINTS], part[3 * MAX_POINTS];
    split_at(cp, n, t1, NULL, head, NULL);
    split_at(head, n, t1 > 0 ? t0 / t1 : 0.0, NULL, NULL, part);
    *u_min = INFINITY;
    *u_max = -INFINITY;
    for (int i = 0; i <= n; i++) {
        double u = part[3 * i] / part[3 * i + 2];
        *u_min = fmin(*u_min, u);
        *u_max = fmax(*u_max, u);
    }
}

static int compare_floats(const void *pa, const void *pb)
{
    float a = *(const float *)pa, b = *(const float *)pb;
    return (a > b) - (a < b);
}

typedef struct slab_item {
    int piece;
    double order;            /* u at the slab's middle */
    float u_min, u_max;
} slab_item;

static int compare_items(const void *pa, const void *pb)
{
    const slab_item *a = pa, *b = pb;
    return (a->order > b->order) - (a->order < b->order);
}

static float *texel(sc_trim_block *block, int index) { return block->texels + 4 * (size_t)index; }

/* The prepared pieces elevated to `degree`, normalised to [0,1]² and
 * rounded to float; pieces whose v range collapses in float are left out.
 * Returns the count kept. */
static int pack_pieces(const sc_trim *trim, const double domain[4], int degree,
                       packed_piece *pieces)
{
    double u0 = domain[0], v0 = domain[2];
    double su = 1.0 / (domain[1] - u0), sv = 1.0 / (domain[3] - v0);
    int npieces = 0;
    for (int k = 0; k < trim->npieces; k++) {
        const sc_trim_piece *src = &trim->pieces[k];
        packed_piece *pc = &pieces[npieces];
        pc->v_lo = (float)((src->v_lo - v0) * sv);
        pc->v_hi = (float)((src->v_hi - v0) * sv);
        if (!(pc->v_lo < pc->v_hi))
            continue;
        pc->u_lo = (float)((src->u_lo - u0) * su);
        double cp[3 * MAX_POINTS];
        elevate(src->cp, src->degree, degree, cp);
        double lo = fmin(pc->u_lo, (src->u_hi - u0) * su), hi = fmax(pc->u_lo, (src->u_hi - u0) * su);
        for (int i = 0; i <= degree; i++) {
            double w = cp[3 * i + 2];
            pc->cp[3 * i + 0] = (float)((cp[3 * i + 0] - u0 * w) * su);
            pc->cp[3 * i + 1] = (float)((cp[3 * i + 1] - v0 * w) * sv);
            pc->cp[3 * i + 2] = (float)w;
            double u = (double)pc->cp[3 * i] / (double)pc->cp[3 * i + 2];
            lo = fmin(lo, u);
            hi = fmax(hi, u);
        }
        pc->u_min = float_down(lo - BOUND_MARGIN);
        pc->u_max = float_up(hi + BOUND_MARGIN);
        npieces++;
    }
    return npieces;
}

/* The v slabs between consecutive distinct piece end points, and for each
 * the pieces spanning it, ordered by u at its middle. */
typedef struct slab_list {
    float *ys;               /* nslabs + 1 slab boundaries (1 when no pieces) */
    int nslabs;
    int *start;              /* nslabs + 1: first item of each slab, then nitems */
    slab_item *items;
    int nitems;
} slab_list;

static void build_slabs(const packed_piece *pieces, int npieces, int degree, slab_list *out)
{
    float *ys = sc_alloc(2 * (size_t)npieces + 1, sizeof *ys);
    int ny = 0;
    for (int k = 0; k < npieces; k++) {
        ys[ny++] = pieces[k].v_lo;
        ys[ny++] = pieces[k].v_hi;
    }
    qsort(ys, (size_t)ny, sizeof *ys, compare_floats);
    int m = 0;
    for (int k = 0; k < ny; k++)
        if (m == 0 || ys[k] != ys[m - 1])
            ys[m++] = ys[k];
    if (m == 0)
        ys[0] = 0.0f;
    int nslabs = m > 1 ? m - 1 : 0;
    int *slab_start = sc_alloc((size_t)nslabs + 1, sizeof *slab_start);
    int items_cap = 64, nitems = 0;
    slab_item *items = sc_alloc((size_t)items_cap, sizeof *items);
    for (int sl = 0; sl < nslabs; sl++) {
        slab_start[sl] = nitems;
        double y_lo = ys[sl], y_hi = ys[sl + 1], y_mid = 0.5 * (y_lo + y_hi);
        for (int k = 0; k < npieces; k++) {
            const packed_piece *pc = &pieces[k];
            if (!(pc->v_lo <= ys[sl] && pc->v_hi >= ys[sl + 1]))
                continue;
            double cp[3 * MAX_POINTS];
            piece_points(pc, degree, cp);
            /* The part in the slab, a little wider so that it surely covers
             * the float curve's part. */
            double t0 = pc->v_lo == ys[sl] ? 0.0 : fmax(0.0, param_at_v(cp, degree, y_lo) - 1e-9);
            double t1 = pc->v_hi == ys[sl + 1] ? 1.0 : fmin(1.0, param_at_v(cp, degree, y_hi) + 1e-9);
            double lo, hi, mid_pt[3];
            part_bounds(cp, degree, t0, t1, &lo, &hi);
            if (t0 == 0.0)
                lo = fmin(lo, pc->u_lo), hi = fmax(hi, pc->u_lo);
            split_at(cp, degree, param_at_v(cp, degree, y_mid), mid_pt, NULL, NULL);
            if (nitems == items_cap) {
                items_cap *= 2;
                items = sc_realloc(items, (size_t)items_cap, sizeof *items);
            }
            items[nitems++] = (slab_item){k, mid_pt[0] / mid_pt[2], float_down(lo - BOUND_MARGIN),
                                          float_up(hi + BOUND_MARGIN)};
        }
        qsort(items + slab_start[sl], (size_t)(nitems - slab_start[sl]), sizeof *items,
              compare_items);
    }
    slab_start[nslabs] = nitems;
    *out = (slab_list){ys, nslabs, slab_start, items, nitems};
}

static void free_slabs(slab_list *slabs)
{
    free(slabs->ys);
    free(slabs->start);
    free(slabs->items);
}

/* The texels: header, pieces, slab table, slab entries (gpu_layout.h). */
static void write_block(const packed_piece *pieces, int npieces, const slab_list *slabs,
                        const double domain[4], sc_trim_block *out)
{
    int degree = out->degree;
    double u0 = domain[0], v0 = domain[2];
    double su = 1.0 / (domain[1] - u0), sv = 1.0 / (domain[3] - v0);
    int piece_texels = SCG_TRIM_PIECE_TEXELS(degree);
    int slab_offset = SCG_TRIM_HEADER_TEXELS + npieces * piece_texels;
    int item_offset = slab_offset + slabs->nslabs + 1;
    out->npieces = npieces;
    out->nslabs = slabs->nslabs;
    out->nitems = slabs->nitems;
    out->ntexels = item_offset + slabs->nitems;
    out->texels = sc_alloc(4 * (size_t)out->ntexels, sizeof(float));
    float *h = texel(out, 0);
    h[0] = (float)npieces;
    h[1] = (float)slabs->nslabs;
    h[2] = (float)out->bias;
    h[3] = (float)slab_offset;
    h = texel(out, 1);
    h[0] = (float)su;
    h[1] = (float)sv;
    h[2] = (float)(-u0 * su);
    h[3] = (float)(-v0 * sv);
    for (int k = 0; k < npieces; k++) {
        const packed_piece *pc = &pieces[k];
        int at = SCG_TRIM_HEADER_TEXELS + k * piece_texels;
        float *t = texel(out, at);
        t[0] = pc->v_lo;
        t[1] = pc->v_hi;
        t[2] = pc->u_min;
        t[3] = pc->u_max;
        for (int i = 0; i <= degree; i++)
            memcpy(texel(out, at + 1 + i), &pc->cp[3 * i], 3 * sizeof(float));
        texel(out, at + 1)[3] = pc->u_lo;
    }
    for (int sl = 0; sl <= slabs->nslabs; sl++) {
        float *t = texel(out, slab_offset + sl);
        t[0] = slabs->ys[sl];
        t[1] = (float)(item_offset + slabs->start[sl]);
        t[2] = sl < slabs->nslabs ? (float)(slabs->start[sl + 1] - slabs->start[sl]) : 0.0f;
    }
    for (int i = 0; i < slabs->nitems; i++) {
        float *t = texel(out, item_offset + i);
        t[0] = (float)(SCG_TRIM_HEADER_TEXELS + slabs->items[i].piece * piece_texels);
        t[1] = slabs->items[i].u_min;
        t[2] = slabs->items[i].u_max;
    }
}

int sc_trim_pack(const sc_surface *s, int degree, sc_trim_block *out, sc_error *err)
{
    memset(out, 0, sizeof *out);
    out->degree = degree;
    if (s->nloops == 0)
        return SC_OK;
    int needed = sc_surface_trim_degree(s);
    if (degree < needed || degree > SCG_MAX_DEGREE)
        return sc_fail(err, NULL, 0,
                       "surface '%s': trim degree %d cannot hold its trim curves of degree %d "
                       "(1..%d)",
                       s->name, degree, needed, SCG_MAX_DEGREE);
    sc_trim *trim;
    if (sc_trim_prepare(s, &trim, err) != SC_OK)
        return SC_FAIL;
    double domain[4];
    sc_surface_domain(s, &domain[0], &domain[1], &domain[2], &domain[3]);
    packed_piece *pieces = sc_alloc((size_t)trim->npieces + 1, sizeof *pieces);
    int npieces = pack_pieces(trim, domain, degree, pieces);
    slab_list slabs;
    build_slabs(pieces, npieces, degree, &slabs);
    out->bias = trim->kept_without_crossings;
    write_block(pieces, npieces, &slabs, domain, out);
    free_slabs(&slabs);
    free(pieces);
    sc_trim_free(trim);
    return SC_OK;
}

void sc_trim_block_free(sc_trim_block *block)
{
    free(block->texels);
    memset(block, 0, sizeof *block);
}
