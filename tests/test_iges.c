/* test_iges.c — the IGES reader: surface counts and facts of the real CAD
 * files (known from the data README), exact conversion of trim curves and
 * domains checked against analytic shapes in small IGES files written
 * here (malformed files: test_iges_malformed.c). */
#include "test.h"

#include <stdlib.h>

#include "iges_files.h"
#include "trim.h"

static const char *occt_dir = "/usr/share/opencascade/data/iges";

/* ---- the real files ---- */

typedef struct file_fact {
    const char *file;
    int surfaces;
} file_fact;

TEST(iges_counts_shared_files)
{
    REQUIRE_DATA("iges");
    static const file_fact facts[] = {
        {"iges/bug24012_face.igs", 1}, {"iges/OCC131-2.igs", 3},
        {"iges/OCC26138_Torus.igs", 1}, {"iges/PRO20359-L1.igs", 1},
        {"iges/occ22470.igs", 18},     {"iges/gpucast_part.igs", 134},
        {"iges/gpucast_teapot.igs", 32}, {"iges/Disc.igs", 0},
        {"iges/bad_header.igs", 1},
    };
    for (size_t i = 0; i < sizeof facts / sizeof facts[0]; i++) {
        sc_scene s;
        sc_error err;
        int status = iges_read_path(test_data(facts[i].file), &s, &err);
        if (status)
            fprintf(stderr, "  %s\n", iges_error_text(&err));
        CHECK_INT(status, SC_OK);
        if (s.nsurfaces != facts[i].surfaces || s.dropped_loops != 0)
            fprintf(stderr, "  in %s\n", facts[i].file);
        CHECK_INT(s.nsurfaces, facts[i].surfaces);
        CHECK_INT(s.dropped_loops, 0);
        CHECK(strstr(s.source, facts[i].file) != NULL);
        sc_scene_free(&s);
    }
}

TEST(iges_counts_occt_files)
{
    char path[512];
    snprintf(path, sizeof path, "%s/hammer.iges", occt_dir);
    if (access(path, R_OK) != 0)
        SKIP("%s is missing (Debian package occt-misc)", occt_dir);
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_path(path, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 45);
    CHECK_INT(s.dropped_loops, 0);
    /* README: degrees (2,2)x12, (1,2)x15, (1,1)x14, (3,1)x4; 27 rational;
     * 3 holes. */
    int d22 = 0, d12 = 0, d11 = 0, d31 = 0, rational = 0, trimmed = 0, holes = 0;
    for (int i = 0; i < s.nsurfaces; i++) {
        const sc_surface *f = &s.surfaces[i];
        d22 += f->deg_u == 2 && f->deg_v == 2;
        d12 += f->deg_u == 1 && f->deg_v == 2;
        d11 += f->deg_u == 1 && f->deg_v == 1;
        d31 += f->deg_u == 3 && f->deg_v == 1;
        rational += f->rational;
        trimmed += f->nloops > 0;
        for (int l = 0; l < f->nloops; l++)
            holes += f->loops[l].is_hole;
    }
    CHECK_INT(d22, 12);
    CHECK_INT(d12, 15);
    CHECK_INT(d11, 14);
    CHECK_INT(d31, 4);
    CHECK_INT(rational, 27);
    CHECK_INT(trimmed, 45);
    CHECK_INT(holes, 3);
    sc_scene_free(&s);

    snprintf(path, sizeof path, "%s/bearing.iges", occt_dir);
    CHECK_INT(iges_read_path(path, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 213);
    /* Polynomial, degrees up to 8. Its curves go up to degree 11, but
     * those of parameter space (142 BPTR) only up to 6. */
    int max_deg = 0, max_trim = 0, rat = 0, untrimmed = 0;
    for (int i = 0; i < s.nsurfaces; i++) {
        const sc_surface *f = &s.surfaces[i];
        max_deg = f->deg_u > max_deg ? f->deg_u : max_deg;
        max_deg = f->deg_v > max_deg ? f->deg_v : max_deg;
        rat += f->rational;
        untrimmed += f->nloops == 0;
        for (int l = 0; l < f->nloops; l++)
            for (int c = 0; c < f->loops[l].ncurves; c++)
                if (f->loops[l].curves[c].degree > max_trim)
                    max_trim = f->loops[l].curves[c].degree;
    }
    CHECK_INT(max_deg, 8);
    CHECK_INT(max_trim, 6);
    CHECK_INT(rat, 0);
    /* Every loop the file has is kept, or dropped by validation and
     * counted (a few of its loops overlap themselves where their curves
     * overshoot by 5e-7). */
    CHECK_INT(untrimmed, s.dropped_loops);
    CHECK(s.dropped_loops <= 3);
    sc_scene_free(&s);
}

TEST(iges_bug24012_face)
{
    REQUIRE_DATA("iges/bug24012_face.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_path(test_data("iges/bug24012_face.igs"), &s, &err), SC_OK);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->deg_u, 3);
    CHECK_INT(f->deg_v, 3);
    CHECK_INT(f->nu, 9);
    CHECK_INT(f->nv, 9);
    CHECK_INT(f->nloops, 1);
    CHECK_INT(f->loops[0].is_hole, 0);
    /* Its 142 holds both representations of the one loop: four cubic 126
     * curves in model space (CPTR) and four lines around the unit square in
     * parameter space (BPTR), which is the trim. */
    CHECK_INT(f->loops[0].ncurves, 4);
    static const double corner[4][2] = {{0, 1}, {0, 0}, {1, 0}, {1, 1}};
    for (int c = 0; c < 4; c++) {
        const sc_curve *k = &f->loops[0].curves[c];
        CHECK_INT(k->dim, 2);
        CHECK_INT(k->degree, 1);
        double p[2];
        iges_eval2(k, k->knots[0], p);
        CHECK_NEAR(p[0], corner[c][0], 0);
        CHECK_NEAR(p[1], corner[c][1], 0);
    }
    CHECK_INT(f->rational, 0);
    sc_scene_free(&s);
}

TEST(iges_torus_high_degree_across_seam)
{
    REQUIRE_DATA("iges/OCC26138_Torus.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_path(test_data("iges/OCC26138_Torus.igs"), &s, &err), SC_OK);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->deg_u, 12);
    CHECK_INT(f->deg_v, 12);
    CHECK_INT(f->nloops, 1);
    /* Its trims run across the u seam: the domain now covers them. */
    double u0, u1, v0, v1;
    sc_surface_domain(f, &u0, &u1, &v0, &v1);
    for (int c = 0; c < f->loops[0].ncurves; c++) {
        const sc_curve *k = &f->loops[0].curves[c];
        for (int i = 0; i < k->ncp; i++) {
            double u = k->cp[3 * i] / k->cp[3 * i + 2], v = k->cp[3 * i + 1] / k->cp[3 * i + 2];
            CHECK(u >= u0 - 1e-9 && u <= u1 + 1e-9);
            CHECK(v >= v0 - 1e-9 && v <= v1 + 1e-9);
        }
    }
    sc_scene_free(&s);
}

TEST(iges_brep_faces_projected_and_coloured)
{
    /* The 508 loops have only model-space edges: each face's loop is
     * projected onto its surface, so every face is trimmed, and the
     * projected loop stays within the stated tolerance of the 3D edges
     * (the file's edges themselves lie up to about 1e-5 of the part's size
     * off their faces). */
    REQUIRE_DATA("iges/occ22470.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_path(test_data("iges/occ22470.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 18);
    CHECK_INT(s.projected_loops, 18);
    CHECK_INT(s.dropped_loops, 0);
    double lo[3], hi[3];
    sc_scene_bounds(&s, lo, hi);
    double size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    CHECK(s.projection_dev > 0);
    CHECK(s.projection_dev < 1e-5 * size);
    int rational = 0, grey = 0, trimmed_away = 0;
    for (int i = 0; i < s.nsurfaces; i++) {
        const sc_surface *f = &s.surfaces[i];
        CHECK_INT(f->nloops, 1);
        rational += f->rational;
        grey += f->color[0] == 0.8f && f->color[1] == 0.8f;
        /* Trimmed as meant: part of the face is kept, and on most faces
         * part of the domain is cut away. */
        sc_trim *trim = NULL;
        CHECK_INT(sc_trim_prepare(f, &trim, &err), SC_OK);
        double u0, u1, v0, v1;
        sc_surface_domain(f, &u0, &u1, &v0, &v1);
        int inside = 0, n = 24;
        for (int j = 0; trim && j < n; j++)
            for (int k = 0; k < n; k++)
                inside += sc_trim_inside(trim, u0 + (u1 - u0) * (k + 0.5) / n,
                                         v0 + (v1 - v0) * (j + 0.5) / n);
        CHECK(inside > 0);
        trimmed_away += inside < n * n;
        sc_trim_free(trim);
    }
    CHECK(trimmed_away >= 9);
    CHECK_INT(rational, 14);
    CHECK_INT(grey, 0); /* every face has a 314 colour */
    CHECK_INT(iges_skipped_count(&s, "iges-508", "no-curve"), 0);
    sc_scene_free(&s);
}

TEST(iges_teapot_leniency)
{
    REQUIRE_DATA("iges/gpucast_teapot.igs");
    sc_scene s, bpt;
    sc_error err;
    CHECK_INT(iges_read_path(test_data("iges/gpucast_teapot.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 32);
    for (int i = 0; i < s.nsurfaces; i++) {
        CHECK_INT(s.surfaces[i].deg_u, 3);
        CHECK_INT(s.surfaces[i].deg_v, 3);
        CHECK_INT(s.surfaces[i].nloops, 0);
    }
    /* The same teapot as the .bpt file, read by another reader. */
    CHECK_INT(iges_read_path(TEST_TEAPOT32, &bpt, &err), SC_OK);
    double lo[3], hi[3], blo[3], bhi[3];
    sc_scene_bounds(&s, lo, hi);
    sc_scene_bounds(&bpt, blo, bhi);
    for (int d = 0; d < 3; d++) {
        CHECK_NEAR(lo[d], blo[d], 1e-12);
        CHECK_NEAR(hi[d], bhi[d], 1e-12);
    }
    sc_scene_free(&bpt);
    sc_scene_free(&s);
}

TEST(iges_disc_without_line_breaks)
{
    REQUIRE_DATA("iges/Disc.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_path(test_data("iges/Disc.igs"), &s, &err), SC_OK);
    /* Its 408 instances place 308 subfigures of curves only: nothing to
     * draw, nothing refused. */
    CHECK_INT(s.nsurfaces, 0);
    CHECK_INT(iges_skipped_count(&s, "iges-408", "unsupported"), 0);
    CHECK_INT(iges_skipped_count(&s, "iges-406", "unsupported"), 1);
    sc_scene_free(&s);
}

TEST(iges_bad_header_read_leniently)
{
    REQUIRE_DATA("iges/bad_header.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(iges_read_path(test_data("iges/bad_header.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->deg_u, 1);
    CHECK_INT(f->deg_v, 2);
    CHECK_INT(f->nloops, 1);
    /* The outer loop is the rectangle [0.3, 0.7] x [0, 1] of four lines. */
    CHECK_INT(f->loops[0].ncurves, 4);
    double p[2];
    iges_eval2(&f->loops[0].curves[0], 0, p);
    CHECK_NEAR(p[0], 0.3, 1e-12);
    CHECK_NEAR(p[1], 0.0, 1e-12);
    sc_scene_free(&s);
}

TEST(iges_cli_info)
{
    REQUIRE_DATA("iges/occ22470.igs");
    char cmd[1024], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, test_data("iges/occ22470.igs"));
    int status = test_run(cmd, &out, &err);
    CHECK_INT(status, 0);
    CHECK(out && !strncmp(out, "surfaces 18\n", 12));
    CHECK_CONTAINS(out, "\nprojected_loops 18 max_dev ");
    free(out);
    free(err);
}

/* ---- exact conversion, on small files ---- */

TEST(iges_arcs_exact)
{
    /* A full circle as the outer loop of one plane; on a second plane a
     * circle moved by a 124 (shear y += 0.1 z, translation x += 0.1) at
     * ZT = 1, as a hole with the domain as outer boundary. */
    char *plane = iges_plane_params(1);
    spec e[] = {
        {128, plane, 0, 0, NULL},
        {100, "100,0.,0.5,0.5,0.75,0.5,0.75,0.5;", 0, 0, NULL},
        {142, "142,0,1,3,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,5;", 0, 0, NULL},
        {128, plane, 0, 0, NULL},
        {124, "124,1.,0.,0.,0.1,0.,1.,0.1,0.,0.,0.,1.,0.;", 0, 0, NULL},
        {100, "100,1.,0.5,0.5,0.75,0.5,0.5,0.25;", 11, 0, NULL},
        {110, "110,0.5,0.25,1.,0.75,0.5,1.;", 11, 0, NULL},
        {102, "102,2,13,15;", 0, 0, NULL},
        {142, "142,0,9,17,0,2;", 0, 0, NULL},
        {144, "144,9,0,1,0,19;", 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 11, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    const sc_curve *c = &s.surfaces[0].loops[0].curves[0];
    CHECK_INT(c->degree, 2);
    CHECK_INT(c->ncp, 9); /* four quarter arcs */
    double t0, t1, p[2];
    sc_curve_domain(c, &t0, &t1);
    for (int i = 0; i <= 64; i++) {
        iges_eval2(c, t0 + (t1 - t0) * i / 64, p);
        CHECK_NEAR(hypot(p[0] - 0.5, p[1] - 0.5), 0.25, 1e-14);
    }
    iges_eval2(c, t0, p);
    CHECK_NEAR(p[0], 0.75, 1e-15);
    iges_eval2(c, t0 + (t1 - t0) / 4, p); /* counter-clockwise: a quarter on */
    CHECK_NEAR(p[0], 0.5, 1e-15);
    CHECK_NEAR(p[1], 0.75, 1e-15);

    const sc_surface *f = &s.surfaces[1];
    CHECK_INT(f->nloops, 2);
    CHECK_INT(f->loops[0].is_hole, 0); /* the domain rectangle */
    CHECK_INT(f->loops[0].ncurves, 4);
    CHECK_INT(f->loops[1].is_hole, 1);
    CHECK_INT(f->loops[1].ncurves, 2);
    /* 270° from (0.75, 0.5) to (0.5, 0.25): three pieces, on the circle
     * about (0.6, 0.6) after the transformation. */
    c = &f->loops[1].curves[0];
    CHECK_INT(c->ncp, 7);
    sc_curve_domain(c, &t0, &t1);
    for (int i = 0; i <= 48; i++) {
        iges_eval2(c, t0 + (t1 - t0) * i / 48, p);
        CHECK_NEAR(hypot(p[0] - 0.6, p[1] - 0.6), 0.25, 1e-14);
    }
    iges_eval2(c, t1, p);
    CHECK_NEAR(p[0], 0.6, 1e-14);
    CHECK_NEAR(p[1], 0.35, 1e-14);
    CHECK_INT(s.dropped_loops, 0);
    sc_scene_free(&s);
}

TEST(iges_unclamped_and_subrange_126)
{
    /* A uniform cubic B-spline with control points x_i = i (knots 0..9,
     * not clamped): linear precision gives x(t) = t - 2 on its domain
     * [3, 6]. The loop closes it with three lines; a second copy is
     * restricted to V(0), V(1) = 3.5, 5.5. */
    const char *uniform = "126,5,3,0,0,1,0,0.,1.,2.,3.,4.,5.,6.,7.,8.,9.,"
                          "1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,0.,0.,2.,0.,0.,3.,0.,0.,4.,0.,0.,"
                          "5.,0.,0.,%s;";
    char full[512], part[512];
    snprintf(full, sizeof full, uniform, "3.,6.");
    snprintf(part, sizeof part, uniform, "3.5,5.5");
    spec e[] = {
        {128, iges_plane_params(5), 0, 0, NULL},
        {126, full, 0, 0, NULL},
        {110, "110,4.,0.,0.,4.,1.,0.;", 0, 0, NULL},
        {110, "110,4.,1.,0.,1.,1.,0.;", 0, 0, NULL},
        {110, "110,1.,1.,0.,1.,0.,0.;", 0, 0, NULL},
        {102, "102,4,3,5,7,9;", 0, 0, NULL},
        {142, "142,0,1,11,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,13;", 0, 0, NULL},
        {126, part, 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 9, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_INT(s.dropped_loops, 0);
    const sc_curve *c = &s.surfaces[0].loops[0].curves[0];
    CHECK_INT(c->degree, 3);
    CHECK(c->knots[0] == c->knots[3]); /* clamped now */
    double t0, t1, p[2];
    sc_curve_domain(c, &t0, &t1);
    CHECK_NEAR(t0, 3, 1e-12);
    CHECK_NEAR(t1, 6, 1e-12);
    for (int i = 0; i <= 30; i++) {
        double t = 3 + 0.1 * i;
        iges_eval2(c, t, p);
        CHECK_NEAR(p[0], t - 2, 1e-12);
        CHECK_NEAR(p[1], 0, 1e-12);
    }
    sc_scene_free(&s);

    /* The sub-range copy, as the bottom edge of a loop of its own. */
    spec e2[] = {
        {128, iges_plane_params(5), 0, 0, NULL},
        {126, part, 0, 0, NULL},
        {110, "110,3.5,0.,0.,2.5,1.,0.;", 0, 0, NULL},
        {110, "110,2.5,1.,0.,1.5,0.,0.;", 0, 0, NULL},
        {102, "102,3,3,5,7;", 0, 0, NULL},
        {142, "142,0,1,9,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,11;", 0, 0, NULL},
    };
    CHECK_INT(iges_read_specs(e2, 7, &s), SC_OK);
    c = &s.surfaces[0].loops[0].curves[0];
    sc_curve_domain(c, &t0, &t1);
    CHECK_NEAR(t0, 3.5, 1e-12);
    CHECK_NEAR(t1, 5.5, 1e-12);
    iges_eval2(c, t0, p);
    CHECK_NEAR(p[0], 1.5, 1e-12);
    iges_eval2(c, t1, p);
    CHECK_NEAR(p[0], 3.5, 1e-12);
    sc_scene_free(&s);
}

/* A biquadratic-by-linear patch; U0 U1 V0 V1 appended. */
static void wavy_params(char *buf, size_t size, const char *range)
{
    snprintf(buf, size, "128,3,1,2,1,0,0,1,0,0,0.,0.,0.,1.,2.,2.,2.,0.,0.,1.,1.,"
             "1.,1.,1.,1.,1.,1.,1.,1.,"
             "0.,0.,0.,1.,0.,2.,2.,0.,-1.,3.,0.,1.,0.,1.,0.5,1.,1.,0.,2.,1.,3.,3.,1.,0.,%s;",
             range);
}

TEST(iges_128_subrange_and_order)
{
    /* The same patch twice: full range, and U0 U1 V0 V1 = 0.5 1.5 0.25
     * 0.75. The second must be the first's piece (so the order of the four
     * values is the specification's). */
    char a[512], b[512];
    wavy_params(a, sizeof a, "0.,2.,0.,1.");
    wavy_params(b, sizeof b, "0.5,1.5,0.25,0.75");
    spec e[] = {{128, a, 0, 0, "FULL"}, {128, b, 0, 0, NULL}};
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 2, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    CHECK_STR(s.surfaces[0].name, "FULL");
    CHECK_STR(s.surfaces[1].name, "iges3");
    double u0, u1, v0, v1;
    sc_surface_domain(&s.surfaces[1], &u0, &u1, &v0, &v1);
    CHECK_NEAR(u0, 0.5, 0);
    CHECK_NEAR(u1, 1.5, 0);
    CHECK_NEAR(v0, 0.25, 0);
    CHECK_NEAR(v1, 0.75, 0);
    for (int i = 0; i <= 10; i++)
        for (int j = 0; j <= 10; j++) {
            double u = 0.5 + 0.1 * i, v = 0.25 + 0.05 * j, p[3], q[3];
            sc_surface_eval(&s.surfaces[0], u, v, p, NULL, NULL);
            sc_surface_eval(&s.surfaces[1], u, v, q, NULL, NULL);
            for (int d = 0; d < 3; d++)
                CHECK_NEAR(p[d], q[d], 1e-13);
        }
    sc_scene_free(&s);
}

/* The unit cylinder x² + y² = 1, 0 <= z <= 1: u a full circle of four
 * rational quadratic quarters (knots 0..4), v linear. Closed in u. */
static const char *cylinder =
    "128,8,1,2,1,1,0,0,0,0,0.,0.,0.,1.,1.,2.,2.,3.,3.,4.,4.,4.,0.,0.,1.,1.,"
    "1.,0.70710678118654757,1.,0.70710678118654757,1.,0.70710678118654757,1.,"
    "0.70710678118654757,1.,1.,0.70710678118654757,1.,0.70710678118654757,1.,"
    "0.70710678118654757,1.,0.70710678118654757,1.,"
    "1.,0.,0.,1.,1.,0.,0.,1.,0.,-1.,1.,0.,-1.,0.,0.,-1.,-1.,0.,0.,-1.,0.,1.,-1.,0.,1.,0.,0.,"
    "1.,0.,1.,1.,1.,1.,0.,1.,1.,-1.,1.,1.,-1.,0.,1.,-1.,-1.,1.,0.,-1.,1.,1.,-1.,1.,1.,0.,1.,"
    "0.,4.,0.,1.;";

TEST(iges_trims_across_seam)
{
    /* A band u in [-1, 1] across the seam u = 0 of the cylinder. */
    spec e[] = {
        {128, cylinder, 0, 0, NULL},
        {110, "110,-1.,0.2,0.,1.,0.2,0.;", 0, 0, NULL},
        {110, "110,1.,0.2,0.,1.,0.8,0.;", 0, 0, NULL},
        {110, "110,1.,0.8,0.,-1.,0.8,0.;", 0, 0, NULL},
        {110, "110,-1.,0.8,0.,-1.,0.2,0.;", 0, 0, NULL},
        {102, "102,4,3,5,7,9;", 0, 0, NULL},
        {142, "142,0,1,11,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,13;", 0, 0, NULL},
        {128, cylinder, 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 9, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    const sc_surface *band = &s.surfaces[0], *whole = &s.surfaces[1];
    double u0, u1, v0, v1;
    sc_surface_domain(band, &u0, &u1, &v0, &v1);
    CHECK_NEAR(u0, -1, 1e-12);
    CHECK_NEAR(u1, 1, 1e-12);
    for (int i = 0; i <= 20; i++) {
        double u = -1 + 0.1 * i, v = 0.5, p[3], q[3];
        sc_surface_eval(band, u, v, p, NULL, NULL);
        sc_surface_eval(whole, u < 0 ? u + 4 : u, v, q, NULL, NULL);
        CHECK_NEAR(hypot(p[0], p[1]), 1, 1e-14);
        for (int d = 0; d < 3; d++)
            CHECK_NEAR(p[d], q[d], 1e-14);
    }
    CHECK_INT(s.dropped_loops, 0);
    sc_scene_free(&s);
}

TEST(iges_transform_colour_name)
{
    /* Plane -> 124 translate (1, 2, 3) -> 124 scale 2: x' = 2x + (2, 4, 6).
     * Colour from a 314 (percent) and from the standard table. */
    spec e[] = {
        {128, iges_plane_params(1), 3, -7, "PANEL"},
        {124, "124,1.,0.,0.,1.,0.,1.,0.,2.,0.,0.,1.,3.;", 5, 0, NULL},
        {124, "124,2.,0.,0.,0.,0.,2.,0.,0.,0.,0.,2.,0.;", 0, 0, NULL},
        {314, "314,100.,50.,0.,6Hsunset;", 0, 0, NULL},
        {128, iges_plane_params(1), 0, 3, NULL},
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 5, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    const double expect[12] = {2, 0, 0, 2, 0, 2, 0, 4, 0, 0, 2, 6};
    for (int i = 0; i < 12; i++)
        CHECK_NEAR(s.surfaces[0].xform[i], expect[i], 0);
    CHECK_NEAR(s.surfaces[0].color[0], 1.0, 1e-7);
    CHECK_NEAR(s.surfaces[0].color[1], 0.5, 1e-7);
    CHECK_NEAR(s.surfaces[0].color[2], 0.0, 1e-7);
    CHECK_STR(s.surfaces[0].name, "PANEL");
    CHECK_NEAR(s.surfaces[1].color[0], 0, 0);
    CHECK_NEAR(s.surfaces[1].color[1], 1, 0);
    CHECK_STR(s.surfaces[1].name, "iges9");
    sc_scene_free(&s);
}

TEST(iges_reversed_member_and_missing_pcurve)
{
    /* The composite's third line is written backwards: the loop still
     * closes. A second surface's 142 has no parameter-space curve: kept
     * untrimmed, counted, warned once. */
    spec e[] = {
        {128, iges_plane_params(1), 0, 0, NULL},
        {110, "110,0.2,0.2,0.,0.8,0.2,0.;", 0, 0, NULL},
        {110, "110,0.8,0.2,0.,0.8,0.8,0.;", 0, 0, NULL},
        {110, "110,0.2,0.8,0.,0.8,0.8,0.;", 0, 0, NULL},
        {110, "110,0.2,0.8,0.,0.2,0.2,0.;", 0, 0, NULL},
        {102, "102,4,3,5,7,9;", 0, 0, NULL},
        {142, "142,0,1,11,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,13;", 0, 0, NULL},
        {128, iges_plane_params(1), 0, 0, NULL},
        {110, "110,0.,0.,0.,1.,1.,0.;", 0, 0, NULL},
        {142, "142,0,17,0,0,1;", 0, 0, NULL},
        {144, "144,17,1,0,21;", 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(iges_read_specs(e, 12, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    CHECK_INT(s.dropped_loops, 0);
    CHECK_INT(s.repaired_gaps, 0);
    const sc_loop *l = &s.surfaces[0].loops[0];
    double p[2];
    iges_eval2(&l->curves[2], 0, p);
    CHECK_NEAR(p[0], 0.8, 0);
    CHECK_NEAR(p[1], 0.8, 0);
    CHECK_INT(s.surfaces[1].nloops, 0);
    CHECK_INT(iges_skipped_count(&s, "iges-142", "no-curve"), 1);
    CHECK_CONTAINS(iges_warnings, "t.igs:");
    CHECK_CONTAINS(iges_warnings, "entity 142 (D 21)");
    sc_scene_free(&s);
}

/* ---- bounded surfaces and B-rep faces ---- */

/* The plane over [0, 1]^2 with the square hole [0.4, 0.6]^2, as entities
 * 0..16 shared by the 143 and the B-rep file: the plane (D 1), the domain's
 * sides as 110s (D 3..9, counter-clockwise), the hole's sides P_i -> P_i+1
 * (P = (.4,.4), (.6,.4), (.6,.6), (.4,.6)) each split at its midpoint M_i and
 * written against the loop, P_i+1 -> M_i (D 11 + 4i) then M_i -> P_i
 * (D 13 + 4i), and the hole's sides in model space, also written against
 * the loop (D 27 + 2i). */
enum { HOLE_SHARED = 17 };
static void holed_plane(spec *e)
{
    static char text[16][128];
    static const double corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const double hole[4][2] = {{.4, .4}, {.6, .4}, {.6, .6}, {.4, .6}};
    e[0] = (spec){128, iges_plane_params(1), 0, 0, NULL};
    for (int i = 0; i < 4; i++) {
        const double *a = corner[i], *b = corner[(i + 1) % 4];
        const double *p = hole[i], *q = hole[(i + 1) % 4];
        double m[2] = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2};
        snprintf(text[i], sizeof text[i], "110,%g,%g,0.,%g,%g,0.;", a[0], a[1], b[0], b[1]);
        snprintf(text[4 + 2 * i], sizeof text[0], "110,%g,%g,0.,%g,%g,0.;", q[0], q[1], m[0], m[1]);
        snprintf(text[5 + 2 * i], sizeof text[0], "110,%g,%g,0.,%g,%g,0.;", m[0], m[1], p[0], p[1]);
        snprintf(text[12 + i], sizeof text[0], "110,%g,%g,0.,%g,%g,0.;", q[0], q[1], p[0], p[1]);
    }
    for (int k = 0; k < 16; k++)
        e[1 + k] = (spec){110, text[k], 0, 0, NULL};
}

/* The read face: one surface, the domain as outer loop (4 segments) and
 * the hole (8 segments) running P0 -> M0 -> P1 -> ... -> P0 once the
 * reversed edges are turned around, closed without repair; points in the
 * hole are trimmed away, points of the face kept. */
static void check_holed_face(const sc_scene *s)
{
    CHECK_INT(s->nsurfaces, 1);
    CHECK_INT(s->dropped_loops, 0);
    CHECK_INT(s->repaired_gaps, 0);
    if (s->nsurfaces != 1)
        return;
    const sc_surface *f = &s->surfaces[0];
    CHECK_INT(f->nloops, 2);
    int hole_curves = f->nloops == 2 ? f->loops[1].ncurves : 0;
    if (f->nloops == 2) {
        CHECK_INT(f->loops[0].is_hole, 0);
        CHECK_INT(f->loops[0].ncurves, 4);
        CHECK_INT(f->loops[1].is_hole, 1);
        CHECK_INT(hole_curves, 8);
    }
    static const double walk[9][2] = {{.4, .4}, {.5, .4}, {.6, .4}, {.6, .5}, {.6, .6},
                                      {.5, .6}, {.4, .6}, {.4, .5}, {.4, .4}};
    for (int i = 0; hole_curves == 8 && i < 8; i++) {
        const sc_curve *c = &f->loops[1].curves[i];
        double t0, t1, a[2], b[2];
        sc_curve_domain(c, &t0, &t1);
        iges_eval2(c, t0, a);
        iges_eval2(c, t1, b);
        CHECK_NEAR(a[0], walk[i][0], 1e-15);
        CHECK_NEAR(a[1], walk[i][1], 1e-15);
        CHECK_NEAR(b[0], walk[i + 1][0], 1e-15);
        CHECK_NEAR(b[1], walk[i + 1][1], 1e-15);
    }
    sc_trim *trim = NULL;
    sc_error err;
    CHECK_INT(sc_trim_prepare(f, &trim, &err), SC_OK);
    CHECK(trim != NULL);
    static const struct { double u, v; int kept; } cases[] = {
        {0.5, 0.5, 0},   {0.41, 0.41, 0}, {0.59, 0.45, 0}, {0.45, 0.59, 0}, {0.2, 0.2, 1},
        {0.5, 0.3, 1},   {0.7, 0.5, 1},   {0.5, 0.65, 1},  {0.39, 0.5, 1},  {0.95, 0.95, 1},
        {0.05, 0.61, 1},
    };
    for (size_t i = 0; trim && i < sizeof cases / sizeof cases[0]; i++)
        CHECK_INT(sc_trim_inside(trim, cases[i].u, cases[i].v), cases[i].kept);
    sc_trim_free(trim);
}

TEST(iges_bounded_surface_with_hole)
{
    /* 143 over the plane: the first 141 is the domain, the second the hole,
     * whose edges run against the boundary (SENSE = 2) with two
     * parameter-space curves each, the model-space curve shared. */
    spec e[HOLE_SHARED + 3];
    holed_plane(e);
    char hole[256];
    int at = snprintf(hole, sizeof hole, "141,1,2,1,4");
    for (int i = 0; i < 4; i++)
        at += snprintf(hole + at, sizeof hole - (size_t)at, ",%d,2,2,%d,%d", 27 + 2 * i,
                       11 + 4 * i, 13 + 4 * i);
    snprintf(hole + at, sizeof hole - (size_t)at, ";");
    e[HOLE_SHARED] = (spec){141, "141,1,2,1,4,3,1,1,3,5,1,1,5,7,1,1,7,9,1,1,9;", 0, 0, NULL};
    e[HOLE_SHARED + 1] = (spec){141, hole, 0, 0, NULL};
    e[HOLE_SHARED + 2] = (spec){143, "143,1,1,2,35,37;", 0, 0, NULL};
    sc_scene s;
    CHECK_INT(iges_read_specs(e, HOLE_SHARED + 3, &s), SC_OK);
    check_holed_face(&s);
    CHECK_INT(s.nskipped, 0);
    CHECK_STR(iges_warnings, "");
    sc_scene_free(&s);
}

TEST(iges_brep_face_with_hole)
{
    /* 186 -> 514 -> 510 -> 508 over the plane, with the 502 vertices and
     * 504 edges of a real solid. The hole's edges are used against their
     * direction (orientation flag 0) with two parameter-space curves each. */
    spec e[HOLE_SHARED + 7];
    holed_plane(e);
    char vertices[256], edges[256], outer[256], hole[256];
    int nv = snprintf(vertices, sizeof vertices, "502,8,0.,0.,0.,1.,0.,0.,1.,1.,0.,0.,1.,0.,"
                      ".4,.4,0.,.6,.4,0.,.6,.6,0.,.4,.6,0.;");
    int ne = snprintf(edges, sizeof edges, "504,8");
    int no = snprintf(outer, sizeof outer, "508,4");
    int nh = snprintf(hole, sizeof hole, "508,4");
    for (int i = 0; i < 4; i++) {
        ne += snprintf(edges + ne, sizeof edges - (size_t)ne, ",%d,35,%d,35,%d", 3 + 2 * i, 1 + i,
                       1 + (i + 1) % 4);
        no += snprintf(outer + no, sizeof outer - (size_t)no, ",0,37,%d,1,1,0,%d", 1 + i, 3 + 2 * i);
    }
    for (int i = 0; i < 4; i++) {
        ne += snprintf(edges + ne, sizeof edges - (size_t)ne, ",%d,35,%d,35,%d", 27 + 2 * i,
                       5 + (i + 1) % 4, 5 + i);
        nh += snprintf(hole + nh, sizeof hole - (size_t)nh, ",0,37,%d,0,2,0,%d,0,%d", 5 + i,
                       11 + 4 * i, 13 + 4 * i);
    }
    CHECK(nv < (int)sizeof vertices && ne + 1 < (int)sizeof edges);
    snprintf(edges + ne, sizeof edges - (size_t)ne, ";");
    snprintf(outer + no, sizeof outer - (size_t)no, ";");
    snprintf(hole + nh, sizeof hole - (size_t)nh, ";");
    e[HOLE_SHARED] = (spec){502, vertices, 0, 0, NULL};     /* D 35 */
    e[HOLE_SHARED + 1] = (spec){504, edges, 0, 0, NULL};    /* D 37 */
    e[HOLE_SHARED + 2] = (spec){508, outer, 0, 0, NULL};    /* D 39 */
    e[HOLE_SHARED + 3] = (spec){508, hole, 0, 0, NULL};     /* D 41 */
    e[HOLE_SHARED + 4] = (spec){510, "510,1,2,1,39,41;", 0, 0, NULL}; /* D 43 */
    e[HOLE_SHARED + 5] = (spec){514, "514,1,43,1;", 0, 0, NULL};      /* D 45 */
    e[HOLE_SHARED + 6] = (spec){186, "186,45,1,0;", 0, 0, NULL};
    sc_scene s;
    CHECK_INT(iges_read_specs(e, HOLE_SHARED + 7, &s), SC_OK);
    check_holed_face(&s);
    CHECK_INT(s.nskipped, 0);
    CHECK_STR(iges_warnings, "");
    sc_scene_free(&s);
}

/* Colour number 0 in directory field 13 means "none assigned": such
 * surfaces get the scene's default colour, not black. */
TEST(iges_unassigned_colour_is_default)
{
    REQUIRE_DATA("iges/gpucast_part.igs");
    sc_scene scene, blank;
    sc_error err;
    CHECK_INT(sc_read_scene(test_data("iges/gpucast_part.igs"), &scene, &err), SC_OK);
    sc_scene_init(&blank);
    const sc_surface *fresh = sc_scene_add_surface(&blank);
    CHECK(scene.nsurfaces > 0);
    for (int i = 0; i < scene.nsurfaces; i++)
        for (int c = 0; c < 3; c++)
            CHECK_NEAR(scene.surfaces[i].color[c], fresh->color[c], 0);
    sc_scene_free(&blank);
    sc_scene_free(&scene);
}
