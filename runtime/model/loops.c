/* loops.c — trim-loop validation (sc_scene_validate_loops in scene.h), run
 * once by every reader. Real files have loops whose curves do not quite meet
 * and, now and then, loops that cross themselves; the trimming stages
 * (parity tests, Bézier clipping) need closed, simple loops, so gaps are
 * closed or the loop is dropped here, once, with a warning that names it.
 *
 * Self-crossings are found on a polyline flattened to FLAT_TOL of the
 * domain size; its segments are binned in a uniform grid so that loops of
 * thousands of pieces are not tested pair by pair. Segments that overlap
 * (a curve repeated many times) all land in the same cells, where the
 * pairs grow with the square of their number: past PAIR_BUDGET tests per
 * segment the loop is dropped with a warning instead of being checked for
 * minutes (a simple loop of real data needs a few per segment). Whether a crossing
 * counts depends only on the loop's shape, never on what was repaired, so
 * that validating a validated loop (a scene written and read back) changes
 * nothing. */
#include "bezier.h"
#include "nurbs.h"
#include "trim.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Gaps relative to the domain size (the larger extent of u and v). */
static const double GAP_SILENT = 1e-9;
static const double GAP_REPAIR = 1e-3;
/* A crossing that cuts off a lobe through a curve junction no longer than
 * CORNER_LOBE of the domain size and CORNER_SHARE of the rest of the loop
 * is the rounding of a sharp corner (see corner_lobe). */
static const double CORNER_LOBE = 1e-3;
static const double CORNER_SHARE = 1e-2;
/* Chordal tolerance of the flattened loop, relative to the domain size. */
static const double FLAT_TOL = 1e-6;
/* Subdivision depth per Bézier segment, and vertices per loop, beyond
 * which a curve is flattened no further. */
enum { FLAT_MAX_DEPTH = 14, FLAT_MAX_POINTS = 1 << 22, GRID_MAX_SIDE = 2048 };
/* Grid entries and segment pairs tested per loop: PAIR_BUDGET per segment,
 * and at least PAIR_FLOOR (any loop of up to about 2,900 segments is
 * checked whole). */
enum { PAIR_BUDGET = 16, PAIR_FLOOR = 1 << 22, CROSSING_UNKNOWN = -1, CROSSING_NO_MEMORY = -2 };

/* ---- curve ends ---- */

static void end_point(const sc_curve *c, int last, double out[2])
{
    const double *P = c->cp + (last ? 3 * (size_t)(c->ncp - 1) : 0);
    out[0] = P[0] / P[2];
    out[1] = P[1] / P[2];
}

/* Moves an end control point (the curve interpolates it: knots clamped)
 * keeping its weight. */
static void set_end_point(sc_curve *c, int last, const double at[2])
{
    double *P = c->cp + (last ? 3 * (size_t)(c->ncp - 1) : 0);
    P[0] = at[0] * P[2];
    P[1] = at[1] * P[2];
}

/* Ends that differ only by the rounding of set_end_point (at most 2 units
 * in the last place each way, whatever the weights): moving them again
 * would change nothing but the last bits, and would make a second
 * validation alter what the first one left. */
static int agree_to_rounding(const double a[2], const double b[2])
{
    for (int k = 0; k < 2; k++)
        if (fabs(a[k] - b[k]) > 4 * DBL_EPSILON * fmax(fabs(a[k]), fabs(b[k])))
            return 0;
    return 1;
}

static void make_line(sc_curve *c, const double a[2], const double b[2])
{
    sc_curve_alloc(c, 2, 1, 2);
    const double knots[4] = {0, 0, 1, 1};
    memcpy(c->knots, knots, sizeof knots);
    const double cp[6] = {a[0], a[1], 1, b[0], b[1], 1};
    memcpy(c->cp, cp, sizeof cp);
}

/* ---- flattening ---- */

typedef struct polyline {
    double *xy;   /* 2 per vertex */
    int *curve;   /* curve index of the segment starting at each vertex */
    int n, cap;
    /* Filled once the loop is complete (measure_loop): arc length from
     * vertex 0 to vertex k (arc[n]: the whole loop), and the number of
     * vertices 1..k where one curve ends and the next begins. */
    double *arc;
    int *junctions;
    size_t failed; /* bytes that could not be allocated */
} polyline;

/* Consecutive equal vertices are merged: the crossing test below relies on
 * segments of non-zero length. Fails when memory runs out (pl->failed). */
static void poly_push(polyline *pl, double x, double y, int curve)
{
    if (pl->failed || (pl->n > 0 && pl->xy[2 * pl->n - 2] == x && pl->xy[2 * pl->n - 1] == y))
        return;
    if (pl->n == pl->cap) {
        int cap = pl->cap ? 2 * pl->cap : 256;
        double *xy = sc_try_realloc(pl->xy, (size_t)cap * 2, sizeof(double));
        if (xy)
            pl->xy = xy;
        int *c = xy ? sc_try_realloc(pl->curve, (size_t)cap, sizeof(int)) : NULL;
        if (!c) {
            pl->failed = (size_t)cap * (2 * sizeof(double) + sizeof(int));
            return;
        }
        pl->curve = c;
        pl->cap = cap;
    }
    pl->xy[2 * pl->n] = x;
    pl->xy[2 * pl->n + 1] = y;
    pl->curve[pl->n] = curve;
    pl->n++;
}

/* Distance of the control polygon from the chord: by the convex hull
 * property (weights > 0) a bound of the curve's distance from it. */
static double bezier_flatness(const double *B, int degree)
{
    double ax = B[0] / B[2], ay = B[1] / B[2];
    const double *E = B + 3 * degree;
    double bx = E[0] / E[2], by = E[1] / E[2];
    double dx = bx - ax, dy = by - ay, len = hypot(dx, dy), worst = 0;
    for (int i = 1; i < degree; i++) {
        double px = B[3 * i] / B[3 * i + 2] - ax, py = B[3 * i + 1] / B[3 * i + 2] - ay;
        double d = len > 0 ? fabs(px * dy - py * dx) / len : hypot(px, py);
        if (d > worst)
            worst = d;
    }
    return worst;
}

/* Appends the curve's points after its first (which the caller has). */
static void flatten_bezier(const double *B, int degree, double tol, int depth, int curve,
                           polyline *pl)
{
    if (pl->failed)
        return;
    if (depth >= FLAT_MAX_DEPTH || pl->n >= FLAT_MAX_POINTS ||
        bezier_flatness(B, degree) <= tol) {
        const double *E = B + 3 * degree;
        poly_push(pl, E[0] / E[2], E[1] / E[2], curve);
        return;
    }
    /* check_curves has refused degrees above SC_TRIM_MAX_DEGREE. */
    assert(degree <= SC_TRIM_MAX_DEGREE);
    double left[3 * (SC_TRIM_MAX_DEGREE + 1)], right[3 * (SC_TRIM_MAX_DEGREE + 1)];
    sc_bezier_split(B, degree, 3, 3, 0.5, left, right);
    flatten_bezier(left, degree, tol, depth + 1, curve, pl);
    flatten_bezier(right, degree, tol, depth + 1, curve, pl);
}

/* The loop as one closed polyline: each curve contributes its vertices
 * but its last, which is the next curve's first. */
static void flatten_loop(const sc_loop *loop, double tol, polyline *pl)
{
    for (int c = 0; c < loop->ncurves && !pl->failed; c++) {
        const sc_curve *cv = &loop->curves[c];
        double start[2];
        end_point(cv, 0, start);
        poly_push(pl, start[0], start[1], c);
        sc_curve *segs;
        int nseg;
        if (sc_curve_to_bezier(cv, &segs, &nseg)) {
            pl->failed = sc_alloc_failed_bytes();
            break;
        }
        for (int s = 0; s < nseg; s++) {
            flatten_bezier(segs[s].cp, cv->degree, tol, 0, c, pl);
            sc_curve_free(&segs[s]);
        }
        free(segs);
        if (pl->n > 1)
            pl->n--; /* the curve's last vertex */
    }
    while (pl->n > 1 && pl->xy[0] == pl->xy[2 * pl->n - 2] && pl->xy[1] == pl->xy[2 * pl->n - 1])
        pl->n--;
}

/* ---- crossings ---- */

static double orient(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static const double *vertex(const polyline *pl, int i)
{
    return pl->xy + 2 * (((i % pl->n) + pl->n) % pl->n);
}

static int on_segment(const double *p, const double *a, const double *b)
{
    return orient(a, b, p) == 0 && p[0] >= fmin(a[0], b[0]) && p[0] <= fmax(a[0], b[0]) &&
           p[1] >= fmin(a[1], b[1]) && p[1] <= fmax(a[1], b[1]);
}

static int same_point(const double *p, const double *q) { return p[0] == q[0] && p[1] == q[1]; }

/* Directions in which the loop arrives at and leaves x along segment i
 * (x is one of its end points or lies inside it), as angles. */
static void branch_angles(const polyline *pl, int i, const double *x, double angle[2])
{
    const double *in = vertex(pl, i), *out = vertex(pl, i + 1);
    if (same_point(x, in))
        in = vertex(pl, i - 1);
    else if (same_point(x, out))
        out = vertex(pl, i + 2);
    angle[0] = atan2(in[1] - x[1], in[0] - x[0]);
    angle[1] = atan2(out[1] - x[1], out[0] - x[0]);
}

/* Counter-clockwise turn from angle a to angle b, in [0, 2π). */
static double ccw_turn(double a, double b)
{
    double t = fmod(b - a, 2 * M_PI);
    return t < 0 ? t + 2 * M_PI : t;
}

/* Segments i and j (not neighbours) cross: at a point interior to both,
 * or where they touch, when the two passes of the loop through the touching
 * point interleave (one pass's directions separate the other's). Passes
 * that share a direction (overlapping pieces) are not decided here. */
static int segments_cross(const polyline *pl, int i, int j, double at[2])
{
    const double *a = vertex(pl, i), *b = vertex(pl, i + 1);
    const double *c = vertex(pl, j), *d = vertex(pl, j + 1);
    double o1 = orient(a, b, c), o2 = orient(a, b, d);
    double o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) {
        double t = o3 / (o3 - o4);
        at[0] = a[0] + t * (b[0] - a[0]);
        at[1] = a[1] + t * (b[1] - a[1]);
        return 1;
    }
    if (o1 == 0 && o2 == 0)
        return 0;
    const double *x = on_segment(a, c, d) ? a : on_segment(b, c, d) ? b
                    : on_segment(c, a, b) ? c : on_segment(d, a, b) ? d : NULL;
    if (!x)
        return 0;
    double p[2], q[2];
    branch_angles(pl, i, x, p);
    branch_angles(pl, j, x, q);
    double arc = ccw_turn(p[0], p[1]), tq0 = ccw_turn(p[0], q[0]), tq1 = ccw_turn(p[0], q[1]);
    if (arc == 0 || tq0 == 0 || tq1 == 0 || tq0 == arc || tq1 == arc)
        return 0;
    at[0] = x[0];
    at[1] = x[1];
    return (tq0 < arc) != (tq1 < arc);
}

/* ---- corners ---- */

static void measure_loop(polyline *pl)
{
    int n = pl->n;
    pl->arc = sc_try_alloc((size_t)n + 1, sizeof(double));
    pl->junctions = sc_try_alloc((size_t)n + 1, sizeof(int));
    if (!pl->arc || !pl->junctions) {
        pl->failed = ((size_t)n + 1) * (sizeof(double) + sizeof(int));
        return;
    }
    for (int k = 1; k <= n; k++) {
        const double *a = vertex(pl, k - 1), *b = vertex(pl, k);
        pl->arc[k] = pl->arc[k - 1] + hypot(b[0] - a[0], b[1] - a[1]);
        pl->junctions[k] = pl->junctions[k - 1] + (k < n && pl->curve[k] != pl->curve[k - 1]);
    }
}

/* A crossing of segments i < j at `at` splits the loop into two lobes: from
 * `at` along i+1 .. j back to `at`, and the rest. Where two curves meet at
 * a sharp corner, rounding in the file (or a straight segment closing a gap
 * there, which may run backwards) can make them cross just beside the
 * corner, cutting off a lobe that holds the corner and encloses next to
 * nothing. Such a crossing is accepted: the shorter lobe passes through a
 * junction of curves (vertex 0 always is one: the last curve ends there),
 * is at most CORNER_LOBE of the domain size and at most CORNER_SHARE of the
 * other lobe. A figure-eight has two large lobes; a curve crossing itself
 * away from its ends has a lobe without a junction. Only the loop's shape
 * counts, so the answer is the same before and after gaps are closed. */
static int corner_lobe(const polyline *pl, int i, int j, const double at[2], double size)
{
    assert(i < j);
    const double *a = vertex(pl, i), *c = vertex(pl, j);
    double from = pl->arc[i] + hypot(at[0] - a[0], at[1] - a[1]);
    double to = pl->arc[j] + hypot(at[0] - c[0], at[1] - c[1]);
    double inner = to - from, outer = pl->arc[pl->n] - inner;
    double lobe = fmin(inner, outer);
    int through_junction = inner < outer ? pl->junctions[j] > pl->junctions[i] : 1;
    double rest = inner + outer - lobe;
    return through_junction && lobe <= CORNER_LOBE * size && lobe <= CORNER_SHARE * rest;
}

/* For each curve of a loop after closing its gaps: its index in the loop as
 * read, or -1 - k for the segment closing the gap after curve k (for
 * messages). */
typedef struct loop_layout {
    int *origin;
} loop_layout;

static const char *curve_name(const loop_layout *lay, int curve, char *buf, size_t size)
{
    int o = lay->origin[curve];
    if (o >= 0)
        snprintf(buf, size, "curve %d", o);
    else
        snprintf(buf, size, "the segment closing the gap after curve %d", -1 - o);
    return buf;
}

typedef struct grid {
    double x0, y0, cell_w, cell_h;
    int nx, ny;
    int *start; /* nx*ny + 1 offsets into entries */
    int *entries;
} grid;

static int cell_of(double x, double origin, double size, int n)
{
    int i = (int)floor((x - origin) / size);
    return i < 0 ? 0 : i >= n ? n - 1 : i;
}

/* Counts or fills every cell the segment passes through (conservatively:
 * column by column, the y range of the segment within the column), and
 * returns how many. */
static int cover_cells(const grid *g, const double *a, const double *b, int seg, int *count,
                       int *fill)
{
    int cells = 0;
    double xmin = fmin(a[0], b[0]), xmax = fmax(a[0], b[0]);
    int ix0 = cell_of(xmin, g->x0, g->cell_w, g->nx);
    int ix1 = cell_of(xmax, g->x0, g->cell_w, g->nx);
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double pad = 1e-9 * g->cell_h;
    for (int ix = ix0; ix <= ix1; ix++) {
        double xa = fmax(xmin, g->x0 + ix * g->cell_w);
        double xb = fmin(xmax, g->x0 + (ix + 1) * g->cell_w);
        double ya, yb;
        if (dx == 0 || ix0 == ix1) {
            ya = a[1];
            yb = b[1];
        } else {
            ya = a[1] + dy * (xa - a[0]) / dx;
            yb = a[1] + dy * (xb - a[0]) / dx;
        }
        int iy0 = cell_of(fmin(ya, yb) - pad, g->y0, g->cell_h, g->ny);
        int iy1 = cell_of(fmax(ya, yb) + pad, g->y0, g->cell_h, g->ny);
        for (int iy = iy0; iy <= iy1; iy++) {
            int cell = iy * g->nx + ix;
            if (fill)
                g->entries[fill[cell]++] = seg;
            else
                count[cell]++;
            cells++;
        }
    }
    return cells;
}

/* Finds a crossing between two segments of the closed polyline that are
 * not neighbours (corner lobes excepted); returns 1, the two segment
 * indices and the crossing point, or CROSSING_UNKNOWN past the budget of
 * pair tests. */
static int find_crossing(const polyline *pl, double size, int *seg_a, int *seg_b, double at[2])
{
    int n = pl->n;
    if (n < 4)
        return 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], pl->xy[2 * i + k]);
            hi[k] = fmax(hi[k], pl->xy[2 * i + k]);
        }
    grid g;
    int side = (int)ceil(sqrt((double)n));
    side = side < 1 ? 1 : side > GRID_MAX_SIDE ? GRID_MAX_SIDE : side;
    g.nx = g.ny = side;
    g.x0 = lo[0];
    g.y0 = lo[1];
    g.cell_w = (hi[0] - lo[0]) / side;
    g.cell_h = (hi[1] - lo[1]) / side;
    if (!(g.cell_w > 0))
        g.cell_w = 1, g.nx = 1;
    if (!(g.cell_h > 0))
        g.cell_h = 1, g.ny = 1;
    int ncells = g.nx * g.ny;
    g.start = sc_try_alloc((size_t)ncells + 1, sizeof(int));
    int *count = sc_try_alloc((size_t)ncells, sizeof(int));
    if (!g.start || !count) {
        free(g.start);
        free(count);
        return CROSSING_NO_MEMORY;
    }
    /* Long overlapping segments cover many cells each: the entries share
     * the budget of the pair tests. */
    long long budget = (long long)PAIR_BUDGET * n > PAIR_FLOOR ? (long long)PAIR_BUDGET * n
                                                                : PAIR_FLOOR;
    for (int i = 0; i < n; i++) {
        budget -= cover_cells(&g, pl->xy + 2 * i, pl->xy + 2 * ((i + 1) % n), i, count, NULL);
        if (budget < 0) {
            free(count);
            free(g.start);
            return CROSSING_UNKNOWN;
        }
    }
    for (int c = 0; c < ncells; c++)
        g.start[c + 1] = g.start[c] + count[c];
    g.entries = sc_try_alloc((size_t)g.start[ncells], sizeof(int));
    if (!g.entries) {
        free(count);
        free(g.start);
        return CROSSING_NO_MEMORY;
    }
    memcpy(count, g.start, sizeof(int) * (size_t)ncells);
    for (int i = 0; i < n; i++)
        cover_cells(&g, pl->xy + 2 * i, pl->xy + 2 * ((i + 1) % n), i, NULL, count);
    int found = 0;
    for (int c = 0; c < ncells && !found; c++)
        for (int x = g.start[c]; x < g.start[c + 1] && !found; x++) {
            budget -= g.start[c + 1] - x - 1;
            if (budget < 0) {
                found = CROSSING_UNKNOWN;
                break;
            }
            for (int y = x + 1; y < g.start[c + 1]; y++) {
                int i = g.entries[x], j = g.entries[y];
                if (i > j) {
                    int t = i;
                    i = j;
                    j = t;
                }
                if (j - i <= 1 || j - i == n - 1)
                    continue;
                if (segments_cross(pl, i, j, at) && !corner_lobe(pl, i, j, at, size)) {
                    *seg_a = i;
                    *seg_b = j;
                    found = 1;
                    break;
                }
            }
        }
    free(count);
    free(g.start);
    free(g.entries);
    return found;
}

/* ---- one loop ---- */

/* What a step of one loop's validation returns when memory runs out. */
enum { LOOP_NO_MEMORY = -1 };

typedef struct loop_site {
    sc_scene *scene;
    int surface;
    int loop;
    size_t *oom; /* the bytes that could not be allocated */
} loop_site;

/* "FILE: " when the scene came from a file (readers set scene->source
 * before validating). */
#define LOOP_FMT "%s%ssurface %d (%s): trim loop %d"
#define LOOP_ARGS(site)                                                                      \
    (site)->scene->source, (site)->scene->source[0] ? ": " : "", (site)->surface,           \
        (site)->scene->surfaces[(site)->surface].name, (site)->loop

/* Closes the gaps of a loop or decides to drop it. Returns 1 to keep, and
 * then fills `lay`; LOOP_NO_MEMORY when memory runs out (the loop as it
 * was). */
static int close_gaps(const loop_site *site, sc_loop *loop, double size, loop_layout *lay)
{
    int n = loop->ncurves;
    double *gaps = sc_try_alloc((size_t)n, sizeof(double));
    if (!gaps)
        return *site->oom = (size_t)n * sizeof(double), LOOP_NO_MEMORY;
    for (int k = 0; k < n; k++) {
        double a[2], b[2];
        end_point(&loop->curves[k], 1, a);
        end_point(&loop->curves[(k + 1) % n], 0, b);
        gaps[k] = hypot(b[0] - a[0], b[1] - a[1]) / size;
        if (!(gaps[k] <= GAP_REPAIR)) {
            sc_log(SC_LOG_WARN, LOOP_FMT " dropped: gap of %.3g of the domain size after "
                   "curve %d (more than %g)", LOOP_ARGS(site), gaps[k], k, GAP_REPAIR);
            free(gaps);
            return 0;
        }
    }
    int repairs = 0;
    for (int k = 0; k < n; k++)
        if (gaps[k] > GAP_SILENT)
            repairs++;
    sc_curve *curves = sc_try_alloc((size_t)(n + repairs), sizeof(sc_curve));
    lay->origin = sc_try_alloc((size_t)(n + repairs), sizeof(int));
    if (!curves || !lay->origin) {
        free(curves);
        free(gaps);
        return *site->oom = (size_t)(n + repairs) * (sizeof(sc_curve) + sizeof(int)),
               LOOP_NO_MEMORY;
    }
    int out = 0;
    for (int k = 0; k < n; k++) {
        sc_curve *cur = &loop->curves[k], *next = &loop->curves[(k + 1) % n];
        double a[2], b[2];
        end_point(cur, 1, a);
        end_point(next, 0, b);
        lay->origin[out] = k;
        curves[out++] = *cur;
        if (gaps[k] > GAP_SILENT) {
            lay->origin[out] = -1 - k;
            make_line(&curves[out++], a, b);
            site->scene->repaired_gaps++;
            sc_log(SC_LOG_WARN, LOOP_FMT ": gap of %.3g of the domain size after curve %d "
                   "closed with a straight segment", LOOP_ARGS(site), gaps[k], k);
        } else if (!agree_to_rounding(a, b)) {
            /* `curves` holds the same point arrays as loop->curves. */
            double mid[2] = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])};
            set_end_point(cur, 1, mid);
            set_end_point(next, 0, mid);
        }
    }
    free(loop->curves);
    loop->curves = curves;
    loop->ncurves = out;
    free(gaps);
    return 1;
}

static int check_curves(const loop_site *site, const sc_loop *loop)
{
    if (loop->ncurves < 1) {
        sc_log(SC_LOG_WARN, LOOP_FMT " dropped: it has no curves", LOOP_ARGS(site));
        return 0;
    }
    for (int k = 0; k < loop->ncurves; k++) {
        sc_error err = {0};
        const sc_curve *c = &loop->curves[k];
        if (c->dim != 2)
            sc_fail(&err, NULL, 0, "dimension %d, not 2", c->dim);
        else
            sc_curve_check(c, &err);
        if (err.message[0]) {
            sc_log(SC_LOG_WARN, LOOP_FMT " dropped: curve %d is invalid: %s", LOOP_ARGS(site),
                   k, err.message);
            return 0;
        }
        if (c->degree > SC_TRIM_MAX_DEGREE) {
            sc_log(SC_LOG_WARN, LOOP_FMT " dropped: curve %d has degree %d; trimming handles "
                   "degrees up to %d", LOOP_ARGS(site), k, c->degree, SC_TRIM_MAX_DEGREE);
            return 0;
        }
    }
    return 1;
}

static int check_simple(const loop_site *site, const sc_loop *loop, const loop_layout *lay,
                        double size)
{
    polyline pl = {0};
    flatten_loop(loop, FLAT_TOL * size, &pl);
    if (!pl.failed)
        measure_loop(&pl);
    int a, b;
    double at[2];
    int crossing = pl.failed ? CROSSING_NO_MEMORY : find_crossing(&pl, size, &a, &b, at);
    int no_memory = crossing == CROSSING_NO_MEMORY;
    if (no_memory) {
        *site->oom = pl.failed ? pl.failed : (size_t)pl.n * 2 * sizeof(int);
    } else if (crossing == CROSSING_UNKNOWN) {
        sc_log(SC_LOG_WARN, LOOP_FMT " dropped: %d of its segments overlap so much that "
               "checking it for self-crossings would take too long (collinear repeated "
               "curves?)", LOOP_ARGS(site), pl.n);
    } else if (crossing) {
        char name_a[64], name_b[64];
        sc_log(SC_LOG_WARN, LOOP_FMT " dropped: it crosses itself (%s and %s, near u=%.6g "
               "v=%.6g)", LOOP_ARGS(site), curve_name(lay, pl.curve[a], name_a, sizeof name_a),
               curve_name(lay, pl.curve[b], name_b, sizeof name_b), at[0], at[1]);
    }
    free(pl.xy);
    free(pl.curve);
    free(pl.arc);
    free(pl.junctions);
    return no_memory ? LOOP_NO_MEMORY : !crossing;
}

static void free_loop(sc_loop *loop)
{
    for (int c = 0; c < loop->ncurves; c++)
        sc_curve_free(&loop->curves[c]);
    free(loop->curves);
    memset(loop, 0, sizeof *loop);
}

int sc_scene_validate_loops(sc_scene *scene, sc_error *err)
{
    for (int si = 0; si < scene->nsurfaces; si++) {
        sc_surface *s = &scene->surfaces[si];
        if (s->nloops == 0)
            continue;
        double u0, u1, v0, v1;
        sc_surface_domain(s, &u0, &u1, &v0, &v1);
        double size = fmax(u1 - u0, v1 - v0);
        if (!(size > 0))
            size = 1;
        int kept = 0;
        for (int li = 0; li < s->nloops; li++) {
            size_t oom = 0;
            loop_site site = {scene, si, li, &oom};
            sc_loop *loop = &s->loops[li];
            loop_layout lay = {0};
            int keep = check_curves(&site, loop);
            if (keep)
                keep = close_gaps(&site, loop, size, &lay);
            if (keep == 1)
                keep = check_simple(&site, loop, &lay, size);
            free(lay.origin);
            if (keep == LOOP_NO_MEMORY) {
                /* The loops not yet validated stay, so that the scene can
                 * be freed whole; the reader fails. */
                for (int rest = li; rest < s->nloops; rest++)
                    s->loops[kept++] = s->loops[rest];
                s->nloops = kept;
                char what[160];
                snprintf(what, sizeof what, "validating trim loop %d of surface %d (%s)", li, si,
                         s->name);
                return sc_fail_oom(err, scene->source[0] ? scene->source : NULL, 0, oom, 1,
                                   what);
            }
            if (keep) {
                s->loops[kept++] = *loop;
                continue;
            }
            /* Without its outer loop the surface is bounded by its domain;
             * its holes stay. */
            free_loop(loop);
            scene->dropped_loops++;
        }
        s->nloops = kept;
        if (kept == 0) {
            free(s->loops);
            s->loops = NULL;
        }
    }
    return SC_OK;
}
