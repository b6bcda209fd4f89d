/* trim_probe.c — shapes, curve distances and the trim-stage probe of the
 * GPU trimming tests (trim_probe.h). */
#include "trim_probe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

/* ---- shapes ---- */

/* A flat bicubic patch over the domain [u0, u1] × [v0, v1]: x = u, y = v. */
sc_surface *add_patch(sc_scene *scene, double u0, double u1, double v0, double v1)
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

sc_loop *add_loop(sc_surface *s, int is_hole, int ncurves)
{
    s->loops = sc_realloc(s->loops, (size_t)s->nloops + 1, sizeof *s->loops);
    sc_loop *loop = &s->loops[s->nloops++];
    loop->is_hole = is_hole;
    loop->ncurves = ncurves;
    loop->curves = sc_alloc((size_t)ncurves, sizeof *loop->curves);
    return loop;
}

/* Domain coordinates from normalised ones. */
void to_domain(const sc_surface *s, double un, double vn, double *u, double *v)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    *u = u0 + un * (u1 - u0);
    *v = v0 + vn * (v1 - v0);
}

/* A closed polygon (normalised coordinates) as one degree-1 B-spline. */
void add_polygon(sc_surface *s, int is_hole, const double (*pts)[2], int n)
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
void add_circle(sc_surface *s, int is_hole, double cu, double cv, double r)
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

const double outer_square[4][2] = {{0.05, 0.05}, {0.95, 0.05}, {0.95, 0.95}, {0.05, 0.95}};

const char *const shape_names[SHAPE_COUNT] = {
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
sc_surface *make_shape(sc_scene *scene, shape which, double u0, double u1, double v0,
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
    sc_scene_validate_loops(scene, NULL);
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

void curves_of(const sc_surface *s, curves *out)
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

bool near_curves(const curves *c, double un, double vn)
{
    for (int k = 0; k < c->count; k++)
        if (near_piece(c->cp[k], c->degree[k], un, vn, NEAR_CURVE, 0))
            return true;
    return false;
}

/* ---- the probe: the trim stage alone, interpreted ---- */

const int BLOCK_AT = SCG_RECORD_TEXELS;

/* Texel offsets in a block (gpu_layout.h): header, cells, loops, pieces. */
int loops_at(const sc_trim_block *block)
{
    return SCG_TRIM_HEADER_TEXELS + block->grid_u * block->grid_v;
}

int piece_at(const sc_trim_block *block, int k)
{
    return loops_at(block) + SCG_TRIM_LOOP_TEXELS * block->nloops +
           k * SCG_TRIM_PIECE_TEXELS(block->degree);
}

void fill_records(const sc_trim_block *block, float **texels, int *ntexels)
{
    *ntexels = BLOCK_AT + block->ntexels;
    *texels = calloc(4 * (size_t)*ntexels, sizeof(float));
    (*texels)[4 * 3 + 3] = (float)BLOCK_AT;
    memcpy(*texels + 4 * BLOCK_AT, block->texels, sizeof(float) * 4 * (size_t)block->ntexels);
}

int probe_open(probe *p, const char *trim_field, const sc_surface *s, sc_error *err)
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

void probe_close(probe *p)
{
    scg_interp_free(p->it);
    scg_program_free(p->prog);
    sc_trim_block_free(&p->block);
    free(p->texels);
}

/* Kept (1) or not (0) for the surface point (u, v) given in float; -1 on
 * an interpreter error. */
int probe_run(probe *p, float u, float v, long long *steps, int *iters)
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
bool check_surface(const char *trim_field, const sc_surface *s, int npoints, agreement *a)
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

bool check_shape(const char *trim_field, shape which, double u0, double u1, double v0,
                        double v1, int npoints, agreement *a)
{
    sc_scene scene;
    bool ok = check_surface(trim_field, make_shape(&scene, which, u0, u1, v0, v1), npoints, a);
    sc_scene_free(&scene);
    return ok;
}
