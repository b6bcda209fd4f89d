/* test_trim_gpu.c — GPU trimming on the CPU: trimmed variant keys, the
 * trim block layout (runtime/trim_pack.c) against values known by
 * construction, and the generated trim stage run by the IR interpreter in
 * single precision against the reference's exact double-precision
 * classification (runtime/trim.c), for every trim method: on random points
 * farther than 64 float ulps (of 1.0, in normalised domain coordinates)
 * from every curve, and on points level with piece end points. Shapes: a
 * circular hole of rational quadratic arcs, 9 cubic curves, nested holes, a
 * star with sharp corners, a hole whose corner touches the outer loop, a
 * surface with holes only, polygons of 100 and 1000 pieces, and the example
 * scenes examples/scenes/trim_*.obj. */
#include <float.h>
#include <stdlib.h>

#include "io.h"
#include "ir.h"
#include "nurbs.h"
#include "scene_keys.h"
#include "test.h"
#include "trim.h"
#include "trim_gen.h"
#include "trim_pack.h"

/* 64 float ulps of 1.0 (2^-23 each): the largest ulp in [0, 1]. */
#define NEAR_CURVE (64.0 * FLT_EPSILON)

/* Doubles of a homogeneous 2D Bézier curve of the highest trim degree. */
#define CURVE_DOUBLES (3 * (SC_TRIM_MAX_DEGREE + 1))

/* ---- shapes ---- */

/* A flat bicubic patch over the domain [u0, u1] × [v0, v1]: x = u, y = v. */
static sc_surface *add_patch(sc_scene *scene, double u0, double u1, double v0, double v1)
{
    sc_surface *s = sc_scene_add_surface(scene);
    snprintf(s->name, sizeof s->name, "plate");
    sc_surface_alloc(s, 3, 3, 4, 4);
    for (int k = 0; k < 8; k++) {
        s->knots_u[k] = k < 4 ? u0 : u1;
        s->knots_v[k] = k < 4 ? v0 : v1;
    }
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *c = &s->cp[4 * (4 * j + i)];
            c[0] = u0 + (u1 - u0) * i / 3.0;
            c[1] = v0 + (v1 - v0) * j / 3.0;
            c[2] = 0.0;
            c[3] = 1.0;
        }
    sc_surface_update_rational(s);
    return s;
}

static sc_loop *add_loop(sc_surface *s, int is_hole, int ncurves)
{
    s->loops = sc_realloc(s->loops, (size_t)s->nloops + 1, sizeof *s->loops);
    sc_loop *loop = &s->loops[s->nloops++];
    loop->is_hole = is_hole;
    loop->ncurves = ncurves;
    loop->curves = sc_alloc((size_t)ncurves, sizeof *loop->curves);
    return loop;
}

/* Domain coordinates from normalised ones. */
static void to_domain(const sc_surface *s, double un, double vn, double *u, double *v)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    *u = u0 + un * (u1 - u0);
    *v = v0 + vn * (v1 - v0);
}

/* A closed polygon (normalised coordinates) as one degree-1 B-spline. */
static void add_polygon(sc_surface *s, int is_hole, const double (*pts)[2], int n)
{
    sc_loop *loop = add_loop(s, is_hole, 1);
    sc_curve *c = &loop->curves[0];
    sc_curve_alloc(c, 2, 1, n + 1);
    for (int i = 0; i <= n + 2; i++)
        c->knots[i] = i == 0 ? 0.0 : i > n ? (double)n : (double)(i - 1);
    for (int i = 0; i <= n; i++) {
        to_domain(s, pts[i % n][0], pts[i % n][1], &c->cp[3 * i], &c->cp[3 * i + 1]);
        c->cp[3 * i + 2] = 1.0;
    }
}

/* A circle of four rational quadratic quarter arcs (weights 1, √2/2). */
static void add_circle(sc_surface *s, int is_hole, double cu, double cv, double r)
{
    static const double square[9][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0},
                                        {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
    static const double knots[12] = {0, 0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4};
    sc_loop *loop = add_loop(s, is_hole, 1);
    sc_curve *c = &loop->curves[0];
    sc_curve_alloc(c, 2, 2, 9);
    memcpy(c->knots, knots, sizeof knots);
    for (int i = 0; i < 9; i++) {
        double w = i % 2 ? sqrt(0.5) : 1.0, u, v;
        to_domain(s, cu + r * square[i][0], cv + r * square[i][1], &u, &v);
        c->cp[3 * i] = u * w;
        c->cp[3 * i + 1] = v * w;
        c->cp[3 * i + 2] = w;
    }
}

/* A loop of cubic Bézier curves through the corners pts (normalised),
 * each edge an S-shaped wave of `bulge` of its length. */
static void add_cubic_loop_arched(sc_surface *s, int is_hole, const double (*pts)[2], int n,
                                  double bulge, double second);

static void add_cubic_loop(sc_surface *s, int is_hole, const double (*pts)[2], int n, double bulge)
{
    add_cubic_loop_arched(s, is_hole, pts, n, bulge, -bulge);
}

/* The same with the second inner control point moved by `second` (equal
 * to bulge: an arch instead of a wave). */
static void add_cubic_loop_arched(sc_surface *s, int is_hole, const double (*pts)[2], int n,
                                  double bulge, double second)
{
    sc_loop *loop = add_loop(s, is_hole, n);
    for (int k = 0; k < n; k++) {
        const double *a = pts[k], *b = pts[(k + 1) % n];
        double dx = b[0] - a[0], dy = b[1] - a[1];
        double ctrl[4][2] = {{a[0], a[1]},
                             {a[0] + dx / 3 - bulge * dy, a[1] + dy / 3 + bulge * dx},
                             {a[0] + 2 * dx / 3 - second * dy, a[1] + 2 * dy / 3 + second * dx},
                             {b[0], b[1]}};
        sc_curve *c = &loop->curves[k];
        sc_curve_alloc(c, 2, 3, 4);
        for (int i = 0; i < 8; i++)
            c->knots[i] = i < 4 ? 0.0 : 1.0;
        for (int i = 0; i < 4; i++) {
            to_domain(s, ctrl[i][0], ctrl[i][1], &c->cp[3 * i], &c->cp[3 * i + 1]);
            c->cp[3 * i + 2] = 1.0;
        }
    }
}

static const double outer_square[4][2] = {{0.05, 0.05}, {0.95, 0.05}, {0.95, 0.95}, {0.05, 0.95}};

typedef enum shape {
    SHAPE_CIRCLE, SHAPE_NINE, SHAPE_NESTED, SHAPE_STAR, SHAPE_TOUCH, SHAPE_HOLES_ONLY,
    SHAPE_POLY100, SHAPE_POLY1000, SHAPE_TWO, SHAPE_EIGHT, SHAPE_COUNT
} shape;

static const char *const shape_names[SHAPE_COUNT] = {
    "circle", "nine-curves", "nested", "star", "touching", "holes-only", "poly100", "poly1000", "two-curves",
    "eight-curves"};

/* A wavy polygon hole of n vertices around the centre. */
static void add_wavy_polygon(sc_surface *s, int n)
{
    double (*pts)[2] = malloc(sizeof *pts * (size_t)n);
    for (int k = 0; k < n; k++) {
        double a = 2 * M_PI * k / n, r = 0.3 + 0.08 * sin(7 * a) + 0.03 * sin(23 * a);
        pts[k][0] = 0.5 + r * cos(a);
        pts[k][1] = 0.5 + r * sin(a);
    }
    add_polygon(s, 1, (const double(*)[2])pts, n);
    free(pts);
}

/* Builds the shape on a patch of the given domain. */
static sc_surface *make_shape(sc_scene *scene, shape which, double u0, double u1, double v0,
                              double v1)
{
    sc_scene_init(scene);
    sc_surface *s = add_patch(scene, u0, u1, v0, v1);
    switch (which) {
    case SHAPE_CIRCLE:
        add_polygon(s, 0, outer_square, 4);
        add_circle(s, 1, 0.5, 0.5, 0.25);
        break;
    case SHAPE_NINE: {
        /* 4 bulging outer edges and a 5-sided rounded hole: 9 cubics. */
        add_cubic_loop(s, 0, outer_square, 4, 0.06);
        double penta[5][2];
        for (int k = 0; k < 5; k++) {
            double a = 2 * M_PI * k / 5 + 0.3;
            penta[k][0] = 0.5 + 0.28 * cos(a);
            penta[k][1] = 0.5 + 0.28 * sin(a);
        }
        add_cubic_loop(s, 1, (const double(*)[2])penta, 5, -0.15);
        break;
    }
    case SHAPE_TWO: {
        /* Pabst et al. Table 4's first trim: an oval hole of 2 cubics. */
        static const double ends[2][2] = {{0.2, 0.5}, {0.8, 0.5}};
        add_cubic_loop_arched(s, 1, ends, 2, 0.5, 0.5);
        break;
    }
    case SHAPE_EIGHT: {
        static const double diamond[4][2] = {{0.5, 0.2}, {0.8, 0.5}, {0.5, 0.8}, {0.2, 0.5}};
        add_cubic_loop(s, 0, outer_square, 4, 0.06);
        add_cubic_loop(s, 1, diamond, 4, -0.1);
        break;
    }
    case SHAPE_NESTED:
        add_polygon(s, 0, outer_square, 4);
        add_circle(s, 1, 0.5, 0.5, 0.4);
        add_circle(s, 1, 0.5, 0.5, 0.25);
        add_circle(s, 1, 0.45, 0.5, 0.1);
        break;
    case SHAPE_STAR: {
        double star[10][2];
        for (int k = 0; k < 10; k++) {
            double a = M_PI * k / 5 + M_PI / 2, r = k % 2 ? 0.15 : 0.4;
            star[k][0] = 0.5 + r * cos(a);
            star[k][1] = 0.5 + r * sin(a);
        }
        add_polygon(s, 0, outer_square, 4);
        add_polygon(s, 1, (const double(*)[2])star, 10);
        break;
    }
    case SHAPE_TOUCH: {
        /* A triangle whose lowest corner lies on the outer loop's bottom
         * edge, and a square whose corner touches the right edge. */
        static const double tri[3][2] = {{0.5, 0.05}, {0.7, 0.4}, {0.3, 0.4}};
        static const double diamond[4][2] = {{0.95, 0.7}, {0.8, 0.85}, {0.65, 0.7}, {0.8, 0.55}};
        add_polygon(s, 0, outer_square, 4);
        add_polygon(s, 1, tri, 3);
        add_polygon(s, 1, diamond, 4);
        break;
    }
    case SHAPE_HOLES_ONLY:
        add_circle(s, 1, 0.3, 0.6, 0.2);
        add_circle(s, 1, 0.7, 0.3, 0.15);
        break;
    case SHAPE_POLY100:
        add_polygon(s, 0, outer_square, 4);
        add_wavy_polygon(s, 98);
        break;
    case SHAPE_POLY1000:
        add_polygon(s, 0, outer_square, 4);
        add_wavy_polygon(s, 998);
        break;
    default:
        break;
    }
    sc_scene_validate_loops(scene);
    return &scene->surfaces[0];
}

/* ---- distance from the curves (normalised coordinates) ---- */

/* Whether some point of the homogeneous curve (normalised) may lie within
 * `dist` of (u, v): the control points' box, widened, by subdivision. */
static bool near_piece(const double *cp, int n, double u, double v, double dist, int depth)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i <= n; i++)
        for (int a = 0; a < 2; a++) {
            double x = cp[3 * i + a] / cp[3 * i + 2];
            lo[a] = fmin(lo[a], x);
            hi[a] = fmax(hi[a], x);
        }
    if (u < lo[0] - dist || u > hi[0] + dist || v < lo[1] - dist || v > hi[1] + dist)
        return false;
    if (depth > 50 || (hi[0] - lo[0] < dist / 4 && hi[1] - lo[1] < dist / 4))
        return true;
    double left[CURVE_DOUBLES], right[CURVE_DOUBLES], work[CURVE_DOUBLES];
    memcpy(work, cp, sizeof(double) * 3 * (size_t)(n + 1));
    for (int c = 0; c < 3; c++) {
        left[c] = work[c];
        right[3 * n + c] = work[3 * n + c];
    }
    for (int r = 1; r <= n; r++) {
        for (int i = 0; i <= n - r; i++)
            for (int c = 0; c < 3; c++)
                work[3 * i + c] = 0.5 * (work[3 * i + c] + work[3 * (i + 1) + c]);
        for (int c = 0; c < 3; c++) {
            left[3 * r + c] = work[c];
            right[3 * (n - r) + c] = work[3 * (n - r) + c];
        }
    }
    return near_piece(left, n, u, v, dist, depth + 1) || near_piece(right, n, u, v, dist, depth + 1);
}

/* The trim curves as Bézier segments, normalised to the domain: the
 * horizontal ones too, which the pieces leave out. */
typedef struct curves {
    int count;
    int *degree;
    double (*cp)[CURVE_DOUBLES];
} curves;

static void curves_of(const sc_surface *s, curves *out)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    memset(out, 0, sizeof *out);
    for (int l = 0; l < s->nloops; l++)
        for (int c = 0; c < s->loops[l].ncurves; c++) {
            sc_curve *segs;
            int nsegs;
            sc_curve_to_bezier(&s->loops[l].curves[c], &segs, &nsegs);
            out->cp = realloc(out->cp, sizeof *out->cp * (size_t)(out->count + nsegs));
            out->degree = realloc(out->degree, sizeof *out->degree * (size_t)(out->count + nsegs));
            for (int k = 0; k < nsegs; k++) {
                int n = out->count++;
                out->degree[n] = segs[k].degree;
                for (int i = 0; i <= segs[k].degree; i++) {
                    double w = segs[k].cp[3 * i + 2];
                    out->cp[n][3 * i] = (segs[k].cp[3 * i] - u0 * w) / (u1 - u0);
                    out->cp[n][3 * i + 1] = (segs[k].cp[3 * i + 1] - v0 * w) / (v1 - v0);
                    out->cp[n][3 * i + 2] = w;
                }
                sc_curve_free(&segs[k]);
            }
            free(segs);
        }
}

static void bezier_point(const double *cp, int n, double t, double *pt)
{
    double work[CURVE_DOUBLES];
    memcpy(work, cp, sizeof(double) * 3 * (size_t)(n + 1));
    for (int r = 1; r <= n; r++)
        for (int i = 0; i <= n - r; i++)
            for (int c = 0; c < 3; c++)
                work[3 * i + c] = (1 - t) * work[3 * i + c] + t * work[3 * (i + 1) + c];
    memcpy(pt, work, 3 * sizeof(double));
}

static bool near_curves(const curves *c, double un, double vn)
{
    for (int k = 0; k < c->count; k++)
        if (near_piece(c->cp[k], c->degree[k], un, vn, NEAR_CURVE, 0))
            return true;
    return false;
}

/* ---- the probe: the trim stage alone, interpreted ---- */

typedef struct probe {
    scg_program *prog;
    scg_interp *it;
    sc_trim_block block;
    float *texels;          /* record 0, then the block */
    int ntexels;
    scg_interp_env env;
} probe;

static const int BLOCK_AT = SCG_RECORD_TEXELS;

/* Texel offsets in a block (gpu_layout.h): header, cells, loops, pieces. */
static int loops_at(const sc_trim_block *block)
{
    return SCG_TRIM_HEADER_TEXELS + block->grid_u * block->grid_v;
}

static int piece_at(const sc_trim_block *block, int k)
{
    return loops_at(block) + SCG_TRIM_LOOP_TEXELS * block->nloops +
           k * SCG_TRIM_PIECE_TEXELS(block->degree);
}

static void fill_records(const sc_trim_block *block, float **texels, int *ntexels)
{
    *ntexels = BLOCK_AT + block->ntexels;
    *texels = calloc(4 * (size_t)*ntexels, sizeof(float));
    (*texels)[4 * 3 + 3] = (float)BLOCK_AT;
    memcpy(*texels + 4 * BLOCK_AT, block->texels, sizeof(float) * 4 * (size_t)block->ntexels);
}

static int probe_open(probe *p, const char *trim_field, const sc_surface *s, sc_error *err)
{
    char text[SCG_KEY_MAX];
    scg_key key;
    memset(p, 0, sizeof *p);
    snprintf(text, sizeof text, "bez3x3-poly-dc-%s-newton-cp-it6-tol0.05-ert0-out.shade",
             trim_field);
    if (scg_key_parse(text, &key, err) != SC_OK ||
        sc_trim_pack(s, key.trim_degree, &p->block, err) != SC_OK ||
        scg_build_trim_probe(&key, &p->prog, err) != SC_OK ||
        scg_interp_create(p->prog, &p->it, err) != SC_OK)
        return SC_FAIL;
    fill_records(&p->block, &p->texels, &p->ntexels);
    p->env.texels[SCG_TEX_RECORDS] = p->texels;
    p->env.texel_count[SCG_TEX_RECORDS] = p->ntexels;
    return SC_OK;
}

static void probe_close(probe *p)
{
    scg_interp_free(p->it);
    scg_program_free(p->prog);
    sc_trim_block_free(&p->block);
    free(p->texels);
}

/* Kept (1) or not (0) for the surface point (u, v) given in float; -1 on
 * an interpreter error. */
static int probe_run(probe *p, float u, float v, long long *steps, int *iters)
{
    scg_interp_result res;
    sc_error err;
    p->env.inputs[SCG_IN_UV0][0] = u;
    p->env.inputs[SCG_IN_UV0][1] = v;
    if (scg_interp_run(p->it, &p->env, &res, &err) != SC_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return -1;
    }
    if (steps)
        *steps += res.steps;
    if (iters)
        *iters += (int)res.outputs[SCG_OUT_ITERS][0];
    return res.outputs[SCG_OUT_HIT][0] != 0.0f;
}

typedef struct agreement {
    int tested, skipped_near, wrong;
    long long steps;
    int iters;
} agreement;

/* Compares the probe with the reference at one point given in normalised
 * coordinates (rounded to float in the surface's parameters). */
static bool compare_point(probe *p, const sc_surface *s, const sc_trim *trim, const curves *cv,
                          double un, double vn, agreement *a)
{
    double u, v;
    to_domain(s, un, vn, &u, &v);
    float uf = (float)u, vf = (float)v;
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    if (near_curves(cv, ((double)uf - u0) / (u1 - u0), ((double)vf - v0) / (v1 - v0))) {
        a->skipped_near++;
        return true;
    }
    int expected = sc_trim_inside(trim, uf, vf);
    int got = probe_run(p, uf, vf, &a->steps, &a->iters);
    a->tested++;
    if (got != expected) {
        a->wrong++;
        if (a->wrong <= 3)
            fprintf(stderr, "  (u, v) = (%.9g, %.9g) normalised (%.9g, %.9g): probe %d, "
                    "reference %d\n", uf, vf, un, vn, got, expected);
    }
    return got >= 0;
}

/* Random points, then points level with every piece end point (the v of
 * the block's pieces, exact in float for the unit domain). */
static bool check_surface(const char *trim_field, const sc_surface *s, int npoints, agreement *a)
{
    sc_trim *trim;
    sc_error err;
    probe p;
    memset(a, 0, sizeof *a);
    if (sc_trim_prepare(s, &trim, &err) != SC_OK || probe_open(&p, trim_field, s, &err) != SC_OK) {
        fprintf(stderr, "  %s: %s\n", s->name, err.message);
        return false;
    }
    curves cv;
    curves_of(s, &cv);
    unsigned long long rng = 0x5eed + (unsigned)s->nloops;
    bool ok = true;
    for (int k = 0; k < npoints && ok; k++) {
        double un = test_rand(&rng), vn = test_rand(&rng);
        ok = compare_point(&p, s, trim, &cv, un, vn, a);
    }
    /* Points close to the curves: a random curve point moved by 1.5 to
     * 130 times the exclusion distance in a random direction. */
    for (int k = 0; k < npoints / 2 && ok; k++) {
        int seg = (int)(test_rand(&rng) * cv.count);
        double t = test_rand(&rng), pt[3], angle = 2 * M_PI * test_rand(&rng);
        double dist = NEAR_CURVE * 1.5 * pow(2.0, 7 * test_rand(&rng));
        bezier_point(cv.cp[seg], cv.degree[seg], t, pt);
        ok = compare_point(&p, s, trim, &cv, pt[0] / pt[2] + dist * cos(angle),
                           pt[1] / pt[2] + dist * sin(angle), a);
    }
    int level = 0;
    for (int k = 0; k < p.block.npieces && ok && level < npoints; k++) {
        const float *t = p.block.texels + 4 * piece_at(&p.block, k);
        /* A random u, and a point just left of the lower end, whose ray
         * runs exactly through it. */
        for (int end = 0; end < 2 && ok; end++, level++)
            ok = compare_point(&p, s, trim, &cv, test_rand(&rng), t[end], a);
        if (ok)
            ok = compare_point(&p, s, trim, &cv, t[4 + 3] - 0.01 * test_rand(&rng), t[0], a);
    }
    free(cv.cp);
    free(cv.degree);
    probe_close(&p);
    sc_trim_free(trim);
    return ok;
}

static bool check_shape(const char *trim_field, shape which, double u0, double u1, double v0,
                        double v1, int npoints, agreement *a)
{
    sc_scene scene;
    bool ok = check_surface(trim_field, make_shape(&scene, which, u0, u1, v0, v1), npoints, a);
    sc_scene_free(&scene);
    return ok;
}

/* ---- keys ---- */

TEST(trimgpu_key_forms)
{
    static const char *const good[] = {
        "bez3x3-poly-dc-clip3i16-newton-cp-it6-tol0.05-ert0-out.shade",
        "bez3x3-poly-dc-left2i8-newton-cp-it6-tol0.05-ert0-out.shade",
        "nurbs5x5-rat-dc-fast11i64-newton-cp-it8-tol1-ert2-out.aov",
        "bezdyn-poly-loop-fast1i1-newton-cp-it6-tol0.05-ert0-out.shade",
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        scg_key key;
        sc_error err;
        char back[SCG_KEY_MAX];
        CHECK_INT(scg_key_parse(good[i], &key, &err), SC_OK);
        CHECK_STR(scg_key_format(&key, back, sizeof back), good[i]);
        CHECK_INT(scg_key_check(&key, &err), SC_OK);
    }
    scg_key key;
    sc_error err;
    CHECK_INT(scg_key_parse(good[1], &key, &err), SC_OK);
    CHECK_INT(key.trim, SC_TRIM_LEFT);
    CHECK_INT(key.trim_degree, 2);
    CHECK_INT(key.trim_iters, 8);
    static const char *const bad[] = {"clip3", "fast0i4", "left3i0", "clip3i65", "trim1",
                                      "clip17i4", "fast3i", "clipi4", "clip03i4"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[SCG_KEY_MAX];
        snprintf(text, sizeof text, "bez3x3-poly-dc-%s-newton-cp-it6-tol0.05-ert0-out.shade",
                 bad[i]);
        CHECK_INT(scg_key_parse(text, &key, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, "trim configuration");
    }
}

TEST(trimgpu_scene_keys)
{
    sc_scene scene;
    make_shape(&scene, SHAPE_CIRCLE, 0, 1, 0, 1);
    scg_key key;
    char text[SCG_KEY_MAX];
    /* The outer polygon is of degree 1, the circle of degree 2. */
    sc_surface_key(&scene.surfaces[0], NULL, &key);
    CHECK_STR(scg_key_format(&key, text, sizeof text),
              "bez3x3-poly-dc-fast2i16-newton-cp-it6-tol0.05-ert1-out.shade.aov");
    sc_key_options opts;
    memset(&opts, 0, sizeof opts);
    opts.trim_method = SC_TRIM_LEFT;
    opts.trim_iters = 24;
    sc_surface_key(&scene.surfaces[0], &opts, &key);
    CHECK_STR(scg_key_format(&key, text, sizeof text),
              "bez3x3-poly-dc-left2i24-newton-cp-it6-tol0.05-ert1-out.shade.aov");
    opts.ignore_trims = 1;
    sc_surface_key(&scene.surfaces[0], &opts, &key);
    CHECK_STR(scg_key_format(&key, text, sizeof text),
              "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert1-out.shade.aov");
    /* Every trimmed key a scene asks for builds. */
    scg_program *prog;
    sc_error err;
    sc_surface_key(&scene.surfaces[0], NULL, &key);
    CHECK_INT(scg_build_program(&key, &prog, &err), SC_OK);
    scg_program_free(prog);
    sc_scene_free(&scene);
}

/* ---- layout ---- */

TEST(trimgpu_pack_layout)
{
    /* Domain [2, 6] × [-1, 1]; outer rectangle (0.25..0.75)² normalised:
     * two vertical pieces (the horizontal edges leave), a 4 × 4 grid
     * (about 4 cells a piece). */
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 2, 6, -1, 1);
    static const double rect[4][2] = {{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
    add_polygon(s, 0, rect, 4);
    sc_trim_block block;
    sc_error err;
    CHECK_INT(sc_surface_trim_degree(s), 1);
    CHECK_INT(sc_trim_pack(s, 2, &block, &err), SC_OK);
    CHECK_INT(block.degree, 2);
    CHECK_INT(block.npieces, 2);
    CHECK_INT(block.grid_u, 4);
    CHECK_INT(block.grid_v, 4);
    CHECK_INT(block.bias, 0);
    int piece = SCG_TRIM_PIECE_TEXELS(2);
    CHECK_INT(piece, 4);
    /* The edges u = 0.25 and 0.75 are column boundaries: a piece's bounds,
     * widened by a few float steps, reach into the cells on both sides, so
     * rows 1 and 2 list each piece in 2 cells. */
    CHECK_INT(block.nentries, 2 * 2 * 2);
    CHECK_INT(block.nloops, 1);
    /* Header, 16 cells, one loop, its two pieces, the entries. */
    int cells = 2, loop = cells + 16, pieces = loop + 2;
    CHECK_INT(block.ntexels, pieces + 2 * piece + SCG_TRIM_ENTRY_TEXELS * block.nentries);
    const float *t = block.texels;
    CHECK_NEAR(t[0], 1, 0);
    CHECK_NEAR(t[1], 0, 0);
    CHECK_NEAR(t[2], 4, 0);
    CHECK_NEAR(t[3], 4, 0);
    CHECK_NEAR(t[4], 0.25, 0);   /* scale_u = 1 / 4 */
    CHECK_NEAR(t[5], 0.5, 0);    /* scale_v = 1 / 2 */
    CHECK_NEAR(t[6], -0.5, 0);   /* offset_u = -2 / 4 */
    CHECK_NEAR(t[7], 0.5, 0);    /* offset_v = 1 / 2 */
    /* Both pieces run upwards from v = 0.25 to 0.75; one at u = 0.75, the
     * other at 0.25; a line elevated to degree 2 has its middle point at
     * the middle. */
    double seen_u = 0;
    int piece_u[2] = {0, 0};     /* texel offset of the piece at u = 0.25, 0.75 */
    for (int k = 0; k < 2; k++) {
        const float *h = t + 4 * (pieces + k * piece);
        CHECK_NEAR(h[0], 0.25, 0);
        CHECK_NEAR(h[1], 0.75, 0);
        CHECK(h[2] < h[3]);
        double u = h[4 + 3];                 /* u_lo in the first point's w */
        CHECK(u == 0.25 || u == 0.75);
        piece_u[u == 0.75] = pieces + k * piece;
        CHECK_NEAR(h[2], u, 1e-6);
        CHECK_NEAR(h[3], u, 1e-6);
        for (int i = 0; i < 3; i++) {
            CHECK_NEAR(h[4 + 4 * i + 0], u, 1e-7);
            CHECK_NEAR(h[4 + 4 * i + 1], 0.25 + 0.25 * i, 1e-7);
            CHECK_NEAR(h[4 + 4 * i + 2], 1.0, 0);
        }
        seen_u += u;
    }
    CHECK_NEAR(seen_u, 1.0, 0);
    /* The loop: the box of its pieces (u bounds widened by a few float
     * steps, v exact), then its range. */
    const float *box = t + 4 * loop;
    CHECK(box[0] < 0.25f && box[1] > 0.75f);
    CHECK_NEAR(box[0], 0.25, 1e-6);
    CHECK_NEAR(box[1], 0.75, 1e-6);
    CHECK_NEAR(box[2], 0.25, 0);
    CHECK_NEAR(box[3], 0.75, 0);
    CHECK_NEAR(box[4], pieces, 0);
    CHECK_NEAR(box[5], 2, 0);
    /* Cells, known by construction. Rows 0 and 3 (v < 0.25, v >= 0.75)
     * meet no piece: parity 0, no entry. In rows 1 and 2 both pieces span
     * the row. Their bounds, widened by a few float steps, reach into the
     * columns on both sides of their edge: columns 0 and 1 list the piece
     * at 0.25 and have the one at 0.75 wholly right (parity 1), columns 2
     * and 3 list the piece at 0.75 and nothing lies right (parity 0). */
    static const int parity[4] = {1, 1, 0, 0};
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++) {
            const float *cell = t + 4 * (cells + 4 * row + col);
            bool inner = row == 1 || row == 2;
            CHECK_NEAR(cell[0], inner ? parity[col] : 0, 0);
            CHECK_NEAR(cell[2], inner ? 1 : 0, 0);
            if (!inner)
                continue;
            const float *entry = t + 4 * (int)cell[1];
            double u = col < 2 ? 0.25 : 0.75;
            CHECK_INT((int)entry[4], piece_u[col >= 2]);
            CHECK_NEAR(entry[0], 0.25, 0);
            CHECK_NEAR(entry[1], 0.75, 0);
            CHECK(entry[2] < u && u < entry[3]);
            CHECK_NEAR(entry[2], u, 1e-6);
            CHECK_NEAR(entry[3], u, 1e-6);
        }
    sc_trim_block_free(&block);
    /* A degree below the curves' is refused; holes only give bias 1. */
    CHECK_INT(sc_trim_pack(s, 0, &block, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "trim degree 0");
    sc_scene_free(&scene);
    make_shape(&scene, SHAPE_HOLES_ONLY, 0, 1, 0, 1);
    CHECK_INT(sc_trim_pack(&scene.surfaces[0], 2, &block, &err), SC_OK);
    CHECK_INT(block.bias, 1);
    CHECK_NEAR(block.texels[1], 1, 0);
    /* The bottom-left cell lies outside both holes: kept by parity alone. */
    const float *corner = block.texels + 4 * 2;
    CHECK_NEAR(corner[0], 1, 0);
    CHECK_NEAR(corner[2], 0, 0);
    sc_trim_block_free(&block);
    sc_scene_free(&scene);
}

/* Runs of v where the pieces right of a cell flip its parity, on 4 × 4
 * grids; the runs' ends are the pieces' float end points. */
TEST(trimgpu_pack_runs)
{
    /* Outer loop on the domain's edges, a triangle hole with its lowest
     * corner at (0.8, 0.4) and a horizontal top edge at v = 0.9. */
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 0, 1, 0, 1);
    static const double outer[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const double tri[3][2] = {{0.8, 0.4}, {0.95, 0.9}, {0.65, 0.9}};
    add_polygon(s, 0, outer, 4);
    add_polygon(s, 1, tri, 3);
    sc_trim_block block;
    sc_error err;
    CHECK_INT(sc_trim_pack(s, 1, &block, &err), SC_OK);
    CHECK_INT(block.npieces, 4);
    CHECK_INT(block.grid_u, 4);
    CHECK_INT(block.grid_v, 4);
    const float *t = block.texels;
    int cells = 2;
    /* Column 1, row 1 (u, v in [0.25, 0.5)): the outer edge u = 1 spans
     * the row (parity 1); both triangle sides, right of the cell, start at
     * v = 0.4: their flips cancel. Decided by the parity alone. */
    const float *cell = t + 4 * (cells + 4 * 1 + 1);
    CHECK_NEAR(cell[0], 1, 0);
    CHECK_NEAR(cell[2], 0, 0);
    /* Column 1, row 3 (v >= 0.75, to infinity): the triangle's sides end
     * at 0.9 (cancel), the outer edge u = 1 ends at v = 1: one run from
     * 1 on, where the point leaves the outer loop. */
    cell = t + 4 * (cells + 4 * 3 + 1);
    CHECK_NEAR(cell[0], 1, 0);
    CHECK_NEAR(cell[2], 1, 0);
    const float *run = t + 4 * (int)cell[1];
    CHECK_NEAR(run[0], 1.0, 0);
    CHECK(run[1] == FLT_MAX && run[2] == FLT_MAX && run[3] == FLT_MAX);
    CHECK_NEAR(run[4], 0, 0);
    sc_trim_block_free(&block);
    sc_scene_free(&scene);

    /* Holes only (bias 1): a triangle (0.55, 0.3), (0.95, 0.9), (0.05, 0.45).
     * In column 1, row 1 the side from (0.05, 0.45) down to the corner
     * passes through the cell (listed), the side from the corner up to
     * (0.95, 0.9) lies right of it and starts in the row (a run from 0.3),
     * the top side lies left of it. */
    sc_scene_init(&scene);
    s = add_patch(&scene, 0, 1, 0, 1);
    static const double hole[3][2] = {{0.55, 0.3}, {0.95, 0.9}, {0.05, 0.45}};
    add_polygon(s, 1, hole, 3);
    CHECK_INT(sc_trim_pack(s, 1, &block, &err), SC_OK);
    CHECK_INT(block.npieces, 3);
    CHECK_INT(block.grid_u, 4);
    t = block.texels;
    cell = t + 4 * (cells + 4 * 1 + 1);
    CHECK_NEAR(cell[0], 1, 0);
    CHECK_NEAR(cell[2], 2, 0);
    int listed = 0, runs = 0;
    for (int e = 0; e < 2; e++) {
        const float *entry = t + 4 * ((int)cell[1] + SCG_TRIM_ENTRY_TEXELS * e);
        if (entry[4] > 0) {
            listed++;
            CHECK_NEAR(entry[0], 0.3f, 0);
            CHECK_NEAR(entry[1], 0.45f, 0);
            CHECK(entry[2] <= 0.05 + 1e-6 && entry[3] >= 0.55 - 1e-6);
        } else {
            runs++;
            CHECK_NEAR(entry[0], 0.3f, 0);
            CHECK(entry[1] == FLT_MAX && entry[2] == FLT_MAX);
        }
    }
    CHECK_INT(listed, 1);
    CHECK_INT(runs, 1);
    sc_trim_block_free(&block);
    sc_scene_free(&scene);
}

/* The loop table: each loop's pieces together, its range and its box,
 * known by construction; a loop left open is never skipped from the left;
 * the per-piece methods skip the loops whose box misses the point. */
TEST(trimgpu_pack_loops)
{
    /* Nested: the outer square (its two vertical edges), then circles of
     * 4 quarter arcs each (each arc monotone in v), in scene order. */
    sc_scene scene;
    sc_surface *s = make_shape(&scene, SHAPE_NESTED, 0, 1, 0, 1);
    sc_trim_block block;
    sc_error err;
    CHECK_INT(sc_trim_pack(s, 2, &block, &err), SC_OK);
    CHECK_INT(block.nloops, 4);
    CHECK_NEAR(block.texels[0], 4, 0);
    CHECK_INT(block.npieces, 2 + 3 * 4);
    static const double centre[4][2] = {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}, {0.45, 0.5}};
    static const double radius[4] = {0.45, 0.4, 0.25, 0.1};
    static const int count[4] = {2, 4, 4, 4};
    int next = piece_at(&block, 0);
    for (int l = 0; l < 4; l++) {
        const float *box = block.texels + 4 * (loops_at(&block) + SCG_TRIM_LOOP_TEXELS * l);
        double lo_u = centre[l][0] - radius[l], hi_u = centre[l][0] + radius[l];
        double lo_v = centre[l][1] - radius[l], hi_v = centre[l][1] + radius[l];
        CHECK(box[0] <= lo_u && box[1] >= hi_u);
        CHECK_NEAR(box[0], lo_u, 1e-6);
        CHECK_NEAR(box[1], hi_u, 1e-6);
        CHECK_NEAR(box[2], lo_v, 1e-7);
        CHECK_NEAR(box[3], hi_v, 1e-7);
        CHECK_INT((int)box[4], next);
        CHECK_INT((int)box[5], count[l]);
        /* Every piece of a circle's range has both ends on that circle. */
        for (int k = 0; l > 0 && k < count[l]; k++) {
            const float *piece = block.texels + 4 * (next + k * SCG_TRIM_PIECE_TEXELS(2));
            for (int end = 0; end <= 2; end += 2) {
                const float *q = piece + 4 * (1 + end);
                double du = q[0] / q[2] - centre[l][0], dv = q[1] / q[2] - centre[l][1];
                CHECK_NEAR(sqrt(du * du + dv * dv), radius[l], 1e-6);
            }
        }
        next += count[l] * SCG_TRIM_PIECE_TEXELS(2);
    }
    sc_trim_block_free(&block);
    sc_scene_free(&scene);

    /* A curve left open (scene built in code, not validated): from (0.2,
     * 0.2) up to (0.5, 0.8), down to (0.8, 0.5). Its ends do not pair up
     * in v, so its box reaches to -FLT_MAX: the point (0.1, 0.35), left
     * of the curve, gets the crossing of its first edge, as in the
     * reference, with the outer loop's right edge: 2, not kept. */
    sc_scene_init(&scene);
    s = add_patch(&scene, 0, 1, 0, 1);
    add_polygon(s, 0, outer_square, 4);
    sc_curve *open = &add_loop(s, 1, 1)->curves[0];
    static const double bends[3][2] = {{0.2, 0.2}, {0.5, 0.8}, {0.8, 0.5}};
    static const double open_knots[5] = {0, 0, 1, 2, 2};
    sc_curve_alloc(open, 2, 1, 3);
    memcpy(open->knots, open_knots, sizeof open_knots);
    for (int i = 0; i < 3; i++) {
        open->cp[3 * i] = bends[i][0];
        open->cp[3 * i + 1] = bends[i][1];
        open->cp[3 * i + 2] = 1.0;
    }
    CHECK_INT(sc_trim_pack(s, 1, &block, &err), SC_OK);
    CHECK_INT(block.nloops, 2);
    const float *outer_box = block.texels + 4 * loops_at(&block);
    CHECK_NEAR(outer_box[0], 0.05, 1e-6);
    CHECK(outer_box[SCG_TRIM_LOOP_TEXELS * 4] == -FLT_MAX);
    CHECK_NEAR(outer_box[SCG_TRIM_LOOP_TEXELS * 4 + 1], 0.8, 1e-6);
    sc_trim_block_free(&block);
    sc_trim *trim;
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
    CHECK_INT(sc_trim_crossings(trim, 0.1, 0.35), 2);
    static const char *const methods[] = {"clip1i16", "left1i16", "fast1i16"};
    for (int m = 0; m < 3; m++) {
        probe p;
        CHECK_INT(probe_open(&p, methods[m], s, &err), SC_OK);
        CHECK_INT(probe_run(&p, 0.1f, 0.35f, NULL, NULL), 0);
        CHECK_INT(probe_run(&p, 0.3f, 0.35f, NULL, NULL), sc_trim_inside(trim, 0.3f, 0.35f));
        probe_close(&p);
    }
    sc_trim_free(trim);
    sc_scene_free(&scene);

    /* Skipping: 98 pieces of a wavy hole (radius 0.3 ± 0.11 about the
     * centre) and the outer square. Visiting a piece takes more than 4
     * instructions (its address, a fetch, two comparisons, a branch), so
     * a point inside the hole's box, which visits all 98, runs more than
     * 98 · 4; a point left of the box or above it skips the loop whole
     * and runs fewer. */
    s = make_shape(&scene, SHAPE_POLY100, 0, 1, 0, 1);
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
    static const float points[3][2] = {{0.5f, 0.5f}, {0.07f, 0.5f}, {0.5f, 0.93f}};
    for (int m = 0; m < 2; m++) {
        probe p;
        CHECK_INT(probe_open(&p, methods[m], s, &err), SC_OK);
        for (int k = 0; k < 3; k++) {
            long long steps = 0;
            CHECK_INT(probe_run(&p, points[k][0], points[k][1], &steps, NULL),
                      sc_trim_inside(trim, points[k][0], points[k][1]));
            CHECK(k == 0 ? steps > 98 * 4 : steps < 98 * 4);
        }
        probe_close(&p);
    }
    sc_trim_free(trim);
    sc_scene_free(&scene);
}

/* ---- the trim stage against the reference ---- */

static void run_methods(const char *const *fields, int nfields, const shape *shapes, int nshapes,
                        double u0, double u1, double v0, double v1, int npoints)
{
    for (int f = 0; f < nfields; f++)
        for (int k = 0; k < nshapes; k++) {
            agreement a;
            char field[32];
            sc_scene scene;
            make_shape(&scene, shapes[k], u0, u1, v0, v1);
            snprintf(field, sizeof field, fields[f], sc_surface_trim_degree(&scene.surfaces[0]));
            sc_scene_free(&scene);
            CHECK(check_shape(field, shapes[k], u0, u1, v0, v1, npoints, &a));
            fprintf(stderr, "  %-6s %-11s %5d points (%d near a curve left out): %d wrong, "
                    "%.0f instructions and %.2f clipping iterations per point\n",
                    field, shape_names[shapes[k]], a.tested, a.skipped_near, a.wrong,
                    (double)a.steps / a.tested, (double)a.iters / a.tested);
            CHECK_INT(a.wrong, 0);
        }
}

static const char *const all_methods[] = {"clip%di16", "left%di16", "fast%di16"};

TEST(trimgpu_probe_shapes)
{
    static const shape shapes[] = {SHAPE_CIRCLE, SHAPE_NINE, SHAPE_NESTED, SHAPE_STAR,
                                   SHAPE_TOUCH, SHAPE_HOLES_ONLY};
    run_methods(all_methods, 3, shapes, 6, 0, 1, 0, 1, 600);
}

TEST(trimgpu_probe_other_domain)
{
    /* Normalisation: the domain [-3, 5] × [10, 10.5]. */
    static const shape shapes[] = {SHAPE_CIRCLE, SHAPE_STAR, SHAPE_NINE};
    run_methods(all_methods, 3, shapes, 3, -3, 5, 10, 10.5, 400);
}

TEST(trimgpu_probe_many_pieces)
{
    static const shape shapes[] = {SHAPE_POLY100, SHAPE_POLY1000};
    run_methods(all_methods + 2, 1, shapes, 2, 0, 1, 0, 1, 600);
    run_methods(all_methods, 2, shapes, 1, 0, 1, 0, 1, 300);
}

/* The accelerated method's second phase: a point whose cell lists two
 * pieces it lies between the bounds of. A narrow V-shaped hole with its
 * tip at (0.5, 0.3), on a 4 × 4 grid: in the row [0.25, 0.5) the parts of
 * both sides reach u = 0.5, so points above the tip on u = 0.5 lie within
 * the bounds of both; both are clipped — at least one clipping iteration
 * each — the second found by the scan that follows the first clipping.
 * The verdict must be the reference's. */
TEST(trimgpu_probe_two_ambiguous)
{
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 0, 1, 0, 1);
    static const double v_hole[3][2] = {{0.5, 0.3}, {0.51, 0.6}, {0.49, 0.6}};
    add_polygon(s, 1, v_hole, 3);
    sc_trim *trim;
    sc_error err;
    probe p;
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
    CHECK_INT(probe_open(&p, "fast1i16", s, &err), SC_OK);
    int tested = 0, wrong = 0;
    CHECK_INT(p.block.grid_v, 4);
    for (int k = 1; k <= 40; k++) {
        float v = (float)(0.3 + 0.00495 * k);
        int iters = 0;
        int kept = probe_run(&p, 0.5f, v, NULL, &iters);
        tested++;
        wrong += kept != sc_trim_inside(trim, 0.5, v);
        CHECK(iters >= 2);
    }
    CHECK_INT(tested, 40);
    CHECK_INT(wrong, 0);
    probe_close(&p);
    sc_trim_free(trim);
    sc_scene_free(&scene);
}

/* Loops that cross each other (left unvalidated): the reference counts
 * crossings with every piece, the even-odd rule of the loops as they are.
 * The grid needs no order among the pieces of a row, only that each is a
 * curve, so every method must still agree with it. */
TEST(trimgpu_probe_crossing_loops)
{
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 0, 1, 0, 1);
    add_polygon(s, 0, outer_square, 4);
    add_circle(s, 1, 0.42, 0.5, 0.25);
    add_circle(s, 1, 0.58, 0.45, 0.2);
    for (int m = 0; m < 3; m++) {
        char field[32];
        agreement a;
        snprintf(field, sizeof field, all_methods[m], 2);
        CHECK(check_surface(field, s, 400, &a));
        CHECK(a.tested > 500);
        CHECK_INT(a.wrong, 0);
    }
    sc_scene_free(&scene);
}

/* A closed Bézier curve of degree n through points on a circle about
 * (0.5, 0.5) (first point = last), as a hole. */
static void add_bezier_hole(sc_surface *s, int n)
{
    sc_curve *c = &add_loop(s, 1, 1)->curves[0];
    sc_curve_alloc(c, 2, n, n + 1);
    for (int i = 0; i < 2 * (n + 1); i++)
        c->knots[i] = i <= n ? 0.0 : 1.0;
    for (int i = 0; i <= n; i++) {
        double a = 2 * M_PI * (i % n) / n, r = 0.3 + 0.1 * (i % 2);
        to_domain(s, 0.5 + r * cos(a), 0.5 + r * sin(a), &c->cp[3 * i], &c->cp[3 * i + 1]);
        c->cp[3 * i + 2] = 1.0;
    }
}

/* Trim curves up to the degree a key can name (SC_TRIM_MAX_DEGREE) are
 * drawn, every method agreeing with the reference; one degree more is
 * refused with a message that names the surface, the loop and the curve,
 * by the reference and by the packing alike. */
TEST(trimgpu_high_degree)
{
    for (int n = 12; n <= SC_TRIM_MAX_DEGREE; n += SC_TRIM_MAX_DEGREE - 12) {
        sc_scene scene;
        sc_scene_init(&scene);
        sc_surface *s = add_patch(&scene, 0, 1, 0, 1);
        add_polygon(s, 0, outer_square, 4);
        add_bezier_hole(s, n);
        sc_scene_validate_loops(&scene);
        CHECK_INT(scene.dropped_loops, 0);
        CHECK_INT(sc_surface_trim_degree(s), n);
        for (int m = 0; m < 3; m++) {
            char field[32];
            agreement a;
            snprintf(field, sizeof field, all_methods[m], n);
            CHECK(check_surface(field, s, 300, &a));
            CHECK(a.tested > 300);
            CHECK_INT(a.wrong, 0);
        }
        sc_scene_free(&scene);
    }
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 0, 1, 0, 1);
    snprintf(s->name, sizeof s->name, "lid");
    add_polygon(s, 0, outer_square, 4);
    add_bezier_hole(s, SC_TRIM_MAX_DEGREE + 1);
    sc_trim *trim;
    sc_trim_block block;
    sc_error err;
    char expected[160];
    snprintf(expected, sizeof expected,
             "surface 'lid', trim loop 1 (a hole), curve 0: a 2D curve of degree %d; trimming "
             "takes 2D curves of degree 1..%d", SC_TRIM_MAX_DEGREE + 1, SC_TRIM_MAX_DEGREE);
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_FAIL);
    CHECK_STR(err.message, expected);
    CHECK_INT(sc_trim_pack(s, SC_TRIM_MAX_DEGREE, &block, &err), SC_FAIL);
    CHECK_STR(err.message, expected);
    CHECK_INT(block.ntexels, 0);
    sc_scene_free(&scene);
}

TEST(trimgpu_example_scenes)
{
    static const char *const files[] = {"trim_hole.obj", "trim_nine.obj", "trim_nested.obj",
                                        "trim_star.obj", "trim_touch.obj"};
    static const int loops[] = {1, 2, 4, 2, 3};
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        char path[512];
        sc_scene scene;
        sc_error err;
        snprintf(path, sizeof path, "%s/examples/scenes/%s", test_root_dir, files[f]);
        CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
        CHECK_INT(scene.nsurfaces, 1);
        CHECK_INT(scene.surfaces[0].nloops, loops[f]);
        CHECK_INT(scene.dropped_loops, 0);
        for (int m = 0; m < 3; m++) {
            char field[32];
            agreement a;
            snprintf(field, sizeof field, all_methods[m], sc_surface_trim_degree(&scene.surfaces[0]));
            CHECK(check_surface(field, &scene.surfaces[0], 300, &a));
            if (a.wrong)
                fprintf(stderr, "  %s %s: %d of %d wrong\n", files[f], field, a.wrong, a.tested);
            CHECK_INT(a.wrong, 0);
        }
        sc_scene_free(&scene);
    }
}

/* ---- the whole intersection program, interpreted ---- */

/* The GPU data of a flat patch x = u, y = v, z = 0 over [0, 1]² (centre
 * (0.5, 0.5, 0)) with its trim block, and a ray environment. */
typedef struct flat_patch {
    float points[16 * 4];
    float *texels;
    int ntexels;
    scg_interp_env env;
} flat_patch;

static void flat_patch_init(flat_patch *f, const sc_surface *s, const sc_trim_block *block)
{
    memset(f, 0, sizeof *f);
    for (int i = 0; i < 16; i++) {
        f->points[4 * i + 0] = (float)(s->cp[4 * i + 0] - 0.5);
        f->points[4 * i + 1] = (float)(s->cp[4 * i + 1] - 0.5);
        f->points[4 * i + 3] = 1.0f;
    }
    fill_records(block, &f->texels, &f->ntexels);
    const float record[15] = {0, 4, 4, 0, 0, 0, 3, 3, 0, 1, 0, 1, 0.5f, 0.5f, 0};
    memcpy(f->texels, record, sizeof record);
    f->env.texels[SCG_TEX_POINTS] = f->points;
    f->env.texel_count[SCG_TEX_POINTS] = 16;
    f->env.texels[SCG_TEX_RECORDS] = f->texels;
    f->env.texel_count[SCG_TEX_RECORDS] = f->ntexels;
    f->env.uniforms[SCG_UNI_FOOTPRINT][0] = 0.002f;
    const float domain[4] = {0, 1, 0, 1};
    memcpy(f->env.inputs[SCG_IN_DOMAIN], domain, sizeof domain);
    f->env.inputs[SCG_IN_T_LIMIT][0] = 3.0e38f;
}

/* The ray from origin (re-centred) at the target (un, vn) on the patch,
 * the hull at 0.9 of the way. */
static void flat_patch_ray(flat_patch *f, const double origin[3], double un, double vn)
{
    for (int a = 0; a < 3; a++) {
        double target = a == 0 ? un - 0.5 : a == 1 ? vn - 0.5 : 0.0;
        f->env.inputs[SCG_IN_RAY_ORIGIN][a] = (float)origin[a];
        f->env.inputs[SCG_IN_RAY_DIR][a] = (float)(0.9 * (target - origin[a]));
    }
}

static int key_for(const char *trim_field, scg_key *key, scg_program **prog, scg_interp **it,
                   sc_error *err)
{
    char text[SCG_KEY_MAX];
    snprintf(text, sizeof text, "bez3x3-poly-dc-%s-newton-cp-it6-tol0.05-ert0-out.shade",
             trim_field);
    *prog = NULL;
    *it = NULL;
    if (scg_key_parse(text, key, err) != SC_OK || scg_build_program(key, prog, err) != SC_OK)
        return SC_FAIL;
    return scg_interp_create(*prog, it, err);
}

/* Oblique rays at random targets: the hit must be the reference's
 * classification of the (u, v) found. A record without a trim block
 * (texel +3 .w = 0) keeps every hit. */
TEST(trimgpu_newton_trimmed_patch)
{
    static const shape shapes[] = {SHAPE_CIRCLE, SHAPE_STAR};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 2; k++) {
            sc_scene scene;
            sc_surface *s = make_shape(&scene, shapes[k], 0, 1, 0, 1);
            char field[32];
            snprintf(field, sizeof field, all_methods[m], sc_surface_trim_degree(s));
            scg_key key;
            scg_program *prog;
            scg_interp *it;
            sc_trim_block block;
            sc_trim *trim;
            sc_error err;
            CHECK_INT(key_for(field, &key, &prog, &it, &err), SC_OK);
            CHECK_INT(sc_trim_pack(s, key.trim_degree, &block, &err), SC_OK);
            CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
            curves cv;
            curves_of(s, &cv);
            flat_patch f;
            flat_patch_init(&f, s, &block);
            unsigned long long rng = 77;
            int kept = 0, trimmed = 0, missed = 0;
            for (int r = 0; r < 300; r++) {
                double un = 0.02 + 0.96 * test_rand(&rng), vn = 0.02 + 0.96 * test_rand(&rng);
                double origin[3] = {un - 0.5 + 0.3 * (test_rand(&rng) - 0.5),
                                    vn - 0.5 + 0.3 * (test_rand(&rng) - 0.5), 2.0};
                flat_patch_ray(&f, origin, un, vn);
                scg_interp_result res;
                CHECK_INT(scg_interp_run(it, &f.env, &res, &err), SC_OK);
                double u = res.outputs[SCG_OUT_UV][0], v = res.outputs[SCG_OUT_UV][1];
                CHECK_NEAR(u, un, 1e-4);
                CHECK_NEAR(v, vn, 1e-4);
                if (near_curves(&cv, u, v))
                    continue;
                int expected = sc_trim_inside(trim, u, v);
                CHECK_INT(res.outputs[SCG_OUT_HIT][0] != 0, expected);
                kept += expected;
                trimmed += !expected;
                f.texels[4 * 3 + 3] = 0;
                CHECK_INT(scg_interp_run(it, &f.env, &res, &err), SC_OK);
                missed += res.outputs[SCG_OUT_HIT][0] == 0;
                f.texels[4 * 3 + 3] = (float)BLOCK_AT;
            }
            CHECK(kept > 50 && trimmed > 50);
            CHECK_INT(missed, 0);
            free(f.texels);
            free(cv.cp);
            free(cv.degree);
            sc_trim_free(trim);
            sc_trim_block_free(&block);
            scg_interp_free(it);
            scg_program_free(prog);
            sc_scene_free(&scene);
        }
}

static int compare_doubles(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* A first look at the cost of each trim method, per pixel, on the CPU:
 * the whole program interpreted for a 40×40 grid of rays straight down on
 * the flat patch, instructions executed and time per ray (median of 3
 * runs), against the same key untrimmed. Figures for docs/trimming.md;
 * nothing about speed is asserted. */
TEST(trimgpu_cost_per_pixel)
{
    static const shape shapes[] = {SHAPE_TWO, SHAPE_EIGHT, SHAPE_NINE, SHAPE_POLY100,
                                   SHAPE_POLY1000};
    static const char *const fields[] = {"trim0", "clip%di16", "left%di16", "fast%di16"};
    enum { GRID = 40, RUNS = 3 };
    for (size_t k = 0; k < sizeof shapes / sizeof shapes[0]; k++) {
        sc_scene scene;
        sc_surface *s = make_shape(&scene, shapes[k], 0, 1, 0, 1);
        double base_steps = 0;
        for (int m = 0; m < 4; m++) {
            char field[32];
            snprintf(field, sizeof field, fields[m], sc_surface_trim_degree(s));
            scg_key key;
            scg_program *prog;
            scg_interp *it;
            sc_trim_block block;
            sc_error err;
            CHECK_INT(key_for(field, &key, &prog, &it, &err), SC_OK);
            CHECK_INT(sc_trim_pack(s, sc_surface_trim_degree(s), &block, &err), SC_OK);
            flat_patch f;
            flat_patch_init(&f, s, &block);
            double times[RUNS];
            long long steps = 0;
            int hits = 0;
            for (int r = 0; r < RUNS; r++) {
                steps = 0;
                hits = 0;
                double t0 = sc_now();
                for (int j = 0; j < GRID; j++)
                    for (int i = 0; i < GRID; i++) {
                        double un = (i + 0.5) / GRID, vn = (j + 0.5) / GRID;
                        double origin[3] = {un - 0.5, vn - 0.5, 2.0};
                        scg_interp_result res;
                        flat_patch_ray(&f, origin, un, vn);
                        CHECK_INT(scg_interp_run(it, &f.env, &res, &err), SC_OK);
                        steps += res.steps;
                        hits += res.outputs[SCG_OUT_HIT][0] != 0;
                    }
                times[r] = sc_now() - t0;
            }
            qsort(times, RUNS, sizeof times[0], compare_doubles);
            double per_ray = (double)steps / (GRID * GRID);
            if (m == 0)
                base_steps = per_ray;
            fprintf(stderr, "  %-11s %5d pieces %-9s %6.0f instructions/ray (%.2f x untrimmed), "
                    "%6.2f us/ray, %4.1f %% kept\n", shape_names[shapes[k]], block.npieces, field,
                    per_ray, per_ray / base_steps, 1e6 * times[RUNS / 2] / (GRID * GRID),
                    100.0 * hits / (GRID * GRID));
            if (m == 3)
                fprintf(stderr, "  %-11s block: %d x %d cells, %d entries, %d texels (%d bytes)\n",
                        shape_names[shapes[k]], block.grid_u, block.grid_v, block.nentries,
                        block.ntexels, 16 * block.ntexels);
            free(f.texels);
            sc_trim_block_free(&block);
            scg_interp_free(it);
            scg_program_free(prog);
        }
        sc_scene_free(&scene);
    }
}
