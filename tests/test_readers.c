/* test_readers.c — the .bpt and OBJ readers, the OBJ writer and the info,
 * eval and convert commands. Expected values come from the input text
 * itself, from closed forms (bilinear patches, uniform B-spline blending
 * functions, exact conics) or from a second path through the data (a text
 * scan instead of the reader), never from the code under test. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>
#include <unistd.h>

#include "io.h"
#include "nurbs.h"


static int read_text(const char *text, sc_scene *scene, sc_error *err)
{
    return sc_read_obj(text, strlen(text), "inline.obj", scene, err);
}

/* ---- .bpt ---- */

/* First point of the first patch and last point of the last patch, read
 * from the text with sscanf: an independent path to the same numbers. */
static void bpt_first_last(const char *path, double first[3], double last[3], int *count)
{
    FILE *f = fopen(path, "r");
    char line[256];
    int n = 0, lineno = 0;
    double p[3];
    *count = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (lineno == 1)
            *count = atoi(line);
        if (sscanf(line, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3) {
            if (n++ == 0)
                memcpy(first, p, sizeof p);
            memcpy(last, p, sizeof p);
        }
    }
    fclose(f);
}

TEST(readers_teaset_counts_and_points)
{
    static const struct {
        const char *file;
        int patches;
    } sets[] = {{"teaset/teapot32.bpt", 32}, {"teaset/teapot.bpt", 28},
                {"teaset/teacup.bpt", 26}, {"teaset/teaspoon.bpt", 16}};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        REQUIRE_DATA(sets[i].file);
        const char *path = test_data(sets[i].file);
        sc_scene scene;
        sc_error err;
        CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
        CHECK_INT(scene.nsurfaces, sets[i].patches);
        double first[3], last[3];
        int count;
        bpt_first_last(path, first, last, &count);
        CHECK_INT(count, sets[i].patches);
        for (int s = 0; s < scene.nsurfaces; s++) {
            const sc_surface *su = &scene.surfaces[s];
            CHECK_INT(su->deg_u, 3);
            CHECK_INT(su->deg_v, 3);
            CHECK_INT(su->nu, 4);
            CHECK_INT(su->nv, 4);
            CHECK_INT(su->rational, 0);
            CHECK_INT(su->nloops, 0);
            CHECK(su->knots_u[0] == 0 && su->knots_u[3] == 0 && su->knots_u[4] == 1 &&
                  su->knots_u[7] == 1);
        }
        const double *p0 = scene.surfaces[0].cp;
        const double *pl = scene.surfaces[scene.nsurfaces - 1].cp + 4 * 15;
        for (int d = 0; d < 3; d++) {
            CHECK(p0[d] == first[d]);
            CHECK(pl[d] == last[d]);
        }
        CHECK(p0[3] == 1 && pl[3] == 1);
        sc_scene_free(&scene);
    }
}

TEST(readers_bpt_row_is_v)
{
    /* A 2 x 1 patch: the three points of a row vary in u, the two rows in v. */
    const char *text = "1\n2 1\n0 0 0\n1 0 0\n2 0 5\n0 1 0\n1 1 0\n2 1 7\n";
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_bpt(text, strlen(text), "rows.bpt", &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 1);
    const sc_surface *s = &scene.surfaces[0];
    CHECK_INT(s->deg_u, 2);
    CHECK_INT(s->deg_v, 1);
    CHECK_INT(s->nu, 3);
    CHECK_INT(s->nv, 2);
    CHECK(s->cp[4 * 2 + 2] == 5);          /* (i=2, j=0) */
    CHECK(s->cp[4 * (1 * 3 + 2) + 2] == 7); /* (i=2, j=1) */
    sc_scene_free(&scene);
}

TEST(readers_default_scene)
{
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 32);
    CHECK_STR(scene.source, "teapot");
    /* teapot32.bpt begins with the rim patch whose first point is (1.4, 0, 2.4). */
    CHECK(scene.surfaces[0].cp[0] == 1.4 && scene.surfaces[0].cp[1] == 0 &&
          scene.surfaces[0].cp[2] == 2.4);
    sc_scene_free(&scene);
}

/* ---- OBJ: geometry against closed forms ---- */

TEST(readers_obj_bilinear_eval)
{
    const char *text = "v 0 0 0\nv 2 0 0\nv 0 1 0\nv 2 1 1\n"
                       "cstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    CHECK_INT(read_text(text, &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 1);
    /* Bilinear interpolation of the corners: P = (2u, v, uv). */
    double uv[3][2] = {{0.25, 0.5}, {0.9, 0.1}, {0.5, 0.5}};
    for (int k = 0; k < 3; k++) {
        double u = uv[k][0], v = uv[k][1], p[3], su[3], sv[3];
        sc_surface_eval(&scene.surfaces[0], u, v, p, su, sv);
        CHECK_NEAR(p[0], 2 * u, 1e-15);
        CHECK_NEAR(p[1], v, 1e-15);
        CHECK_NEAR(p[2], u * v, 1e-15);
        CHECK_NEAR(su[0], 2, 1e-14);
        CHECK_NEAR(su[2], v, 1e-14);
        CHECK_NEAR(sv[1], 1, 1e-14);
        CHECK_NEAR(sv[2], u, 1e-14);
    }
    sc_scene_free(&scene);
}

/* Uniform cubic B-spline blending functions on one span, t in [0, 1]. */
static void uniform_cubic(double t, double b[4])
{
    double s = 1 - t;
    b[0] = s * s * s / 6;
    b[1] = (3 * t * t * t - 6 * t * t + 4) / 6;
    b[2] = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6;
    b[3] = t * t * t / 6;
}

TEST(readers_obj_unclamped_bspline_is_clamped)
{
    /* Five control points on a uniform knot vector 0..8 (degree 3): the
     * curve lives on [3, 5]. Linear in v. */
    const char *text = "v 0 0 0\nv 1 0 3\nv 2 0 -1\nv 3 0 4\nv 4 0 2\n"
                       "v 0 1 0\nv 1 1 3\nv 2 1 -1\nv 3 1 4\nv 4 1 2\n"
                       "cstype bspline\ndeg 3 1\nsurf 3 5 0 1 1 2 3 4 5 6 7 8 9 10\n"
                       "parm u 0 1 2 3 4 5 6 7 8\nparm v 0 0 1 1\nend\n";
    double z[5] = {0, 3, -1, 4, 2};
    sc_scene scene;
    sc_error err;
    CHECK_INT(read_text(text, &scene, &err), SC_OK);
    const sc_surface *s = &scene.surfaces[0];
    CHECK_INT(s->nu, 5);
    double knots[9] = {3, 3, 3, 3, 4, 5, 5, 5, 5};
    for (int i = 0; i < 9; i++)
        CHECK_NEAR(s->knots_u[i], knots[i], 1e-15);
    /* End points and end tangents of a uniform cubic B-spline. */
    double expect[5] = {(z[0] + 4 * z[1] + z[2]) / 6, (2 * z[1] + z[2]) / 3, z[2],
                        (z[2] + 2 * z[3]) / 3, (z[2] + 4 * z[3] + z[4]) / 6};
    for (int i = 0; i < 5; i++)
        CHECK_NEAR(s->cp[4 * i + 2], expect[i], 1e-14);
    for (int k = 0; k <= 8; k++) {
        double u = 3 + k * 0.25, b[4], p[3];
        int span = u < 4 ? 0 : 1;
        uniform_cubic(u - 3 - span, b);
        double zz = 0;
        for (int i = 0; i < 4; i++)
            zz += b[i] * z[span + i];
        if (u == 5) /* the last span's end */
            uniform_cubic(1, b), zz = b[0] * z[1] + b[1] * z[2] + b[2] * z[3] + b[3] * z[4];
        sc_surface_eval(s, u, 0.5, p, NULL, NULL);
        CHECK_NEAR(p[2], zz, 1e-14);
        CHECK_NEAR(p[1], 0.5, 1e-15);
    }
    sc_scene_free(&scene);
}

TEST(readers_obj_surf_range_restricts)
{
    /* A Bezier line in u over [0, 2] evaluated only over [0.5, 1.5]: the
     * surface keeps its parameterisation on the smaller range. */
    const char *text = "v 0 0 0\nv 4 0 0\nv 0 1 0\nv 4 1 0\n"
                       "cstype bezier\ndeg 1 1\nsurf 0.5 1.5 0 1 1 2 3 4\nparm u 0 2\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    CHECK_INT(read_text(text, &scene, &err), SC_OK);
    const sc_surface *s = &scene.surfaces[0];
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    CHECK_NEAR(u0, 0.5, 0);
    CHECK_NEAR(u1, 1.5, 0);
    CHECK_NEAR(s->cp[0], 1, 1e-15); /* x = 2u at u = 0.5 */
    CHECK_NEAR(s->cp[4], 3, 1e-15);
    sc_scene_free(&scene);
}

static int read_text_warnings(const char *text, sc_scene *scene, sc_error *err,
                              test_warnings *w)
{
    memset(w, 0, sizeof *w);
    sc_set_logger(test_gather_warnings, w);
    int status = read_text(text, scene, err);
    sc_set_logger(NULL, NULL);
    return status;
}

TEST(readers_obj_surf_range_wider_is_cut_with_warning)
{
    /* surf asks for u over [-1, 3] and v over [0, 1 + 1e-12]; the knots
     * define [0, 2] × [0, 1]. u is cut with a warning at the surf line (6);
     * the v excess is a writer's rounding, cut silently. */
    const char *text = "v 0 0 0\nv 4 0 0\nv 0 1 0\nv 4 1 0\n"
                       "cstype bezier\ndeg 1 1\nsurf -1 3 0 1.000000000001 1 2 3 4\n"
                       "parm u 0 2\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    test_warnings w;
    CHECK_INT(read_text_warnings(text, &scene, &err, &w), SC_OK);
    CHECK_INT(w.count, 1);
    CHECK_CONTAINS(w.text, "inline.obj:7: surf u range [-1, 3] is wider than the knots' range "
                           "[0, 2]; cut to [0, 2]");
    double u0, u1, v0, v1;
    sc_surface_domain(&scene.surfaces[0], &u0, &u1, &v0, &v1);
    CHECK_NEAR(u0, 0, 0);
    CHECK_NEAR(u1, 2, 0);
    CHECK_NEAR(v1, 1, 0);
    sc_scene_free(&scene);
}

/* Appends to text an OBJ Bézier curv2 of the given degree whose control
 * points are a regular polygon around (0.5, 0.5), closed; vp numbers start
 * after `used` earlier vp lines. */
static void append_closed_curv2(char *text, size_t size, int degree, double radius, int used)
{
    size_t n = strlen(text);
    for (int i = 0; i < degree; i++) {
        double a = 2 * M_PI * i / degree;
        n += (size_t)snprintf(text + n, size - n, "vp %.17g %.17g\n", 0.5 + radius * cos(a),
                              0.5 + radius * sin(a));
    }
    n += (size_t)snprintf(text + n, size - n, "cstype bezier\ndeg %d\ncurv2", degree);
    for (int i = 0; i < degree; i++)
        n += (size_t)snprintf(text + n, size - n, " %d", used + 1 + i);
    snprintf(text + n, size - n, " %d\nparm u 0 1\nend\n", used + 1);
}

TEST(readers_obj_trim_degree_above_limit_dropped)
{
    /* The outer loop is one curve of degree 17, above what trimming
     * handles: loop validation drops it, with a warning naming the file,
     * surface and loop, and counts it. The hole, of degree 12, stays. */
    char text[8192] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    append_closed_curv2(text, sizeof text, 17, 0.4, 0);
    append_closed_curv2(text, sizeof text, 12, 0.2, 17);
    size_t n = strlen(text);
    snprintf(text + n, sizeof text - n,
             "o lid\ncstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\n"
             "trim 0 1 1\nhole 0 1 2\nend\n");
    sc_scene scene;
    sc_error err;
    test_warnings w;
    CHECK_INT(read_text_warnings(text, &scene, &err, &w), SC_OK);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_INT(w.count, 1);
    CHECK_CONTAINS(w.text, "inline.obj: surface 0 (lid): trim loop 0 dropped: curve 0 has "
                           "degree 17");
    const sc_surface *s = &scene.surfaces[0];
    CHECK_INT(s->nloops, 1);
    CHECK_INT(s->loops[0].is_hole, 1);
    CHECK_INT(s->loops[0].curves[0].degree, 12);
    sc_scene_free(&scene);
}

TEST(readers_obj_multisegment_bezier_knots)
{
    /* deg 3, parm u 0 1 2: two segments sharing an end point, 7 points. */
    const char *text = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 1\nv 4 0 0\nv 5 0 0\nv 6 0 0\n"
                       "v 0 1 0\nv 1 1 0\nv 2 1 0\nv 3 1 1\nv 4 1 0\nv 5 1 0\nv 6 1 0\n"
                       "cstype bezier\ndeg 3 1\nsurf 0 2 0 1 1 2 3 4 5 6 7 8 9 10 11 12 13 14\n"
                       "parm u 0 1 2\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    CHECK_INT(read_text(text, &scene, &err), SC_OK);
    const sc_surface *s = &scene.surfaces[0];
    CHECK_INT(s->nu, 7);
    double knots[11] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2};
    for (int i = 0; i < 11; i++)
        CHECK(s->knots_u[i] == knots[i]);
    /* The shared point is on the surface at the break: (3, v, 1). */
    double p[3];
    sc_surface_eval(s, 1, 0.25, p, NULL, NULL);
    CHECK_NEAR(p[0], 3, 1e-14);
    CHECK_NEAR(p[1], 0.25, 1e-14);
    CHECK_NEAR(p[2], 1, 1e-14);
    sc_scene_free(&scene);
}

TEST(readers_obj_rational_quarter_cylinder)
{
    /* A quarter circle (1,0) (1,1) (0,1) with weights 1 1 2 in (y, z), swept
     * along x. Weights in OBJ follow Euclidean x y z. At t = 1/2 the point is
     * (0.25·1·(1,0) + 0.5·1·(1,1) + 0.25·2·(0,1)) / 1.25 = (0.6, 0.8). */
    const char *text = "v 0 1 0\nv 2 1 0\nv 0 1 1\nv 2 1 1\nv 0 0 1 2\nv 2 0 1 2\n"
                       "cstype rat bezier\ndeg 1 2\nsurf 0 1 0 1 1 2 3 4 5 6\nparm u 0 1\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    CHECK_INT(read_text(text, &scene, &err), SC_OK);
    const sc_surface *s = &scene.surfaces[0];
    CHECK_INT(s->rational, 1);
    /* homogeneous storage: (x·w, y·w, z·w, w) */
    CHECK(s->cp[4 * 4 + 0] == 0 && s->cp[4 * 4 + 2] == 2 && s->cp[4 * 4 + 3] == 2);
    double p[3];
    sc_surface_eval(s, 0.5, 0.5, p, NULL, NULL);
    CHECK_NEAR(p[0], 1, 1e-15);
    CHECK_NEAR(p[1], 0.6, 1e-15);
    CHECK_NEAR(p[2], 0.8, 1e-15);
    for (int k = 0; k <= 10; k++) {
        sc_surface_eval(s, 0.3, k / 10.0, p, NULL, NULL);
        CHECK_NEAR(p[1] * p[1] + p[2] * p[2], 1, 1e-14);
    }
    sc_scene_free(&scene);
}

TEST(readers_obj_sphere_example)
{
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_scene(test_root("examples/scenes/sphere.obj"), &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 1);
    const sc_surface *s = &scene.surfaces[0];
    CHECK_STR(s->name, "sphere");
    CHECK_INT(s->rational, 1);
    CHECK_INT(s->nu, 9);
    CHECK_INT(s->nv, 5);
    CHECK_NEAR(s->color[0], 0.2, 1e-7); /* Kd of `blue` in examples.mtl */
    CHECK_NEAR(s->color[2], 0.9, 1e-7);
    unsigned long long seed = 7;
    for (int k = 0; k < 200; k++) {
        double p[3];
        sc_surface_eval(s, test_rand(&seed), test_rand(&seed), p, NULL, NULL);
        CHECK_NEAR(p[0] * p[0] + p[1] * p[1] + p[2] * p[2], 1, 1e-14);
    }
    /* the middle of the first quarter arc on the equator: 45 degrees */
    double p[3];
    sc_surface_eval(s, 0.125, 0.5, p, NULL, NULL);
    CHECK_NEAR(p[0], sqrt(0.5), 1e-15);
    CHECK_NEAR(p[1], sqrt(0.5), 1e-15);
    CHECK_NEAR(p[2], 0, 1e-15);
    sc_surface_eval(s, 0.25, 1, p, NULL, NULL);
    CHECK_NEAR(p[2], 1, 1e-15);
    sc_scene_free(&scene);
}

/* Euclidean end points of a clamped 2D curve. */
static void curve_ends(const sc_curve *c, double a[2], double b[2])
{
    const double *p = c->cp, *q = c->cp + 3 * (c->ncp - 1);
    a[0] = p[0] / p[2], a[1] = p[1] / p[2];
    b[0] = q[0] / q[2], b[1] = q[1] / q[2];
}

TEST(readers_obj_trim_pieces)
{
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_scene(test_root("examples/scenes/trimmed_hole.obj"), &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 1);
    const sc_surface *s = &scene.surfaces[0];
    CHECK_INT(s->nloops, 2);
    CHECK_INT(s->loops[0].is_hole, 0);
    CHECK_INT(s->loops[0].ncurves, 1);
    CHECK_INT(s->loops[1].is_hole, 1);
    CHECK_INT(s->loops[1].ncurves, 2);
    /* `hole 0 2 2 2 4 2`: the two halves of the circle of radius 0.25
     * around (0.5, 0.5), each two rational quadratic arcs. */
    double a[2], b[2];
    const sc_curve *h0 = &s->loops[1].curves[0], *h1 = &s->loops[1].curves[1];
    CHECK_INT(h0->degree, 2);
    CHECK_INT(h0->ncp, 5);
    curve_ends(h0, a, b);
    CHECK_NEAR(a[0], 0.75, 1e-12);
    CHECK_NEAR(a[1], 0.5, 1e-12);
    CHECK_NEAR(b[0], 0.25, 1e-12);
    CHECK_NEAR(b[1], 0.5, 1e-12);
    curve_ends(h1, a, b);
    CHECK_NEAR(a[0], 0.25, 1e-12);
    CHECK_NEAR(b[0], 0.75, 1e-12);
    for (int k = 0; k <= 8; k++) {
        double t0, t1, p[2];
        sc_curve_domain(h1, &t0, &t1);
        sc_curve_eval(h1, t0 + (t1 - t0) * k / 8, p, NULL);
        CHECK_NEAR(hypot(p[0] - 0.5, p[1] - 0.5), 0.25, 1e-14);
        CHECK(p[1] <= 0.5 + 1e-12); /* the lower half */
    }
    sc_scene_free(&scene);
}

TEST(readers_obj_trim_reversed_range)
{
    /* u0 > u1 walks the curve backwards. */
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                       "vp 0.2 0.2\nvp 0.8 0.2\nvp 0.5 0.8\n"
                       "cstype bspline\ndeg 1\ncurv2 1 2 3 1\nparm u 0 0 1 2 3 3\nend\n"
                       "cstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\n"
                       "trim 3 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    CHECK_INT(read_text(text, &scene, &err), SC_OK);
    const sc_curve *c = &scene.surfaces[0].loops[0].curves[0];
    CHECK_INT(c->ncp, 4);
    /* backwards: (0.2,0.2) (0.5,0.8) (0.8,0.2) (0.2,0.2) */
    CHECK_NEAR(c->cp[3 * 1 + 0], 0.5, 1e-15);
    CHECK_NEAR(c->cp[3 * 1 + 1], 0.8, 1e-15);
    CHECK_NEAR(c->cp[3 * 2 + 0], 0.8, 1e-15);
    sc_scene_free(&scene);
}

TEST(readers_obj_syntax_details)
{
    /* Continuation lines, negative references, v/vt/vn triplets, comments,
     * a vertex colour extension, names from g and o, polygons skipped. */
    const char *text = "# header\n"
                       "v 9 9 9\nvt 0 0\nvn 0 0 1\n"
                       "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0  # a comment\nv 1 1 1\n"
                       "f 1 2 3\nl 1 2\np 4\n"
                       "g first_group other\n"
                       "cstype bezier\ndeg 1 1\n"
                       "surf 0 1 0 1 -4/1/1 -3//1 \\\n   -2/1 \\\n -1\n"
                       "parm u 0 1\nparm v 0 1\nend\n"
                       "o named object\n"
                       "surf 0 1 0 1 2 3 4 5\nparm u 0 1\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    sc_set_log_level(SC_LOG_ERROR); /* the note on skipped polygons */
    int status = read_text(text, &scene, &err);
    sc_set_log_level(SC_LOG_WARN);
    CHECK_INT(status, SC_OK);
    CHECK_INT(scene.nsurfaces, 2);
    CHECK_STR(scene.surfaces[0].name, "first_group");
    CHECK_STR(scene.surfaces[1].name, "named object");
    CHECK(scene.surfaces[0].cp[4 * 3 + 2] == 1);
    CHECK(!memcmp(scene.surfaces[0].cp, scene.surfaces[1].cp, 16 * sizeof(double)));
    CHECK_INT(scene.nskipped, 1);
    CHECK_STR(scene.skipped[0].type, "polygon");
    CHECK_INT(scene.skipped[0].count, 3);
    CHECK_STR(scene.skipped[0].reason, "not-free-form");
    sc_scene_free(&scene);
}

TEST(readers_obj_missing_mtl_is_a_warning)
{
    const char *text = "mtllib no_such_file.mtl\nusemtl red\n"
                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                       "cstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\nend\n";
    sc_scene scene;
    sc_error err;
    sc_set_log_level(SC_LOG_ERROR);
    int status = read_text(text, &scene, &err);
    sc_set_log_level(SC_LOG_WARN);
    CHECK_INT(status, SC_OK);
    CHECK_INT(scene.nsurfaces, 1);
    CHECK_NEAR(scene.surfaces[0].color[0], 0.8, 1e-7);
    sc_scene_free(&scene);
}

/* ---- round trips ---- */

static int curves_identical(const sc_curve *a, const sc_curve *b)
{
    return a->dim == b->dim && a->degree == b->degree && a->ncp == b->ncp &&
           !memcmp(a->knots, b->knots, sizeof(double) * (size_t)(a->ncp + a->degree + 1)) &&
           !memcmp(a->cp, b->cp, sizeof(double) * (size_t)a->ncp * (size_t)(a->dim + 1));
}

/* Every knot, control point, trim curve, name and colour bit for bit. */
static int scenes_identical(const sc_scene *a, const sc_scene *b, char *why, size_t size)
{
    if (a->nsurfaces != b->nsurfaces) {
        snprintf(why, size, "%d vs %d surfaces", a->nsurfaces, b->nsurfaces);
        return 0;
    }
    for (int i = 0; i < a->nsurfaces; i++) {
        const sc_surface *s = &a->surfaces[i], *t = &b->surfaces[i];
        snprintf(why, size, "surface %d differs", i);
        if (s->deg_u != t->deg_u || s->deg_v != t->deg_v || s->nu != t->nu || s->nv != t->nv ||
            s->rational != t->rational || s->nloops != t->nloops || strcmp(s->name, t->name) ||
            memcmp(s->color, t->color, sizeof s->color))
            return 0;
        if (memcmp(s->knots_u, t->knots_u, sizeof(double) * (size_t)(s->nu + s->deg_u + 1)) ||
            memcmp(s->knots_v, t->knots_v, sizeof(double) * (size_t)(s->nv + s->deg_v + 1)) ||
            memcmp(s->cp, t->cp, sizeof(double) * 4 * (size_t)s->nu * (size_t)s->nv))
            return 0;
        for (int l = 0; l < s->nloops; l++) {
            if (s->loops[l].is_hole != t->loops[l].is_hole ||
                s->loops[l].ncurves != t->loops[l].ncurves)
                return 0;
            for (int c = 0; c < s->loops[l].ncurves; c++)
                if (!curves_identical(&s->loops[l].curves[c], &t->loops[l].curves[c]))
                    return 0;
        }
    }
    return 1;
}

static void roundtrip(const char *scene_path, const char *out_name)
{
    sc_scene a, b;
    sc_error err;
    char buf[1024], why[128];
    if (sc_read_scene(scene_path, &a, &err)) {
        TEST_FAIL_("%s", sc_error_text(&err, buf, sizeof buf));
        return;
    }
    char out[1024];
    snprintf(out, sizeof out, "%s/%s", test_tmpdir(), out_name);
    CHECK_INT(sc_write_obj(out, &a, &err), SC_OK);
    if (sc_read_scene(out, &b, &err)) {
        TEST_FAIL_("%s", sc_error_text(&err, buf, sizeof buf));
        sc_scene_free(&a);
        return;
    }
    int same = scenes_identical(&a, &b, why, sizeof why);
    sc_scene_free(&a);
    sc_scene_free(&b);
    if (!same)
        TEST_FAIL_("%s: round trip through %s: %s", scene_path, out, why);
}

TEST(readers_roundtrip_teapot32)
{
    roundtrip(TEST_TEAPOT32, "teapot32.obj");
}

TEST(readers_roundtrip_trimmed_rational)
{
    roundtrip(test_root("examples/scenes/trimmed_hole.obj"), "trimmed_hole.obj");
    roundtrip(test_root("examples/scenes/sphere.obj"), "sphere.obj");
    roundtrip(test_root("examples/scenes/mixed.obj"), "mixed.obj");
}

TEST(readers_writer_bakes_transform)
{
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    double shift[12] = {1, 0, 0, 10, 0, 1, 0, 0, 0, 0, 1, 0};
    memcpy(scene.surfaces[0].xform, shift, sizeof shift);
    char out[1024];
    snprintf(out, sizeof out, "%s/shifted.obj", test_tmpdir());
    CHECK_INT(sc_write_obj(out, &scene, &err), SC_OK);
    sc_scene back;
    CHECK_INT(sc_read_scene(out, &back, &err), SC_OK);
    CHECK(back.surfaces[0].cp[0] == 1.4 + 10);
    CHECK(back.surfaces[1].cp[0] == scene.surfaces[1].cp[0]);
    sc_scene_free(&scene);
    sc_scene_free(&back);
}

/* ---- malformed input ---- */

static const struct {
    const char *file;
    int line;
    const char *phrase;
} malformed[] = {
    {"bpt_truncated.bpt", 19, "file ends early: patch 1 of degree 1 x 1 needs 4"},
    {"bpt_truncated_point.bpt", 18, "file ends early: expected coordinate z of control point 15"},
    {"bpt_extra_patch.bpt", 7, "unexpected data after the last"},
    {"bpt_degree_zero.bpt", 2, "degree u 0 is out of range"},
    {"bpt_nan.bpt", 4, "not a finite number"},
    {"bpt_not_a_number.bpt", 5, "found 'abc'"},
    {"bpt_huge_degree.bpt", 2, "degree u 100000 is out of range (1 to "},
    {"bpt_nul_byte.bpt", 4, "NUL byte"},
    {"bpt_bad_count.bpt", 1, "the patch count (a whole number)"},
    {"obj_invalid_utf8.obj", 3, "invalid byte 0xff"},
    {"obj_knots_decrease.obj", 10, "knots decrease"},
    {"obj_zero_weight.obj", 2, "weights must be > 0"},
    {"obj_negative_weight.obj", 6, "has weight -1"},
    {"obj_index_out_of_range.obj", 7, "vertex reference 99 is out of range"},
    {"obj_undefined_curve.obj", 19, "refers to curve 2, which is not defined"},
    {"obj_wrong_count.obj", 9, "need 2 x 2 = 4"},
    {"obj_degree_zero.obj", 4, "degree 0 is out of range"},
    {"obj_degree_too_high.obj", 8, "degree 3 needs at least 8"},
    {"obj_missing_end.obj", 7, "has no end statement"},
    {"obj_infinite.obj", 2, "not a finite number"},
    {"obj_cardinal.obj", 5, "not supported"},
    {"obj_trim_range.obj", 18, "lies outside the parameter range"},
    {"obj_unterminated_body.obj", 9, "needs its end statement first"},
    {"obj_knot_multiplicity.obj", 10, "repeats 3 times"},
    {"obj_curv2_one_coordinate.obj", 5, "has no v coordinate"},
};

TEST(readers_malformed_library)
{
    for (size_t i = 0; i < sizeof malformed / sizeof malformed[0]; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/tests/malformed/%s", test_root_dir, malformed[i].file);
        sc_scene scene;
        sc_error err;
        memset(&err, 0, sizeof err);
        if (sc_read_scene(path, &scene, &err) != SC_FAIL) {
            TEST_FAIL_("%s was accepted", path);
            sc_scene_free(&scene);
            return;
        }
        CHECK_STR(err.file, path);
        if (err.line != malformed[i].line)
            TEST_FAIL_("%s: error at line %d, expected %d (%s)", malformed[i].file, err.line,
                       malformed[i].line, err.message);
        CHECK_INT(err.line, malformed[i].line);
        CHECK_CONTAINS(err.message, malformed[i].phrase);
        CHECK_INT(scene.nsurfaces, 0);
        CHECK(scene.surfaces == NULL);
    }
}

TEST(readers_malformed_cli)
{
    static const char *const cases[] = {"bpt_truncated.bpt", "obj_zero_weight.obj",
                                        "obj_undefined_curve.obj", "bpt_nul_byte.bpt"};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int line = 0;
        for (size_t k = 0; k < sizeof malformed / sizeof malformed[0]; k++)
            if (!strcmp(malformed[k].file, cases[i]))
                line = malformed[k].line;
        char in[512], out[512], cmd[2048], where[600];
        snprintf(in, sizeof in, "%s/tests/malformed/%s", test_root_dir, cases[i]);
        snprintf(out, sizeof out, "%s/malformed_%zu.obj", test_tmpdir(), i);
        snprintf(where, sizeof where, "%s:%d: ", in, line);
        char *o, *e;
        snprintf(cmd, sizeof cmd, "%s info %s", test_cli, in);
        CHECK_INT(test_run(cmd, &o, &e), 1);
        CHECK_CONTAINS(e, where);
        CHECK_STR(o, "");
        free(o);
        free(e);
        snprintf(cmd, sizeof cmd, "%s convert %s -o %s", test_cli, in, out);
        CHECK_INT(test_run(cmd, &o, &e), 1);
        CHECK_CONTAINS(e, where);
        free(o);
        free(e);
        CHECK(access(out, F_OK) != 0);
    }
}

/* ---- commands ---- */

TEST(readers_cli_help)
{
    static const char *const commands[] = {"info", "eval", "convert"};
    for (int i = 0; i < 3; i++) {
        char cmd[1024], *o, *e;
        snprintf(cmd, sizeof cmd, "%s %s --help", test_cli, commands[i]);
        CHECK_INT(test_run(cmd, &o, &e), 0);
        CHECK_CONTAINS(o, "usage: splinecast ");
        CHECK_CONTAINS(o, commands[i]);
        free(o);
        free(e);
    }
}

TEST(readers_cli_info_teapot)
{
    const char *path = TEST_TEAPOT32;
    /* The bounding box from a plain scan of every control point in the file. */
    FILE *f = fopen(path, "r");
    char line[256];
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY}, p[3];
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3)
            for (int d = 0; d < 3; d++)
                lo[d] = fmin(lo[d], p[d]), hi[d] = fmax(hi[d], p[d]);
    fclose(f);
    char cmd[1024], *o, *e;
    snprintf(cmd, sizeof cmd, "%s info teapot", test_cli);
    CHECK_INT(test_run(cmd, &o, &e), 0);
    CHECK(!strncmp(o, "surfaces 32\nsurface 0 deg 3 3 rational 0 ctrl 4 4 loops 0 segments 0\n",
                   strlen("surfaces 32\nsurface 0 deg 3 3 rational 0 ctrl 4 4 loops 0 segments 0\n")));
    CHECK_CONTAINS(o, "surface 31 deg 3 3 rational 0 ctrl 4 4 loops 0 segments 0\nbbox ");
    double b[6];
    CHECK_INT(sscanf(strstr(o, "bbox "), "bbox %lf %lf %lf %lf %lf %lf", &b[0], &b[1], &b[2],
                     &b[3], &b[4], &b[5]), 6);
    for (int d = 0; d < 3; d++) {
        CHECK(b[d] == lo[d]);
        CHECK(b[3 + d] == hi[d]);
    }
    free(o);
    free(e);
}

TEST(readers_cli_info_obj)
{
    char cmd[1024], *o, *e;
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, test_root("examples/scenes/trimmed_hole.obj"));
    CHECK_INT(test_run(cmd, &o, &e), 0);
    CHECK_CONTAINS(o, "surfaces 1\nsurface 0 deg 3 3 rational 0 ctrl 4 4 loops 2 segments 3\n");
    free(o);
    free(e);
    const char *scene = test_write_tmp("skips.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"
                                       "cstype rat bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\n"
                                       "parm u 0 0 1 1\nparm v 0 0 1 1\nend\n");
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, scene);
    CHECK_INT(test_run(cmd, &o, &e), 0);
    /* all weights 1: polygonal despite `rat` */
    CHECK_CONTAINS(o, "surface 0 deg 1 1 rational 0 ctrl 2 2 loops 0 segments 0\n"
                      "skipped polygon 2 not-free-form\nbbox 0 0 0 1 1 0\n");
    free(o);
    free(e);
}

/* A scene the GPU programs cannot draw all of: info still describes it,
 * lists the key of the surface they can draw and warns about the other. */
TEST(readers_cli_info_undrawable_surface)
{
    char text[4096] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    size_t n = strlen(text);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i <= 17; i++)
            n += (size_t)snprintf(text + n, sizeof text - n, "v %d %d %d\n", i, j, i % 2);
    n += (size_t)snprintf(text + n, sizeof text - n,
                          "cstype bezier\no flat\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\n"
                          "parm v 0 1\nend\no wavy\ndeg 17 1\nsurf 0 1 0 1");
    for (int k = 5; k <= 40; k++)
        n += (size_t)snprintf(text + n, sizeof text - n, " %d", k);
    snprintf(text + n, sizeof text - n, "\nparm u 0 1\nparm v 0 1\nend\n");
    const char *scene = test_write_tmp("deg17.obj", text);
    char cmd[1024], *o, *e;
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, scene);
    CHECK_INT(test_run(cmd, &o, &e), 0);
    CHECK_CONTAINS(o, "surfaces 2\n");
    CHECK_CONTAINS(o, "surface 1 deg 17 1 rational 0 ctrl 18 2 loops 0 segments 0\n");
    CHECK_CONTAINS(o, "\nbbox 0 0 0 17 1 1\nkey bez1x1-poly-");
    const char *key = strstr(o, "key ");
    CHECK(key && !strstr(key + 1, "key "));
    CHECK_CONTAINS(e, "deg17.obj: surface 1 (wavy): degree 17×1 is above 16");
    CHECK(!strstr(e, "surface 0"));
    free(o);
    free(e);
}

/* The three numbers after `key` on the line that starts with it. */
static int parse_vec(const char *out, const char *key, double v[3])
{
    size_t n = strlen(key);
    for (const char *p = out; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : NULL)
        if (!strncmp(p, key, n) && p[n] == ' ')
            return sscanf(p + n, "%lf %lf %lf", &v[0], &v[1], &v[2]) == 3;
    return 0;
}

TEST(readers_cli_eval)
{
    /* The twisted bilinear quad P = (2u, v, uv): Su = (2, 0, v), Sv = (0, 1, u),
     * normal along Su x Sv = (-v, -2u, 2). */
    const char *scene = test_write_tmp("bilinear.obj",
                                       "v 0 0 0\nv 2 0 0\nv 0 1 0\nv 2 1 1\ncstype bezier\n"
                                       "deg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\nend\n");
    char cmd[1024], *o, *e;
    snprintf(cmd, sizeof cmd, "%s eval %s --surface 0 --uv 0.25,0.5", test_cli, scene);
    CHECK_INT(test_run(cmd, &o, &e), 0);
    double p[3], du[3], dv[3], n[3];
    CHECK(parse_vec(o, "point", p) && parse_vec(o, "du", du) && parse_vec(o, "dv", dv) &&
          parse_vec(o, "normal", n));
    CHECK_NEAR(p[0], 0.5, 1e-15);
    CHECK_NEAR(p[1], 0.5, 1e-15);
    CHECK_NEAR(p[2], 0.125, 1e-15);
    CHECK_NEAR(du[0], 2, 1e-14);
    CHECK_NEAR(du[2], 0.5, 1e-14);
    CHECK_NEAR(dv[1], 1, 1e-14);
    CHECK_NEAR(dv[2], 0.25, 1e-14);
    double len = sqrt(0.25 + 0.25 + 4);
    CHECK_NEAR(n[0], -0.5 / len, 1e-14);
    CHECK_NEAR(n[1], -0.5 / len, 1e-14);
    CHECK_NEAR(n[2], 2 / len, 1e-14);
    free(o);
    free(e);
    /* outside the knot range, a surface that does not exist, bad usage */
    snprintf(cmd, sizeof cmd, "%s eval %s --surface 0 --uv 1.5,0.5", test_cli, scene);
    CHECK_INT(test_run(cmd, &o, &e), 1);
    CHECK_CONTAINS(e, "outside the range");
    CHECK_STR(o, "");
    free(o);
    free(e);
    snprintf(cmd, sizeof cmd, "%s eval %s --surface 3 --uv 0.5,0.5", test_cli, scene);
    CHECK_INT(test_run(cmd, &o, &e), 1);
    CHECK_CONTAINS(e, "there is no surface 3");
    free(o);
    free(e);
    snprintf(cmd, sizeof cmd, "%s eval %s --surface 0 --uv 0.5", test_cli, scene);
    CHECK_INT(test_run(cmd, &o, &e), 2);
    free(o);
    free(e);
}

TEST(readers_cli_convert)
{
    char out[512], cmd[1024], mtl[512], *o, *e;
    snprintf(out, sizeof out, "%s/converted.obj", test_tmpdir());
    snprintf(mtl, sizeof mtl, "%s/converted.mtl", test_tmpdir());
    snprintf(cmd, sizeof cmd, "%s convert teapot -o %s", test_cli, out);
    CHECK_INT(test_run(cmd, &o, &e), 0);
    CHECK_CONTAINS(o, "surfaces 32\n");
    CHECK(access(out, R_OK) == 0);
    CHECK(access(mtl, R_OK) == 0);
    free(o);
    free(e);
    sc_scene a, b;
    sc_error err;
    char why[128];
    CHECK_INT(sc_read_scene("teapot", &a, &err), SC_OK);
    CHECK_INT(sc_read_scene(out, &b, &err), SC_OK);
    int same = scenes_identical(&a, &b, why, sizeof why);
    sc_scene_free(&a);
    sc_scene_free(&b);
    if (!same)
        TEST_FAIL_("converted teapot differs: %s", why);
    CHECK(same);
}

TEST(readers_check_text)
{
    sc_error err;
    CHECK_INT(sc_check_text("a\nb\xc3\xa9\n", 6, "t", &err), SC_OK);            /* é */
    CHECK_INT(sc_check_text("a\n\xc0\x80\n", 5, "t", &err), SC_FAIL);           /* overlong */
    CHECK_INT(err.line, 2);
    CHECK_INT(sc_check_text("a\n\nb\x01", 5, "t", &err), SC_FAIL);
    CHECK_INT(err.line, 3);
    CHECK_CONTAINS(err.message, "control character 0x01");
    CHECK_INT(sc_check_text("\xed\xa0\x80", 3, "t", &err), SC_FAIL);            /* surrogate */
}
