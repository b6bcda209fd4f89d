/* test_project_seam.c — model-space loops projected onto a closed
 * surface whose seam and poles they follow (runtime/model/project.c):
 * a sphere with a window cut across its seam, bounded by one loop that
 * runs down the seam above the window and below it, around the window on
 * both sides and over both poles. Validation must keep the loop, and the
 * trimming must keep the sphere and cut the window. */
#include <math.h>
#include <stdlib.h>

#include "analytic.h"
#include "nurbs.h"
#include "test.h"
#include "trim.h"

enum { R = 2 };

/* The arc of the circle about (0, 0, cz) of radius r, or of a meridian,
 * from angle a to b (either order): sc_ellipse_arc wants a < b. */
static void arc(const double c[3], const double x[3], const double y[3], double r, double a,
                double b, sc_curve *out)
{
    sc_ellipse_arc(3, c, x, y, r, r, fmin(a, b), fmax(a, b), out);
    if (a > b)
        sc_curve_reverse(out);
}

static void meridian(double lon, double lat0, double lat1, sc_curve *out)
{
    double o[3] = {0, 0, 0}, x[3] = {cos(lon), sin(lon), 0}, z[3] = {0, 0, 1};
    arc(o, x, z, R, lat0, lat1, out);
}

static void parallel(double lat, double lon0, double lon1, sc_curve *out)
{
    double c[3] = {0, 0, R * sin(lat)}, x[3] = {1, 0, 0}, y[3] = {0, 1, 0};
    arc(c, x, y, R * cos(lat), lon0, lon1, out);
}

TEST(project_sphere_window_across_seam)
{
    const double lo = -0.3, hi = 0.4, w = 0.5, pole = M_PI / 2;
    double o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, z[3] = {0, 0, 1};
    sc_curve gen, c[10];
    sc_ellipse_arc(3, o, x, z, R, R, -pole, pole, &gen);
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = sc_scene_add_surface(&scene);
    sc_revolve(&gen, o, z, 0, 2 * M_PI, s); /* the seam at longitude 0 (+x) */
    sc_curve_free(&gen);
    meridian(0, pole, hi, &c[0]);   /* the seam above the window, down */
    parallel(hi, 0, w, &c[1]);
    meridian(w, hi, lo, &c[2]);
    parallel(lo, w, 0, &c[3]);
    meridian(0, lo, -pole, &c[4]);  /* the seam below the window, down */
    meridian(0, -pole, lo, &c[5]);  /* and up again, on the other side */
    parallel(lo, 0, -w, &c[6]);
    meridian(-w, lo, hi, &c[7]);
    parallel(hi, -w, 0, &c[8]);
    meridian(0, hi, pole, &c[9]);   /* the seam above, up */
    sc_curve *out;
    int nout;
    double dev;
    CHECK_INT(sc_project_loop(s, c, 10, 1e-6 * 4 * R, 1e-3 * 4 * R, &out, &nout, &dev), SC_OK);
    CHECK(dev < 1e-5);
    for (int i = 0; i < 10; i++)
        sc_curve_free(&c[i]);
    s->nloops = 1;
    s->loops = sc_alloc(1, sizeof(sc_loop));
    s->loops[0].curves = out;
    s->loops[0].ncurves = nout;
    sc_surface_unwrap_seams(s);
    CHECK_INT(sc_scene_validate_loops(&scene, NULL), SC_OK);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(s->nloops, 1);
    sc_trim *trim = NULL;
    sc_error err;
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    int kept = 0, cut = 0;
    for (int j = 0; j < 40; j++)
        for (int i = 0; i < 40; i++) {
            double u = u0 + (u1 - u0) * (i + 0.5) / 40, v = v0 + (v1 - v0) * (j + 0.5) / 40, p[3];
            sc_surface_eval(s, u, v, p, NULL, NULL);
            double lat = asin(fmax(-1, fmin(1, p[2] / R))), lon = atan2(p[1], p[0]);
            double margin = fmin(fmin(fabs(lat - lo), fabs(lat - hi)), fabs(fabs(lon) - w));
            if (margin < 0.02)
                continue;
            int in_window = lat > lo && lat < hi && fabs(lon) < w;
            CHECK_INT(sc_trim_inside(trim, u, v), !in_window);
            kept += !in_window;
            cut += in_window;
        }
    CHECK(kept > 0 && cut > 0);
    sc_trim_free(trim);
    sc_scene_free(&scene);
}
