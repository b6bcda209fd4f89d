/* test_ert.c — early ray termination and draw order (gl_render.h) on real
 * Mesa: every early-termination mode and every draw-order policy gives the
 * image of no early termination (fail_pct 0 against it, same surface at
 * every pixel), on the stacked patches and on the scene of six keys; the
 * scenes' known answers (the nearest layer everywhere, the CPU reference);
 * tile values read back that hide nothing (a strip just in front of a
 * tilted patch), and their reduction against a plain maximum; the batch rule (read-back count); hulls holding the eye; the options on the
 * command line. */
#include "gl_context_util.h"
#include "test.h"

#include <stdlib.h>

#include "gl_context.h"
#include "gl_render_private.h"
#include "imgdiff.h"
#include "io.h"
#include "emit_glsl.h"
#include "options.h"
#include "refcast.h"

static const char *scene_path(const char *name)
{
    static char path[4][1024];
    static int next;
    char *p = path[next++ % 4];
    snprintf(p, sizeof path[0], "%s/examples/scenes/%s", test_root_dir, name);
    return p;
}

static int render(sc_gl_context *ctx, const sc_scene *scene, const sc_render_desc *desc,
                  const sc_camera *cam, sc_aov *aov, sc_render_stats *stats)
{
    sc_error err = {0};
    sc_renderer *r;
    int ok = sc_renderer_create(sc_gl_context_gl(ctx), scene, desc, &r, &err) == SC_OK;
    if (ok) {
        ok = sc_renderer_draw(r, cam, &err) == SC_OK &&
             sc_renderer_read(r, NULL, aov, &err) == SC_OK;
        sc_renderer_stats(r, stats);
        sc_renderer_destroy(r);
    }
    if (!ok)
        fprintf(stderr, "  render: %s\n", err.message);
    return ok;
}

/* fail_pct 0 against the image without early termination, and the same
 * surface at every pixel. */
static int same_image(const sc_aov *none, const sc_aov *test, const char *what)
{
    sc_accuracy acc;
    sc_error err = {0};
    if (sc_accuracy_compare(none, test, &acc, &err) != SC_OK) {
        fprintf(stderr, "  %s: %s\n", what, err.message);
        return 0;
    }
    long other_surface = 0;
    for (int p = 0; p < none->width * none->height; p++)
        other_surface += none->surface[p] != test->surface[p];
    if (acc.fail_pct != 0 || other_surface)
        fprintf(stderr, "  %s: fail_pct %g, %ld pixels on another surface\n", what, acc.fail_pct,
                other_surface);
    return acc.fail_pct == 0 && other_surface == 0;
}

/* Looking down -z at the stack: the nearest layer (surface 0) covers the
 * whole view. */
static const sc_camera stack_camera = {.eye = {0, 0, 4.5}, .target = {0, 0, 0},
                                       .fovy_deg = 22.6, .width = 128, .height = 128};

TEST(ert_modes_stack_same_image)
{
    TEST_NEED_GL_CONTEXT(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(scene_path("stack_16.obj"), &scene, &err), SC_OK);
    CHECK_INT(scene.nsurfaces, 16);
    sc_render_desc desc = {.ert = SC_TERMINATION_NONE};
    sc_aov none;
    sc_render_stats stats;
    CHECK(render(ctx, &scene, &desc, &stack_camera, &none, &stats));
    CHECK_INT(stats.readbacks, 0);
    int hulls = stats.hulls;
    long not_nearest = 0;
    for (int p = 0; p < none.width * none.height; p++)
        not_nearest += none.surface[p] != 0;
    CHECK_INT(not_nearest, 0);

    static const struct {
        sc_ray_termination ert;
        int batch;
    } cases[] = {{SC_TERMINATION_CONSERVATIVE, 0}, {SC_TERMINATION_MANUAL, 0},      {SC_TERMINATION_MANUAL, 1},
                 {SC_TERMINATION_MANUAL, 1000000}, {SC_TERMINATION_MANUAL_BOTH, 0}, {SC_TERMINATION_MANUAL_BOTH, 5}};
    int ok = 1;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0] && ok; c++) {
        for (int order = SC_HULL_ORDER_FRONT_TO_BACK; order <= SC_HULL_ORDER_HYBRID && ok; order++) {
            desc = (sc_render_desc){.ert = cases[c].ert, .batch_hulls = cases[c].batch,
                                    .order = (sc_hull_order)order};
            sc_aov aov;
            CHECK(render(ctx, &scene, &desc, &stack_camera, &aov, &stats));
            char what[96];
            snprintf(what, sizeof what, "%s batch %d %s", cli_termination_name(cases[c].ert),
                     cases[c].batch, cli_order_name((sc_hull_order)order));
            ok = same_image(&none, &aov, what);
            /* At most one read-back after every batch but the last (no
             * hull holds the eye), none without the texture. Layer 0 covers
             * the view and a layer's hulls reach at most 3 layers down (the
             * bump), so once a batch has drawn the top layers, every hull
             * more than 4 layers down (plus a tile's margin) is culled. */
            int batch = cases[c].batch ? cases[c].batch : SC_RENDER_DEFAULT_BATCH_HULLS;
            int manual = cases[c].ert != SC_TERMINATION_CONSERVATIVE;
            int most_readbacks = manual ? (hulls + batch - 1) / batch - 1 : 0;
            int per_layer = hulls / 16;
            int least_culled = manual && batch <= 2 * per_layer ? hulls - 6 * per_layer : 0;
            if (stats.readbacks > most_readbacks || stats.culled_hulls < least_culled ||
                (!manual && stats.culled_hulls)) {
                fprintf(stderr, "  %s: %d read-backs (at most %d), %d hulls culled (at least %d)\n",
                        what, stats.readbacks, most_readbacks, stats.culled_hulls, least_culled);
                ok = 0;
            }
            sc_aov_free(&aov);
        }
    }
    sc_aov_free(&none);
    sc_scene_free(&scene);
    CHECK(ok);
}

/* The programs count the intersections they run on the GPU. Every covered
 * pixel ran one at least; without early termination the hulls of all 16
 * layers overlap the centre of the view, so the count exceeds the covered
 * pixels several times; culling hulls behind the first layer (one hull per
 * batch, front to back) runs fewer, and never fewer than the covered pixels. */
TEST(ert_counts_intersections)
{
    TEST_NEED_GL_CONTEXT(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(scene_path("stack_16.obj"), &scene, &err), SC_OK);
    sc_render_desc descs[2] = {{.ert = SC_TERMINATION_NONE},
                               {.ert = SC_TERMINATION_MANUAL, .batch_hulls = 1,
                                .order = SC_HULL_ORDER_FRONT_TO_BACK}};
    long long counted[2] = {0};
    long covered[2] = {0};
    for (int i = 0; i < 2; i++) {
        sc_aov aov;
        sc_render_stats stats;
        CHECK(render(ctx, &scene, &descs[i], &stack_camera, &aov, &stats));
        for (int p = 0; p < aov.width * aov.height; p++)
            covered[i] += aov.surface[p] >= 0;
        counted[i] = stats.intersections;
        CHECK(i == 0 || stats.culled_hulls > 0);
        sc_aov_free(&aov);
    }
    CHECK_INT(covered[0], 128 * 128);
    CHECK_INT(covered[1], covered[0]);
    CHECK(counted[0] >= 4 * (long long)covered[0]);
    CHECK(counted[1] >= covered[1]);
    CHECK(counted[1] < counted[0]);
    sc_scene_free(&scene);
}

/* A camera turned away from the stack: every hull lies outside the view,
 * so nothing is drawn, nothing read back and no intersection runs, in every
 * mode; and a camera looking at it draws it (the test is not vacuous). */
TEST(ert_turned_away_draws_nothing)
{
    TEST_NEED_GL_CONTEXT(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(scene_path("stack_4.obj"), &scene, &err), SC_OK);
    sc_camera away = stack_camera;
    away.target[2] = 2 * away.eye[2];  /* looking up +z, the stack behind */
    for (int ert = SC_TERMINATION_NONE; ert <= SC_TERMINATION_PEEL; ert++) {
        sc_render_desc desc = {.ert = (sc_ray_termination)ert};
        for (int look = 0; look < 2; look++) {
            sc_aov aov;
            sc_render_stats stats;
            CHECK(render(ctx, &scene, &desc, look ? &stack_camera : &away, &aov, &stats));
            long covered = 0;
            for (int p = 0; p < aov.width * aov.height; p++)
                covered += aov.surface[p] >= 0;
            if (look) {
                CHECK(covered > 0 && stats.draw_calls > 0 && stats.intersections >= covered);
            } else {
                CHECK_INT(covered, 0);
                CHECK_INT(stats.draw_calls, 0);
                CHECK_INT(stats.readbacks, 0);
                CHECK(stats.intersections == 0);
            }
            sc_aov_free(&aov);
        }
    }
    sc_scene_free(&scene);
}

/* The programs of a batch read only what the batches before it wrote (GL
 * leaves reading what the same draw writes undefined): what they read is
 * left in sc_nearest_t after the frame. With one batch that is the cleared
 * value everywhere, though every pixel has a hit; with one hull per batch,
 * front to back, it is the largest over each tile of the hits before the
 * last batch: never nearer than a pixel's final hit, and a hit (not the
 * cleared value) on most of the image. */
TEST(ert_nearest_from_earlier_batches)
{
    TEST_NEED_GL_CONTEXT(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(scene_path("stack_16.obj"), &scene, &err), SC_OK);
    int n = stack_camera.width * stack_camera.height;
    float *nearest = sc_alloc((size_t)n, sizeof(float));
    static const int batches[] = {1000000, 1};
    for (int b = 0; b < 2; b++) {
        sc_render_desc desc = {.ert = SC_TERMINATION_MANUAL, .batch_hulls = batches[b],
                               .order = SC_HULL_ORDER_FRONT_TO_BACK};
        sc_renderer *r;
        sc_aov aov;
        CHECK_INT(sc_renderer_create(sc_gl_context_gl(ctx), &scene, &desc, &r, &err), SC_OK);
        CHECK_INT(sc_renderer_draw(r, &stack_camera, &err), SC_OK);
        CHECK_INT(sc_renderer_read(r, NULL, &aov, &err), SC_OK);
        CHECK_INT(sc_renderer_read_nearest(r, nearest, &err), SC_OK);
        long cleared = 0, nearer = 0, missed = 0;
        for (int p = 0; p < n; p++) {
            missed += aov.surface[p] < 0;
            cleared += nearest[p] == 3.0e38f;
            nearer += nearest[p] < aov.t[p];
        }
        sc_render_stats stats;
        sc_renderer_stats(r, &stats);
        sc_renderer_destroy(r);
        sc_aov_free(&aov);
        CHECK_INT(missed, 0);
        CHECK_INT(nearer, 0);
        if (b == 0) {
            CHECK_INT(stats.readbacks, 0);
            CHECK_INT(cleared, n);
        } else {
            CHECK(stats.readbacks > 0);
            CHECK(cleared < n / 4);
        }
    }
    free(nearest);
    sc_scene_free(&scene);
}

/* The read-backs' reduction against a plain maximum over each tile, on
 * sizes that end in part tiles and in part runs of the vectorised column
 * pass (widths 1 to 21 past a multiple of 8); values in [0, 256), as
 * distances and depths are. */
TEST(ert_tile_maxima_is_each_tile_s_largest_value)
{
    const int T = SCG_NEAREST_TILE;
    unsigned seed = 12345;
    int sizes[][2] = {{1, 1}, {3, 2}, {8, 4}, {13, 7}, {29, 9}, {64, 17}, {1027, 13}};
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
        int w = sizes[i][0], h = sizes[i][1], tw = (w + T - 1) / T, th = (h + T - 1) / T;
        float *pixels = malloc((size_t)w * (size_t)h * sizeof *pixels);
        float *expect = malloc((size_t)tw * (size_t)th * sizeof *expect);
        float *got = malloc((size_t)tw * (size_t)th * sizeof *got);
        for (int t = 0; t < tw * th; t++)
            expect[t] = -1;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                seed = seed * 1103515245u + 12345u;
                float v = (float)((seed >> 8) & 0xffff) / 256.0f;
                pixels[y * w + x] = v;
                float *e = &expect[(y / T) * tw + x / T];
                *e = v > *e ? v : *e;
            }
        sc_tile_maxima(pixels, w, h, tw, got);
        int wrong = 0;
        for (int t = 0; t < tw * th; t++)
            wrong += got[t] != expect[t];
        if (wrong)
            fprintf(stderr, "  %d x %d: %d tiles wrong\n", w, h, wrong);
        CHECK_INT(wrong, 0);
        free(pixels);
        free(expect);
        free(got);
    }
}

/* A flat bilinear patch with corners at z = z0 + slope · y, x within
 * half_x and y within half_y of (0, cy). */
static void add_tilted_rectangle(sc_scene *scene, double cy, double half_x, double half_y,
                                 double z0, double slope)
{
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, 1, 1, 2, 2);
    static const double knots[4] = {0, 0, 1, 1};
    memcpy(s->knots_u, knots, sizeof knots);
    memcpy(s->knots_v, knots, sizeof knots);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            double *c = &s->cp[4 * (j * 2 + i)];
            c[0] = i ? half_x : -half_x;
            c[1] = cy + (j ? half_y : -half_y);
            c[2] = z0 + slope * c[1];
            c[3] = 1;
        }
    sc_surface_update_rational(s);
}

/* Culling never hides a surface, and neither does the programs' discard:
 * a large patch tilted away from the eye (its box's nearest corner close,
 * so it is drawn first) and a strip 0.02–0.08 in front of it, drawn after
 * it (its box farther). Once the large patch is read back, every tile the
 * strip's box touches holds the large patch's depth, up to 1.6 % beyond
 * the strip: tile values that erred small by that much would cull the
 * strip's hull or discard its rays. One hull per batch, front to back, in
 * frames with the AOVs (distances from the uvt attachment) and colour-only
 * ones (window depths from the depth buffer, converted once a tile),
 * against the image of no early termination. */
TEST(ert_tile_values_never_hide_a_surface)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_scene_init(&scene);
    add_tilted_rectangle(&scene, 0, 2, 2, 0, 0.3);         /* z from -0.6 to 0.6 */
    add_tilted_rectangle(&scene, -1.5, 0.5, 0.1, -0.4, 0); /* the first at -0.48..-0.42 */
    sc_error err = {0};
    const sc_camera cam = {.eye = {0, 0, 10}, .target = {0, 0, 0}, .fovy_deg = 30,
                           .width = 96, .height = 96};
    for (int colour_only = 0; colour_only < 2; colour_only++) {
        sc_image image[2] = {{0}};
        sc_aov aov[2] = {{0}};
        for (int manual = 0; manual < 2; manual++) {
            sc_render_desc desc = {.ert = manual ? SC_TERMINATION_MANUAL : SC_TERMINATION_NONE,
                                   .batch_hulls = 1, .order = SC_HULL_ORDER_FRONT_TO_BACK,
                                   .aovs_on_demand = colour_only};
            sc_renderer *r;
            CHECK_INT(sc_renderer_create(gl, &scene, &desc, &r, &err), SC_OK);
            CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
            sc_render_stats stats;
            sc_renderer_stats(r, &stats);
            CHECK(manual ? stats.readbacks > 0 : stats.readbacks == 0);
            /* The frame itself: its colour attachment, or its AOVs (a read
             * would draw a colour-only frame again, with them). */
            if (colour_only)
                CHECK_INT(sc_gl_target_read_image(gl, &r->target, SCG_FRAG_OUT_COLOUR,
                                                  &image[manual], &err), SC_OK);
            else
                CHECK_INT(sc_renderer_read(r, NULL, &aov[manual], &err), SC_OK);
            sc_renderer_destroy(r);
        }
        if (colour_only) {
            long differ = 0;
            for (int p = 0; image[0].pixels && image[1].pixels && p < cam.width * cam.height; p++)
                for (int c = 0; c < 3; c++)
                    if (image[0].pixels[p * image[0].channels + c] !=
                        image[1].pixels[p * image[1].channels + c]) {
                        differ++;
                        break;
                    }
            if (differ)
                fprintf(stderr, "  colour-only: %ld pixels differ\n", differ);
            CHECK(image[0].pixels && image[1].pixels);
            CHECK_INT(differ, 0);
        } else {
            /* The strip shows (surface 1), and the same pixels in both. */
            long strip = 0;
            for (int p = 0; aov[0].surface && p < cam.width * cam.height; p++)
                strip += aov[0].surface[p] == 1;
            CHECK(strip > 30);
            CHECK(same_image(&aov[0], &aov[1], "aov frames"));
        }
        for (int m = 0; m < 2; m++) {
            sc_image_free(&image[m]);
            sc_aov_free(&aov[m]);
        }
    }
    sc_scene_free(&scene);
}

/* Six keys interleaved in depth: every policy, with and without early
 * termination, gives the image of by-program order without it, and that
 * one matches the CPU reference. */
TEST(ert_orders_mixed_same_image)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const char *path = scene_path("mixed_keys.obj");
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
    sc_camera cam = {.eye = {0.3, 0.2, 5}, .target = {0, 0, -0.5}, .fovy_deg = 30,
                     .width = 128, .height = 128};
    sc_aov ref, none;
    CHECK_INT(sc_refcast_cached(path, &cam, test_tmpdir(), &ref, &err), SC_OK);
    sc_render_desc desc = {.ert = SC_TERMINATION_NONE, .order = SC_HULL_ORDER_BY_PROGRAM};
    sc_render_stats stats;
    CHECK(render(ctx, &scene, &desc, &cam, &none, &stats));
    CHECK_INT(stats.programs, 6);
    CHECK_INT(stats.program_switches, 6);
    sc_accuracy acc;
    CHECK_INT(sc_accuracy_compare(&ref, &none, &acc, &err), SC_OK);
    sc_aov_free(&ref);
    CHECK(acc.ref_hits > 128 * 128 * 9 / 10);
    if (acc.fail_pct > 0.1)
        fprintf(stderr, "  against the reference: fail_pct %g\n", acc.fail_pct);
    CHECK(acc.fail_pct <= 0.1);

    int switches[4] = {0};
    int ok = 1;
    for (int order = SC_HULL_ORDER_FRONT_TO_BACK; order <= SC_HULL_ORDER_HYBRID && ok; order++) {
        desc = (sc_render_desc){.ert = SC_TERMINATION_MANUAL_BOTH, .order = (sc_hull_order)order,
                                .batch_hulls = 16};
        sc_aov aov;
        CHECK(render(ctx, &scene, &desc, &cam, &aov, &stats));
        ok = same_image(&none, &aov, cli_order_name((sc_hull_order)order));
        switches[order] = stats.program_switches;
        sc_aov_free(&aov);
    }
    sc_aov_free(&none);
    sc_scene_free(&scene);
    CHECK(ok);
    /* By program: once per program; strictly front to back switches most,
     * the hybrid at most once per program and bucket. */
    CHECK_INT(switches[SC_HULL_ORDER_BY_PROGRAM], 6);
    CHECK(switches[SC_HULL_ORDER_FRONT_TO_BACK] > switches[SC_HULL_ORDER_HYBRID]);
    CHECK(switches[SC_HULL_ORDER_HYBRID] >= 6);
}

/* The eye inside the (single) hull of the top layer: that hull is drawn by
 * its back faces with the same key without early termination, and the
 * image is the reference's. */
TEST(ert_eye_inside_hull)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const char *path = scene_path("stack_4.obj");
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
    /* Above the surface (0.016 there) and below the hull's top (0.03). */
    sc_camera cam = {.eye = {0.2, 0.1, 0.025}, .target = {0.2, 0.1, -1}, .fovy_deg = 60,
                     .width = 64, .height = 64};
    sc_render_desc desc = {.ert = SC_TERMINATION_NONE, .hulls = {.mode = SC_SPLIT_UNIFORM, .divisions = 1}};
    sc_aov ref, none, manual;
    sc_render_stats stats;
    CHECK_INT(sc_refcast_cached(path, &cam, test_tmpdir(), &ref, &err), SC_OK);
    CHECK(render(ctx, &scene, &desc, &cam, &none, &stats));
    CHECK_INT(stats.programs, 1);
    desc.ert = SC_TERMINATION_MANUAL;
    CHECK(render(ctx, &scene, &desc, &cam, &manual, &stats));
    CHECK_INT(stats.programs, 2);  /* ert1, and ert0 for the hull holding the eye */
    CHECK_INT(stats.readbacks, 1);  /* after the hull holding the eye */
    sc_accuracy acc;
    CHECK_INT(sc_accuracy_compare(&ref, &manual, &acc, &err), SC_OK);
    CHECK_INT(acc.ref_hits, 64 * 64);
    CHECK(acc.fail_pct <= 0.1);
    long not_top = 0;
    for (int p = 0; p < ref.width * ref.height; p++)
        not_top += ref.surface[p] != 0;
    CHECK_INT(not_top, 0);
    int ok = same_image(&none, &manual, "manual, eye inside a hull");
    sc_aov_free(&ref);
    sc_aov_free(&none);
    sc_aov_free(&manual);
    sc_scene_free(&scene);
    CHECK(ok);
}

TEST(ert_names)
{
    sc_ray_termination mode;
    for (int m = SC_TERMINATION_NONE; m <= SC_TERMINATION_PEEL; m++) {
        CHECK_INT(cli_termination_parse(cli_termination_name((sc_ray_termination)m), &mode, NULL), SC_OK);
        CHECK_INT(mode, m);
    }
    CHECK_STR(cli_termination_name(SC_TERMINATION_MANUAL_BOTH), "manual-both");
    sc_hull_order order;
    CHECK_INT(cli_order_parse("by-program", &order, NULL), SC_OK);
    CHECK_INT(order, SC_HULL_ORDER_BY_PROGRAM);
    CHECK_STR(cli_order_name(SC_HULL_ORDER_HYBRID), "hybrid");
    sc_error err = {0};
    CHECK_INT(cli_termination_parse("early", &mode, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "unknown early ray termination 'early'");
    CHECK_INT(cli_order_parse("default", &order, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "front-to-back, by-program or hybrid");
}

TEST(ert_cli)
{
    char cmd[2048], *out = NULL, *err_text = NULL;
    const char *dir = test_tmpdir();
    snprintf(cmd, sizeof cmd,
             "%s render %s -o %s/ert.png --size 32x32 --frames 1 --camera 0,0,4.5,0,0,0,22.6 "
             "--ert manual-both --order front-to-back --batch 1",
             test_cli, scene_path("stack_2.obj"), dir);
    int status = test_run(cmd, &out, &err_text);
    if (status == 1 && err_text && strstr(err_text, "OSMesa")) {
        free(out);
        free(err_text);
        SKIP("no GL context");
    }
    CHECK_INT(status, 0);
    CHECK_CONTAINS(out, " draw_calls=");
    CHECK_CONTAINS(out, " program_switches=1 ");
    free(out);
    free(err_text);

    snprintf(cmd, sizeof cmd, "%s render %s -o %s/bad.png --ert sometimes", test_cli,
             scene_path("stack_2.obj"), dir);
    CHECK_INT(test_run(cmd, &out, &err_text), 2);
    CHECK_CONTAINS(err_text, "unknown early ray termination 'sometimes'");
    free(out);
    free(err_text);
    snprintf(cmd, sizeof cmd, "%s bench --order front,back", test_cli);
    CHECK_INT(test_run(cmd, &out, &err_text), 2);
    CHECK_CONTAINS(err_text, "unknown draw order 'front'");
    free(out);
    free(err_text);
    snprintf(cmd, sizeof cmd, "%s bench --batch 0", test_cli);
    CHECK_INT(test_run(cmd, &out, &err_text), 2);
    CHECK_CONTAINS(err_text, "--batch takes sizes of 1 to 1000000 hulls, not '0'");
    free(out);
    free(err_text);
    snprintf(cmd, sizeof cmd, "%s bench --help", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "--ert LIST");
    free(out);
}

/* What each mode asks of the generated program: ert3 declares
 * depth_greater and reads no texture; ert1 reads the nearest distance and
 * leaves before the intersection when the hull lies behind it. */
TEST(ert_generated_programs)
{
    scg_key key;
    sc_error err = {0};
    CHECK_INT(scg_key_parse("bez3x3-poly-dc-trim0-newton-cp-it4-tol0.05-ert3-out.shade.aov", &key,
                            &err),
              SC_OK);
    CHECK_INT(key.ert, SCG_ERT_CONSERVATIVE);
    scg_generated gen;
    CHECK_INT(scg_generate(&key, &gen, &err), SC_OK);
    const char *frag = scg_text_str(&gen.fragment);
    int ok = strstr(frag, "layout(depth_greater) out float gl_FragDepth;") != NULL &&
             strstr(frag, "sc_nearest_t") == NULL;
    scg_generated_free(&gen);
    CHECK(ok);
    key.ert = SCG_ERT_BEFORE;
    CHECK_INT(scg_generate(&key, &gen, &err), SC_OK);
    frag = scg_text_str(&gen.fragment);
    const char *read = strstr(frag, "texelFetch(sc_nearest_t");
    const char *leave = strstr(frag, "if (sc_t_limit < 1.0)\n        discard;");
    const char *call = strstr(frag, "sc_intersect(hit");
    ok = read && leave && call && read < leave && leave < call && !strstr(frag, "depth_greater");
    scg_generated_free(&gen);
    CHECK(ok);
}

/* `splinecast render SCENE -o NAME.png --frames 1 OPTIONS`, into the
 * test's folder; its exit status, stdout and stderr. */
static int render_cli(const char *scene, const char *name, const char *options, char **out,
                      char **err_text)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s render %s -o %s/%s.png --frames 1 %s", test_cli, scene,
             test_tmpdir(), name, options);
    return test_run(cmd, out, err_text);
}

/* The teapot at 128². */
static int render_teapot(const char *name, const char *options, char **out, char **err_text)
{
    char with_size[1024];
    snprintf(with_size, sizeof with_size, "--size 128x128 %s", options);
    return render_cli("teapot", name, with_size, out, err_text);
}

/* Whether a render's exit and stderr say that no GL context could be made
 * (then out and err_text are freed). */
static int no_gl_context(int status, char *out, char *err_text)
{
    if (!(status == 1 && err_text && strstr(err_text, "OSMesa")))
        return 0;
    free(out);
    free(err_text);
    return 1;
}

/* coverage_pct, fail_pct and normal_mean_deg of the `accuracy` line in
 * out; 0 when it has none. */
static int read_accuracy(const char *out, double *coverage, double *fail, double *normal_mean)
{
    const char *acc = out ? strstr(out, "accuracy coverage_pct=") : NULL;
    return acc && sscanf(acc,
                         "accuracy coverage_pct=%lf fail_pct=%lf pos_median_px=%*f pos_max_px=%*f "
                         "normal_mean_deg=%lf",
                         coverage, fail, normal_mean) == 3;
}

/* Candidate lists (ert5, gl_lists.c): every hull of the teapot listed
 * (`--ert lists`: one draw of tiles, no read-back), and the image within
 * the chart's bound of the CPU reference. The manual mode lists hulls up
 * to 8 pixels by default, and only those up to the size asked. */
TEST(ert_lists_match_the_reference)
{
    char *out = NULL, *err_text = NULL;
    int status = render_teapot("lists", "--ref --ert lists", &out, &err_text);
    if (no_gl_context(status, out, err_text))
        SKIP("no GL context");
    CHECK_INT(status, 0);
    CHECK_CONTAINS(out, " draw_calls=1 ");
    CHECK_CONTAINS(out, " readbacks=0 ");
    CHECK_CONTAINS(out, "program bez3x3-poly-pow-trim0-hybrid-mid-it6-tol0.05-ert5-out.shade.aov\n");
    double coverage = 1, fail = 1, normal_mean = 1;
    CHECK(read_accuracy(out, &coverage, &fail, &normal_mean));
    CHECK(coverage == 0);
    CHECK(fail <= 0.1);
    free(out);
    free(err_text);

    /* Hulls up to 4 pixels wide at 128²: some listed (a second program),
     * the rest drawn after the lists' hits were read back; none with off. */
    static const struct { const char *name, *options, *says; int status; } cases[] = {
        {"default", "", " program_switches=2 ", 0},
        {"small", "--lists-below 4", " program_switches=2 ", 0},
        {"none", "--lists-below off", " program_switches=1 ", 0},
        {"bad", "--lists-below 0", "--lists-below takes off or 1 to 65536 pixels, not '0'", 2},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        CHECK_INT(render_teapot(cases[i].name, cases[i].options, &out, &err_text),
                  cases[i].status);
        CHECK_CONTAINS(cases[i].status ? err_text : out, cases[i].says);
        free(out);
        free(err_text);
    }
}

/* A listed hull's ray starts at the nearest crossing of the sub-patch's
 * control net, in front of the nearer of two crossings where the surface
 * turns back near a silhouette, as the hull's front face starts it. The
 * teacup at 256², hulls up to 8 pixels listed (the default): with the
 * surface point of a 3 × 3 grid nearest the ray as the start, 0.073 % of
 * the pixels failed and the normals were off by 0.126° on average (a
 * farther crossing's normal, 130–170° off); with a mesh of surface points,
 * 0.042°; from the net, 0.00007°, as the hulls alone (docs/speed.md,
 * "Candidate lists"). */
TEST(ert_lists_start_at_the_nearer_crossing)
{
    REQUIRE_DATA("teaset/teacup.bpt");
    char *out = NULL, *err_text = NULL;
    int status = render_cli(test_data("teaset/teacup.bpt"), "teacup_lists", "--size 256x256 --ref",
                            &out, &err_text);
    if (no_gl_context(status, out, err_text))
        SKIP("no GL context");
    CHECK_INT(status, 0);
    CHECK_CONTAINS(out, " program_switches=2 ");   /* lists and hulls */
    double coverage = 1, fail = 1, normal_mean = 1;
    CHECK(read_accuracy(out, &coverage, &fail, &normal_mean));
    CHECK(coverage == 0);
    CHECK(fail == 0);
    CHECK(normal_mean < 0.001);
    free(out);
    free(err_text);
}
