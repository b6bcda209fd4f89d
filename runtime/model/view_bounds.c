/* view_bounds.c — the box the default camera frames (camera.h): what a
 * scene shows, not where its control points lie. A trimmed face of a CAD
 * part keeps a small piece of a large underlying surface, whose control
 * points would frame the face small and off-centre; so trimmed surfaces
 * contribute points of their kept region (a grid over the domain and points
 * along the trim curves), untrimmed ones their control points as before. */
#include <stdlib.h>

#include "camera.h"
#include "nurbs.h"
#include "trim.h"

/* Samples per direction of the grid, and along each trim curve: enough to
 * frame a face within a fraction of a percent of its size. */
enum { GRID = 64, CURVE_SAMPLES = 32 };

static void grow(double lo[3], double hi[3], const double p[3], int *any)
{
    for (int d = 0; d < 3; d++) {
        if (!*any || p[d] < lo[d]) lo[d] = p[d];
        if (!*any || p[d] > hi[d]) hi[d] = p[d];
    }
    *any = 1;
}

/* The kept region's bounds of a trimmed surface; 0 when no sample is kept
 * or its loops cannot be prepared (the caller falls back to the control
 * points). */
static int trimmed_bounds(const sc_surface *s, double lo[3], double hi[3])
{
    sc_trim *trim = NULL;
    if (sc_trim_prepare(s, &trim, NULL) != SC_OK || !trim)
        return 0;
    double u0, u1, v0, v1, p[3];
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    int any = 0;
    for (int j = 0; j <= GRID; j++)
        for (int i = 0; i <= GRID; i++) {
            double u = u0 + (u1 - u0) * i / GRID, v = v0 + (v1 - v0) * j / GRID;
            if (!sc_trim_inside(trim, u, v))
                continue;
            sc_surface_eval_world(s, u, v, p, NULL, NULL);
            grow(lo, hi, p, &any);
        }
    for (int l = 0; l < s->nloops; l++)
        for (int c = 0; c < s->loops[l].ncurves; c++) {
            const sc_curve *curve = &s->loops[l].curves[c];
            double t0, t1, uv[2];
            sc_curve_domain(curve, &t0, &t1);
            for (int k = 0; k <= CURVE_SAMPLES; k++) {
                sc_curve_eval(curve, t0 + (t1 - t0) * k / CURVE_SAMPLES, uv, NULL);
                double u = uv[0] < u0 ? u0 : uv[0] > u1 ? u1 : uv[0];
                double v = uv[1] < v0 ? v0 : uv[1] > v1 ? v1 : uv[1];
                sc_surface_eval_world(s, u, v, p, NULL, NULL);
                grow(lo, hi, p, &any);
            }
        }
    sc_trim_free(trim);
    return any;
}

int sc_scene_view_bounds(const sc_scene *scene, double lo[3], double hi[3])
{
    int any = 0;
    for (int i = 0; i < scene->nsurfaces; i++) {
        const sc_surface *s = &scene->surfaces[i];
        double l[3], h[3];
        if (!(s->nloops > 0 && trimmed_bounds(s, l, h)))
            sc_surface_bounds(s, l, h);
        grow(lo, hi, l, &any);
        grow(lo, hi, h, &any);
    }
    if (!any)
        for (int d = 0; d < 3; d++)
            lo[d] = hi[d] = 0;
    return any;
}
