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
 *
 * Pieces stay grouped by loop; each loop's range and the box of its pieces
 * let the per-piece methods skip the loops a point lies outside of (see
 * pack_loops for why that is exact).
 *
 * The accelerated method reads a uniform grid over the normalised domain
 * (the outer rows and columns reach to infinity). A cell is a full-height
 * slice of its row, so the part of a piece inside the row that does not
 * touch the cell lies wholly left or wholly right of it: left, it is never
 * crossed from the cell; right, it is crossed exactly when v is in its
 * half-open range. Those right pieces are therefore folded into the cell's
 * parity at the row's bottom plus the v values where that parity flips
 * (equal flips cancel, so a chain of pieces through the row costs nothing),
 * and only the pieces that may pass through the cell are listed with their
 * bounds for the program to test. A cell no curve passes through is decided
 * by its parity alone. */
#include "trim_pack.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bezier.h"
#include "gpu_layout.h"
#include "key.h"
#include "nurbs.h"
#include "trim.h"

/* Widening of u bounds, in normalised units (2^-21: four float steps at
 * 1.0). */
#define BOUND_MARGIN (1.0 / 2097152.0)

enum { MAX_POINTS = SCG_MAX_DEGREE + 1 };
_Static_assert(SC_TRIM_MAX_DEGREE <= SCG_MAX_DEGREE, "every prepared piece fits a key's degree");

/* Grid size: square, about GRID_CELLS_PER_PIECE cells a piece, a power of
 * two up to MAX_GRID_SIDE a side. More cells, or more rows than columns,
 * measured no faster on llvmpipe (docs/trimming.md) and cost memory. */
enum { GRID_CELLS_PER_PIECE = 4, MAX_GRID_SIDE = 256 };

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
    int loop;            /* the scene loop it came from */
} packed_piece;

/* A loop's range of pieces and the box that holds them. */
typedef struct packed_loop {
    int first, count;    /* pieces first … first + count - 1 */
    float u_min, u_max, v_lo, v_hi;
} packed_loop;

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

/* Subdivisions after which a sub-curve straddling a row edge is taken
 * whole: its control polygon is then far narrower than a float step of
 * the bounds' margin. */
enum { PART_DEPTH = 24 };

/* Widens [*u_min, *u_max] to the u of every part of the curve whose v may
 * lie in [y_lo, y_hi]. Works from control polygons only (the convex hull
 * property), so it needs no monotony that rounding might have broken. */
static void part_bounds(const double *cp, int n, double y_lo, double y_hi, int depth,
                        double *u_min, double *u_max)
{
    double lo_v = INFINITY, hi_v = -INFINITY, lo_u = INFINITY, hi_u = -INFINITY;
    for (int i = 0; i <= n; i++) {
        double u = cp[3 * i] / cp[3 * i + 2], v = cp[3 * i + 1] / cp[3 * i + 2];
        lo_v = fmin(lo_v, v);
        hi_v = fmax(hi_v, v);
        lo_u = fmin(lo_u, u);
        hi_u = fmax(hi_u, u);
    }
    if (hi_v < y_lo || lo_v > y_hi || (lo_u >= *u_min && hi_u <= *u_max))
        return;
    if ((lo_v >= y_lo && hi_v <= y_hi) || depth == PART_DEPTH) {
        *u_min = fmin(*u_min, lo_u);
        *u_max = fmax(*u_max, hi_u);
        return;
    }
    double left[3 * MAX_POINTS], right[3 * MAX_POINTS];
    sc_bezier_split(cp, n, 3, 3, 0.5, left, right);
    part_bounds(left, n, y_lo, y_hi, depth + 1, u_min, u_max);
    part_bounds(right, n, y_lo, y_hi, depth + 1, u_min, u_max);
}

static int compare_floats(const void *pa, const void *pb)
{
    float a = *(const float *)pa, b = *(const float *)pb;
    return (a > b) - (a < b);
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
        pc->loop = src->loop;
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

/* Whether every v is covered by an even number of the pieces: the v ends
 * of the pieces, each value an even number of times. A closed chain of
 * pieces sharing end points bit for bit is even this way. */
static int even_coverage(const packed_piece *pieces, int count, float *ends)
{
    for (int k = 0; k < count; k++) {
        ends[2 * k] = pieces[k].v_lo;
        ends[2 * k + 1] = pieces[k].v_hi;
    }
    qsort(ends, 2 * (size_t)count, sizeof *ends, compare_floats);
    for (int k = 0; k < 2 * count; k += 2)
        if (ends[k] != ends[k + 1])
            return 0;
    return 1;
}

/* The loops' ranges and boxes. The preparation emits each loop's pieces
 * together, so a loop is a run of pieces. A point outside a loop's box
 * gets no crossing from it, or (left of the box) one for every piece
 * covering its v, which is an even number for a closed loop: either way
 * the loop leaves the parity alone and the per-piece methods skip it. A
 * loop whose ends do not pair up (left open, or broken by rounding) has
 * its box opened to the left, so that it is never skipped there. */
static int pack_loops(const packed_piece *pieces, int npieces, packed_loop *loops)
{
    float *ends = sc_try_alloc(2 * (size_t)npieces + 1, sizeof *ends);
    if (!ends)
        return -1;
    int nloops = 0;
    for (int k = 0; k < npieces;) {
        packed_loop *lp = &loops[nloops++];
        lp->first = k;
        lp->u_min = lp->v_lo = FLT_MAX;
        lp->u_max = lp->v_hi = -FLT_MAX;
        for (; k < npieces && pieces[k].loop == pieces[lp->first].loop; k++) {
            lp->u_min = fminf(lp->u_min, pieces[k].u_min);
            lp->u_max = fmaxf(lp->u_max, pieces[k].u_max);
            lp->v_lo = fminf(lp->v_lo, pieces[k].v_lo);
            lp->v_hi = fmaxf(lp->v_hi, pieces[k].v_hi);
        }
        lp->count = k - lp->first;
        if (!even_coverage(&pieces[lp->first], lp->count, ends))
            lp->u_min = -FLT_MAX;
    }
    free(ends);
    return nloops;
}

/* ---- the grid ---- */

/* One entry of a cell's list: a piece that may pass through the cell, with
 * the bounds of u over its part in the row, or (piece -1) a run of v where
 * the pieces right of the cell add one crossing. */
typedef struct grid_entry {
    float v_lo, v_hi, u_min, u_max;
    int piece;
} grid_entry;

typedef struct grid {
    int cols, rows;
    int *parity;             /* per cell (row-major): crossings mod 2 at the row's bottom */
    int *first, *count;      /* per cell: its entries */
    grid_entry *entries;
    int nentries, cap;
    size_t failed;           /* bytes that could not be allocated: the grid is unusable */
} grid;

/* A piece's part in one row: its bounds of u. */
typedef struct row_part {
    int piece;
    float u_min, u_max;
} row_part;

/* Cells per side: a power of two keeps u·side exact in float, so the cell
 * the program computes is the one the packer means. */
static int grid_side(int npieces)
{
    int side = 1;
    while (side * side < GRID_CELLS_PER_PIECE * npieces && side < MAX_GRID_SIDE)
        side *= 2;
    return side;
}

static void add_entry(grid *gr, grid_entry e)
{
    if (gr->failed)
        return;
    if (gr->nentries == gr->cap) {
        int cap = gr->cap ? 2 * gr->cap : 64;
        grid_entry *grown = sc_try_realloc(gr->entries, (size_t)cap, sizeof *gr->entries);
        if (!grown) {
            gr->failed = (size_t)cap * sizeof *gr->entries;
            return;
        }
        gr->entries = grown;
        gr->cap = cap;
    }
    gr->entries[gr->nentries++] = e;
}

/* Edge k of n equal divisions of [0, 1], the outer edges at infinity. */
static double grid_edge(int k, int n)
{
    return k == 0 ? -INFINITY : k == n ? INFINITY : (double)k / n;
}

/* The cell's entries and parity, from the pieces meeting its row. */
static void fill_cell(grid *gr, const packed_piece *pieces, const row_part *parts, int nparts,
                      int row, int col, int bias, float *flips)
{
    double y0 = grid_edge(row, gr->rows), y1 = grid_edge(row + 1, gr->rows);
    double x0 = grid_edge(col, gr->cols), x1 = grid_edge(col + 1, gr->cols);
    int cell = row * gr->cols + col, parity = bias, nflips = 0;
    gr->first[cell] = gr->nentries;
    for (int k = 0; k < nparts; k++) {
        const row_part *part = &parts[k];
        const packed_piece *pc = &pieces[part->piece];
        if (part->u_max <= x0)
            continue;
        if (part->u_min < x1) {
            add_entry(gr, (grid_entry){pc->v_lo, pc->v_hi, part->u_min, part->u_max, part->piece});
            continue;
        }
        parity += pc->v_lo <= y0 && y0 < pc->v_hi;
        if (pc->v_lo > y0 && pc->v_lo < y1)
            flips[nflips++] = pc->v_lo;
        if (pc->v_hi > y0 && pc->v_hi < y1)
            flips[nflips++] = pc->v_hi;
    }
    /* The parity flips at each v left after equal pairs cancel: runs
     * [f1, f2), [f3, f4), … add one crossing each. */
    qsort(flips, (size_t)nflips, sizeof *flips, compare_floats);
    int kept = 0;
    for (int k = 0; k < nflips; k++) {
        if (kept > 0 && flips[kept - 1] == flips[k])
            kept--;
        else
            flips[kept++] = flips[k];
    }
    for (int k = 0; k < kept; k += 2) {
        float end = k + 1 < kept ? flips[k + 1] : FLT_MAX;
        add_entry(gr, (grid_entry){flips[k], end, FLT_MAX, FLT_MAX, -1});
    }
    gr->parity[cell] = parity % 2;
    gr->count[cell] = gr->nentries - gr->first[cell];
}

static void build_grid(const packed_piece *pieces, int npieces, int degree, int bias, int cols,
                       int rows, grid *gr)
{
    memset(gr, 0, sizeof *gr);
    gr->cols = cols;
    gr->rows = rows;
    size_t ncells = (size_t)gr->cols * (size_t)gr->rows;
    gr->parity = sc_try_alloc(ncells, sizeof *gr->parity);
    gr->first = sc_try_alloc(ncells, sizeof *gr->first);
    gr->count = sc_try_alloc(ncells, sizeof *gr->count);
    row_part *parts = sc_try_alloc((size_t)npieces + 1, sizeof *parts);
    float *flips = sc_try_alloc(2 * (size_t)npieces + 1, sizeof *flips);
    if (!gr->parity || !gr->first || !gr->count || !parts || !flips)
        gr->failed = ncells * 3 * sizeof(int) + ((size_t)npieces + 1) * sizeof *parts +
                     (2 * (size_t)npieces + 1) * sizeof *flips;
    for (int row = 0; row < gr->rows && !gr->failed; row++) {
        double y0 = grid_edge(row, gr->rows), y1 = grid_edge(row + 1, gr->rows);
        int nparts = 0;
        for (int k = 0; k < npieces; k++) {
            const packed_piece *pc = &pieces[k];
            if (!(pc->v_lo < y1 && y0 < pc->v_hi))
                continue;
            double cp[3 * MAX_POINTS], lo = INFINITY, hi = -INFINITY;
            piece_points(pc, degree, cp);
            part_bounds(cp, degree, fmax(y0, pc->v_lo), fmin(y1, pc->v_hi), 0, &lo, &hi);
            if (pc->v_lo >= y0) {
                lo = fmin(lo, pc->u_lo);
                hi = fmax(hi, pc->u_lo);
            }
            parts[nparts++] = (row_part){k, float_down(lo - BOUND_MARGIN),
                                         float_up(hi + BOUND_MARGIN)};
        }
        for (int col = 0; col < gr->cols; col++)
            fill_cell(gr, pieces, parts, nparts, row, col, bias, flips);
    }
    free(flips);
    free(parts);
}

static void free_grid(grid *gr)
{
    free(gr->parity);
    free(gr->first);
    free(gr->count);
    free(gr->entries);
}

/* Texel offsets of the parts of a block (gpu_layout.h): header, cells,
 * loops, pieces, entries. */
typedef struct block_layout {
    long long cells, loops, pieces, entries, total;
} block_layout;

static block_layout layout_of(int nloops, int npieces, int degree, const grid *gr)
{
    block_layout at;
    at.cells = SCG_TRIM_HEADER_TEXELS;
    at.loops = at.cells + (long long)gr->cols * gr->rows;
    at.pieces = at.loops + (long long)SCG_TRIM_LOOP_TEXELS * nloops;
    at.entries = at.pieces + (long long)npieces * SCG_TRIM_PIECE_TEXELS(degree);
    at.total = at.entries + (long long)SCG_TRIM_ENTRY_TEXELS * gr->nentries;
    return at;
}

/* The grid of the preferred size, or, when its block would reach the
 * texels a float offset can address, of half the rows and columns. */
static void fitting_grid(const packed_piece *pieces, int npieces, int nloops, int degree, int bias,
                         grid *gr)
{
    int cols = grid_side(npieces), rows = cols;
    for (;;) {
        build_grid(pieces, npieces, degree, bias, cols, rows, gr);
        if (gr->failed || layout_of(nloops, npieces, degree, gr).total < SCG_TRIM_MAX_TEXELS ||
            (cols == 1 && rows == 1))
            return;
        free_grid(gr);
        cols = cols > 1 ? cols / 2 : 1;
        rows = rows > 1 ? rows / 2 : 1;
    }
}

/* The texels (gpu_layout.h). */
static int write_block(const packed_piece *pieces, int npieces, const packed_loop *loops,
                       int nloops, const grid *gr, const double domain[4], sc_trim_block *out,
                       sc_error *err)
{
    int degree = out->degree;
    double u0 = domain[0], v0 = domain[2];
    double su = 1.0 / (domain[1] - u0), sv = 1.0 / (domain[3] - v0);
    int piece_texels = SCG_TRIM_PIECE_TEXELS(degree);
    block_layout at = layout_of(nloops, npieces, degree, gr);
    if (at.total >= SCG_TRIM_MAX_TEXELS)
        return sc_fail(err, NULL, 0, "trim block of %lld texels: offsets from %d on are not exact "
                       "in float", at.total, SCG_TRIM_MAX_TEXELS);
    out->npieces = npieces;
    out->nloops = nloops;
    out->grid_u = gr->cols;
    out->grid_v = gr->rows;
    out->nentries = gr->nentries;
    out->ntexels = (int)at.total;
    out->texels = sc_try_alloc(4 * (size_t)out->ntexels, sizeof(float));
    if (!out->texels)
        return sc_fail_oom(err, NULL, 0, 4 * (size_t)out->ntexels, sizeof(float),
                           "a trim block");
    float *h = texel(out, 0);
    h[0] = (float)nloops;
    h[1] = (float)out->bias;
    h[2] = (float)gr->cols;
    h[3] = (float)gr->rows;
    h = texel(out, 1);
    h[0] = (float)su;
    h[1] = (float)sv;
    h[2] = (float)(-u0 * su);
    h[3] = (float)(-v0 * sv);
    for (int cell = 0; cell < gr->cols * gr->rows; cell++) {
        float *t = texel(out, (int)at.cells + cell);
        t[0] = (float)gr->parity[cell];
        t[1] = gr->count[cell] ? (float)(at.entries + SCG_TRIM_ENTRY_TEXELS * gr->first[cell])
                               : 0.0f;
        t[2] = (float)gr->count[cell];
    }
    for (int l = 0; l < nloops; l++) {
        float *t = texel(out, (int)at.loops + SCG_TRIM_LOOP_TEXELS * l);
        t[0] = loops[l].u_min;
        t[1] = loops[l].u_max;
        t[2] = loops[l].v_lo;
        t[3] = loops[l].v_hi;
        t[4] = (float)(at.pieces + (long long)loops[l].first * piece_texels);
        t[5] = (float)loops[l].count;
    }
    for (int k = 0; k < npieces; k++) {
        const packed_piece *pc = &pieces[k];
        int first = (int)at.pieces + k * piece_texels;
        float *t = texel(out, first);
        t[0] = pc->v_lo;
        t[1] = pc->v_hi;
        t[2] = pc->u_min;
        t[3] = pc->u_max;
        for (int i = 0; i <= degree; i++)
            memcpy(texel(out, first + 1 + i), &pc->cp[3 * i], 3 * sizeof(float));
        texel(out, first + 1)[3] = pc->u_lo;
    }
    for (int k = 0; k < gr->nentries; k++) {
        const grid_entry *e = &gr->entries[k];
        float *t = texel(out, (int)at.entries + SCG_TRIM_ENTRY_TEXELS * k);
        t[0] = e->v_lo;
        t[1] = e->v_hi;
        t[2] = e->u_min;
        t[3] = e->u_max;
        if (e->piece >= 0)
            t[4] = (float)(at.pieces + (long long)e->piece * piece_texels);
    }
    return SC_OK;
}

int sc_trim_pack(const sc_surface *s, int degree, sc_trim_block *out, sc_error *err)
{
    memset(out, 0, sizeof *out);
    out->degree = degree;
    if (s->nloops == 0)
        return SC_OK;
    int needed = sc_surface_trim_degree(s);
    /* A curve above the limit is the preparation's to report, naming it. */
    if (needed <= SC_TRIM_MAX_DEGREE && (degree < needed || degree > SCG_MAX_DEGREE))
        return sc_fail(err, NULL, 0,
                       "surface '%s': a program of trim degree %d cannot draw its trim curves "
                       "of degree up to %d (the surface's key names trim degree %d)",
                       s->name, degree, needed, needed);
    sc_trim *trim;
    if (sc_trim_prepare(s, &trim, err) != SC_OK)
        return SC_FAIL;
    double domain[4];
    sc_surface_domain(s, &domain[0], &domain[1], &domain[2], &domain[3]);
    /* Every array here is as large as the surface's trim pieces. */
    packed_piece *pieces = sc_try_alloc((size_t)trim->npieces + 1, sizeof *pieces);
    int npieces = pieces ? pack_pieces(trim, domain, degree, pieces) : 0;
    packed_loop *loops = pieces ? sc_try_alloc((size_t)npieces + 1, sizeof *loops) : NULL;
    int nloops = loops ? pack_loops(pieces, npieces, loops) : -1;
    out->bias = trim->kept_without_crossings;
    grid gr = {0};
    if (nloops >= 0)
        fitting_grid(pieces, npieces, nloops, degree, out->bias, &gr);
    int status;
    if (nloops < 0 || gr.failed) {
        char what[160];
        snprintf(what, sizeof what, "the trim block of surface '%s'", s->name);
        status = sc_fail_oom(err, NULL, 0, gr.failed ? gr.failed : sc_alloc_failed_bytes(), 1,
                             what);
    } else {
        status = write_block(pieces, npieces, loops, nloops, &gr, domain, out, err);
    }
    free_grid(&gr);
    free(loops);
    free(pieces);
    sc_trim_free(trim);
    if (status != SC_OK)
        sc_trim_block_free(out);
    return status;
}

void sc_trim_block_free(sc_trim_block *block)
{
    free(block->texels);
    memset(block, 0, sizeof *block);
}
