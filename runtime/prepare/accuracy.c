/* accuracy.c — per-surface settings from an accuracy target (accuracy.h).
 *
 * The bound, per surface (docs/accuracy.md has the derivation):
 * - the program accepts a point only when it lies within tol footprints of
 *   the ray (its verdict, gen/intersect.c), so tol = the position target
 *   bounds every accepted point; a normal target δ (radians) asks in
 *   addition that tol · footprint / R ≤ δ, the normal turning by 1/R per
 *   unit of length on a surface whose radius of curvature is R;
 * - Newton from the hull's start converges quadratically: from a start
 *   h (the hull flatness) off the surface, e_k ≈ R (h/R)^(2^k), and the
 *   iteration stops on a step below SCG_STOP_FRACTION · tol · footprint,
 *   that step taken (one more); so k iterations suffice where
 *   R (h/R)^(2^k) ≤ 0.3 tol fp;
 * - the hulls are the defaults', made finer only where their start would
 *   need more than NEWTON_STEPS iterations or lie more than RHO_MAX · R
 *   off (outside the quadratic model); the iteration cap is then the
 *   bound's count from the hull's start, plus the converged step and a
 *   margin.
 * The footprint is taken at the surface's nearest distance to the eye (its
 * control points' box), the smallest it has in the view; R comes from the
 * flatness of the control net (patch_radius). */
#include "accuracy.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "bezier.h"
#include "hulls.h"
#include "intersect.h"

/* The largest start error, as a fraction of the radius: the quadratic
 * model e' = e²/R shrinks the error only while e < R. */
#define RHO_MAX 1.0
/* Newton iterations a hull may need from its start: with the converged
 * step and the margin, the defaults' 6 (SCG_DEFAULT_ITERS), so that a
 * target never runs more iterations than the defaults. */
#define NEWTON_STEPS 4
/* Iterations beyond the bound's count: the start's error and the
 * convergence constant are estimates. */
#define ITER_MARGIN 1
/* The coarsest hulls a target chooses, as a fraction of the scene's size:
 * the defaults' (hulls.h). Coarser hulls, down to those from which Newton
 * lands in 2 iterations, cost 0.79-0.88 of the defaults' frame on the
 * teapot but 1.03-1.16 on the teaspoon and up to 1.21 on gpucast_part.igs
 * (docs/accuracy.md, "Coarser hulls"): fewer hulls, but larger ones, whose
 * extra pixels and iterations cost more than the hulls saved. */
#define HULL_CEILING SC_HULL_DEFAULT_TOLERANCE

const char *sc_accuracy_check(double px, double normal_deg)
{
    if (!(px >= SC_ACCURACY_MIN_PX && px <= SC_ACCURACY_MAX_PX))
        return "the position bound takes 0.001 to 100 pixel footprints";
    if (!(normal_deg >= 0 && normal_deg <= SC_ACCURACY_MAX_DEG))
        return "the normal bound takes 0 (none) to 90 degrees";
    return NULL;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void net_point(const sc_bezier_patch *p, int i, int j, double out[3])
{
    const double *h = p->cp + 4 * (j * (p->deg_u + 1) + i);
    for (int c = 0; c < 3; c++)
        out[c] = h[c] / h[3];
}

/* The radius of the arc through the ends of one row (or column) of the
 * control net that sags as far as the row's farthest point from its chord:
 * L² / (8·sag) + sag / 2. The net sags at least as far as the surface, so this is no
 * more than the surface's radius along that row. *len gets L. HUGE_VAL for
 * a straight row or one collapsed to a point. */
static double row_radius(const sc_bezier_patch *p, int dir, int line, double *len,
                         double *sagged)
{
    int n = dir == 0 ? p->deg_u : p->deg_v;
    double a[3], b[3], chord[3];
    net_point(p, dir == 0 ? 0 : line, dir == 0 ? line : 0, a);
    net_point(p, dir == 0 ? n : line, dir == 0 ? line : n, b);
    for (int c = 0; c < 3; c++)
        chord[c] = b[c] - a[c];
    double l = sqrt(dot3(chord, chord)), sag = 0;
    *len = l;
    for (int k = 1; k < n; k++) {
        double q[3], d[3];
        net_point(p, dir == 0 ? k : line, dir == 0 ? line : k, q);
        for (int c = 0; c < 3; c++)
            d[c] = q[c] - a[c];
        double along = l > 0 ? dot3(d, chord) / l : 0;
        sag = fmax(sag, sqrt(fmax(0, dot3(d, d) - along * along)));
    }
    *sagged = sag;
    if (!(sag > 0) || !(l > 0))
        return HUGE_VAL;
    return l * l / (8 * sag) + sag / 2;
}

/* The smallest radius over the rows and columns of the patch's net (and
 * in *flatness the largest sag of any row, at least as far as the patch
 * is from flat),
 * leaving out rows shorter than ROW_SHORT of the longest in their
 * direction: near a pole (the teapot's lid and bottom) the rows shrink to
 * small circles about it whose bend lies in the tangent plane, not across
 * the surface. */
#define ROW_SHORT 0.25
static double patch_radius(const sc_bezier_patch *p, double *flatness)
{
    double r = HUGE_VAL;
    for (int dir = 0; dir < 2; dir++) {
        int lines = dir == 0 ? p->deg_v + 1 : p->deg_u + 1;
        double radius[17], len[17], longest = 0;
        for (int k = 0; k < lines; k++) {
            double sag;
            radius[k] = row_radius(p, dir, k, &len[k], &sag);
            longest = fmax(longest, len[k]);
            *flatness = fmax(*flatness, sag);
        }
        for (int k = 0; k < lines; k++)
            if (len[k] >= ROW_SHORT * longest)
                r = fmin(r, radius[k]);
    }
    return r;
}

/* Distance from p to the box [lo, hi] (0 inside). */
static double box_distance(const double lo[3], const double hi[3], const double p[3])
{
    double d2 = 0;
    for (int c = 0; c < 3; c++) {
        double d = p[c] < lo[c] ? lo[c] - p[c] : p[c] > hi[c] ? p[c] - hi[c] : 0;
        d2 += d * d;
    }
    return sqrt(d2);
}

/* Fewest Newton iterations k with R ρ^(2^k) ≤ stop (the bound's count). */
static int newton_iterations(double radius, double rho, double stop)
{
    double e = isinf(radius) ? 0 : radius * rho;
    int k = 0;
    while (e > stop * (1 + 1e-9) && k < SC_MAX_ITERS) {
        e = e * e / radius;
        k++;
    }
    return k;
}

void sc_accuracy_choose(const sc_scene *scene, const sc_patch_list *patches,
                        const sc_accuracy_target *target, sc_method method,
                        sc_accuracy_choice *out)
{
    double slo[3], shi[3];
    double diag = 0;
    if (sc_scene_bounds(scene, slo, shi))
        diag = sqrt((shi[0] - slo[0]) * (shi[0] - slo[0]) + (shi[1] - slo[1]) * (shi[1] - slo[1]) +
                    (shi[2] - slo[2]) * (shi[2] - slo[2]));
    if (!(diag > 0))
        diag = 1;
    sc_method m = method == SC_METHOD_DEFAULT ? SC_DEFAULT_METHOD : method;
    int newton_like = m == SC_METHOD_NEWTON || m == SC_METHOD_BROYDEN || m == SC_METHOD_HYBRID;
    for (int s = 0; s < scene->nsurfaces; s++) {
        const sc_patch_list *list = &patches[s];
        double lo[3] = {DBL_MAX, DBL_MAX, DBL_MAX}, hi[3] = {-DBL_MAX, -DBL_MAX, -DBL_MAX};
        double radius = HUGE_VAL, flatness = 0;
        for (int p = 0; p < list->count; p++) {
            const sc_bezier_patch *bp = &list->patches[p];
            int n = (bp->deg_u + 1) * (bp->deg_v + 1);
            for (int k = 0; k < n; k++)
                for (int c = 0; c < 3; c++) {
                    double x = bp->cp[4 * k + c] / bp->cp[4 * k + 3];
                    lo[c] = fmin(lo[c], x);
                    hi[c] = fmax(hi[c], x);
                }
            radius = fmin(radius, patch_radius(bp, &flatness));
        }
        /* Nearest distance to the eye; an eye inside the box sees the
         * surface from as near as a thousandth of the scene. */
        double nearest = list->count ? box_distance(lo, hi, target->view.eye) : diag;
        nearest = fmax(nearest, 1e-3 * diag);
        double fp = sc_camera_footprint(&target->view, nearest);
        double tol = target->px;
        if (target->normal_deg > 0 && !isinf(radius))
            tol = fmin(tol, target->normal_deg * M_PI / 180 * radius / fp);
        tol = fmax(tol, SC_ACCURACY_MIN_PX);
        double stop = SCG_STOP_FRACTION * tol * fp;
        /* The hulls: the defaults', finer only where a start that far off
         * would need more than NEWTON_STEPS iterations (R ρ^(2^k) ≤ stop)
         * or lie outside Newton's basin. */
        double h = HULL_CEILING * diag;
        if (!isinf(radius)) {
            h = fmin(h, RHO_MAX * radius);
            h = fmin(h, radius * pow(stop / radius, 1.0 / (1 << NEWTON_STEPS)));
        }
        sc_accuracy_choice *c = &out[s];
        c->hull_tolerance = h / diag;
        c->tol_milli = (int)fmin(1e6, floor(tol * 1000 + 1e-9));
        if (c->tol_milli < 1)
            c->tol_milli = 1;
        c->max_iters = 0;
        if (newton_like) {
            /* A start is no farther from the surface than its hull allows,
             * nor than the patch's net is from flat. */
            double start = fmin(h, flatness);
            int k = newton_iterations(radius, isinf(radius) ? 0 : start / radius, stop);
            c->max_iters = k + 1 + ITER_MARGIN;  /* + the converged step */
            if (c->max_iters > SC_MAX_ITERS)
                c->max_iters = SC_MAX_ITERS;
        }
        c->footprint = fp;
        c->radius = radius;
    }
}
