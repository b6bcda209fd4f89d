/* test_trim_gpu.c — the generated trim stage run by the IR interpreter in
 * single precision against the reference's exact double-precision
 * classification (runtime/model/trim.c), for every trim method: on random
 * points farther than 64 float ulps (of 1.0, in normalised domain
 * coordinates) from every curve, and on points level with piece end points.
 * Shapes (trim_probe.c): a circular hole of rational quadratic arcs, 9 cubic
 * curves, nested holes, a star with sharp corners, a hole whose corner
 * touches the outer loop, a surface with holes only, polygons of 100 and
 * 1000 pieces, and the example scenes examples/scenes/trim_*.obj. Keys and
 * the block layout: test_trim_pack.c. */
#include <stdlib.h>

#include "io.h"
#include "test.h"
#include "trim_probe.h"

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
        sc_scene_validate_loops(&scene, NULL);
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
