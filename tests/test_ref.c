/* test_ref.c — the CPU reference and its companions: camera, exact
 * trimming and accuracy metrics (AOV and PNG files and the `ref` / `diff`
 * commands: test_ref_files.c). The
 * scenes are built here from exact shapes (a rational sphere, planes, a
 * square with a hole bounded by rational circular arcs), so every expected
 * value comes from analytic geometry, not from the code under test. */
#include "test.h"


#include "imgdiff.h"
#include "io.h"
#include "refcast.h"

static const double sqrt_half = 0.70710678118654752440;

/* ---------------------------------------------------------- scenes -- */

static void set_knots(double *knots, const double *values, int n)
{
    memcpy(knots, values, sizeof(double) * (size_t)n);
}

/* A unit sphere as one rational biquadratic NURBS surface (a full circle in
 * u times a half circle from pole to pole in v), placed by its transform at
 * centre c with radius r. */
static void add_sphere(sc_scene *scene, const double c[3], double r)
{
    static const double circle[9][3] = {{1, 0, 1}, {1, 1, 0}, {0, 1, 1}, {-1, 1, 0}, {-1, 0, 1},
                                        {-1, -1, 0}, {0, -1, 1}, {1, -1, 0}, {1, 0, 1}};
    static const double half[5][3] = {{0, -1, 1}, {1, -1, 0}, {1, 0, 1}, {1, 1, 0}, {0, 1, 1}};
    static const double ku[12] = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
    static const double kv[8] = {0, 0, 0, 0.5, 0.5, 1, 1, 1};
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, 2, 2, 9, 5);
    set_knots(s->knots_u, ku, 12);
    set_knots(s->knots_v, kv, 8);
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 9; i++) {
            /* The third column marks corner points (weight 1) and middle
             * points (weight sqrt(1/2)). */
            double wu = circle[i][2] ? 1.0 : sqrt_half, wv = half[j][2] ? 1.0 : sqrt_half;
            double w = wu * wv;
            double *p = &s->cp[4 * (j * 9 + i)];
            p[0] = circle[i][0] * half[j][0] * w;
            p[1] = circle[i][1] * half[j][0] * w;
            p[2] = half[j][1] * w;
            p[3] = w;
        }
    double xform[12] = {r, 0, 0, c[0], 0, r, 0, c[1], 0, 0, r, c[2]};
    memcpy(s->xform, xform, sizeof xform);
    sc_surface_update_rational(s);
}

/* A bicubic patch lying in the plane z = z0 over the square [-1, 1]²: edge
 * control points evenly on the edges, inner ones moved within the plane so
 * that the parametrisation is not trivial. */
static void add_planar_bicubic(sc_scene *scene, double z0)
{
    static const double k[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, 3, 3, 4, 4);
    set_knots(s->knots_u, k, 8);
    set_knots(s->knots_v, k, 8);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *p = &s->cp[4 * (j * 4 + i)];
            int inner = i > 0 && i < 3 && j > 0 && j < 3;
            p[0] = -1.0 + 2.0 * i / 3.0 + (inner ? 0.15 * (j - 1.5) : 0.0);
            p[1] = -1.0 + 2.0 * j / 3.0 + (inner ? -0.1 * (i - 1.5) : 0.0);
            p[2] = z0;
            p[3] = 1.0;
        }
    sc_surface_update_rational(s);
}

static void make_line(sc_curve *c, double u0, double v0, double u1, double v1)
{
    static const double k[4] = {0, 0, 1, 1};
    sc_curve_alloc(c, 2, 1, 2);
    set_knots(c->knots, k, 4);
    double cp[6] = {u0, v0, 1, u1, v1, 1};
    memcpy(c->cp, cp, sizeof cp);
}

/* A circle of centre (cu, cv) and radius r as four rational quadratic
 * arcs (weights 1, sqrt(1/2), 1), the first starting at angle a0. */
static void make_circle_loop(sc_loop *loop, double cu, double cv, double r, double a0, int is_hole)
{
    static const double k[6] = {0, 0, 0, 1, 1, 1};
    loop->is_hole = is_hole;
    loop->ncurves = 4;
    loop->curves = sc_alloc(4, sizeof(sc_curve));
    for (int q = 0; q < 4; q++) {
        double a = a0 + q * M_PI / 2, b = a + M_PI / 2, m = 0.5 * (a + b);
        sc_curve *c = &loop->curves[q];
        sc_curve_alloc(c, 2, 2, 3);
        set_knots(c->knots, k, 6);
        /* The middle control point is where the end tangents meet, at
         * distance r / cos(45°) from the centre. */
        double cp[9] = {cu + r * cos(a), cv + r * sin(a), 1,
                        (cu + r * cos(m) / sqrt_half) * sqrt_half, (cv + r * sin(m) / sqrt_half) * sqrt_half,
                        sqrt_half, cu + r * cos(b), cv + r * sin(b), 1};
        memcpy(c->cp, cp, sizeof cp);
    }
    /* Consecutive arcs meet exactly. */
    for (int q = 0; q < 4; q++) {
        sc_curve *c = &loop->curves[q], *next = &loop->curves[(q + 1) % 4];
        next->cp[0] = c->cp[6];
        next->cp[1] = c->cp[7];
    }
}

static void make_polygon_loop(sc_loop *loop, const double (*pts)[2], int n, int is_hole)
{
    loop->is_hole = is_hole;
    loop->ncurves = n;
    loop->curves = sc_alloc((size_t)n, sizeof(sc_curve));
    for (int k = 0; k < n; k++)
        make_line(&loop->curves[k], pts[k][0], pts[k][1], pts[(k + 1) % n][0], pts[(k + 1) % n][1]);
}

/* A bilinear plane z = 0 mapping (u, v) in [0, 1]² to x = 4u - 2,
 * y = 2v - 1, trimmed to the unit square minus a circle of radius 0.3
 * around (0.5, 0.5) whose arcs start at angle a0. */
static sc_surface *add_holed_square(sc_scene *scene, double a0)
{
    static const double k[4] = {0, 0, 1, 1};
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, 1, 1, 2, 2);
    set_knots(s->knots_u, k, 4);
    set_knots(s->knots_v, k, 4);
    double cp[16] = {-2, -1, 0, 1, 2, -1, 0, 1, -2, 1, 0, 1, 2, 1, 0, 1};
    memcpy(s->cp, cp, sizeof cp);
    sc_surface_update_rational(s);
    static const double square[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    s->nloops = 2;
    s->loops = sc_alloc(2, sizeof(sc_loop));
    make_polygon_loop(&s->loops[0], square, 4, 0);
    make_circle_loop(&s->loops[1], 0.5, 0.5, 0.3, a0, 1);
    return s;
}

/* An untrimmed plane z = z0 over [-3, 3]². */
static void add_floor(sc_scene *scene, double z0)
{
    static const double k[4] = {0, 0, 1, 1};
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, 1, 1, 2, 2);
    set_knots(s->knots_u, k, 4);
    set_knots(s->knots_v, k, 4);
    double cp[16] = {-3, -3, z0, 1, 3, -3, z0, 1, -3, 3, z0, 1, 3, 3, z0, 1};
    memcpy(s->cp, cp, sizeof cp);
    sc_surface_update_rational(s);
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* --------------------------------------------------------- camera -- */

TEST(ref_camera_parse_format)
{
    sc_camera cam = {.width = 10, .height = 10}, back = cam;
    sc_error err;
    CHECK_INT(sc_camera_parse("0.1,-3.3333333333333335,1e-7,2,0,1.5,33.3", &cam, &err), SC_OK);
    CHECK(cam.eye[0] == 0.1 && cam.eye[1] == -3.3333333333333335 && cam.eye[2] == 1e-7);
    CHECK(cam.fovy_deg == 33.3);
    char text[512];
    sc_camera_format(&cam, text, sizeof text);
    CHECK_INT(sc_camera_parse(text, &back, &err), SC_OK);
    CHECK(!memcmp(cam.eye, back.eye, sizeof cam.eye));
    CHECK(!memcmp(cam.target, back.target, sizeof cam.target));
    CHECK(cam.fovy_deg == back.fovy_deg);
    CHECK_INT(sc_camera_parse("1,2,3", &cam, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "7");
    CHECK_INT(sc_camera_parse("1,2,3,4,5,6,180", &cam, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "field of view");
    CHECK_INT(sc_camera_parse("1,2,x,4,5,6,30", &cam, &err), SC_FAIL);
    CHECK_INT(sc_camera_parse("1,2,3,1,2,3,30", &cam, &err), SC_FAIL);
    CHECK_INT(sc_camera_parse("1,2,3,4,5,6,30,7", &cam, &err), SC_FAIL);
}

TEST(ref_camera_frame_and_rays)
{
    sc_camera cam = {.eye = {0, 0, 5}, .target = {0, 0, 0}, .fovy_deg = 40, .width = 64, .height = 48};
    double f[3], r[3], u[3];
    sc_camera_frame(&cam, f, r, u);
    /* Looking down z: up is +y. */
    CHECK_NEAR(u[1], 1.0, 1e-15);
    CHECK_NEAR(f[2], -1.0, 1e-15);
    CHECK_NEAR(r[0], 1.0, 1e-15);
    /* A general view: +z up, frame orthonormal. */
    sc_camera side = {.eye = {3, -4, 2}, .target = {0, 1, 0.5}, .fovy_deg = 30, .width = 8, .height = 8};
    sc_camera_frame(&side, f, r, u);
    CHECK(u[2] > 0.0);
    CHECK_NEAR(dot3(f, r), 0.0, 1e-15);
    CHECK_NEAR(dot3(f, u), 0.0, 1e-15);
    CHECK_NEAR(dot3(r, u), 0.0, 1e-15);
    CHECK_NEAR(r[2], 0.0, 1e-15);
    /* The image centre looks at the target; row 0 is at the top. */
    double d[3];
    sc_camera_ray(&side, 4.0, 4.0, d);
    CHECK_NEAR(dot3(d, f), 1.0, 1e-15);
    sc_camera_ray(&side, 0.5, 0.5, d);
    CHECK(dot3(d, u) > 0.0 && dot3(d, r) < 0.0);
    /* Footprint: the spacing of neighbouring pixel centres on the plane at
     * distance t in front of the eye. */
    double t = 7.0, a[3], b[3];
    sc_camera_ray(&cam, 32.0, 23.5, a);
    sc_camera_ray(&cam, 32.0, 24.5, b);
    sc_camera_frame(&cam, f, r, u);
    double pa[3], pb[3], dist2 = 0.0;
    for (int k = 0; k < 3; k++) {
        pa[k] = a[k] * t / dot3(a, f);
        pb[k] = b[k] * t / dot3(b, f);
        dist2 += (pa[k] - pb[k]) * (pa[k] - pb[k]);
    }
    CHECK_NEAR(sc_camera_footprint(&cam, t), sqrt(dist2), 1e-12);
    CHECK_NEAR(sc_camera_footprint(&cam, t), t * 2.0 * tan(20.0 * M_PI / 180.0) / 48.0, 1e-15);
}

TEST(ref_camera_default_frames_scene)
{
    sc_scene scene;
    sc_scene_init(&scene);
    double c[3] = {1, 2, 3};
    add_sphere(&scene, c, 2.0);
    sc_camera cam = {.width = 32, .height = 32};
    sc_camera_default(&scene, &cam);
    /* The target is the box centre; the box's bounding sphere just fits
     * the vertical field of view. */
    double lo[3], hi[3];
    sc_scene_bounds(&scene, lo, hi);
    double radius = 0.0, dist = 0.0;
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(cam.target[k], 0.5 * (lo[k] + hi[k]), 1e-12);
        radius += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
        dist += (cam.eye[k] - cam.target[k]) * (cam.eye[k] - cam.target[k]);
    }
    CHECK_NEAR(asin(sqrt(radius) / sqrt(dist)) * 2.0 * 180.0 / M_PI, cam.fovy_deg, 1e-9);
    CHECK(cam.eye[2] > cam.target[2]);
    sc_scene_free(&scene);
}

/* ------------------------------------------------------- trimming -- */

/* An L-shaped loop whose vertices and horizontal edges lie on the rows of
 * the test points: (0,0) (1,0) (1,.5) (.5,.5) (.5,1) (0,1). */
TEST(ref_trim_polygon_vertex_rows)
{
    static const double l_shape[6][2] = {{0, 0}, {1, 0}, {1, 0.5}, {0.5, 0.5}, {0.5, 1}, {0, 1}};
    sc_surface s;
    memset(&s, 0, sizeof s);
    sc_surface_alloc(&s, 1, 1, 2, 2);
    static const double k[4] = {0, 0, 1, 1};
    set_knots(s.knots_u, k, 4);
    set_knots(s.knots_v, k, 4);
    s.nloops = 1;
    s.loops = sc_alloc(1, sizeof(sc_loop));
    make_polygon_loop(&s.loops[0], l_shape, 6, 0);
    sc_trim *trim;
    sc_error err;
    CHECK_INT(sc_trim_prepare(&s, &trim, &err), SC_OK);
    CHECK(trim);
    /* Points on the rows of vertices and horizontal edges, classified by
     * looking at the shape. */
    static const struct { double u, v; int kept; } cases[] = {
        {0.25, 0.5, 1}, {0.25, 0.0 + 0.25, 1}, {0.75, 0.25, 1}, {0.75, 0.75, 0}, {0.25, 0.75, 1},
        {-0.5, 0.5, 0}, {1.5, 0.5, 0}, {-0.5, 0.0, 0}, {-0.5, 1.0, 0},
        {-1.0, 0.25, 0}, {0.6, 0.5 - 1e-12, 1}, {0.6, 0.5 + 1e-12, 0}, {0.4, 0.999, 1},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        int kept = sc_trim_inside(trim, cases[i].u, cases[i].v);
        if (kept != cases[i].kept)
            fprintf(stderr, "  at (%g, %g)\n", cases[i].u, cases[i].v);
        CHECK_INT(kept, cases[i].kept);
    }
    /* Whole rectangles: across the horizontal top edge, inside, in the
     * notch, far away, beside the notch's corner. */
    CHECK_INT(sc_trim_classify_rect(trim, 0.1, 0.2, 0.9, 1.1), -1);
    CHECK_INT(sc_trim_classify_rect(trim, 0.6, 0.9, 0.4, 0.6), -1);
    CHECK_INT(sc_trim_classify_rect(trim, 0.1, 0.2, 0.1, 0.2), 1);
    CHECK_INT(sc_trim_classify_rect(trim, 0.6, 0.9, 0.6, 0.9), 0);
    CHECK_INT(sc_trim_classify_rect(trim, 2.0, 3.0, 2.0, 3.0), 0);
    CHECK_INT(sc_trim_classify_rect(trim, 0.1, 0.4, 0.45, 0.55), 1);
    /* Rays along a horizontal edge or through vertices: even crossings. */
    CHECK_INT(sc_trim_crossings(trim, -0.5, 0.5) % 2, 0);
    CHECK_INT(sc_trim_crossings(trim, -0.5, 0.0) % 2, 0);
    /* Random points against the shape's own description. */
    unsigned long long state = 3;
    for (int i = 0; i < 20000; i++) {
        double u = 1.4 * test_rand(&state) - 0.2, v = 1.4 * test_rand(&state) - 0.2;
        if (i % 4 == 0)
            v = 0.5 * (int)(test_rand(&state) * 3); /* on a vertex row */
        int inside = u > 0 && u < 1 && v > 0 && v < 1 && !(u > 0.5 && v > 0.5);
        int on_edge = (u == 0 || u == 1 || u == 0.5) || v == 0 || v == 1 || (v == 0.5 && u > 0.5);
        if (on_edge)
            continue;
        CHECK_INT(sc_trim_inside(trim, u, v), inside);
    }
    sc_trim_free(trim);
    sc_surface_free(&s);
}

TEST(ref_trim_circle_arcs)
{
    /* Arcs joined at the circle's top and bottom (a0 = 0) and arcs with
     * the top and bottom inside them (a0 = 45°, split into monotone
     * pieces). */
    for (int variant = 0; variant < 2; variant++) {
        sc_scene scene;
        sc_scene_init(&scene);
        sc_surface *s = add_holed_square(&scene, variant ? M_PI / 4 : 0.0);
        sc_trim *trim;
        sc_error err;
        CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
        /* Square: 4 pieces (2 horizontal); circle: 4 arcs, split in two
         * when they hold the top or the bottom. */
        CHECK_INT(trim->npieces, variant ? 10 : 8);
        /* The rows of the arcs' joins and extrema, exactly. */
        static const struct { double u, v; int kept; } cases[] = {
            {0.1, 0.5, 1}, {0.5, 0.5, 0}, {0.9, 0.5, 1}, {0.1, 0.8, 1}, {0.9, 0.8, 1},
            {0.1, 0.2, 1}, {0.9, 0.2, 1}, {0.5, 0.79, 0}, {0.5, 0.21, 0}, {0.5, 0.81, 1},
            {-0.1, 0.8, 0}, {-0.1, 0.2, 0}, {-0.1, 0.5, 0},
        };
        for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
            CHECK_INT(sc_trim_inside(trim, cases[i].u, cases[i].v), cases[i].kept);
        unsigned long long state = 11 + variant;
        for (int i = 0; i < 20000; i++) {
            double u = 1.2 * test_rand(&state) - 0.1, v = 1.2 * test_rand(&state) - 0.1;
            double d = sqrt((u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5));
            if (fabs(d - 0.3) < 1e-12 || fabs(u) < 1e-12 || fabs(v) < 1e-12 || fabs(u - 1) < 1e-12 ||
                fabs(v - 1) < 1e-12)
                continue;
            int kept = u > 0 && u < 1 && v > 0 && v < 1 && d > 0.3;
            CHECK_INT(sc_trim_inside(trim, u, v), kept);
        }
        /* Close to the circle, on both sides. */
        for (int i = 0; i < 2000; i++) {
            double a = 2 * M_PI * test_rand(&state), side = i % 2 ? 1e-9 : -1e-9;
            double u = 0.5 + (0.3 + side) * cos(a), v = 0.5 + (0.3 + side) * sin(a);
            CHECK_INT(sc_trim_inside(trim, u, v), side > 0);
        }
        sc_trim_free(trim);
        sc_scene_free(&scene);
    }
}

/* ------------------------------------------------------ reference -- */

TEST(ref_sphere_rational_exact)
{
    sc_scene scene;
    sc_scene_init(&scene);
    const double c[3] = {0.3, -0.2, 0.5}, r = 1.7;
    add_sphere(&scene, c, r);
    CHECK_INT(scene.surfaces[0].rational, 1);
    sc_refcast *rc;
    sc_error err;
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_OK);
    CHECK_INT(sc_refcast_patch_count(rc), 8);
    sc_camera cam = {.eye = {4, -5, 3.5}, .target = {0.3, -0.2, 0.5}, .fovy_deg = 40, .width = 36, .height = 36};
    int hits = 0, misses = 0;
    for (int pass = 0; pass < 2; pass++)
        for (int j = 0; j < cam.height; j++)
            for (int i = 0; i < cam.width; i++) {
                double o[3], d[3];
                if (pass == 0) {
                    memcpy(o, cam.eye, sizeof o);
                    sc_camera_ray(&cam, i + 0.5, j + 0.5, d);
                } else {
                    /* Straight down onto the sphere, the poles included. */
                    double x = c[0] + (i - 17.5) / 18.0 * r, y = c[1] + (j - 17.5) / 18.0 * r;
                    if (i == 0 && j == 0)
                        x = c[0], y = c[1];
                    o[0] = x, o[1] = y, o[2] = c[2] + 3 * r;
                    d[0] = 0, d[1] = 0, d[2] = -1;
                }
                /* Analytic: |o + t d - c|² = r². */
                double oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
                double b = dot3(oc, d), q = dot3(oc, oc) - r * r;
                double disc = b * b - q;
                double miss_distance = sqrt(fmax(0.0, dot3(oc, oc) - b * b)); /* ray to centre */
                sc_ref_hit hit;
                sc_refcast_trace(rc, o, d, &hit);
                if (fabs(miss_distance - r) < 1e-6 * r)
                    continue; /* grazing: either answer is right */
                if (disc < 0) {
                    CHECK_INT(hit.surface, -1);
                    misses++;
                    continue;
                }
                CHECK_INT(hit.surface, 0);
                hits++;
                double t = -b - sqrt(disc);
                CHECK_NEAR(hit.t, t, 1e-9 * t);
                double pc[3] = {hit.point[0] - c[0], hit.point[1] - c[1], hit.point[2] - c[2]};
                CHECK_NEAR(sqrt(dot3(pc, pc)), r, 1e-9 * r);
                for (int k = 0; k < 3; k++) {
                    CHECK_NEAR(hit.point[k], o[k] + t * d[k], 1e-9 * r);
                    CHECK_NEAR(hit.normal[k], pc[k] / r, 1e-7);
                }
            }
    CHECK(hits > 500 && misses > 200);
    sc_refcast_free(rc);
    sc_scene_free(&scene);
}

TEST(ref_planar_patch_coverage)
{
    sc_scene scene;
    sc_scene_init(&scene);
    const double z0 = 0.25;
    add_planar_bicubic(&scene, z0);
    sc_refcast *rc;
    sc_error err;
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_OK);
    sc_camera cam = {.eye = {1.5, -2.5, 2.2}, .target = {0, 0, 0}, .fovy_deg = 50, .width = 48, .height = 40};
    sc_aov aov;
    sc_refcast_options opt = {.threads = 2};
    CHECK_INT(sc_refcast_render(rc, &cam, &opt, &aov, NULL, &err), SC_OK);
    long expected_hits = 0, hits = 0;
    for (int j = 0; j < cam.height; j++)
        for (int i = 0; i < cam.width; i++) {
            double d[3];
            sc_camera_ray(&cam, i + 0.5, j + 0.5, d);
            double t = (z0 - cam.eye[2]) / d[2];
            double x = cam.eye[0] + t * d[0], y = cam.eye[1] + t * d[1];
            size_t px = (size_t)j * cam.width + i;
            if (fabs(fabs(x) - 1) < 1e-9 || fabs(fabs(y) - 1) < 1e-9)
                continue;
            int inside = t > 0 && fabs(x) < 1 && fabs(y) < 1;
            expected_hits += inside;
            hits += aov.surface[px] == 0;
            CHECK_INT(aov.surface[px], inside ? 0 : -1);
            if (!inside)
                continue;
            CHECK_NEAR(aov.t[px], t, 1e-6 * t);
            CHECK_NEAR(aov.point[3 * px + 0], x, 1e-6);
            CHECK_NEAR(aov.point[3 * px + 1], y, 1e-6);
            CHECK_NEAR(aov.point[3 * px + 2], z0, 1e-6);
            /* The eye is above the plane: the normal faces up. */
            CHECK(aov.normal[3 * px + 0] == 0.0f && aov.normal[3 * px + 1] == 0.0f);
            CHECK(aov.normal[3 * px + 2] == 1.0f);
        }
    CHECK_INT(hits, expected_hits);
    CHECK(expected_hits > 300);
    sc_aov_free(&aov);
    sc_refcast_free(rc);
    sc_scene_free(&scene);
}

/* The holed square in front of an untrimmed floor: pixel centres inside
 * the hole must see the floor (a trimmed-away candidate hides a farther
 * hit), counted against the analytic shapes. */
TEST(ref_trimmed_square_coverage)
{
    static const char *const cameras[] = {"0.1,0.05,6,0.1,0.05,0,30", "1.2,-3.1,4.4,0,0,-0.3,42"};
    for (int variant = 0; variant < 4; variant++) {
        sc_scene scene;
        sc_scene_init(&scene);
        add_holed_square(&scene, variant % 2 ? M_PI / 4 : 0.0);
        add_floor(&scene, -0.6);
        sc_scene_validate_loops(&scene, NULL);
        sc_refcast *rc;
        sc_error err;
        CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_OK);
        sc_camera cam = {.width = 48, .height = 48};
        CHECK_INT(sc_camera_parse(cameras[variant / 2], &cam, &err), SC_OK);
        sc_aov aov;
        CHECK_INT(sc_refcast_render(rc, &cam, NULL, &aov, NULL, &err), SC_OK);
        long counts[3] = {0, 0, 0}, expected[3] = {0, 0, 0};
        for (int j = 0; j < cam.height; j++)
            for (int i = 0; i < cam.width; i++) {
                double d[3];
                sc_camera_ray(&cam, i + 0.5, j + 0.5, d);
                double t = -cam.eye[2] / d[2];
                double u = (cam.eye[0] + t * d[0] + 2) / 4, v = (cam.eye[1] + t * d[1] + 1) / 2;
                double dc = sqrt((u - 0.5) * (u - 0.5) + (v - 0.5) * (v - 0.5));
                double tf = (-0.6 - cam.eye[2]) / d[2];
                double xf = cam.eye[0] + tf * d[0], yf = cam.eye[1] + tf * d[1];
                if (fabs(dc - 0.3) < 1e-9 || fabs(u) < 1e-9 || fabs(v) < 1e-9 ||
                    fabs(u - 1) < 1e-9 || fabs(v - 1) < 1e-9 || fabs(fabs(xf) - 3) < 1e-9 ||
                    fabs(fabs(yf) - 3) < 1e-9)
                    continue;
                int on_square = u > 0 && u < 1 && v > 0 && v < 1 && dc > 0.3;
                int on_floor = fabs(xf) < 3 && fabs(yf) < 3;
                int want = on_square ? 0 : on_floor ? 1 : -1;
                int got = aov.surface[(size_t)j * cam.width + i];
                expected[want + 1]++;
                counts[got + 1]++;
                if (got != want)
                    fprintf(stderr, "  variant %d pixel (%d, %d): u %.17g v %.17g\n", variant, i, j, u, v);
                CHECK_INT(got, want);
            }
        CHECK_INT(counts[1], expected[1]);
        CHECK_INT(counts[2], expected[2]);
        CHECK(expected[1] > 100 && expected[2] > 100);
        sc_aov_free(&aov);
        sc_refcast_free(rc);
        sc_scene_free(&scene);
    }
}

TEST(ref_teapot_deterministic)
{
    sc_scene scene;
    sc_error err;
    if (sc_read_scene("teapot", &scene, &err) != SC_OK)
        SKIP("the embedded teapot does not read: %s", err.message);
    sc_refcast *rc;
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_OK);
    sc_camera cam = {.width = 64, .height = 64};
    sc_camera_default(&scene, &cam);
    sc_aov one, two;
    sc_refcast_options opt1 = {.threads = 1}, opt2 = {.threads = 2};
    CHECK_INT(sc_refcast_render(rc, &cam, &opt1, &one, NULL, &err), SC_OK);
    CHECK_INT(sc_refcast_render(rc, &cam, &opt2, &two, NULL, &err), SC_OK);
    size_t n = 64 * 64;
    CHECK(!memcmp(one.surface, two.surface, n * sizeof(int32_t)));
    CHECK(!memcmp(one.uv, two.uv, 2 * n * sizeof(float)));
    CHECK(!memcmp(one.t, two.t, n * sizeof(float)));
    CHECK(!memcmp(one.point, two.point, 3 * n * sizeof(float)));
    CHECK(!memcmp(one.normal, two.normal, 3 * n * sizeof(float)));
    long hits = 0;
    for (size_t px = 0; px < n; px++)
        if (one.surface[px] >= 0) {
            hits++;
            CHECK(one.surface[px] < scene.nsurfaces);
            /* The normal faces the eye. */
            double d[3];
            sc_camera_ray(&cam, px % 64 + 0.5, px / 64 + 0.5, d);
            CHECK(d[0] * one.normal[3 * px] + d[1] * one.normal[3 * px + 1] +
                      d[2] * one.normal[3 * px + 2] <= 0.0);
        }
    CHECK(hits > 300);
    /* Every hit is on its ray: the surface evaluated at the reported
     * (u, v) lies at the reported distance along it (the poles of the lid
     * and the bottom included). */
    for (int j = 0; j < 64; j += 3)
        for (int i = 0; i < 64; i += 3) {
            double d[3];
            sc_camera_ray(&cam, i + 0.5, j + 0.5, d);
            sc_ref_hit hit;
            sc_refcast_trace(rc, cam.eye, d, &hit);
            CHECK_INT(hit.surface, one.surface[j * 64 + i]);
            if (hit.surface < 0)
                continue;
            for (int k = 0; k < 3; k++)
                CHECK_NEAR(hit.point[k], cam.eye[k] + hit.t * d[k], 1e-10 * hit.t);
        }
    sc_aov_free(&one);
    sc_aov_free(&two);
    sc_refcast_free(rc);
    sc_scene_free(&scene);
}

TEST(ref_cache_reuses_render)
{
    sc_camera cam = {.width = 24, .height = 16};
    sc_scene scene;
    sc_error err;
    if (sc_read_scene("teapot", &scene, &err) != SC_OK)
        SKIP("the embedded teapot does not read: %s", err.message);
    sc_camera_default(&scene, &cam);
    sc_scene_free(&scene);
    char dir[512];
    snprintf(dir, sizeof dir, "%s/refcache", test_tmpdir());
    sc_aov a, b;
    CHECK_INT(sc_refcast_cached("teapot", &cam, dir, &a, &err), SC_OK);
    CHECK_INT(sc_refcast_cached("teapot", &cam, dir, &b, &err), SC_OK);
    CHECK(!memcmp(a.surface, b.surface, 24 * 16 * sizeof(int32_t)));
    CHECK(!memcmp(a.point, b.point, 3 * 24 * 16 * sizeof(float)));
    sc_aov_free(&a);
    sc_aov_free(&b);
}

/* What the reference refuses (a patch degree above its limit, a trim curve
 * above SC_TRIM_MAX_DEGREE in a scene built in code) is reported with the
 * scene's file. */
TEST(ref_prepare_errors_name_the_file)
{
    sc_scene scene;
    sc_scene_init(&scene);
    snprintf(scene.source, sizeof scene.source, "parts.obj");
    sc_surface *s = sc_scene_add_surface(&scene);
    sc_surface_alloc(s, 64, 1, 65, 2);
    snprintf(s->name, sizeof s->name, "ribbon");
    sc_refcast *rc = NULL;
    sc_error err = {0};
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_FAIL);
    CHECK_STR(err.file, "parts.obj");
    CHECK_CONTAINS(err.message, "surface 0 ('ribbon'): degree 64x1");
    sc_scene_free(&scene);

    sc_scene_init(&scene);
    snprintf(scene.source, sizeof scene.source, "parts.obj");
    add_planar_bicubic(&scene, 0);
    s = &scene.surfaces[0];
    s->nloops = 1;
    s->loops = sc_alloc(1, sizeof(sc_loop));
    s->loops[0].ncurves = 1;
    s->loops[0].curves = sc_alloc(1, sizeof(sc_curve));
    sc_curve *c = &s->loops[0].curves[0];
    int p = SC_TRIM_MAX_DEGREE + 1;
    sc_curve_alloc(c, 2, p, p + 1);
    for (int i = 0; i <= p; i++) {
        c->knots[i] = 0;
        c->knots[p + 1 + i] = 1;
        double a = 2 * M_PI * (i % p) / p;
        c->cp[3 * i] = 0.5 + 0.3 * cos(a);
        c->cp[3 * i + 1] = 0.5 + 0.3 * sin(a);
        c->cp[3 * i + 2] = 1;
    }
    memset(&err, 0, sizeof err);
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_FAIL);
    CHECK_STR(err.file, "parts.obj");
    CHECK_CONTAINS(err.message, "degree 17");
    sc_scene_free(&scene);
}

/* ------------------------------------------------------- accuracy -- */

TEST(ref_diff_metrics_known)
{
    /* Five pixels in one row, 90° field of view: the footprint at t = 10
     * is 10 · 2 · tan(45°) / 1 = 20. */
    sc_camera cam = {.eye = {0, 0, 10}, .target = {0, 0, 0}, .fovy_deg = 90, .width = 5, .height = 1};
    sc_aov ref, test;
    sc_aov_alloc(&ref, &cam, 0);
    sc_aov_alloc(&test, &cam, 1);
    for (int px = 0; px < 4; px++) {
        ref.surface[px] = 0;
        ref.t[px] = 10;
        ref.normal[3 * px + 2] = 1;
    }
    /* 0: hole; 1: exact; 2: 2 footprints off, normal 90° away; 3: half a
     * footprint off, normal 30° away; 4: false hit. */
    for (int px = 1; px < 5; px++) {
        test.surface[px] = 0;
        test.normal[3 * px + 2] = 1;
        test.iters[px] = (float)(2 * px);
    }
    test.point[3 * 2 + 0] = 40;
    test.normal[3 * 2 + 0] = 1, test.normal[3 * 2 + 2] = 0;
    test.point[3 * 3 + 1] = 10;
    test.normal[3 * 3 + 0] = 0.5f, test.normal[3 * 3 + 2] = (float)(sqrt(3.0) / 2);
    test.iters[0] = 1000; /* a miss: not counted */
    sc_accuracy acc;
    sc_error err;
    CHECK_INT(sc_accuracy_compare(&ref, &test, &acc, &err), SC_OK);
    CHECK_INT(acc.ref_hits, 4);
    CHECK_INT(acc.holes, 1);
    CHECK_INT(acc.false_hits, 1);
    CHECK_INT(acc.off, 1);
    /* Of the 4 pixels the reference hits: 2 (hole, false hit) and 3. */
    CHECK_NEAR(acc.coverage_pct, 50.0, 1e-12);
    CHECK_NEAR(acc.fail_pct, 75.0, 1e-12);
    CHECK_NEAR(acc.pos_median_px, 0.5, 1e-12);
    CHECK_NEAR(acc.pos_max_px, 2.0, 1e-12);
    CHECK_NEAR(acc.normal_mean_deg, 40.0, 1e-5);
    CHECK_NEAR(acc.normal_max_deg, 90.0, 1e-5);
    CHECK_NEAR(acc.iters_mean, 5.0, 1e-12);
    CHECK_NEAR(acc.iters_max, 8.0, 1e-12);
    /* Three pixels both hit: the 99th percentile by nearest rank is the
     * largest of them. */
    CHECK_NEAR(acc.pos_p99_px, 2.0, 1e-12);
    CHECK_NEAR(acc.normal_p99_deg, 90.0, 1e-5);
    char line[512];
    sc_accuracy_format(&acc, line, sizeof line);
    CHECK_CONTAINS(line, "accuracy coverage_pct=50 fail_pct=75 pos_median_px=0.5 pos_max_px=2 ");
    CHECK_CONTAINS(line, " iters_mean=5 iters_max=8 pos_p99_px=2 normal_p99_deg=90");
    /* A different camera or size is refused. */
    sc_aov other;
    sc_camera moved = cam;
    moved.eye[0] = 1e-3;
    sc_aov_alloc(&other, &moved, 0);
    CHECK_INT(sc_accuracy_compare(&ref, &other, &acc, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "camera");
    sc_aov_free(&other);
    moved = cam;
    moved.width = 4;
    sc_aov_alloc(&other, &moved, 0);
    CHECK_INT(sc_accuracy_compare(&ref, &other, &acc, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "size");
    sc_aov_free(&other);
    sc_aov_free(&ref);
    sc_aov_free(&test);
}

/* The 99th percentiles by nearest rank: of 200 pixels whose points are k
 * hundredths of a footprint off (k = 1 … 200, in scrambled order), 99 % do
 * not exceed 1.98 footprints; the normals likewise, k tenths of a degree. */
TEST(ref_diff_p99_nearest_rank)
{
    enum { N = 200 };
    sc_camera cam = {.eye = {0, 0, 10}, .target = {0, 0, 0}, .fovy_deg = 90, .width = N, .height = 1};
    sc_aov ref, test;
    sc_aov_alloc(&ref, &cam, 0);
    sc_aov_alloc(&test, &cam, 0);
    const double pi = 3.14159265358979323846;
    for (int px = 0; px < N; px++) {
        int k = 1 + (px * 37) % N;      /* 37 is prime to 200: a permutation */
        /* t · 2 tan(45°) / height */
        double footprint = 10.0 * 2.0 / 1, angle = k * 0.1 * pi / 180.0;
        ref.surface[px] = test.surface[px] = 0;
        ref.t[px] = test.t[px] = 10;
        ref.normal[3 * px + 2] = 1;
        test.point[3 * px] = (float)(k * 0.01 * footprint);
        test.normal[3 * px] = (float)sin(angle);
        test.normal[3 * px + 2] = (float)cos(angle);
    }
    sc_accuracy acc;
    sc_error err;
    CHECK_INT(sc_accuracy_compare(&ref, &test, &acc, &err), SC_OK);
    CHECK_INT(acc.both_hit, N);
    CHECK_NEAR(acc.pos_p99_px, 1.98, 1e-6);
    CHECK_NEAR(acc.pos_max_px, 2.00, 1e-6);
    CHECK_NEAR(acc.normal_p99_deg, 19.8, 1e-3);
    CHECK_NEAR(acc.normal_max_deg, 20.0, 1e-3);
    sc_aov_free(&ref);
    sc_aov_free(&test);
}

/* False hits count whatever the reference hits: against a reference that
 * hits nothing, a test with hits scores infinite percentages (not 0);
 * against one pixel of reference, one exact hit and three false hits fail
 * 300 % of it. */
TEST(ref_diff_false_hits_against_empty_reference)
{
    sc_camera cam = {.eye = {0, 0, 10}, .target = {0, 0, 0}, .fovy_deg = 60, .width = 2, .height = 2};
    sc_aov ref, test;
    sc_aov_alloc(&ref, &cam, 0);
    sc_aov_alloc(&test, &cam, 0);
    sc_accuracy acc;
    sc_error err;
    CHECK_INT(sc_accuracy_compare(&ref, &test, &acc, &err), SC_OK);
    CHECK_NEAR(acc.coverage_pct, 0.0, 0);
    CHECK_NEAR(acc.fail_pct, 0.0, 0);
    for (int px = 1; px < 4; px++) {
        test.surface[px] = 0;
        test.t[px] = 10;
        test.normal[3 * px + 2] = 1;
    }
    CHECK_INT(sc_accuracy_compare(&ref, &test, &acc, &err), SC_OK);
    CHECK_INT(acc.false_hits, 3);
    CHECK(isinf(acc.coverage_pct) && acc.coverage_pct > 0);
    CHECK(isinf(acc.fail_pct) && acc.fail_pct > 0);
    char line[512];
    sc_accuracy_format(&acc, line, sizeof line);
    CHECK_CONTAINS(line, "accuracy coverage_pct=inf fail_pct=inf ");
    test.surface[0] = 0;
    test.t[0] = 10;
    ref.surface[0] = 0;
    ref.t[0] = 10;
    CHECK_INT(sc_accuracy_compare(&ref, &test, &acc, &err), SC_OK);
    CHECK_NEAR(acc.coverage_pct, 300.0, 1e-12);
    CHECK_NEAR(acc.fail_pct, 300.0, 1e-12);
    sc_aov_free(&ref);
    sc_aov_free(&test);
}

TEST(ref_diff_self_is_zero)
{
    sc_scene scene;
    sc_scene_init(&scene);
    const double c[3] = {0, 0, 0};
    add_sphere(&scene, c, 1.0);
    add_planar_bicubic(&scene, -1.2);
    sc_refcast *rc;
    sc_error err;
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_OK);
    sc_camera cam = {.width = 32, .height = 24};
    sc_camera_default(&scene, &cam);
    sc_aov aov;
    CHECK_INT(sc_refcast_render(rc, &cam, NULL, &aov, NULL, &err), SC_OK);
    sc_accuracy acc;
    CHECK_INT(sc_accuracy_compare(&aov, &aov, &acc, &err), SC_OK);
    CHECK(acc.ref_hits > 100);
    char line[512];
    sc_accuracy_format(&acc, line, sizeof line);
    CHECK_STR(line, "accuracy coverage_pct=0 fail_pct=0 pos_median_px=0 pos_max_px=0 "
                    "normal_mean_deg=0 normal_max_deg=0 pos_p99_px=0 normal_p99_deg=0");
    sc_aov_free(&aov);
    sc_refcast_free(rc);
    sc_scene_free(&scene);
}

