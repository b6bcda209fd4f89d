/* test_geometry.c — the geometry every part shares: the de Casteljau split
 * (bezier.h) against Bernstein sums written here, restriction and reversal
 * (nurbs.h) against evaluation of the original, and the one reversal
 * convention seen through both readers: a trim curve on [2, 5] used
 * backwards keeps the domain [2, 5] whether it comes from OBJ or IGES. */
#include "test.h"

#include <math.h>
#include <stdlib.h>

#include "bezier.h"
#include "io.h"
#include "nurbs.h"

/* Bernstein sum of a Bézier curve with `dim` doubles per point. */
static void bernstein_point(const double *cp, int n, int dim, double t, double *out)
{
    for (int c = 0; c < dim; c++)
        out[c] = 0;
    for (int i = 0; i <= n; i++) {
        double b = 1;
        for (int k = 1; k <= i; k++)
            b = b * (n - i + k) / k;
        b *= pow(t, i) * pow(1 - t, n - i);
        for (int c = 0; c < dim; c++)
            out[c] += b * cp[i * dim + c];
    }
}

static double rand01(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

TEST(geometry_bezier_split_matches_bernstein)
{
    unsigned long long rng = 7;
    enum { N = 5, DIM = 4 };
    double cp[(N + 1) * DIM], left[(N + 1) * DIM], right[(N + 1) * DIM];
    for (int i = 0; i < (N + 1) * DIM; i++)
        cp[i] = (i % DIM == DIM - 1) ? 0.5 + rand01(&rng) : rand01(&rng) - 0.5;
    double t = 0.3;
    sc_bezier_split(cp, N, DIM, DIM, t, left, right);
    for (int k = 0; k <= 10; k++) {
        double s = k / 10.0, a[DIM], b[DIM];
        bernstein_point(left, N, DIM, s, a);
        bernstein_point(cp, N, DIM, s * t, b);
        for (int c = 0; c < DIM; c++)
            CHECK_NEAR(a[c], b[c], 1e-14);
        bernstein_point(right, N, DIM, s, a);
        bernstein_point(cp, N, DIM, t + s * (1 - t), b);
        for (int c = 0; c < DIM; c++)
            CHECK_NEAR(a[c], b[c], 1e-14);
    }
    for (int c = 0; c < DIM; c++)
        CHECK(left[N * DIM + c] == right[c]);
    double p[DIM];
    sc_bezier_point(cp, N, DIM, DIM, t, p);
    for (int c = 0; c < DIM; c++)
        CHECK(p[c] == right[c]);
    /* The output may be the input; at 1/2 every point is an exact mean. */
    double halves[(N + 1) * DIM], mean[DIM];
    memcpy(halves, cp, sizeof cp);
    sc_bezier_split(halves, N, DIM, DIM, 0.5, NULL, halves);
    for (int c = 0; c < DIM; c++)
        mean[c] = 0.5 * (cp[(N - 1) * DIM + c] + cp[N * DIM + c]);
    for (int c = 0; c < DIM; c++)
        CHECK(halves[(N - 1) * DIM + c] == mean[c]);
}

TEST(geometry_grid_split_is_the_curve_split_per_line)
{
    unsigned long long rng = 11;
    enum { DU = 3, DV = 2, NPTS = (DU + 1) * (DV + 1) };
    double cp[4 * NPTS], lo[4 * NPTS], hi[4 * NPTS];
    for (int i = 0; i < 4 * NPTS; i++)
        cp[i] = (i % 4 == 3) ? 1 + rand01(&rng) : rand01(&rng);
    for (int dir = 0; dir < 2; dir++) {
        sc_bezier_grid_split(cp, DU, DV, dir, 0.25, lo, hi);
        int lines = dir == 0 ? DV + 1 : DU + 1, deg = dir == 0 ? DU : DV;
        for (int l = 0; l < lines; l++) {
            double line[4 * (DU + 1)], left[4 * (DU + 1)], right[4 * (DU + 1)];
            for (int k = 0; k <= deg; k++) {
                int idx = dir == 0 ? l * (DU + 1) + k : k * (DU + 1) + l;
                memcpy(line + 4 * k, cp + 4 * idx, 4 * sizeof(double));
            }
            sc_bezier_split(line, deg, 4, 4, 0.25, left, right);
            for (int k = 0; k <= deg; k++) {
                int idx = dir == 0 ? l * (DU + 1) + k : k * (DU + 1) + l;
                CHECK(memcmp(lo + 4 * idx, left + 4 * k, 4 * sizeof(double)) == 0);
                CHECK(memcmp(hi + 4 * idx, right + 4 * k, 4 * sizeof(double)) == 0);
            }
        }
    }
}

/* A planar cubic B-spline on [a, b] with one interior knot. */
static void test_curve(sc_curve *c, double a, double b)
{
    sc_curve_alloc(c, 2, 3, 5);
    double knots[9] = {a, a, a, a, 0.5 * (a + b), b, b, b, b};
    memcpy(c->knots, knots, sizeof knots);
    double pts[5][3] = {{0, 0, 1}, {1, 2, 2}, {2, -1, 1}, {3, 1, 0.5}, {4, 0, 1}};
    for (int i = 0; i < 5; i++) {
        c->cp[3 * i + 0] = pts[i][0] * pts[i][2];
        c->cp[3 * i + 1] = pts[i][1] * pts[i][2];
        c->cp[3 * i + 2] = pts[i][2];
    }
}

static void check_same_point(const sc_curve *x, double s, const sc_curve *y, double t)
{
    double p[2], q[2];
    sc_curve_eval(x, s, p, NULL);
    sc_curve_eval(y, t, q, NULL);
    CHECK_NEAR(p[0], q[0], 1e-13);
    CHECK_NEAR(p[1], q[1], 1e-13);
}

TEST(geometry_curve_restrict)
{
    sc_curve c, r;
    test_curve(&c, 2, 5);
    sc_curve_copy(&r, &c);
    CHECK_INT(sc_curve_restrict(&r, 2.25, 4.0), SC_OK);
    double t0, t1;
    sc_curve_domain(&r, &t0, &t1);
    CHECK(t0 == 2.25 && t1 == 4.0);
    for (int k = 0; k <= 8; k++)
        check_same_point(&r, 2.25 + k * 1.75 / 8, &c, 2.25 + k * 1.75 / 8);
    sc_curve_free(&r);
    /* An end within rounding of a knot is the knot: no sliver span. */
    sc_curve_copy(&r, &c);
    CHECK_INT(sc_curve_restrict(&r, 3.5 + 1e-12, 7), SC_OK);
    sc_curve_domain(&r, &t0, &t1);
    CHECK(t0 == 3.5 && t1 == 5);
    CHECK_INT(r.ncp, 4);
    sc_curve_free(&r);
    /* An empty range keeps the whole domain. */
    sc_curve_copy(&r, &c);
    CHECK_INT(sc_curve_restrict(&r, 4, 3), SC_OK);
    CHECK(memcmp(r.knots, c.knots, 9 * sizeof(double)) == 0);
    sc_curve_free(&r);
    sc_curve_free(&c);
}

TEST(geometry_curve_reverse_keeps_domain)
{
    /* 0.1 + 0.7 - 0.7 is not 0.1: the ends must be exchanged exactly. */
    sc_curve c, r;
    test_curve(&c, 0.1, 0.7);
    sc_curve_copy(&r, &c);
    sc_curve_reverse(&r);
    double t0, t1;
    sc_curve_domain(&r, &t0, &t1);
    CHECK(t0 == 0.1 && t1 == 0.7);
    for (int i = 1; i < 9; i++)
        CHECK(r.knots[i] >= r.knots[i - 1]);
    for (int k = 0; k <= 8; k++) {
        double t = 0.1 + k * 0.6 / 8;
        check_same_point(&r, t, &c, 0.1 + 0.7 - t);
    }
    sc_curve_free(&r);
    sc_curve_free(&c);
}

TEST(geometry_surface_restrict_keeps_loops)
{
    sc_surface s;
    memset(&s, 0, sizeof s);
    sc_surface_alloc(&s, 2, 1, 4, 2);
    double ku[7] = {0, 0, 0, 1, 2, 2, 2}, kv[4] = {0, 0, 3, 3};
    memcpy(s.knots_u, ku, sizeof ku);
    memcpy(s.knots_v, kv, sizeof kv);
    for (int k = 0; k < 8; k++) {
        double w = 1 + 0.25 * (k % 3);
        s.cp[4 * k + 0] = (k % 4) * w;
        s.cp[4 * k + 1] = (k / 4) * w;
        s.cp[4 * k + 2] = (k * k % 5) * 0.1 * w;
        s.cp[4 * k + 3] = w;
    }
    static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    memcpy(s.xform, identity, sizeof identity);
    sc_surface r;
    sc_surface_copy(&r, &s);
    r.nloops = 1;
    r.loops = sc_alloc(1, sizeof(sc_loop));
    CHECK_INT(sc_surface_try_restrict(&r, 0, 0.5, 1.5), SC_OK);
    CHECK_INT(sc_surface_try_restrict(&r, 1, 1, 2), SC_OK);
    CHECK_INT(r.nloops, 1);
    double u0, u1, v0, v1;
    sc_surface_domain(&r, &u0, &u1, &v0, &v1);
    CHECK(u0 == 0.5 && u1 == 1.5 && v0 == 1 && v1 == 2);
    for (int k = 0; k <= 4; k++) {
        double u = 0.5 + 0.25 * k, v = 1 + 0.25 * k, p[3], q[3];
        sc_surface_eval(&r, u, v, p, NULL, NULL);
        sc_surface_eval(&s, u, v, q, NULL, NULL);
        for (int c = 0; c < 3; c++)
            CHECK_NEAR(p[c], q[c], 1e-13);
    }
    sc_surface_free(&r);
    sc_surface_free(&s);
}

/* ---- one reversal through both readers ---- */

/* The reversed curve of the loops below runs from (0.2, 0.8) at t = 2 to
 * (0.2, 0.2) at t = 5. */
static void check_reversed_side(const sc_curve *c)
{
    double t0, t1, p[2];
    sc_curve_domain(c, &t0, &t1);
    CHECK(t0 == 2 && t1 == 5);
    sc_curve_eval(c, 2, p, NULL);
    CHECK_NEAR(p[0], 0.2, 1e-15);
    CHECK_NEAR(p[1], 0.8, 1e-15);
    sc_curve_eval(c, 4, p, NULL);
    CHECK_NEAR(p[0], 0.2, 1e-15);
    CHECK_NEAR(p[1], 0.4, 1e-15);
    sc_curve_eval(c, 5, p, NULL);
    CHECK_NEAR(p[0], 0.2, 1e-15);
    CHECK_NEAR(p[1], 0.2, 1e-15);
}

TEST(geometry_obj_reversed_trim_keeps_domain)
{
    /* Curve 2 goes up the left side on [2, 5]; the loop uses it from 5 to 2. */
    const char *text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                       "vp 0.2 0.2\nvp 0.8 0.2\nvp 0.5 0.8\nvp 0.2 0.8\n"
                       "cstype bspline\ndeg 1\ncurv2 1 2 3 4\nparm u 0 0 1 2 3 3\nend\n"
                       "curv2 1 4\nparm u 2 2 5 5\nend\n"
                       "cstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\n"
                       "trim 0 3 1 5 2 2\nend\n";
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_obj(text, strlen(text), "reversed.obj", &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 1);
    CHECK_INT(scene.surfaces[0].nloops, 1);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.surfaces[0].loops[0].ncurves, 2);
    check_reversed_side(&scene.surfaces[0].loops[0].curves[1]);
    sc_scene_free(&scene);
}

/* A fixed-format IGES file: S and G records, two D records per entity,
 * the parameters in 64-column P records (entity k is D 2k+1). */
static char *iges_file(const char *const *params, const int *types, int n)
{
    size_t cap = 81 * (size_t)(4 + 2 * n + 64), len = 0;
    char *buf = malloc(cap), line[128];
    int seq[4] = {0}; /* S G D P */
#define RECORD(text, section, si)                                                              \
    len += (size_t)snprintf(buf + len, cap - len, "%-72.72s%c%7d\n", text, section, ++seq[si])
    RECORD("splinecast geometry test", 'S', 0);
    RECORD("1H,,1H;,4Htest,5Ht.igs,;", 'G', 1);
    int pline = 1;
    for (int k = 0; k < n; k++) {
        int count = ((int)strlen(params[k]) + 63) / 64;
        snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d%8d%8d%8s", types[k], pline, 0, 0, 0, 0,
                 0, 0, "00000000");
        RECORD(line, 'D', 2);
        snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8s%8s%8s%8d", types[k], 0, 0, count, 0, "",
                 "", "", 0);
        RECORD(line, 'D', 2);
        pline += count;
    }
    for (int k = 0; k < n; k++)
        for (int c = 0; c < ((int)strlen(params[k]) + 63) / 64; c++) {
            snprintf(line, sizeof line, "%-64.64s%8d", params[k] + 64 * c, 2 * k + 1);
            RECORD(line, 'P', 3);
        }
    snprintf(line, sizeof line, "S%7dG%7dD%7dP%7d", seq[0], seq[1], seq[2], seq[3]);
    RECORD(line, 'T', 0);
#undef RECORD
    return buf;
}

TEST(geometry_iges_reversed_member_keeps_domain)
{
    /* A square loop whose last side, a 126 on [2, 5], is written from
     * (0.2, 0.2) up to (0.2, 0.8), against the loop: the reader turns it. */
    const char *params[] = {
        "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,"
        "0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;",
        "110,0.2,0.2,0.,0.8,0.2,0.;",
        "110,0.8,0.2,0.,0.8,0.8,0.;",
        "110,0.8,0.8,0.,0.2,0.8,0.;",
        "126,1,1,0,0,1,0,2.,2.,5.,5.,1.,1.,0.2,0.2,0.,0.2,0.8,0.,2.,5.,0.,0.,1.;",
        "102,4,3,5,7,9;",
        "142,0,1,11,0,2;",
        "144,1,1,0,13;",
    };
    const int types[] = {128, 110, 110, 110, 126, 102, 142, 144};
    char *text = iges_file(params, types, 8);
    sc_scene scene;
    sc_error err = {0};
    int status = sc_read_iges(text, strlen(text), "t.igs", &scene, &err);
    free(text);
    CHECK_INT(status, SC_OK);
    if (status != SC_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return;
    }
    CHECK_INT(scene.nsurfaces, 1);
    CHECK_INT(scene.surfaces[0].nloops, 1);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.surfaces[0].loops[0].ncurves, 4);
    check_reversed_side(&scene.surfaces[0].loops[0].curves[3]);
    sc_scene_free(&scene);
}
