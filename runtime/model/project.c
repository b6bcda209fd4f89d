/* project.c — model-space trim loops into a surface's parameter space
 * (sc_project_loop, analytic.h). CAD files often bound a face by 3D edges
 * only; the trimming test works in (u, v), so each edge is followed along
 * the surface: closest points by Gauss–Newton from the previous point (so
 * the parameters stay continuous across a closed surface's seam), cubic
 * Hermite pieces in (u, v) whose tangents come from the 3D tangent through
 * the surface's Jacobian, split until the surface at the fitted curve is
 * within the tolerance of the edge at every check. */
#include "analytic.h"
#include "nurbs.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum {
    MAX_DEPTH = 12,        /* 4096 pieces per curve at most */
    GRID = 24,             /* global search for a start point */
    NEWTON_STEPS = 40,
    STALLS = 3,            /* Newton steps without progress before it stops */
    MAX_SEAMS = 64         /* seam runs remembered per loop */
};

typedef struct proj {
    const sc_surface *s;
    double dom[4];         /* u0 u1 v0 v1 */
    int closed[2];
    double tol, dev;
    /* Set when a point of a curve lies farther than off_limit from the
     * surface even by the global search, or a fitted piece strays farther:
     * the loop is refused, so nothing more is sampled or refined (a hostile
     * file's off-surface curve would otherwise split every piece to
     * MAX_DEPTH, each split a global search). */
    double off_limit;
    int off;
    int oom; /* memory ran out: nothing more is refined, the loop fails */
    /* The global search's grid of surface points, evaluated once per loop:
     * an edge lying off its surface by more than the tolerance searches at
     * every sample, and the grid's evaluations were most of the reading. */
    double grid[(GRID + 1) * (GRID + 1)][3];
    int have_grid;
} proj;

typedef struct sample {
    double t, uv[2], duv[2];
    int has_duv;
} sample;

/* The surface at (u, v), wrapped into the domain along closed directions
 * (parameters run on across the seam) and clamped along the others. */
static void eval(const proj *pj, const double uv[2], double p[3], double su[3], double sv[3])
{
    double w[2];
    for (int k = 0; k < 2; k++) {
        double a = pj->dom[2 * k], b = pj->dom[2 * k + 1], x = uv[k];
        if (pj->closed[k])
            x = a + fmod(fmod(x - a, b - a) + (b - a), b - a);
        w[k] = x < a ? a : x > b ? b : x;
    }
    sc_surface_eval(pj->s, w[0], w[1], p, su, sv);
}

static double dist3(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void keep_in(const proj *pj, double uv[2])
{
    for (int k = 0; k < 2; k++)
        if (!pj->closed[k])
            uv[k] = fmin(fmax(uv[k], pj->dom[2 * k]), pj->dom[2 * k + 1]);
}

/* Solves the 2x2 normal equations J^T J x = J^T r, damped so that a
 * collapsed direction (a pole) keeps its value. Returns 0 when J has rank
 * below 2 there. */
static int solve_jt(const double su[3], const double sv[3], const double r[3], double x[2])
{
    double a = dot(su, su), b = dot(su, sv), c = dot(sv, sv);
    double g0 = dot(su, r), g1 = dot(sv, r), tr = a + c, lam = 1e-12 * tr;
    double det = (a + lam) * (c + lam) - b * b;
    if (!(tr > 0) || !(det > 0)) {
        x[0] = x[1] = 0;
        return 0;
    }
    x[0] = ((c + lam) * g0 - b * g1) / det;
    x[1] = ((a + lam) * g1 - b * g0) / det;
    return det > 1e-10 * tr * tr;
}

/* Closest point by Gauss–Newton from uv (the target lies on the surface,
 * so the residual vanishes and first derivatives suffice). Where the target
 * lies off the surface, Gauss–Newton creeps or circles instead of
 * converging: after STALLS steps that bring it no nearer it stops, at the
 * nearest point it reached. */
static double newton(const proj *pj, const double target[3], double uv[2])
{
    double p[3], su[3], sv[3], r[3], step[2], best = INFINITY, best_uv[2] = {uv[0], uv[1]};
    double size = fmax(pj->dom[1] - pj->dom[0], pj->dom[3] - pj->dom[2]);
    for (int it = 0, stalls = 0; it < NEWTON_STEPS; it++) {
        eval(pj, uv, p, su, sv);
        for (int d = 0; d < 3; d++)
            r[d] = target[d] - p[d];
        double dist = sqrt(dot(r, r));
        if (dist < best * (1 - 1e-12)) {
            stalls = 0;
        } else if (++stalls >= STALLS) {
            break;
        }
        if (dist < best) {
            best = dist;
            best_uv[0] = uv[0];
            best_uv[1] = uv[1];
        }
        solve_jt(su, sv, r, step);
        /* Damped: a step longer than a quarter of the domain is cut. */
        double len = hypot(step[0], step[1]), cap = 0.25 * size;
        if (len > cap) {
            step[0] *= cap / len;
            step[1] *= cap / len;
        }
        uv[0] += step[0];
        uv[1] += step[1];
        keep_in(pj, uv);
        if (len < 1e-14 * size)
            break;
    }
    eval(pj, uv, p, NULL, NULL);
    double dist = dist3(p, target);
    if (dist <= best)
        return dist;
    uv[0] = best_uv[0];
    uv[1] = best_uv[1];
    return best;
}

/* Best grid point, then Newton; the result taken nearest to `near` among
 * the periods of a closed direction. */
static double global(proj *pj, const double target[3], const double *near, double uv[2])
{
    double best = INFINITY;
    for (int j = 0; j <= GRID; j++)
        for (int i = 0; i <= GRID; i++) {
            double q[2] = {pj->dom[0] + (pj->dom[1] - pj->dom[0]) * i / GRID,
                           pj->dom[2] + (pj->dom[3] - pj->dom[2]) * j / GRID};
            double *p = pj->grid[j * (GRID + 1) + i];
            if (!pj->have_grid)
                eval(pj, q, p, NULL, NULL);
            double d = dist3(p, target);
            if (d < best) {
                best = d;
                uv[0] = q[0];
                uv[1] = q[1];
            }
        }
    pj->have_grid = 1;
    double d = newton(pj, target, uv);
    for (int k = 0; near && k < 2; k++)
        if (pj->closed[k]) {
            double period = pj->dom[2 * k + 1] - pj->dom[2 * k];
            uv[k] += period * round((near[k] - uv[k]) / period);
        }
    return d;
}

/* The sample at t: closest point from `guess`, and the (u, v) tangent. */
static void sample_at(proj *pj, const sc_curve *c, double t, const double guess[2], sample *out)
{
    double x[3], dx[3], p[3], su[3], sv[3];
    sc_curve_eval(c, t, x, dx);
    out->t = t;
    out->uv[0] = guess[0];
    out->uv[1] = guess[1];
    double d = newton(pj, x, out->uv);
    if (d > pj->tol) {
        double uv[2], dg = global(pj, x, guess, uv);
        if (dg < d) {
            out->uv[0] = uv[0];
            out->uv[1] = uv[1];
            d = dg;
        }
        if (d > pj->off_limit) {
            pj->off = 1;
            pj->dev = fmax(pj->dev, d);
        }
    }
    eval(pj, out->uv, p, su, sv);
    out->has_duv = solve_jt(su, sv, dx, out->duv);
}

static void hermite(const sample *a, const sample *b, double s, double uv[2])
{
    double h = b->t - a->t, h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
    double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
    for (int k = 0; k < 2; k++) {
        double chord = b->uv[k] - a->uv[k];
        double da = a->has_duv && b->has_duv ? a->duv[k] * h : chord;
        double db = a->has_duv && b->has_duv ? b->duv[k] * h : chord;
        uv[k] = h00 * a->uv[k] + h10 * da + h01 * b->uv[k] + h11 * db;
    }
}

typedef struct piece_list {
    sample *s;
    int n, cap;
} piece_list;

static void push_sample(proj *pj, piece_list *l, const sample *s)
{
    if (pj->oom)
        return;
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 32;
        sample *grown = sc_try_realloc(l->s, (size_t)cap, sizeof(sample));
        if (!grown) {
            pj->oom = 1;
            return;
        }
        l->s = grown;
        l->cap = cap;
    }
    l->s[l->n++] = *s;
}

/* How far the surface at the fitted piece a..b strays from the curve, at
 * three checks: *total the distance itself (what the loop is off by), the
 * return value that part of it which refinement can remove (the distance
 * less the curve's own distance from the surface there, for edges that
 * a file gives slightly off their surface). */
static double piece_dev(proj *pj, const sc_curve *c, const sample *a, const sample *b,
                        double *total)
{
    double worst = 0;
    *total = 0;
    for (int k = 1; k <= 3; k++) {
        double s = 0.25 * k, uv[2], x[3], p[3], near[2];
        hermite(a, b, s, uv);
        sc_curve_eval(c, a->t + s * (b->t - a->t), x, NULL);
        eval(pj, uv, p, NULL, NULL);
        double d = dist3(p, x);
        near[0] = uv[0];
        near[1] = uv[1];
        double off = newton(pj, x, near);
        *total = fmax(*total, d);
        worst = fmax(worst, d - off);
    }
    return worst;
}

/* Appends the samples after a up to b, splitting until within tolerance. */
static void refine(proj *pj, const sc_curve *c, const sample *a, const sample *b, int depth,
                   piece_list *out)
{
    double total, dev = piece_dev(pj, c, a, b, &total);
    if (dev > pj->tol && depth < MAX_DEPTH && !pj->off && !pj->oom) {
        sample m;
        double guess[2];
        hermite(a, b, 0.5, guess);
        sample_at(pj, c, 0.5 * (a->t + b->t), guess, &m);
        refine(pj, c, a, &m, depth + 1, out);
        refine(pj, c, &m, b, depth + 1, out);
        return;
    }
    pj->dev = fmax(pj->dev, total);
    /* Past the limit the loop is refused: nothing more is worth refining. */
    if (pj->dev > pj->off_limit)
        pj->off = 1;
    push_sample(pj, out, b);
}

/* The fitted pieces as one cubic curve on the 3D curve's parameter: knots
 * of multiplicity 3 at the piece ends. */
static int to_curve(const piece_list *l, sc_curve *out)
{
    int pieces = l->n - 1;
    if (sc_curve_try_alloc(out, 2, 3, 3 * pieces + 1))
        return SC_FAIL;
    for (int i = 0; i < 4; i++) {
        out->knots[i] = l->s[0].t;
        out->knots[3 * pieces + 1 + i] = l->s[pieces].t;
    }
    for (int i = 1; i < pieces; i++)
        for (int k = 0; k < 3; k++)
            out->knots[3 * i + 1 + k] = l->s[i].t;
    for (int i = 0; i < pieces; i++) {
        const sample *a = &l->s[i], *b = &l->s[i + 1];
        double q[4][2];
        for (int k = 0; k < 2; k++) {
            double h = b->t - a->t, chord = b->uv[k] - a->uv[k];
            double da = a->has_duv && b->has_duv ? a->duv[k] * h : chord;
            double db = a->has_duv && b->has_duv ? b->duv[k] * h : chord;
            q[0][k] = a->uv[k];
            q[1][k] = a->uv[k] + da / 3;
            q[2][k] = b->uv[k] - db / 3;
            q[3][k] = b->uv[k];
        }
        for (int j = 0; j < 4; j++) {
            double *cp = out->cp + 3 * (3 * i + j);
            cp[0] = q[j][0];
            cp[1] = q[j][1];
            cp[2] = 1;
        }
    }
    return SC_OK;
}

static int line2(const double a[2], const double b[2], sc_curve *out)
{
    if (sc_curve_try_alloc(out, 2, 1, 2))
        return SC_FAIL;
    out->knots[0] = out->knots[1] = 0;
    out->knots[2] = out->knots[3] = 1;
    double cp[6] = {a[0], a[1], 1, b[0], b[1], 1};
    memcpy(out->cp, cp, sizeof cp);
    return SC_OK;
}

/* Whether the surface collapses along direction k at uv: a pole, where
 * the whole line of uv[k] values is one point. */
static int collapsed(const proj *pj, const double uv[2], int k)
{
    double p[3], q[3], w[2] = {uv[0], uv[1]};
    eval(pj, uv, p, NULL, NULL);
    for (int j = 1; j <= 3; j += 2) {
        w[k] = pj->dom[2 * k] + (pj->dom[2 * k + 1] - pj->dom[2 * k]) * 0.25 * j;
        eval(pj, w, q, NULL, NULL);
        if (dist3(p, q) > pj->tol)
            return 0;
    }
    return 1;
}

/* A curve that starts or ends at a pole has there any value of the
 * collapsed parameter: Newton keeps its guess (the previous curve's, or
 * the grid's), and the curve's first piece would cross the domain
 * diagonally to where the curve leaves the pole. The end takes the value
 * the curve has just off the pole (at t_in), so that a meridian stays one
 * line (on its seam, where it is one) and the move along the pole becomes
 * a segment of its own between curves. */
static void off_pole(proj *pj, const sc_curve *c, sample *s, double t_in)
{
    for (int k = 0; k < 2; k++) {
        if (!collapsed(pj, s->uv, k))
            continue;
        /* From the pole itself Newton may not move (the collapsed value
         * decides which way is off the pole, and the domain's end stops
         * it): start at several values. */
        double x[3], best = INFINITY, at = s->uv[k];
        sc_curve_eval(c, t_in, x, NULL);
        for (int j = 0; j < 8; j++) {
            double uv[2] = {s->uv[0], s->uv[1]};
            uv[k] = pj->dom[2 * k] + (pj->dom[2 * k + 1] - pj->dom[2 * k]) * (j + 0.5) / 8;
            double d = newton(pj, x, uv);
            if (d < best && !collapsed(pj, uv, k)) {
                best = d;
                at = uv[k];
            }
        }
        if (best <= pj->tol) {
            /* the period nearest the value it had */
            if (pj->closed[k]) {
                double period = pj->dom[2 * k + 1] - pj->dom[2 * k];
                at += period * round((s->uv[k] - at) / period);
            }
            s->uv[k] = at;
        }
    }
}

/* The samples of curve c from `start` (its first point's parameters) on. */
static void follow(proj *pj, const sc_curve *c, const double start[2], piece_list *l)
{
    double t0, t1;
    sc_curve_domain(c, &t0, &t1);
    /* At least 8 first pieces, more for a curve of many spans, so that
     * each Newton start lies near its target. */
    int steps = 8;
    for (int k = c->degree + 1; k < c->ncp; k++)
        steps += c->knots[k] > c->knots[k - 1];
    steps = steps > 64 ? 64 : steps;
    const double in = 1e-3 * (t1 - t0);
    sample a;
    sample_at(pj, c, t0, start, &a);
    off_pole(pj, c, &a, t0 + in);
    push_sample(pj, l, &a);
    for (int k = 1; k <= steps && !pj->oom && !pj->off; k++) {
        sample b, last = l->s[l->n - 1];
        sample_at(pj, c, t0 + (t1 - t0) * k / steps, last.uv, &b);
        if (k == steps)
            off_pole(pj, c, &b, t1 - in);
        refine(pj, c, &last, &b, 0, l);
    }
}

static int closed_curve(const sc_curve *c, double tol)
{
    double t0, t1, a[3], b[3];
    sc_curve_domain(c, &t0, &t1);
    sc_curve_eval(c, t0, a, NULL);
    sc_curve_eval(c, t1, b, NULL);
    return dist3(a, b) <= tol;
}

/* A loop runs along a closed surface's seam twice (a sphere bounded by
 * its seam edge, there and back): the two runs lie on the two sides, one
 * period apart, or the loop would enclose nothing. A curve whose samples
 * all lie on a stretch of seam already used by an earlier curve of the
 * loop is moved to the other side. Runs along different stretches of the
 * seam line (a face crossing the seam, touching it above and below) are
 * not the same edge and stay where they are. Each remembered run: the
 * direction, the seam's value, the range of the other parameter. */
static void seam_side(const proj *pj, piece_list *l, double *seams, int *nseams)
{
    for (int k = 0; k < 2; k++) {
        if (!pj->closed[k])
            continue;
        double a = pj->dom[2 * k], period = pj->dom[2 * k + 1] - a, eps = 1e-9 * period;
        double x = l->s[0].uv[k], m = round((x - a) / period);
        if (fabs(x - (a + m * period)) > eps)
            continue;
        int along = 1;
        double lo = l->s[0].uv[1 - k], hi = lo;
        for (int i = 1; i < l->n && along; i++) {
            along = fabs(l->s[i].uv[k] - x) <= eps;
            lo = fmin(lo, l->s[i].uv[1 - k]);
            hi = fmax(hi, l->s[i].uv[1 - k]);
        }
        if (!along)
            continue;
        double span = pj->dom[3 - 2 * k] - pj->dom[2 - 2 * k], overlap = 1e-6 * span;
        int seen = 0;
        for (int i = 0; i < *nseams; i++) {
            const double *r = seams + 4 * i;
            seen |= r[0] == k && fabs(r[1] - x) <= eps &&
                    fmin(hi, r[3]) - fmax(lo, r[2]) > overlap;
        }
        if (seen) {
            double shift = x - a < 0.5 * period ? period : -period;
            for (int i = 0; i < l->n; i++)
                l->s[i].uv[k] += shift;
            x += shift;
        }
        if (*nseams < MAX_SEAMS) {
            double *r = seams + 4 * *nseams;
            r[0] = k;
            r[1] = x;
            r[2] = lo;
            r[3] = hi;
            ++*nseams;
        }
    }
}

int sc_project_loop(const sc_surface *s, const sc_curve *curves, int n, double tol,
                    double off_limit, sc_curve **out, int *nout, double *dev)
{
    proj pj = {.s = s, .tol = tol, .off_limit = off_limit};
    sc_surface_domain(s, &pj.dom[0], &pj.dom[1], &pj.dom[2], &pj.dom[3]);
    pj.closed[0] = sc_surface_closed(s, 0);
    pj.closed[1] = sc_surface_closed(s, 1);
    double size = fmax(pj.dom[1] - pj.dom[0], pj.dom[3] - pj.dom[2]);
    *nout = 0;
    *dev = 0;
    *out = sc_try_alloc((size_t)2 * n + 1, sizeof(sc_curve));
    if (!*out)
        return SC_FAIL;
    double prev[2] = {0, 0}, first[2] = {0, 0}, seams[4 * MAX_SEAMS];
    int status = SC_OK, nseams = 0;
    for (int i = 0; i < n && status == SC_OK; i++) {
        const sc_curve *c = &curves[i];
        piece_list l = {0};
        if (i == 0) {
            double t0, t1, x0[3];
            sc_curve_domain(c, &t0, &t1);
            sc_curve_eval(c, t0, x0, NULL);
            global(&pj, x0, NULL, first);
            memcpy(prev, first, sizeof prev);
        }
        follow(&pj, c, prev, &l);
        if (i > 0 && closed_curve(c, tol) && !pj.oom) {
            /* A closed edge (a whole circle) says nothing by its ends about
             * its direction, and written either way it runs on across the
             * seam to a different end: the direction that leads back
             * towards the loop's start is the loop's. */
            sc_curve rev;
            piece_list lr = {0};
            if (sc_curve_try_copy(&rev, c)) {
                pj.oom = 1;
            } else {
                sc_curve_reverse(&rev);
                follow(&pj, &rev, prev, &lr);
                sc_curve_free(&rev);
            }
            if (!pj.oom) {
                const double *e = l.s[l.n - 1].uv, *er = lr.s[lr.n - 1].uv;
                if (hypot(er[0] - first[0], er[1] - first[1]) <
                    hypot(e[0] - first[0], e[1] - first[1])) {
                    free(l.s);
                    l = lr;
                    lr.s = NULL;
                }
            }
            free(lr.s);
        }
        if (pj.oom) {
            free(l.s);
            status = SC_FAIL;
            break;
        }
        seam_side(&pj, &l, seams, &nseams);
        const double *a = l.s[0].uv;
        /* Newton ends within 1e-7 of the domain of where the last curve
         * ended: the same point, made exactly so. */
        if (i > 0 && hypot(a[0] - prev[0], a[1] - prev[1]) > 1e-7 * size)
            status = line2(prev, a, &(*out)[(*nout)++]);
        else if (i > 0)
            memcpy(l.s[0].uv, prev, sizeof prev);
        if (i == n - 1 && hypot(first[0] - l.s[l.n - 1].uv[0], first[1] - l.s[l.n - 1].uv[1]) <=
                              1e-7 * size)
            memcpy(l.s[l.n - 1].uv, first, sizeof first);
        if (i == 0)
            memcpy(first, l.s[0].uv, sizeof first);
        if (status == SC_OK)
            status = to_curve(&l, &(*out)[(*nout)++]);
        prev[0] = l.s[l.n - 1].uv[0];
        prev[1] = l.s[l.n - 1].uv[1];
        free(l.s);
        if (status == SC_OK && pj.off)
            status = SC_PROJECT_OFF;
    }
    if (status == SC_OK && n > 0 && hypot(first[0] - prev[0], first[1] - prev[1]) > 1e-7 * size)
        status = line2(prev, first, &(*out)[(*nout)++]);
    *dev = pj.dev;
    if (status != SC_OK) {
        /* a curve that failed to allocate is zeroed: freeing it is harmless */
        for (int i = 0; i < *nout; i++)
            sc_curve_free(&(*out)[i]);
        free(*out);
        *out = NULL;
        *nout = 0;
    }
    return status;
}
