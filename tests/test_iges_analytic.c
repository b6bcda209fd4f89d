/* test_iges_analytic.c — the exact NURBS forms of analytic curves and
 * surfaces (runtime/model/analytic.c), checked point by point against
 * their analytic definitions, and the IGES entities converted with them
 * (108/190–198, 118, 120, 122, 104 in trims, 308/408 instances), in small
 * files written by the tests; loops given only in model space, projected
 * onto a cylinder; a file with nothing to draw refused by `render`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "analytic.h"
#include "iges_files.h"
#include "test.h"
#include "trim.h"

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Distance of p from the line through o along the unit vector a, and
 * its height along a. */
static double axis_distance(const double p[3], const double o[3], const double a[3], double *h)
{
    double rel[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
    *h = dot3(rel, a);
    double r[3] = {rel[0] - *h * a[0], rel[1] - *h * a[1], rel[2] - *h * a[2]};
    return sqrt(dot3(r, r));
}

/* A grid of n x n points over the surface's domain, each given to `check`,
 * which returns how far it is from the analytic surface. The largest. */
static double worst_over(const sc_surface *s, int n,
                         double (*check)(const double p[3], const void *), const void *data)
{
    double u0, u1, v0, v1, worst = 0;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double p[3];
            sc_surface_eval(s, u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * j / n, p, NULL, NULL);
            worst = fmax(worst, check(p, data));
        }
    return worst;
}

typedef struct quadric {
    double o[3], a[3];
    double r, slope, major; /* cylinder, cone: radius at o and its change; torus: major */
    int kind;               /* 0 cylinder/cone, 1 sphere, 2 torus */
} quadric;

static double off_quadric(const double p[3], const void *data)
{
    const quadric *q = data;
    double h, d = axis_distance(p, q->o, q->a, &h);
    switch (q->kind) {
    case 0: return fabs(d - (q->r + q->slope * h));
    case 1: return fabs(sqrt(d * d + h * h) - q->r);
    default: return fabs(sqrt((d - q->major) * (d - q->major) + h * h) - q->r);
    }
}

TEST(analytic_ellipse_arc_exact)
{
    double c[3] = {1, 2, 3}, s2 = sqrt(0.5);
    double x[3] = {s2, s2, 0}, y[3] = {0, 0, 1}, n[3] = {s2, -s2, 0};
    sc_curve arc;
    sc_ellipse_arc(3, c, x, y, 3, 1.5, 0.3, 5.5, &arc);
    CHECK_INT(arc.degree, 2);
    double t0, t1;
    sc_curve_domain(&arc, &t0, &t1);
    for (int i = 0; i <= 200; i++) {
        double p[3], rel[3];
        sc_curve_eval(&arc, t0 + (t1 - t0) * i / 200, p, NULL);
        for (int d = 0; d < 3; d++)
            rel[d] = p[d] - c[d];
        double ex = dot3(rel, x) / 3, ey = dot3(rel, y) / 1.5;
        CHECK_NEAR(ex * ex + ey * ey, 1, 1e-14);
        CHECK_NEAR(dot3(rel, n), 0, 1e-14);
    }
    /* The ends are where the angles say. */
    double p[3];
    sc_curve_eval(&arc, t1, p, NULL);
    for (int d = 0; d < 3; d++)
        CHECK_NEAR(p[d], c[d] + 3 * cos(5.5) * x[d] + 1.5 * sin(5.5) * y[d], 1e-14);
    sc_curve_free(&arc);
}

TEST(analytic_revolutions_exact)
{
    /* A cylinder and a cone (revolved lines), a sphere (a half circle) and
     * a torus (a circle), about a tilted axis; every point on the quadric. */
    double o[3] = {0.5, -1, 2}, a[3] = {0, 0.6, 0.8}, x[3] = {1, 0, 0};
    double y[3] = {0, 0.8, -0.6};
    for (int kind = 0; kind < 4; kind++) {
        sc_curve gen;
        quadric q = {{o[0], o[1], o[2]}, {a[0], a[1], a[2]}, 2, 0, 0, kind < 2 ? 0 : kind - 1};
        if (kind < 2) {
            q.slope = kind == 1 ? 0.5 : 0;
            double p0[3], p1[3];
            for (int d = 0; d < 3; d++) {
                p0[d] = o[d] - 1 * a[d] + (2 - q.slope) * x[d];
                p1[d] = o[d] + 3 * a[d] + (2 + 3 * q.slope) * x[d];
            }
            sc_line3(p0, p1, &gen);
        } else if (kind == 2) {
            sc_ellipse_arc(3, o, x, a, 2, 2, -M_PI / 2, M_PI / 2, &gen);
        } else {
            double c[3];
            q.major = 5;
            for (int d = 0; d < 3; d++)
                c[d] = o[d] + 5 * x[d];
            sc_ellipse_arc(3, c, x, a, 2, 2, 0, 2 * M_PI, &gen);
        }
        sc_surface s;
        sc_revolve(&gen, o, a, 0.25, 0.25 + (kind == 1 ? 2.5 : 2 * M_PI), &s);
        CHECK_INT(s.rational, 1);
        CHECK(worst_over(&s, 40, off_quadric, &q) < 1e-13 * 8);
        /* The start of the turn is the generatrix turned by 0.25 rad. */
        double t0, t1, g[3], p[3], u0, u1, v0, v1;
        sc_curve_domain(&gen, &t0, &t1);
        sc_surface_domain(&s, &u0, &u1, &v0, &v1);
        sc_curve_eval(&gen, t0, g, NULL);
        sc_surface_eval(&s, u0, v0, p, NULL, NULL);
        double hg, hp, dg = axis_distance(g, o, a, &hg), dp = axis_distance(p, o, a, &hp);
        CHECK_NEAR(dp, dg, 1e-13);
        CHECK_NEAR(hp, hg, 1e-13);
        double rel[3] = {p[0] - o[0] - hp * a[0], p[1] - o[1] - hp * a[1], p[2] - o[2] - hp * a[2]};
        if (dg > 1e-9) { /* not a pole on the axis */
            CHECK_NEAR(dot3(rel, x) / dp, cos(0.25), 1e-13);
            CHECK_NEAR(dot3(rel, y) / dp, sin(0.25), 1e-13);
        }
        CHECK_INT(sc_surface_closed(&s, 1), kind != 1);
        sc_surface_free(&s);
        sc_curve_free(&gen);
    }
}

/* A cubic B-spline with an interior knot, polynomial. */
static void test_cubic(sc_curve *c, double t0, double t1)
{
    static const double pts[5][3] = {{0, 0, 0}, {1, 2, 0}, {2, -1, 1}, {3, 0, 0}, {4, 1, -1}};
    sc_curve_alloc(c, 3, 3, 5);
    double k[9] = {0, 0, 0, 0, 0.4, 1, 1, 1, 1};
    for (int i = 0; i < 9; i++)
        c->knots[i] = t0 + (t1 - t0) * k[i];
    for (int i = 0; i < 5; i++) {
        memcpy(c->cp + 4 * i, pts[i], sizeof pts[i]);
        c->cp[4 * i + 3] = 1;
    }
}

TEST(analytic_extrusion_ruled_join_exact)
{
    sc_curve c, line, joined;
    test_cubic(&c, 2, 5);
    double d[3] = {1, 1, 5}, p0[3] = {0, 0, 0}, p1[3] = {4, 0, 0};
    sc_surface ext, ruled;
    sc_extrude(&c, d, &ext);
    sc_line3(p0, p1, &line);
    sc_ruled(&line, &c, &ruled);
    CHECK_INT(ruled.deg_u, 3);
    double u0, u1, v0, v1;
    sc_surface_domain(&ruled, &u0, &u1, &v0, &v1);
    CHECK_NEAR(u0, 0, 0);
    CHECK_NEAR(u1, 1, 0);
    for (int j = 0; j <= 10; j++)
        for (int i = 0; i <= 30; i++) {
            double s = i / 30.0, v = j / 10.0, pc[3], pl[3], pe[3], pr[3];
            sc_curve_eval(&c, 2 + 3 * s, pc, NULL);
            sc_curve_eval(&line, s, pl, NULL);
            sc_surface_eval(&ext, 2 + 3 * s, v, pe, NULL, NULL);
            sc_surface_eval(&ruled, s, v, pr, NULL, NULL);
            for (int k = 0; k < 3; k++) {
                CHECK_NEAR(pe[k], pc[k] + v * d[k], 1e-14);
                CHECK_NEAR(pr[k], (1 - v) * pl[k] + v * pc[k], 1e-14);
            }
        }
    /* Two curves joined: the first on [0, 1], the second on [1, 2]. */
    sc_curve pair[2];
    sc_curve_copy(&pair[0], &line);
    sc_curve_reverse(&pair[0]);
    sc_curve_copy(&pair[1], &c);
    CHECK_INT(sc_curve_join(pair, 2, &joined), 0);
    for (int i = 0; i <= 40; i++) {
        double t = i / 20.0, pj[3], pe[3];
        sc_curve_eval(&joined, t, pj, NULL);
        if (t <= 1) {
            sc_curve_domain(&pair[0], &u0, &u1);
            sc_curve_eval(&pair[0], u0 + (u1 - u0) * t, pe, NULL);
        } else {
            sc_curve_domain(&pair[1], &u0, &u1);
            sc_curve_eval(&pair[1], u0 + (u1 - u0) * (t - 1), pe, NULL);
        }
        for (int k = 0; k < 3; k++)
            CHECK_NEAR(pj[k], pe[k], 1e-13);
    }
    sc_curve_free(&pair[0]);
    sc_curve_free(&pair[1]);
    sc_curve_free(&joined);
    sc_surface_free(&ext);
    sc_surface_free(&ruled);
    sc_curve_free(&line);
    sc_curve_free(&c);
}

/* ---- IGES surfaces ---- */

static const char cubic_126[] =
    "126,4,3,0,0,1,0,0.,0.,0.,0.,0.4,1.,1.,1.,1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,2.,0.,2.,-1.,1.,3.,"
    "0.,0.,4.,1.,-1.,0.,1.,0.,0.,0.;";

TEST(iges_free_analytic_surfaces_exact)
{
    /* A sphere (196), a torus (198), a cone-like surface of revolution
     * (120, half a turn), a tabulated cylinder (122) and a ruled surface
     * (118), none referenced by a face: each drawn whole, untrimmed. */
    spec e[] = {
        {116, "116,1.,2.,3.,0;", 0, 0, NULL},                    /* D 1 */
        {123, "123,0.,0.,2.;", 0, 0, NULL},                      /* D 3 */
        {196, "196,1,1.5;", 0, 0, NULL},                         /* D 5 */
        {198, "198,1,3,3.,1.;", 0, 0, NULL},                     /* D 7 */
        {110, "110,0.,0.,0.,0.,0.,1.;", 0, 0, NULL},             /* D 9 */
        {110, "110,1.,0.,0.,2.,0.,1.;", 0, 0, NULL},             /* D 11 */
        {120, "120,9,11,0.,3.141592653589793;", 0, 0, NULL},    /* D 13 */
        {126, cubic_126, 0, 0, NULL},                            /* D 15 */
        {122, "122,15,1.,1.,5.;", 0, 0, NULL},                   /* D 17 */
        {110, "110,0.,0.,0.,4.,0.,0.;", 0, 0, NULL},             /* D 19 */
        {118, "118,19,15,0,1;", 0, 0, NULL},                     /* D 21 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 11, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 5);
    quadric sphere = {{1, 2, 3}, {0, 0, 1}, 1.5, 0, 0, 1};
    quadric torus = {{1, 2, 3}, {0, 0, 1}, 1, 0, 3, 2};
    quadric cone = {{0, 0, 0}, {0, 0, 1}, 1, 1, 0, 0};
    CHECK(worst_over(&s.surfaces[0], 30, off_quadric, &sphere) < 1e-14 * 8);
    CHECK(worst_over(&s.surfaces[1], 30, off_quadric, &torus) < 1e-14 * 8);
    CHECK(worst_over(&s.surfaces[2], 30, off_quadric, &cone) < 1e-14 * 8);
    /* half a turn: y >= 0 on the whole surface */
    double u0, u1, v0, v1, p[3];
    sc_surface_domain(&s.surfaces[2], &u0, &u1, &v0, &v1);
    for (int i = 0; i <= 20; i++) {
        sc_surface_eval(&s.surfaces[2], 0.5 * (u0 + u1), v0 + (v1 - v0) * i / 20, p, NULL, NULL);
        CHECK(p[1] >= -1e-15);
    }
    sc_surface_eval(&s.surfaces[2], u1, v1, p, NULL, NULL);
    CHECK_NEAR(p[0], -2, 1e-14);
    CHECK_NEAR(p[2], 1, 1e-14);
    /* 122 and 118 against the curve they are made of */
    sc_curve c;
    test_cubic(&c, 0, 1);
    double d[3] = {1, 1, 5};
    for (int j = 0; j <= 8; j++)
        for (int i = 0; i <= 24; i++) {
            double t = i / 24.0, v = j / 8.0, pc[3], pt[3], pr[3];
            sc_curve_eval(&c, t, pc, NULL);
            sc_surface_eval(&s.surfaces[3], t, v, pt, NULL, NULL);
            sc_surface_eval(&s.surfaces[4], t, v, pr, NULL, NULL);
            double pl[3] = {4 * t, 0, 0};
            for (int k = 0; k < 3; k++) {
                CHECK_NEAR(pt[k], pc[k] + v * d[k], 1e-14);
                CHECK_NEAR(pr[k], (1 - v) * pl[k] + v * pc[k], 1e-14);
            }
        }
    sc_curve_free(&c);
    sc_scene_free(&s);
}

/* A point of a trim curve on the surface, in object space. */
static void trim_point(const sc_surface *f, const sc_curve *c, double s, double p[3])
{
    double t0, t1, uv[2];
    sc_curve_domain(c, &t0, &t1);
    sc_curve_eval(c, t0 + (t1 - t0) * s, uv, NULL);
    sc_surface_eval(f, uv[0], uv[1], p, NULL, NULL);
}

TEST(iges_cylinder_face_projected)
{
    /* A B-rep face on a 192 cylinder of radius 2 about z, bounded by its
     * 508 loop of model-space edges only (504: two circles at z = 0 and
     * z = 3, and the seam line, used twice): the cylinder is made as long
     * as its trims, the loop is projected across the seam, and what is
     * kept is the band 0 < z < 3. */
    spec e[] = {
        {116, "116,0.,0.,0.,0;", 0, 0, NULL},                                   /* D 1 */
        {123, "123,0.,0.,1.;", 0, 0, NULL},                                     /* D 3 */
        {192, "192,1,3,2.;", 0, 0, NULL},                                       /* D 5 */
        {100, "100,0.,0.,0.,2.,0.,2.,0.;", 0, 0, NULL},                         /* D 7 */
        {100, "100,3.,0.,0.,2.,0.,2.,0.;", 0, 0, NULL},                         /* D 9 */
        {110, "110,2.,0.,0.,2.,0.,3.;", 0, 0, NULL},                            /* D 11 */
        {504, "504,3,7,0,0,0,0,9,0,0,0,0,11,0,0,0,0;", 0, 0, NULL},             /* D 13 */
        {508, "508,4,0,13,1,1,0,0,13,3,1,0,0,13,2,0,0,0,13,3,0,0;", 0, 0, NULL}, /* D 15 */
        {510, "510,5,1,1,15;", 0, 0, NULL},                                     /* D 17 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 9, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_INT(s.projected_loops, 1);
    CHECK_INT(s.dropped_loops, 0);
    CHECK(s.projection_dev < 1e-5);
    const sc_surface *f = &s.surfaces[0];
    quadric cyl = {{0, 0, 0}, {0, 0, 1}, 2, 0, 0, 0};
    CHECK(worst_over(f, 30, off_quadric, &cyl) < 1e-14 * 8);
    CHECK_INT(f->nloops, 1);
    /* Every point of the loop lies on one of the three edges. */
    for (int i = 0; i < f->loops[0].ncurves; i++)
        for (int k = 0; k <= 50; k++) {
            double p[3];
            trim_point(f, &f->loops[0].curves[i], k / 50.0, p);
            double on_circle = fabs(hypot(p[0], p[1]) - 2) + fmin(fabs(p[2]), fabs(p[2] - 3));
            double on_seam = hypot(p[0] - 2, p[1]);
            CHECK(fmin(on_circle, on_seam) < 1e-5);
        }
    sc_trim *trim = NULL;
    sc_error err;
    CHECK_INT(sc_trim_prepare(f, &trim, &err), SC_OK);
    double u0, u1, v0, v1;
    sc_surface_domain(f, &u0, &u1, &v0, &v1);
    int kept = 0;
    for (int j = 0; j < 20; j++)
        for (int i = 0; i < 20; i++) {
            double u = u0 + (u1 - u0) * (i + 0.5) / 20, v = v0 + (v1 - v0) * (j + 0.5) / 20, p[3];
            sc_surface_eval(f, u, v, p, NULL, NULL);
            if (fabs(p[2]) < 1e-3 || fabs(p[2] - 3) < 1e-3)
                continue;
            int inside = p[2] > 0 && p[2] < 3;
            CHECK_INT(sc_trim_inside(trim, u, v), inside);
            kept += inside;
        }
    CHECK(kept > 0);
    /* The cylinder reaches a little past the edges: cut away there. */
    CHECK_INT(sc_trim_inside(trim, u0 + 1e-3 * (u1 - u0), 0.5 * (v0 + v1)), 0);
    CHECK_INT(sc_trim_inside(trim, u1 - 1e-3 * (u1 - u0), 0.3 * v0 + 0.7 * v1), 0);
    sc_trim_free(trim);
    sc_scene_free(&s);
}

TEST(iges_plane_face_from_model_curves_exact)
{
    /* A 108 plane z = 1 under a 144 whose 142 has only a model-space
     * curve: a circle of radius 0.5 about (0.5, 0.5, 1). On a plane the
     * curve maps exactly: every point of the loop on the circle. */
    spec e[] = {
        {108, "108,0.,0.,1.,1.,0,0.,0.,0.,0.;", 0, 0, NULL},        /* D 1 */
        {100, "100,1.,0.5,0.5,1.,0.5,1.,0.5;", 0, 0, NULL},          /* D 3 */
        {142, "142,0,1,0,3,2;", 0, 0, NULL},                         /* D 5 */
        {144, "144,1,1,0,5;", 0, 0, NULL},                           /* D 7 */
        {108, "108,0.,0.,1.,0.,0,0.,0.,0.,0.;", 0, 0, NULL},        /* D 9: no trims */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 5, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_INT(iges_skipped_count(&s, "iges-108", "unbounded"), 1);
    CHECK_INT(s.projected_loops, 1);
    CHECK_NEAR(s.projection_dev, 0, 0);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->deg_u, 1);
    CHECK_INT(f->deg_v, 1);
    for (int i = 0; i < f->loops[0].ncurves; i++)
        for (int k = 0; k <= 50; k++) {
            double p[3];
            trim_point(f, &f->loops[0].curves[i], k / 50.0, p);
            CHECK_NEAR(p[2], 1, 1e-14);
            CHECK_NEAR(hypot(p[0] - 0.5, p[1] - 0.5), 0.5, 1e-14);
        }
    sc_scene_free(&s);
}

TEST(iges_conic_trims_exact)
{
    /* Trim loops of 104 conic arcs in parameter space: a whole ellipse
     * (semi-axes 0.3, 0.2, moved to (0.5, 0.5) by a 124), a parabola arc
     * y = x^2 and a hyperbola arc x^2 - y^2 = 0.04 (s from -1 to 1), each
     * closed by a line, on three planes over [0, 1]^2. */
    spec e[] = {
        {128, iges_plane_params(1), 0, 0, NULL},                                     /* D 1 */
        {124, "124,1.,0.,0.,0.5,0.,1.,0.,0.5,0.,0.,1.,0.;", 0, 0, NULL},             /* D 3 */
        {104, "104,11.111111111111111,0.,25.,0.,0.,-1.,0.,0.3,0.,0.3,0.;", 3, 0, NULL}, /* D 5 */
        {142, "142,0,1,5,0,1;", 0, 0, NULL},                                         /* D 7 */
        {144, "144,1,1,0,7;", 0, 0, NULL},                                           /* D 9 */
        {128, iges_plane_params(1), 0, 0, NULL},                                     /* D 11 */
        {124, "124,1.,0.,0.,0.5,0.,1.,0.,0.2,0.,0.,1.,0.;", 0, 0, NULL},             /* D 13 */
        {104, "104,1.,0.,0.,0.,-1.,0.,0.,-0.5,0.25,0.5,0.25;", 13, 0, NULL},         /* D 15 */
        {110, "110,1.,0.45,0.,0.,0.45,0.;", 0, 0, NULL},                             /* D 17 */
        {102, "102,2,15,17;", 0, 0, NULL},                                           /* D 19 */
        {142, "142,0,11,19,0,1;", 0, 0, NULL},                                       /* D 21 */
        {144, "144,11,1,0,21;", 0, 0, NULL},                                         /* D 23 */
        {128, iges_plane_params(1), 0, 0, NULL},                                     /* D 25 */
        {124, "124,1.,0.,0.,0.3,0.,1.,0.,0.5,0.,0.,1.,0.;", 0, 0, NULL},             /* D 27 */
        {104, "104,1.,0.,-1.,0.,0.,-0.04,0.,0.30861612696304874,-0.2350402387287603,0.30861612696304874,0.2350402387287603;", 27, 0, NULL},          /* D 29 */
        {110, "110,0.30861612696304874,0.2350402387287603,0.,0.30861612696304874,-0.2350402387287603,0.;", 27, 0, NULL},                           /* D 31 */
        {102, "102,2,29,31;", 0, 0, NULL},                                           /* D 33 */
        {142, "142,0,25,33,0,1;", 0, 0, NULL},                                       /* D 35 */
        {144, "144,25,1,0,35;", 0, 0, NULL},                                         /* D 37 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 19, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 3);
    CHECK_INT(s.dropped_loops, 0);
    const sc_curve *ell = &s.surfaces[0].loops[0].curves[0];
    const sc_curve *par = &s.surfaces[1].loops[0].curves[0];
    double t0, t1, p[2];
    sc_curve_domain(ell, &t0, &t1);
    for (int k = 0; k <= 100; k++) {
        iges_eval2(ell, t0 + (t1 - t0) * k / 100, p);
        double x = (p[0] - 0.5) / 0.3, y = (p[1] - 0.5) / 0.2;
        CHECK_NEAR(x * x + y * y, 1, 1e-14);
    }
    sc_curve_domain(par, &t0, &t1);
    for (int k = 0; k <= 100; k++) {
        iges_eval2(par, t0 + (t1 - t0) * k / 100, p);
        CHECK_NEAR(p[1] - 0.2, (p[0] - 0.5) * (p[0] - 0.5), 1e-15);
    }
    const sc_curve *hyp = &s.surfaces[2].loops[0].curves[0];
    sc_curve_domain(hyp, &t0, &t1);
    for (int k = 0; k <= 100; k++) {
        iges_eval2(hyp, t0 + (t1 - t0) * k / 100, p);
        double x = p[0] - 0.3, y = p[1] - 0.5;
        CHECK_NEAR(x * x - y * y, 0.04, 1e-14);
        CHECK(x > 0);
    }
    sc_trim *trim = NULL;
    sc_error err;
    CHECK_INT(sc_trim_prepare(&s.surfaces[0], &trim, &err), SC_OK);
    CHECK_INT(sc_trim_inside(trim, 0.5, 0.5), 1);
    CHECK_INT(sc_trim_inside(trim, 0.5, 0.75), 0);
    CHECK_INT(sc_trim_inside(trim, 0.79, 0.5), 1);
    CHECK_INT(sc_trim_inside(trim, 0.81, 0.5), 0);
    sc_trim_free(trim);
    sc_scene_free(&s);
}

TEST(iges_subfigure_instances)
{
    /* A 308 holding a plane over [0, 1]^2, placed twice by 408s: moved by
     * (10, 0, 0), and scaled by 2 and moved by (0, 5, 0); the plane itself
     * is not drawn on its own. A 408 inside its own definition is a
     * reference cycle. */
    spec e[] = {
        {128, iges_plane_params(1), 0, 0, NULL}, /* D 1 */
        {308, "308,0,1Hs,1,1;", 0, 0, NULL},     /* D 3 */
        {408, "408,3,10.,0.,0.,1.;", 0, 0, NULL}, /* D 5 */
        {408, "408,3,0.,5.,0.,2.;", 0, 0, NULL},  /* D 7 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 4, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    double p[3];
    sc_surface_eval_world(&s.surfaces[0], 1, 1, p, NULL, NULL);
    CHECK_NEAR(p[0], 11, 1e-15);
    CHECK_NEAR(p[1], 1, 1e-15);
    sc_surface_eval_world(&s.surfaces[1], 1, 1, p, NULL, NULL);
    CHECK_NEAR(p[0], 2, 1e-15);
    CHECK_NEAR(p[1], 7, 1e-15);
    CHECK_NEAR(p[2], 0, 1e-15);
    sc_scene_free(&s);
    spec cycle[] = {
        {308, "308,0,1Hs,1,3;", 0, 0, NULL},     /* D 1 */
        {408, "408,1,0.,0.,0.,1.;", 0, 0, NULL}, /* D 3 */
        {408, "408,1,0.,0.,0.,1.;", 0, 0, NULL}, /* D 5 */
    };
    char *text = iges_make_iges(cycle, 3);
    sc_error err;
    CHECK_INT(iges_read_text(text, &s, &err), SC_FAIL);
    CHECK_CONTAINS(iges_error_text(&err), "reference cycle");
    free(text);
}

TEST(iges_render_nothing_drawable)
{
    REQUIRE_DATA("iges/Disc.igs");
    char cmd[1024], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "%s render %s -o %s/disc.png --size 16x16", test_cli,
             test_data("iges/Disc.igs"), test_tmpdir());
    int status = test_run(cmd, &out, &err);
    CHECK(status != 0);
    CHECK_CONTAINS(err, "nothing to draw");
    snprintf(cmd, sizeof cmd, "%s/disc.png", test_tmpdir());
    CHECK(access(cmd, F_OK) != 0);
    free(out);
    free(err);
}

TEST(iges_parametric_splines_exact)
{
    /* A 114 of 2 x 1 bicubic patches (breakpoints u: 0, 1, 3; v: 0, 2)
     * holding x = u, y = v, z = u^2 v + v^3, and a 112 curve of two
     * segments (breakpoints 0, 1, 3) holding (t, t^2, t^3 - t), used as a
     * rail of a ruled surface whose other rail is a line: both exactly. */
    char p114[4096], p112[1024];
    int n = snprintf(p114, sizeof p114, "114,3,1,2,1,0.,1.,3.,0.,2.");
    static const double tu[3] = {0, 1, 3};
    for (int i = 0; i < 2; i++) {
        double c[3][16] = {{0}};
        double a = tu[i];
        c[0][0] = a;     /* x = a + s */
        c[0][1] = 1;
        c[1][4] = 1;     /* y = t */
        c[2][4] = a * a; /* z = (a + s)^2 t + t^3 */
        c[2][5] = 2 * a;
        c[2][6] = 1;
        c[2][12] = 1;
        for (int d = 0; d < 3; d++)
            for (int k = 0; k < 16; k++)
                n += snprintf(p114 + n, sizeof p114 - (size_t)n, ",%.17g", c[d][k]);
        for (int k = 0; k < 48; k++) /* the row's unused values */
            n += snprintf(p114 + n, sizeof p114 - (size_t)n, ",0.");
    }
    for (int k = 0; k < 96; k++)
        n += snprintf(p114 + n, sizeof p114 - (size_t)n, ",0.");
    snprintf(p114 + n, sizeof p114 - (size_t)n, ";");
    snprintf(p112, sizeof p112, "112,3,3,3,2,0.,1.,3.,0.,1.,0.,0.,0.,0.,1.,0.,0.,-1.,0.,1.,"
             "1.,1.,0.,0.,1.,2.,1.,0.,0.,2.,3.,1.,0.,0.,0.,0.,0.,0.,0.,0.,0.,0.,0.,0.;");
    spec e[] = {
        {114, p114, 0, 0, NULL},                          /* D 1 */
        {112, p112, 0, 0, NULL},                          /* D 3 */
        {110, "110,0.,0.,-5.,3.,0.,-5.;", 0, 0, NULL},    /* D 5 */
        {118, "118,5,3,0,1;", 0, 0, NULL},                /* D 7 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 4, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->deg_u, 3);
    CHECK_INT(f->nu, 7);
    CHECK_INT(f->nv, 4);
    for (int j = 0; j <= 10; j++)
        for (int i = 0; i <= 30; i++) {
            double u = 3.0 * i / 30, v = 2.0 * j / 10, p[3];
            sc_surface_eval(f, u, v, p, NULL, NULL);
            CHECK_NEAR(p[0], u, 1e-14);
            CHECK_NEAR(p[1], v, 1e-14);
            CHECK_NEAR(p[2], u * u * v + v * v * v, 1e-13);
        }
    const sc_surface *ruled = &s.surfaces[1];
    for (int i = 0; i <= 30; i++) {
        double w = i / 30.0, t = 3 * w, p[3];
        sc_surface_eval(ruled, w, 1, p, NULL, NULL);
        CHECK_NEAR(p[0], t, 1e-14);
        CHECK_NEAR(p[1], t * t, 1e-13);
        CHECK_NEAR(p[2], t * t * t - t, 1e-13);
        sc_surface_eval(ruled, w, 0, p, NULL, NULL);
        CHECK_NEAR(p[0], t, 1e-14);
        CHECK_NEAR(p[2], -5, 1e-14);
    }
    sc_scene_free(&s);
}

TEST(iges_offset_surface_fitted)
{
    /* A 140 offset of a sphere of radius 2 by 0.5: the fit is another
     * sphere (radius 2.5 or 1.5, by the normal's side) within the stated
     * tolerance, and `info` says how far it is from the true offset. */
    spec e[] = {
        {116, "116,0.,0.,0.,0;", 0, 0, NULL},       /* D 1 */
        {196, "196,1,2.;", 0, 0, NULL},             /* D 3 */
        {140, "140,0.,0.,1.,0.5,3;", 0, 0, NULL},   /* D 5 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 3, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1); /* the sphere is the 140's base, not drawn */
    CHECK_INT(s.offset_surfaces, 1);
    CHECK(s.offset_dev > 0);
    CHECK(s.offset_dev <= 1e-5 * 8);
    double p[3], u0, u1, v0, v1;
    const sc_surface *f = &s.surfaces[0];
    sc_surface_domain(f, &u0, &u1, &v0, &v1);
    sc_surface_eval(f, 0.5 * (u0 + u1), 0.5 * (v0 + v1), p, NULL, NULL);
    double r = sqrt(dot3(p, p));
    CHECK(fabs(r - 2.5) < 1e-4 || fabs(r - 1.5) < 1e-4);
    quadric sphere = {{0, 0, 0}, {0, 0, 1}, r < 2 ? 1.5 : 2.5, 0, 0, 1};
    CHECK(worst_over(f, 40, off_quadric, &sphere) <= s.offset_dev * 1.5);
    sc_scene_free(&s);
}

TEST(iges_sphere_bounded_by_seam_projected)
{
    /* A B-rep face on a 196 sphere of radius 2 bounded by its seam alone:
     * one edge, a rational 126 half circle from pole to pole in the
     * x–z plane, used twice (508, both orientations), model space only.
     * Each run of the seam starts or ends at a pole, where Newton cannot
     * tell the longitude; the projection takes the one the edge has just
     * off the pole, puts the two runs on the two sides of the seam and
     * joins them along the poles: the whole sphere is kept, no loop
     * dropped. */
    spec e[] = {
        {116, "116,0.,0.,0.,0;", 0, 0, NULL},                                  /* D 1 */
        {196, "196,1,2.;", 0, 0, NULL},                                        /* D 3 */
        {126, "126,4,2,1,0,0,0,0.,0.,0.,.5,.5,1.,1.,1.,"
              "1.,.7071067811865476,1.,.7071067811865476,1.,"
              "0.,0.,2.,2.,0.,2.,2.,0.,0.,2.,0.,-2.,0.,0.,-2.,0.,1.,0.,1.,0.;",
         0, 0, NULL},                                                          /* D 5 */
        {504, "504,1,5,0,0,0,0;", 0, 0, NULL},                                 /* D 7 */
        {508, "508,2,0,7,1,1,0,0,7,1,0,0;", 0, 0, NULL},                       /* D 9 */
        {510, "510,3,1,1,9;", 0, 0, NULL},                                     /* D 11 */
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 6, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_INT(s.projected_loops, 1);
    CHECK_INT(s.dropped_loops, 0);
    CHECK(s.projection_dev < 1e-5);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->nloops, 1);
    /* Every point of the loop lies on the seam (x >= 0, y = 0) or at a
     * pole. */
    for (int i = 0; i < f->loops[0].ncurves; i++)
        for (int k = 0; k <= 50; k++) {
            double p[3];
            trim_point(f, &f->loops[0].curves[i], k / 50.0, p);
            CHECK(fabs(p[1]) < 1e-5 && p[0] > -1e-5);
        }
    sc_trim *trim = NULL;
    sc_error err;
    CHECK_INT(sc_trim_prepare(f, &trim, &err), SC_OK);
    double u0, u1, v0, v1;
    sc_surface_domain(f, &u0, &u1, &v0, &v1);
    for (int j = 0; j < 20; j++)
        for (int i = 0; i < 20; i++)
            CHECK_INT(sc_trim_inside(trim, u0 + (u1 - u0) * (i + 0.5) / 20,
                                     v0 + (v1 - v0) * (j + 0.5) / 20), 1);
    sc_trim_free(trim);
    sc_scene_free(&s);
}
