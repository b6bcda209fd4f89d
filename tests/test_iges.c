/* test_iges.c — the IGES reader: surface counts and facts of the real CAD
 * files (known from the data README), exact conversion of trim curves and
 * domains checked against analytic shapes in small IGES files written
 * here, and malformed files that must be refused with the entity named or
 * read leniently. */
#include "test.h"

#include <stdlib.h>
#include <unistd.h>

#include "io.h"
#include "nurbs.h"
#include "trim.h"

static const char *occt_dir = "/usr/share/opencascade/data/iges";

/* Warnings go to a buffer so that tests can check them and stay quiet. */
static char warnings[4096];
static void capture(sc_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level >= SC_LOG_WARN && strlen(warnings) + strlen(msg) + 2 < sizeof warnings) {
        strcat(warnings, msg);
        strcat(warnings, "\n");
    }
}

static int read_path(const char *path, sc_scene *scene, sc_error *err)
{
    warnings[0] = 0;
    sc_set_logger(capture, NULL);
    int status = sc_read_scene(path, scene, err);
    sc_set_logger(NULL, NULL);
    return status;
}

static int read_text(const char *text, sc_scene *scene, sc_error *err)
{
    warnings[0] = 0;
    memset(err, 0, sizeof *err);
    sc_set_logger(capture, NULL);
    int status = sc_read_iges(text, strlen(text), "t.igs", scene, err);
    sc_set_logger(NULL, NULL);
    return status;
}

static const char *error_text(const sc_error *err)
{
    static char buf[1024];
    return sc_error_text(err, buf, sizeof buf);
}

static int skipped_count(const sc_scene *s, const char *type, const char *reason)
{
    for (int i = 0; i < s->nskipped; i++)
        if (!strcmp(s->skipped[i].type, type) && !strcmp(s->skipped[i].reason, reason))
            return s->skipped[i].count;
    return 0;
}

/* ---- writing small IGES files ---- */

typedef struct spec {
    int type;
    const char *params; /* free-format parameters ending with ';' */
    int xform;          /* directory field 7 */
    int color;          /* directory field 13 */
    const char *label;
} spec;

static void append(char **buf, size_t *len, const char *text72, char section, int seq)
{
    char record[96];
    snprintf(record, sizeof record, "%-72.72s%c%7d\n", text72, section, seq % 10000000);
    *buf = realloc(*buf, *len + 82);
    memcpy(*buf + *len, record, 82); /* 81 characters and the NUL */
    *len += 81;
}

/* A fixed-format file: one S, one G record, two D records per entity, the
 * parameters cut into 64-column P records. Entity k has DE 2k+1; its first
 * P record is at line 3 + 2n + (P records before it). */
static char *make_iges(const spec *e, int n)
{
    char *buf = NULL, line[128];
    size_t len = 0;
    append(&buf, &len, "splinecast test file", 'S', 1);
    append(&buf, &len, "1H,,1H;,4Htest,5Ht.igs,;", 'G', 1);
    int pline = 1, *first = calloc((size_t)n, sizeof(int)), *count = calloc((size_t)n, sizeof(int));
    for (int k = 0; k < n; k++) {
        first[k] = pline;
        count[k] = ((int)strlen(e[k].params) + 63) / 64;
        pline += count[k];
    }
    for (int k = 0; k < n; k++) {
        snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d%8d%8d%8s", e[k].type, first[k], 0, 0, 0,
                 0, e[k].xform, 0, "00000000");
        append(&buf, &len, line, 'D', 2 * k + 1);
        snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8s%8s%8s%8d", e[k].type, 0, e[k].color,
                 count[k], 0, "", "", e[k].label ? e[k].label : "", 0);
        append(&buf, &len, line, 'D', 2 * k + 2);
    }
    int seq = 1;
    for (int k = 0; k < n; k++) {
        const char *p = e[k].params;
        for (int c = 0; c < count[k]; c++) {
            snprintf(line, sizeof line, "%-64.64s%8d", p + 64 * c, 2 * k + 1);
            append(&buf, &len, line, 'P', seq++);
        }
    }
    snprintf(line, sizeof line, "S%7dG%7dD%7dP%7d", 1, 1, 2 * n, seq - 1);
    append(&buf, &len, line, 'T', 1);
    free(first);
    free(count);
    return buf;
}

/* Reads the file make_iges writes for `e`; prints the error on failure. */
static int read_specs(const spec *e, int n, sc_scene *scene)
{
    char *text = make_iges(e, n);
    sc_error err;
    int status = read_text(text, scene, &err);
    free(text);
    if (status)
        fprintf(stderr, "  %s\n", error_text(&err));
    return status;
}

/* "t.igs:N:" for the line of the file holding `needle`. */
static const char *position_of(const char *text, const char *needle)
{
    static char buf[32];
    const char *at = strstr(text, needle);
    int line = 1;
    for (const char *c = text; at && c < at; c++)
        line += *c == '\n';
    snprintf(buf, sizeof buf, "t.igs:%d:", at ? line : -1);
    return buf;
}

/* The plane (u, v, 0) over [0, size]^2, bilinear. */
static char *plane_params(double size)
{
    static char buf[8][256];
    static int next;
    char *b = buf[next++ % 8];
    snprintf(b, 256, "128,1,1,1,1,0,0,1,0,0,0.,0.,%g,%g,0.,0.,%g,%g,1.,1.,1.,1.,"
             "0.,0.,0.,%g,0.,0.,0.,%g,0.,%g,%g,0.,0.,%g,0.,%g;", size, size, size, size, size,
             size, size, size, size, size);
    return b;
}

static void eval2(const sc_curve *c, double t, double p[2]) { sc_curve_eval(c, t, p, NULL); }

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
        int status = read_path(test_data(facts[i].file), &s, &err);
        if (status)
            fprintf(stderr, "  %s\n", error_text(&err));
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
    CHECK_INT(read_path(path, &s, &err), SC_OK);
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
    CHECK_INT(read_path(path, &s, &err), SC_OK);
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
    CHECK_INT(read_path(test_data("iges/bug24012_face.igs"), &s, &err), SC_OK);
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
        eval2(k, k->knots[0], p);
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
    CHECK_INT(read_path(test_data("iges/OCC26138_Torus.igs"), &s, &err), SC_OK);
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

TEST(iges_brep_faces_untrimmed_and_coloured)
{
    REQUIRE_DATA("iges/occ22470.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(read_path(test_data("iges/occ22470.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 18);
    int rational = 0, grey = 0;
    for (int i = 0; i < s.nsurfaces; i++) {
        CHECK_INT(s.surfaces[i].nloops, 0);
        rational += s.surfaces[i].rational;
        grey += s.surfaces[i].color[0] == 0.8f && s.surfaces[i].color[1] == 0.8f;
    }
    CHECK_INT(rational, 14);
    CHECK_INT(grey, 0); /* every face has a 314 colour */
    CHECK_INT(skipped_count(&s, "iges-508", "no-parameter-curve"), 18);
    /* One warning for the file, not one per face. */
    const char *first = strstr(warnings, "model-space");
    CHECK(first != NULL);
    CHECK(strstr(first + 1, "model-space") == NULL);
    sc_scene_free(&s);
}

TEST(iges_teapot_leniency)
{
    REQUIRE_DATA("iges/gpucast_teapot.igs");
    sc_scene s, bpt;
    sc_error err;
    CHECK_INT(read_path(test_data("iges/gpucast_teapot.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 32);
    for (int i = 0; i < s.nsurfaces; i++) {
        CHECK_INT(s.surfaces[i].deg_u, 3);
        CHECK_INT(s.surfaces[i].deg_v, 3);
        CHECK_INT(s.surfaces[i].nloops, 0);
    }
    /* The same teapot as the .bpt file, read by another reader. */
    CHECK_INT(read_path(TEST_TEAPOT32, &bpt, &err), SC_OK);
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
    CHECK_INT(read_path(test_data("iges/Disc.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 0);
    CHECK_INT(skipped_count(&s, "iges-408", "unsupported"), 2);
    CHECK_INT(skipped_count(&s, "iges-308", "unsupported"), 2);
    sc_scene_free(&s);
}

TEST(iges_bad_header_read_leniently)
{
    REQUIRE_DATA("iges/bad_header.igs");
    sc_scene s;
    sc_error err;
    CHECK_INT(read_path(test_data("iges/bad_header.igs"), &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    const sc_surface *f = &s.surfaces[0];
    CHECK_INT(f->deg_u, 1);
    CHECK_INT(f->deg_v, 2);
    CHECK_INT(f->nloops, 1);
    /* The outer loop is the rectangle [0.3, 0.7] x [0, 1] of four lines. */
    CHECK_INT(f->loops[0].ncurves, 4);
    double p[2];
    eval2(&f->loops[0].curves[0], 0, p);
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
    CHECK_CONTAINS(out, "skipped iges-508 18 no-parameter-curve");
    free(out);
    free(err);
}

/* ---- exact conversion, on small files ---- */

TEST(iges_arcs_exact)
{
    /* A full circle as the outer loop of one plane; on a second plane a
     * circle moved by a 124 (shear y += 0.1 z, translation x += 0.1) at
     * ZT = 1, as a hole with the domain as outer boundary. */
    char *plane = plane_params(1);
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
    CHECK_INT(read_specs(e, 11, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    const sc_curve *c = &s.surfaces[0].loops[0].curves[0];
    CHECK_INT(c->degree, 2);
    CHECK_INT(c->ncp, 9); /* four quarter arcs */
    double t0, t1, p[2];
    sc_curve_domain(c, &t0, &t1);
    for (int i = 0; i <= 64; i++) {
        eval2(c, t0 + (t1 - t0) * i / 64, p);
        CHECK_NEAR(hypot(p[0] - 0.5, p[1] - 0.5), 0.25, 1e-14);
    }
    eval2(c, t0, p);
    CHECK_NEAR(p[0], 0.75, 1e-15);
    eval2(c, t0 + (t1 - t0) / 4, p); /* counter-clockwise: a quarter on */
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
        eval2(c, t0 + (t1 - t0) * i / 48, p);
        CHECK_NEAR(hypot(p[0] - 0.6, p[1] - 0.6), 0.25, 1e-14);
    }
    eval2(c, t1, p);
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
        {128, plane_params(5), 0, 0, NULL},
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
    CHECK_INT(read_specs(e, 9, &s), SC_OK);
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
        eval2(c, t, p);
        CHECK_NEAR(p[0], t - 2, 1e-12);
        CHECK_NEAR(p[1], 0, 1e-12);
    }
    sc_scene_free(&s);

    /* The sub-range copy, as the bottom edge of a loop of its own. */
    spec e2[] = {
        {128, plane_params(5), 0, 0, NULL},
        {126, part, 0, 0, NULL},
        {110, "110,3.5,0.,0.,2.5,1.,0.;", 0, 0, NULL},
        {110, "110,2.5,1.,0.,1.5,0.,0.;", 0, 0, NULL},
        {102, "102,3,3,5,7;", 0, 0, NULL},
        {142, "142,0,1,9,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,11;", 0, 0, NULL},
    };
    CHECK_INT(read_specs(e2, 7, &s), SC_OK);
    c = &s.surfaces[0].loops[0].curves[0];
    sc_curve_domain(c, &t0, &t1);
    CHECK_NEAR(t0, 3.5, 1e-12);
    CHECK_NEAR(t1, 5.5, 1e-12);
    eval2(c, t0, p);
    CHECK_NEAR(p[0], 1.5, 1e-12);
    eval2(c, t1, p);
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
    CHECK_INT(read_specs(e, 2, &s), SC_OK);
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
    CHECK_INT(read_specs(e, 9, &s), SC_OK);
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
        {128, plane_params(1), 3, -7, "PANEL"},
        {124, "124,1.,0.,0.,1.,0.,1.,0.,2.,0.,0.,1.,3.;", 5, 0, NULL},
        {124, "124,2.,0.,0.,0.,0.,2.,0.,0.,0.,0.,2.,0.;", 0, 0, NULL},
        {314, "314,100.,50.,0.,6Hsunset;", 0, 0, NULL},
        {128, plane_params(1), 0, 3, NULL},
    };
    sc_scene s;
    CHECK_INT(read_specs(e, 5, &s), SC_OK);
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
        {128, plane_params(1), 0, 0, NULL},
        {110, "110,0.2,0.2,0.,0.8,0.2,0.;", 0, 0, NULL},
        {110, "110,0.8,0.2,0.,0.8,0.8,0.;", 0, 0, NULL},
        {110, "110,0.2,0.8,0.,0.8,0.8,0.;", 0, 0, NULL},
        {110, "110,0.2,0.8,0.,0.2,0.2,0.;", 0, 0, NULL},
        {102, "102,4,3,5,7,9;", 0, 0, NULL},
        {142, "142,0,1,11,0,2;", 0, 0, NULL},
        {144, "144,1,1,0,13;", 0, 0, NULL},
        {128, plane_params(1), 0, 0, NULL},
        {110, "110,0.,0.,0.,1.,1.,0.;", 0, 0, NULL},
        {142, "142,0,17,0,19,1;", 0, 0, NULL},
        {144, "144,17,1,0,21;", 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(read_specs(e, 12, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 2);
    CHECK_INT(s.dropped_loops, 0);
    CHECK_INT(s.repaired_gaps, 0);
    const sc_loop *l = &s.surfaces[0].loops[0];
    double p[2];
    eval2(&l->curves[2], 0, p);
    CHECK_NEAR(p[0], 0.8, 0);
    CHECK_NEAR(p[1], 0.8, 0);
    CHECK_INT(s.surfaces[1].nloops, 0);
    CHECK_INT(skipped_count(&s, "iges-142", "no-parameter-curve"), 1);
    CHECK_CONTAINS(warnings, "t.igs:");
    CHECK_CONTAINS(warnings, "entity 142 (D 21)");
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
    e[0] = (spec){128, plane_params(1), 0, 0, NULL};
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
        eval2(c, t0, a);
        eval2(c, t1, b);
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
    CHECK_INT(read_specs(e, HOLE_SHARED + 3, &s), SC_OK);
    check_holed_face(&s);
    CHECK_INT(s.nskipped, 0);
    CHECK_STR(warnings, "");
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
    CHECK_INT(read_specs(e, HOLE_SHARED + 7, &s), SC_OK);
    check_holed_face(&s);
    CHECK_INT(s.nskipped, 0);
    CHECK_STR(warnings, "");
    sc_scene_free(&s);
}

/* ---- malformed files ---- */

/* Reads text that must fail; checks that the message holds every needle
 * (the entity and its directory number, the position). */
static int refused(const char *text, const char *needle1, const char *needle2)
{
    sc_scene s;
    sc_error err;
    if (read_text(text, &s, &err) == SC_OK) {
        fprintf(stderr, "  read a malformed file without an error\n");
        sc_scene_free(&s);
        return 0;
    }
    const char *msg = error_text(&err);
    if (s.nsurfaces != 0 || s.surfaces != NULL)
        return 0;
    if ((needle1 && !strstr(msg, needle1)) || (needle2 && !strstr(msg, needle2))) {
        fprintf(stderr, "  message \"%s\" lacks \"%s\" / \"%s\"\n", msg, needle1,
                needle2 ? needle2 : "");
        return 0;
    }
    return 1;
}

static const spec good[] = {
    {128, NULL, 0, 0, NULL}, /* plane, filled in */
    {110, "110,0.2,0.2,0.,0.8,0.5,0.;", 0, 0, NULL},
    {110, "110,0.8,0.5,0.,0.2,0.2,0.;", 0, 0, NULL},
    {102, "102,2,3,5;", 0, 0, NULL},
    {142, "142,0,1,7,0,2;", 0, 0, NULL},
    {144, "144,1,1,0,9;", 0, 0, NULL},
};
enum { NGOOD = 6 };

/* The good file with entity k's parameters (and optionally its directory
 * field 7) replaced. */
static char *variant(int k, const char *params, int xform)
{
    spec e[NGOOD];
    memcpy(e, good, sizeof e);
    e[0].params = plane_params(1);
    if (params) {
        e[k].params = params;
        e[k].type = atoi(params);
    }
    if (xform)
        e[k].xform = xform;
    return make_iges(e, NGOOD);
}

TEST(iges_malformed_truncated)
{
    char *text = variant(0, NULL, 0);
    sc_scene s;
    sc_error err;
    CHECK_INT(read_text(text, &s, &err), SC_OK); /* the base file is good */
    sc_scene_free(&s);
    /* Cut after the 144's first record, before its terminator. */
    char *cut = strstr(text, "144,1,1,0,9;");
    CHECK(cut != NULL);
    cut[11] = ',';
    strcpy(strchr(cut, '\n') + 1, "");
    CHECK(refused(text, "entity 144 (D 11)", "ends before the record delimiter"));
    CHECK(refused(text, position_of(text, "144,1,1,0,9,"), NULL));
    /* Cut inside a record. */
    cut[8] = 0;
    CHECK(refused(text, position_of(text, "144,1,1,"), "record of 8 columns"));
    /* Cut inside the directory: an odd number of D records. */
    free(text);
    text = variant(0, NULL, 0);
    char *d = strstr(text, "     110       0");
    CHECK(d != NULL);
    strcpy(d, "");
    CHECK(refused(text, "odd number", NULL));
    free(text);
}

TEST(iges_malformed_pointer_out_of_range)
{
    char *text = variant(5, "144,99,1,0,9;", 0);
    CHECK(refused(text, "entity 144 (D 11): parameter 1: pointer 99",
                  position_of(text, "144,99")));
    free(text);
    /* A parameter data pointer beyond the P section. */
    text = variant(0, NULL, 0);
    char *d = strstr(text, "D      3\n");
    CHECK(d != NULL);
    memcpy(d - 72 + 8, "     999", 8); /* field 2 of DE 3 */
    CHECK(refused(text, "entity 110 (D 3)", "outside the P section"));
    free(text);
    /* A transformation pointer to something that is not a 124. */
    text = variant(0, NULL, 5);
    CHECK(refused(text, "entity 128 (D 1)", "not to a 124"));
    free(text);
}

TEST(iges_unused_entities_never_fail)
{
    /* Next to a good plane: a 142 that nothing uses, pointing nowhere, and
     * a 140 offset surface (unsupported) whose surface pointer is broken.
     * Neither is used by a surface, so the file reads; the 140 is counted. */
    spec e[] = {
        {128, plane_params(1), 0, 0, NULL},
        {142, "142,0,999,0,0,1;", 0, 0, NULL},
        {140, "140,0.,0.,1.,1.,999;", 0, 0, NULL},
    };
    sc_scene s;
    CHECK_INT(read_specs(e, 3, &s), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_INT(skipped_count(&s, "iges-140", "unsupported"), 1);
    sc_scene_free(&s);
    /* The same 142 used as a trim loop: now it matters and fails the file. */
    char *text = variant(4, "142,0,999,7,0,2;", 0);
    CHECK(refused(text, "entity 142 (D 9): parameter 2: pointer 999",
                  position_of(text, "142,0,999")));
    free(text);
}

TEST(iges_malformed_reference_cycle)
{
    /* A composite that contains itself. */
    char *text = variant(3, "102,2,3,7;", 0);
    CHECK(refused(text, "entity 102 (D 7)", "cycle"));
    free(text);
    /* Transformation matrices that refer to each other. */
    spec e[] = {
        {128, plane_params(1), 3, 0, NULL},
        {124, "124,1.,0.,0.,0.,0.,1.,0.,0.,0.,0.,1.,0.;", 5, 0, NULL},
        {124, "124,1.,0.,0.,0.,0.,1.,0.,0.,0.,0.,1.,0.;", 3, 0, NULL},
    };
    text = make_iges(e, 3);
    CHECK(refused(text, "entity 128 (D 1)", "cycle"));
    free(text);
}

TEST(iges_malformed_huge_counts)
{
    char *text = variant(3, "102,1000000000,3,5;", 0);
    CHECK(refused(text, "entity 102 (D 7)", "counts larger than the data"));
    free(text);
    text = variant(0, "128,100000,100000,1,1,0,0,1,0,0,0.,0.,1.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1)", "larger than the data"));
    free(text);
    /* A 126 whose point count runs past its data. */
    text = variant(1, "126,50,3,0,0,1,0,0.,0.,0.,0.,1.,1.,1.,1.;", 0);
    CHECK(refused(text, "entity 126 (D 3)", "needs"));
    free(text);
}

TEST(iges_malformed_hollerith)
{
    /* In the parameter data of a colour the surface uses: fatal. */
    spec e[] = {
        {128, plane_params(1), 0, -3, NULL},
        {314, "314,10.,20.,30.,99Habc;", 0, 0, NULL},
    };
    char *text = make_iges(e, 2);
    CHECK(refused(text, "entity 314 (D 3)", "Hollerith"));
    free(text);
    /* A number where a Hollerith string follows the wrong way. */
    text = variant(1, "110,3Habcdef,0.2,0.,0.8,0.5,0.;", 0);
    CHECK(refused(text, "entity 110 (D 3)", "Hollerith"));
    free(text);
    /* In the global section: reported, the file is read. */
    text = variant(0, NULL, 0);
    char *g = strstr(text, "1H,,1H;,4Htest,5Ht.igs,;");
    CHECK(g != NULL);
    memcpy(g, "1H,,1H;,99Htest,5Ht.igs", 23);
    sc_scene s;
    sc_error err;
    CHECK_INT(read_text(text, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_CONTAINS(warnings, "t.igs:2: global section");
    sc_scene_free(&s);
    free(text);
    /* A count with extra digits is still a count, not plain text. */
    text = variant(0, NULL, 0);
    g = strstr(text, "1H,,1H;,4Htest,5Ht.igs,;");
    CHECK(g != NULL);
    const char *longer = "1H,,1H;,99999HOpen,5Ht.igs,;";
    memcpy(g, longer, strlen(longer));
    CHECK_INT(read_text(text, &s, &err), SC_OK);
    CHECK_INT(s.nsurfaces, 1);
    CHECK_CONTAINS(warnings, "t.igs:2: global section: a Hollerith string");
    sc_scene_free(&s);
    free(text);
}

TEST(iges_malformed_binary_and_not_iges)
{
    char junk[300];
    unsigned long long state = 7;
    for (size_t i = 0; i < sizeof junk; i++)
        junk[i] = (char)(1 + test_rand(&state) * 254);
    junk[sizeof junk - 1] = 0;
    sc_scene s;
    sc_error err;
    CHECK_INT(read_text(junk, &s, &err), SC_FAIL);
    CHECK_CONTAINS(error_text(&err), "t.igs:");
    CHECK_INT(s.nsurfaces, 0);
    /* Text, but not IGES. */
    CHECK(refused("v 0 0 0\nv 1 0 0\n", "t.igs:1:", "record of"));
    char obj[200];
    memset(obj, 'x', 100);
    obj[100] = 0;
    CHECK(refused(obj, "t.igs:1:", "column 73"));
    CHECK(refused("", "empty", NULL));
}

TEST(iges_malformed_missing_sections)
{
    /* S and G only: no directory. */
    char *text = variant(0, NULL, 0);
    char *d = strstr(text, "     128");
    CHECK(d != NULL);
    *d = 0;
    CHECK(refused(text, "no directory section", NULL));
    free(text);
    /* No P section: every entity's parameters are missing. */
    text = variant(0, NULL, 0);
    char *p = strstr(text, "128,1,1,");
    CHECK(p != NULL);
    *p = 0;
    CHECK(refused(text, "outside the P section", "(D "));
    free(text);
    /* Sections out of order. */
    spec e[] = {{128, plane_params(1), 0, 0, NULL}};
    text = make_iges(e, 1);
    char *g = strstr(text, "1H,,");
    char *line2 = strstr(g, "\n") + 1; /* the first D record */
    char save[81];
    memcpy(save, g, 81);
    memmove(g, line2, 81);
    memcpy(g + 81, save, 81);
    CHECK(refused(text, "t.igs:3:", "order"));
    free(text);
}

TEST(iges_malformed_degree_and_numbers)
{
    /* Degree 3 with 2 x 2 control points. */
    char *text = variant(0, "128,1,1,3,1,0,0,1,0,0,0.,0.,0.,0.,1.,1.,1.,1.,0.,0.,1.,1.,1.,1.,1.,"
                            "1.,0.,0.,0.,1.,0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1): degree 3 x 1 needs at least 4 x 2",
                  position_of(text, "128,1,1,3,1")));
    free(text);
    /* Decreasing knots. */
    text = variant(0, "128,1,1,1,1,0,0,1,0,0,0.,1.,0.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,"
                      "0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1)", "decrease"));
    free(text);
    /* A number that overflows. */
    text = variant(1, "110,1.E999,0.2,0.,0.8,0.5,0.;", 0);
    CHECK(refused(text, "entity 110 (D 3)", "not a finite number"));
    free(text);
    /* An integer beyond what any count or pointer can be. */
    text = variant(3, "102,2000000000,3,5;", 0);
    CHECK(refused(text, "entity 102 (D 7): parameter 1: integer 2000000000 is out of range",
                  position_of(text, "102,2000000000")));
    free(text);
    /* Zero weight on a rational surface. */
    text = variant(0, "128,1,1,1,1,0,0,0,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,0.,1.,1.,0.,0.,0.,1.,"
                      "0.,0.,0.,1.,0.,1.,1.,0.,0.,1.,0.,1.;", 0);
    CHECK(refused(text, "entity 128 (D 1)", "weight 1"));
    free(text);
    /* A loop pointer to the wrong kind of entity. */
    text = variant(5, "144,1,1,0,7;", 0);
    CHECK(refused(text, "entity 144 (D 11)", "expected a 142"));
    free(text);
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
