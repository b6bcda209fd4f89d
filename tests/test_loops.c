/* test_loops.c — trim-loop validation on loops built by hand, with known
 * answers: gaps below 1e-9 of the domain closed silently, up to 1e-3
 * repaired with a straight segment, larger ones dropped; self-crossing
 * loops (a bowtie, a figure-eight curve, two triangles crossing at a shared
 * corner) dropped; valid loops left bit for bit as they were. The warnings
 * are captured through the logger and must name the surface and the loop.
 * Validation is idempotent: a validated scene validated again, or written
 * to OBJ and read back, keeps every loop as it was (bearing.iges, whose
 * repaired corners cross by 1e-7, and hand-built sharp corners). */
#include "test.h"

#include <stdlib.h>

#include "io.h"
#include "nurbs.h"
#include "trim.h"

static void validate(sc_scene *scene, test_warnings *cap)
{
    memset(cap, 0, sizeof *cap);
    sc_set_logger(test_gather_warnings, cap);
    sc_scene_validate_loops(scene, NULL);
    sc_set_logger(NULL, NULL);
}

/* Two flat surfaces on the domain [0, 2] × [0, 1] (domain size 2): the
 * loops under test go on the second, named "plate". */
static sc_surface *make_scene(sc_scene *scene)
{
    sc_scene_init(scene);
    for (int k = 0; k < 2; k++) {
        sc_surface *s = sc_scene_add_surface(scene);
        sc_surface_alloc(s, 1, 1, 2, 2);
        const double ku[4] = {0, 0, 2, 2}, kv[4] = {0, 0, 1, 1};
        memcpy(s->knots_u, ku, sizeof ku);
        memcpy(s->knots_v, kv, sizeof kv);
        const double cp[16] = {0, 0, 0, 1, 2, 0, 0, 1, 0, 1, 0, 1, 2, 1, 0, 1};
        memcpy(s->cp, cp, sizeof cp);
    }
    snprintf(scene->surfaces[1].name, sizeof scene->surfaces[1].name, "plate");
    return &scene->surfaces[1];
}

static sc_loop *add_loop(sc_surface *s, int is_hole, int ncurves)
{
    s->loops = sc_realloc(s->loops, (size_t)s->nloops + 1, sizeof(sc_loop));
    sc_loop *l = &s->loops[s->nloops++];
    l->is_hole = is_hole;
    l->ncurves = ncurves;
    l->curves = sc_alloc((size_t)ncurves, sizeof(sc_curve));
    return l;
}

static void line(sc_curve *c, double x0, double y0, double x1, double y1)
{
    sc_curve_alloc(c, 2, 1, 2);
    const double k[4] = {0, 0, 1, 1}, cp[6] = {x0, y0, 1, x1, y1, 1};
    memcpy(c->knots, k, sizeof k);
    memcpy(c->cp, cp, sizeof cp);
}

/* A rational quadratic Bézier curve; cp holds (u·w, v·w, w) per point. */
static void quadratic(sc_curve *c, const double cp[9])
{
    sc_curve_alloc(c, 2, 2, 3);
    const double k[6] = {0, 0, 0, 1, 1, 1};
    memcpy(c->knots, k, sizeof k);
    memcpy(c->cp, cp, 9 * sizeof(double));
}

/* A closed polygon of lines; the end of side `gap_after` is moved by
 * (gap, 0) so that it misses the next side's start. */
static void polygon_loop(sc_surface *s, int is_hole, const double (*xy)[2], int n,
                         int gap_after, double gap)
{
    sc_loop *l = add_loop(s, is_hole, n);
    for (int k = 0; k < n; k++) {
        const double *a = xy[k], *b = xy[(k + 1) % n];
        line(&l->curves[k], a[0], a[1], b[0] + (k == gap_after ? gap : 0), b[1]);
    }
}

static const double square[4][2] = {{0.5, 0.25}, {1.5, 0.25}, {1.5, 0.75}, {0.5, 0.75}};

static void curve_end(const sc_curve *c, int last, double p[2])
{
    const double *P = c->cp + (last ? 3 * (c->ncp - 1) : 0);
    p[0] = P[0] / P[2];
    p[1] = P[1] / P[2];
}

TEST(loops_tiny_gap_closed_silently)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    /* 2e-11 on a domain of size 2: a gap of 1e-11 of the domain. */
    polygon_loop(s, 0, square, 4, 1, 2e-11);
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.repaired_gaps, 0);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(s->nloops, 1);
    CHECK_INT(s->loops[0].ncurves, 4);
    double a[2], b[2];
    curve_end(&s->loops[0].curves[1], 1, a);
    curve_end(&s->loops[0].curves[2], 0, b);
    /* Both moved to the midpoint of the gap. */
    CHECK_NEAR(a[0], 1.5 + 1e-11, 1e-15);
    CHECK_NEAR(b[0], 1.5 + 1e-11, 1e-15);
    CHECK_NEAR(a[1], 0.75, 0);
    sc_scene_free(&scene);
}

TEST(loops_small_gap_repaired_with_a_segment)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, -1, 0);
    /* The hole, loop 1: a gap of 1e-5 of the domain after its curve 2. */
    const double hole[4][2] = {{0.8, 0.4}, {1.2, 0.4}, {1.2, 0.6}, {0.8, 0.6}};
    polygon_loop(s, 1, hole, 4, 2, 2e-5);
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(cap.count, 1);
    CHECK_CONTAINS(cap.text, "surface 1 (plate)");
    CHECK_CONTAINS(cap.text, "trim loop 1");
    CHECK_CONTAINS(cap.text, "straight segment");
    CHECK_INT(scene.repaired_gaps, 1);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(s->nloops, 2);
    CHECK_INT(s->loops[0].ncurves, 4);
    CHECK_INT(s->loops[1].ncurves, 5);
    /* The new piece, after curve 2: a line from (0.8 + 2e-5, 0.6) to (0.8, 0.6). */
    const sc_curve *seg = &s->loops[1].curves[3];
    CHECK_INT(seg->degree, 1);
    double a[2], b[2];
    curve_end(seg, 0, a);
    curve_end(seg, 1, b);
    CHECK_NEAR(a[0], 0.8 + 2e-5, 1e-15);
    CHECK_NEAR(b[0], 0.8, 1e-15);
    CHECK_NEAR(a[1], 0.6, 1e-15);
    CHECK_NEAR(b[1], 0.6, 1e-15);
    sc_scene_free(&scene);
}

TEST(loops_gap_between_last_and_first_curve)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, 3, 1e-4);
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(scene.repaired_gaps, 1);
    CHECK_INT(s->loops[0].ncurves, 5);
    double a[2];
    curve_end(&s->loops[0].curves[4], 1, a);
    CHECK_NEAR(a[0], square[0][0], 0);
    CHECK_NEAR(a[1], square[0][1], 0);
    CHECK_CONTAINS(cap.text, "trim loop 0");
    sc_scene_free(&scene);
}

TEST(loops_repair_at_sharp_corner_kept)
{
    /* A triangle whose second side starts 2.2e-5 down-left of the apex
     * (1, 0.8): the repair segment runs backwards, so the second side
     * crosses the first 1.7e-5 from the apex. That is a rounded corner, not
     * a crossing loop (real CAD files have it: bearing.iges). */
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    sc_loop *l = add_loop(s, 0, 3);
    line(&l->curves[0], 0.7, 0.2, 1.0, 0.8);
    line(&l->curves[1], 1.0 - 2e-5, 0.8 - 1e-5, 1.3, 0.2);
    line(&l->curves[2], 1.3, 0.2, 0.7, 0.2);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.repaired_gaps, 1);
    CHECK_INT(cap.count, 1);
    CHECK_INT(scene.surfaces[1].loops[0].ncurves, 4);
    sc_scene_free(&scene);

    /* Neighbouring curves crossing far from where they meet do count: a
     * quadratic arc from the end of a horizontal line swings back over it. */
    s = make_scene(&scene);
    l = add_loop(s, 0, 3);
    line(&l->curves[0], 0.5, 0.5, 1.5, 0.5);
    const double cp[9] = {1.5, 0.5, 1, 0.6, 1.0, 1, 1.0, 0.2, 1};
    quadratic(&l->curves[1], cp);
    line(&l->curves[2], 1.0, 0.2, 0.5, 0.5);
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_CONTAINS(cap.text, "curve 0 and curve 1");
    sc_scene_free(&scene);
}

TEST(loops_large_gap_dropped)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, -1, 0);
    const double hole[4][2] = {{0.8, 0.4}, {1.2, 0.4}, {1.2, 0.6}, {0.8, 0.6}};
    polygon_loop(s, 1, hole, 4, 0, 0.2); /* 0.1 of the domain */
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_INT(scene.repaired_gaps, 0);
    CHECK_INT(scene.nsurfaces, 2);
    CHECK_INT(s->nloops, 1);
    CHECK_INT(s->loops[0].is_hole, 0);
    CHECK_INT(cap.count, 1);
    CHECK_CONTAINS(cap.text, "surface 1 (plate)");
    CHECK_CONTAINS(cap.text, "trim loop 1 dropped");
    sc_scene_free(&scene);
}

TEST(loops_dropped_outer_loop_keeps_holes)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, 2, 0.2);
    const double hole[4][2] = {{0.8, 0.4}, {1.2, 0.4}, {1.2, 0.6}, {0.8, 0.6}};
    polygon_loop(s, 1, hole, 4, -1, 0);
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_INT(s->nloops, 1);
    CHECK_INT(s->loops[0].is_hole, 1);
    CHECK_CONTAINS(cap.text, "trim loop 0 dropped");
    sc_scene_free(&scene);
}

TEST(loops_bowtie_dropped)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    /* Sides 0 and 2 cross at (1, 0.5). */
    const double bowtie[4][2] = {{0.5, 0.25}, {1.5, 0.75}, {1.5, 0.25}, {0.5, 0.75}};
    polygon_loop(s, 0, bowtie, 4, -1, 0);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_INT(scene.surfaces[1].nloops, 0);
    CHECK_CONTAINS(cap.text, "surface 1 (plate): trim loop 0 dropped: it crosses itself");
    CHECK_CONTAINS(cap.text, "curve 0 and curve 2");
    CHECK_CONTAINS(cap.text, "u=1 v=0.5");
    sc_scene_free(&scene);
}

TEST(loops_figure_eight_curve_dropped)
{
    /* One closed cubic B-spline tracing an 8: its two diagonal strokes
     * cross in the middle, away from its ends. */
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    const double xy[10][2] = {{0.2, 0.5}, {0.2, 0.9}, {0.8, 0.9}, {1.2, 0.1}, {1.8, 0.1},
                              {1.8, 0.9}, {1.2, 0.9}, {0.8, 0.1}, {0.2, 0.1}, {0.2, 0.5}};
    sc_loop *l = add_loop(s, 0, 1);
    sc_curve *c = &l->curves[0];
    sc_curve_alloc(c, 2, 3, 10);
    for (int i = 0; i < 14; i++)
        c->knots[i] = i < 4 ? 0 : i >= 10 ? 1 : (i - 3) / 7.0;
    for (int i = 0; i < 10; i++) {
        c->cp[3 * i] = xy[i][0];
        c->cp[3 * i + 1] = xy[i][1];
        c->cp[3 * i + 2] = 1;
    }
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_INT(scene.surfaces[1].nloops, 0);
    CHECK_CONTAINS(cap.text, "curve 0 and curve 0");
    sc_scene_free(&scene);
}

TEST(loops_crossing_at_shared_corner_dropped_touching_kept)
{
    /* Two triangles meeting at (1, 0.5), drawn as one loop of six lines.
     * Turning opposite ways they form an 8 that crosses at the shared
     * corner; turning the same way they only touch there. */
    const double eight[6][2] = {{1, .5}, {.5, .9}, {.5, .1}, {1, .5}, {1.5, .9}, {1.5, .1}};
    const double touch[6][2] = {{1, .5}, {.5, .9}, {.5, .1}, {1, .5}, {1.5, .1}, {1.5, .9}};
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, eight, 6, -1, 0);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_CONTAINS(cap.text, "crosses itself");
    sc_scene_free(&scene);

    s = make_scene(&scene);
    polygon_loop(s, 0, touch, 6, -1, 0);
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.surfaces[1].loops[0].ncurves, 6);
    sc_scene_free(&scene);
}

TEST(loops_valid_square_and_circle_untouched)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, -1, 0);
    /* A circle of radius 0.2 around (1, 0.5) from four rational quadratic
     * arcs, as a hole. */
    static const double R2 = 0.70710678118654752440;
    const double dir[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0},
                              {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    sc_loop *l = add_loop(s, 1, 4);
    for (int k = 0; k < 4; k++) {
        double cp[9];
        for (int i = 0; i < 3; i++) {
            double w = i == 1 ? R2 : 1;
            cp[3 * i] = (1 + 0.2 * dir[2 * k + i][0]) * w;
            cp[3 * i + 1] = (0.5 + 0.2 * dir[2 * k + i][1]) * w;
            cp[3 * i + 2] = w;
        }
        quadratic(&l->curves[k], cp);
    }
    sc_surface before;
    sc_surface_copy(&before, s);
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.repaired_gaps, 0);
    CHECK_INT(s->nloops, 2);
    for (int li = 0; li < 2; li++) {
        CHECK_INT(s->loops[li].ncurves, before.loops[li].ncurves);
        for (int k = 0; k < s->loops[li].ncurves; k++) {
            const sc_curve *x = &s->loops[li].curves[k], *y = &before.loops[li].curves[k];
            CHECK(memcmp(x->cp, y->cp, sizeof(double) * 3 * (size_t)x->ncp) == 0);
            CHECK(memcmp(x->knots, y->knots, sizeof(double) * (size_t)(x->ncp + x->degree + 1)) == 0);
        }
    }
    sc_surface_free(&before);
    sc_scene_free(&scene);
}

/* A star-shaped polygon of n sides around (1, 0.5), radius varying. */
static void star_loop(sc_surface *s, int n)
{
    sc_loop *l = add_loop(s, 0, n);
    for (int k = 0; k < n; k++) {
        double a0 = 2 * M_PI * k / n, a1 = 2 * M_PI * (k + 1) / n;
        double r0 = 0.3 + 0.1 * sin(37 * a0), r1 = 0.3 + 0.1 * sin(37 * a1);
        line(&l->curves[k], 1 + r0 * cos(a0), 0.5 + r0 * sin(a0), 1 + r1 * cos(a1),
             0.5 + r1 * sin(a1));
    }
}

TEST(loops_thousands_of_pieces)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    star_loop(s, 20000);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(cap.count, 0);
    sc_scene_free(&scene);

    /* The same star with one corner moved to the far side, beyond the
     * outline: its two long sides cross the outline there. */
    s = make_scene(&scene);
    star_loop(s, 20000);
    sc_loop *l = &s->loops[0];
    double *end = l->curves[5000].cp + 3, *start = l->curves[5001].cp;
    double x = 1 - 1.5 * (end[0] - 1), y = 0.5 - 1.5 * (end[1] - 0.5);
    end[0] = start[0] = x;
    end[1] = start[1] = y;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_CONTAINS(cap.text, "crosses itself");
    sc_scene_free(&scene);
}

TEST(loops_invalid_curve_dropped)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, -1, 0);
    s->loops[0].curves[2].cp[2] = -1; /* a negative weight */
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_CONTAINS(cap.text, "curve 2 is invalid");
    sc_scene_free(&scene);
}

/* A closed Bézier curve of the given degree whose control points are the
 * vertices of a regular polygon (the first repeated at the end) around
 * (1, 0.5): a convex control polygon gives a convex, simple loop. */
static void closed_bezier(sc_curve *c, int degree, double radius)
{
    sc_curve_alloc(c, 2, degree, degree + 1);
    for (int i = 0; i <= degree; i++) {
        c->knots[i] = 0;
        c->knots[degree + 1 + i] = 1;
        double a = 2 * M_PI * (i % degree) / degree;
        c->cp[3 * i] = 1 + radius * cos(a);
        c->cp[3 * i + 1] = 0.5 + radius * sin(a);
        c->cp[3 * i + 2] = 1;
    }
}

TEST(loops_curve_above_trim_degree_dropped)
{
    /* Loop 1 (a hole of one curve one degree above what trimming handles)
     * is dropped, counted and named with the file; loop 2 (a hole at the
     * highest degree) and the outer square stay. */
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    snprintf(scene.source, sizeof scene.source, "plate.obj");
    polygon_loop(s, 0, square, 4, -1, 0);
    closed_bezier(&add_loop(s, 1, 1)->curves[0], SC_TRIM_MAX_DEGREE + 1, 0.2);
    closed_bezier(&add_loop(s, 1, 1)->curves[0], SC_TRIM_MAX_DEGREE, 0.1);
    test_warnings cap;
    validate(&scene, &cap);
    s = &scene.surfaces[1];
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_INT(cap.count, 1);
    CHECK_CONTAINS(cap.text, "plate.obj: surface 1 (plate): trim loop 1 dropped: curve 0 has "
                             "degree 17; trimming handles degrees up to 16");
    CHECK_INT(s->nloops, 2);
    CHECK_INT(s->loops[0].ncurves, 4);
    CHECK_INT(s->loops[1].curves[0].degree, SC_TRIM_MAX_DEGREE);
    sc_scene_free(&scene);
}

/* ---- idempotence ---- */

/* 1 when the two surfaces have the same loops, bit for bit. */
static int same_loops(const sc_surface *x, const sc_surface *y)
{
    if (x->nloops != y->nloops)
        return 0;
    for (int li = 0; li < x->nloops; li++) {
        const sc_loop *a = &x->loops[li], *b = &y->loops[li];
        if (a->is_hole != b->is_hole || a->ncurves != b->ncurves)
            return 0;
        for (int k = 0; k < a->ncurves; k++) {
            const sc_curve *c = &a->curves[k], *d = &b->curves[k];
            if (c->dim != d->dim || c->degree != d->degree || c->ncp != d->ncp ||
                memcmp(c->cp, d->cp, sizeof(double) * (size_t)(c->dim + 1) * (size_t)c->ncp) ||
                memcmp(c->knots, d->knots, sizeof(double) * (size_t)(c->ncp + c->degree + 1)))
                return 0;
        }
    }
    return 1;
}

/* Validates the scene a second time: no warning, no count changes, every
 * loop as the first validation left it. Returns the number of surfaces
 * whose loops changed. */
static int revalidate_changes(sc_scene *scene, test_warnings *cap)
{
    sc_surface *before = sc_alloc((size_t)scene->nsurfaces, sizeof(sc_surface));
    for (int i = 0; i < scene->nsurfaces; i++)
        sc_surface_copy(&before[i], &scene->surfaces[i]);
    validate(scene, cap);
    int changed = 0;
    for (int i = 0; i < scene->nsurfaces; i++) {
        changed += !same_loops(&before[i], &scene->surfaces[i]);
        sc_surface_free(&before[i]);
    }
    free(before);
    return changed;
}

/* The triangle of loops_repair_at_sharp_corner_kept: the second side starts
 * 2.2e-5 down-left of the apex, and the segment closing that gap runs
 * backwards, so the second side crosses the first 1.7e-5 below the apex. */
static void sharp_corner_triangle(sc_surface *s)
{
    sc_loop *l = add_loop(s, 0, 3);
    line(&l->curves[0], 0.7, 0.2, 1.0, 0.8);
    line(&l->curves[1], 1.0 - 2e-5, 0.8 - 1e-5, 1.3, 0.2);
    line(&l->curves[2], 1.3, 0.2, 0.7, 0.2);
}

TEST(loops_validate_twice_sharp_corner)
{
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    sharp_corner_triangle(s);
    /* A rational hole with a gap of 3e-11 of the domain after its first
     * arc, closed silently by moving both ends to the middle. With end
     * weights 0.5 and 0.61, (u·w)/w does not give the middle's u back on
     * both sides: the ends differ by rounding afterwards, and moving them
     * again would change their last bits. */
    sc_loop *hole = add_loop(s, 1, 2);
    const double arcs[2][9] = {
        {1.1, 0.4, 1, 1.0 * 1.3, 0.6 * 1.3, 1.3, 0.9 * 0.5, 0.4 * 0.5, 0.5},
        {(0.9 + 6e-11) * 0.61, 0.4 * 0.61, 0.61, 1.0 * 0.8, 0.3 * 0.8, 0.8, 1.1, 0.4, 1}};
    for (int c = 0; c < 2; c++)
        quadratic(&hole->curves[c], arcs[c]);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.repaired_gaps, 1);
    CHECK_INT(cap.count, 1);
    CHECK_INT(scene.surfaces[1].nloops, 2);
    CHECK_INT(scene.surfaces[1].loops[0].ncurves, 4);

    CHECK_INT(revalidate_changes(&scene, &cap), 0);
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.repaired_gaps, 1);
    sc_scene_free(&scene);
}

TEST(loops_corner_lobe_without_gap_kept)
{
    /* The repaired triangle as a file would hold it after a round trip:
     * four curves meeting exactly, the short one running backwards. The
     * crossing beside the apex is accepted without knowing it was a
     * repair. */
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    sc_loop *l = add_loop(s, 0, 4);
    line(&l->curves[0], 0.7, 0.2, 1.0, 0.8);
    line(&l->curves[1], 1.0, 0.8, 1.0 - 2e-5, 0.8 - 1e-5);
    line(&l->curves[2], 1.0 - 2e-5, 0.8 - 1e-5, 1.3, 0.2);
    line(&l->curves[3], 1.3, 0.2, 0.7, 0.2);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.dropped_loops, 0);
    CHECK_INT(scene.surfaces[1].loops[0].ncurves, 4);
    sc_scene_free(&scene);

    /* Two curves sharing the apex exactly: a quadratic leaving it backwards
     * (towards (0.998, 0.8), outside the first side) and turning down
     * crosses the first side about 3e-5 below the apex. */
    s = make_scene(&scene);
    l = add_loop(s, 0, 3);
    line(&l->curves[0], 0.7, 0.2, 1.0, 0.8);
    const double cp[9] = {1.0, 0.8, 1, 0.998, 0.8, 1, 1.3, 0.2, 1};
    quadratic(&l->curves[1], cp);
    line(&l->curves[2], 1.3, 0.2, 0.7, 0.2);
    validate(&scene, &cap);
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.dropped_loops, 0);
    sc_scene_free(&scene);

    /* The same quadratic leaving ten times further back: its lobe (about
     * 0.002 of the domain size) is more than a corner's rounding. */
    s = make_scene(&scene);
    l = add_loop(s, 0, 3);
    line(&l->curves[0], 0.7, 0.2, 1.0, 0.8);
    const double far_back[9] = {1.0, 0.8, 1, 0.98, 0.8, 1, 1.3, 0.2, 1};
    quadratic(&l->curves[1], far_back);
    line(&l->curves[2], 1.3, 0.2, 0.7, 0.2);
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_CONTAINS(cap.text, "curve 0 and curve 1");
    sc_scene_free(&scene);
}

TEST(loops_tiny_figure_eight_dropped)
{
    /* A bowtie hole 2e-4 across: both its lobes are tiny against the
     * domain, but neither is small against the other, so it is a
     * self-crossing loop, not a rounded corner. */
    sc_scene scene;
    sc_surface *s = make_scene(&scene);
    polygon_loop(s, 0, square, 4, -1, 0);
    const double bowtie[4][2] = {
        {1, 0.5}, {1 + 2e-4, 0.5 + 1e-4}, {1 + 2e-4, 0.5}, {1, 0.5 + 1e-4}};
    polygon_loop(s, 1, bowtie, 4, -1, 0);
    test_warnings cap;
    validate(&scene, &cap);
    CHECK_INT(scene.dropped_loops, 1);
    CHECK_CONTAINS(cap.text, "trim loop 1 dropped: it crosses itself");
    CHECK_INT(scene.surfaces[1].nloops, 1);
    sc_scene_free(&scene);
}

static const char *bearing_path = "/usr/share/opencascade/data/iges/bearing.iges";

static int read_quietly(const char *path, sc_scene *scene, test_warnings *cap, sc_error *err)
{
    memset(cap, 0, sizeof *cap);
    sc_set_logger(test_gather_warnings, cap);
    int status = sc_read_scene(path, scene, err);
    sc_set_logger(NULL, NULL);
    return status;
}

TEST(loops_validate_twice_bearing)
{
    FILE *f = fopen(bearing_path, "r");
    if (!f)
        SKIP("%s is missing (Debian package occt-misc)", bearing_path);
    fclose(f);
    sc_scene scene;
    sc_error err;
    test_warnings cap;
    sc_scene_init(&scene);
    CHECK_INT(read_quietly(bearing_path, &scene, &cap, &err), SC_OK);
    /* Its gaps are repaired (66 of them when this was written); three of
     * the repairs run backwards at a sharp corner (surfaces 163, 181, 185)
     * and their loops are kept. */
    int repaired = scene.repaired_gaps;
    CHECK(repaired > 0);
    CHECK_INT(scene.dropped_loops, 0);
    int loops = 0;
    for (int i = 0; i < scene.nsurfaces; i++)
        loops += scene.surfaces[i].nloops;
    CHECK(loops >= 213);

    CHECK_INT(revalidate_changes(&scene, &cap), 0);
    CHECK_INT(cap.count, 0);
    CHECK_INT(scene.repaired_gaps, repaired);
    CHECK_INT(scene.dropped_loops, 0);
    sc_scene_free(&scene);
}

TEST(loops_bearing_obj_round_trip_keeps_loops)
{
    FILE *f = fopen(bearing_path, "r");
    if (!f)
        SKIP("%s is missing (Debian package occt-misc)", bearing_path);
    fclose(f);
    sc_scene first, second;
    sc_error err;
    test_warnings cap;
    sc_scene_init(&first);
    sc_scene_init(&second);
    CHECK_INT(read_quietly(bearing_path, &first, &cap, &err), SC_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/bearing_round_trip.obj", test_tmpdir());
    CHECK_INT(sc_write_obj(path, &first, &err), SC_OK);
    CHECK_INT(read_quietly(path, &second, &cap, &err), SC_OK);
    CHECK_INT(cap.count, 0);
    CHECK_INT(second.dropped_loops, 0);
    CHECK_INT(second.repaired_gaps, 0);
    CHECK_INT(second.nsurfaces, first.nsurfaces);
    for (int i = 0; i < first.nsurfaces; i++) {
        const sc_surface *a = &first.surfaces[i], *b = &second.surfaces[i];
        CHECK_INT(b->nloops, a->nloops);
        for (int l = 0; l < a->nloops; l++) {
            CHECK_INT(b->loops[l].is_hole, a->loops[l].is_hole);
            CHECK_INT(b->loops[l].ncurves, a->loops[l].ncurves);
        }
    }
    sc_scene_free(&first);
    sc_scene_free(&second);
}
