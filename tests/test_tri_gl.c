/* test_tri_gl.c — terrains through the public API and the command line:
 * the GPU render of a terrain against the exact CPU reference, the
 * Manhattan sets against a plain order, bad height files refused with
 * file:line and no image, and the `splines` line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

#include "aov.h"
#include "image.h"
#include "splinecast.h"
#include "test.h"
#include "view_legend.h"

/* One frame of Franke's C2 terrain (N = 144: 288 patches) with the given
 * order, compared with the reference. */
static void render_franke(sc_context_id ctx, sc_scene_id scene, sc_hull_order order,
                          const char *view, sc_comparison *cmp, long *hits)
{
    sc_error err = {0};
    sc_renderer_id renderer;
    sc_renderer_desc desc = {.order = order};
    CHECK_INT(sc_make_renderer(ctx, scene, &desc, &renderer, &err), SC_OK);
    sc_key key;
    int count = 0;
    CHECK_INT(sc_query_renderer_keys(renderer, &key, 1, &count, &err), SC_OK);
    CHECK_INT(count, 1);
    /* The scene key without the AOVs, which sc_draw's frames do not write
     * (sc_render's draw them with the scene key itself). */
    CHECK_STR(key.text, "tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert1-out.shade");
    sc_camera_desc camera = {.width = 128, .height = 96, .text = view};
    sc_frame_id gpu, ref;
    CHECK_INT(sc_render(renderer, &camera, &gpu, &err), SC_OK);
    CHECK_INT(sc_render_reference(scene, &camera, NULL, &ref, &err), SC_OK);
    CHECK_INT(sc_compare_frames(ref, gpu, cmp, &err), SC_OK);
    *hits = cmp->test_hits;
    sc_destroy_frame(gpu);
    sc_destroy_frame(ref);
    sc_destroy_renderer(renderer);
}

TEST(tri_gl_terrain_against_reference)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    sc_scene_desc sdesc = {.franke = 144};
    CHECK_INT(sc_make_scene(&sdesc, &scene, &err), SC_OK);
    sc_scene_info info;
    CHECK_INT(sc_query_scene_info(scene, &info, &err), SC_OK);
    CHECK_INT(info.terrain_patches, 288);
    /* The keys a build would generate are the ones the renderer draws with. */
    sc_key skey;
    int nkeys = 0;
    CHECK_INT(sc_query_scene_keys(scene, NULL, &skey, 1, &nkeys, &err), SC_OK);
    CHECK_INT(nkeys, 1);
    CHECK_STR(skey.text, "tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert1-out.shade.aov");
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_comparison sets, plain;
    long sets_hits, plain_hits;
    const char *oblique = "1.6,-1.2,1.4,0.5,0.5,0.2,35";
    render_franke(ctx, scene, SC_HULL_ORDER_DEFAULT, oblique, &sets, &sets_hits);
    render_franke(ctx, scene, SC_HULL_ORDER_FRONT_TO_BACK, oblique, &plain, &plain_hits);
    printf("  %ld reference hits\n  sets: %s\n  front-to-back: %s\n", sets.reference_hits,
           sets.line, plain.line);
    CHECK(sets.reference_hits > 2000);
    CHECK(sets.fail_pct <= 0.1);
    CHECK(plain.fail_pct <= 0.1);
    CHECK_INT(sets_hits, plain_hits);
    CHECK(sets.normal_max_deg < 1);
    /* From inside the prisms' box, where whole sets near the eye are
     * culled: the sets after them are still drawn. */
    const char *above = "0.5,0.02,1.1,0.5,0.6,0.3,60";
    render_franke(ctx, scene, SC_HULL_ORDER_DEFAULT, above, &sets, &sets_hits);
    render_franke(ctx, scene, SC_HULL_ORDER_FRONT_TO_BACK, above, &plain, &plain_hits);
    printf("  above, sets: %s\n", sets.line);
    CHECK(sets.reference_hits > 2000);
    CHECK(sets.fail_pct <= 0.1);
    CHECK_INT(sets_hits, plain_hits);
    sc_shutdown();
}

/* Malformed height files: `terrain` names file and line, exits 1 and
 * writes no image. */
TEST(tri_cli_terrain_refuses_bad_heights)
{
    static const struct { const char *name, *text, *says; } cases[] = {
        {"ragged.csv", "1,2,3\n4,5\n", "ragged.csv:2:"},
        {"word.csv", "1,2\n3,high\n", "word.csv:2:"},
        {"nan.csv", "1,2\nnan,3\n", "nan.csv:2:"},
        {"empty.csv", "", "empty.csv:"},
        {"short.pgm", "P2\n3 3\n255\n1 2 3\n4 5 6\n", "short.pgm:"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *path = test_write_tmp(cases[i].name, cases[i].text);
        char cmd[2048], png[1024], *err = NULL;
        snprintf(png, sizeof png, "%s/%s.png", test_tmpdir(), cases[i].name);
        snprintf(cmd, sizeof cmd, "%s terrain %s -o %s --size 16x16", test_cli, path, png);
        CHECK_INT(test_run(cmd, NULL, &err), 1);
        CHECK_CONTAINS(err, cases[i].says);
        free(err);
        struct stat st;
        CHECK(stat(png, &st) != 0);
    }
}

TEST(tri_cli_splines_error_line)
{
    char cmd[1024], *out = NULL;
    snprintf(cmd, sizeof cmd, "%s splines --franke 144 --scheme c0 --error --sites 20000",
             test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "splines scheme=c0 points=144 patches=18 rel_rms=");
    CHECK_CONTAINS(out, " rel_max=");
    free(out);
    snprintf(cmd, sizeof cmd, "%s splines %s/examples/scenes/hills33.pgm --scheme c2", test_cli,
             test_root_dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "splines scheme=c2 patches=2048");
    free(out);
}

/* The reflection-line view (Figs. 15–17 of seed 004) of the C0 spline:
 * stripes drawn from the GPU's normals agree with the same stripes drawn
 * from the exact reference's normals, and the image holds both stripe
 * colours. */
TEST(tri_gl_reflection_lines)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    sc_scene_desc sdesc = {.franke = 144, .scheme = SC_SCHEME_C0};
    CHECK_INT(sc_make_scene(&sdesc, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_renderer_id renderer;
    sc_renderer_desc desc = {.show = SC_SHOW_REFLECT};
    CHECK_INT(sc_make_renderer(ctx, scene, &desc, &renderer, &err), SC_OK);
    sc_camera_desc camera = {.width = 128, .height = 96, .text = "1.6,-1.2,1.4,0.5,0.5,0.2,35"};
    sc_frame_id gpu, ref;
    CHECK_INT(sc_render(renderer, &camera, &gpu, &err), SC_OK);
    CHECK_INT(sc_render_reference(scene, &camera, NULL, &ref, &err), SC_OK);
    char png[512], aov_path[512];
    snprintf(png, sizeof png, "%s/reflect.png", test_tmpdir());
    snprintf(aov_path, sizeof aov_path, "%s/reflect_ref.aov", test_tmpdir());
    CHECK_INT(sc_save_png(gpu, png, &err), SC_OK);
    CHECK_INT(sc_save_aov(ref, aov_path, &err), SC_OK);
    sc_image img = {0}, expect = {0};
    sc_aov aov = {0};
    CHECK_INT(sc_png_read(png, &img, &err), SC_OK);
    CHECK_INT(sc_aov_read(aov_path, &aov, &err), SC_OK);
    sc_image_alloc(&expect, aov.width, aov.height, 4);
    sc_view_reflect(&aov, &expect);
    long both = 0, close = 0, dark = 0, bright = 0;
    /* Above the legend strip. */
    for (int y = 0; y < img.height - 16; y++)
        for (int x = 0; x < img.width; x++) {
            int p = y * img.width + x;
            if (aov.surface[p] < 0)
                continue;
            int g = img.pixels[4 * p], e = expect.pixels[4 * p];
            both++;
            close += abs(g - e) <= 8;
            dark += g < 60;
            bright += g > 220;
        }
    printf("  %ld pixels, %ld within 8 grey levels, %ld dark, %ld bright\n", both, close, dark,
           bright);
    CHECK(both > 2000);
    CHECK(close >= 0.97 * both);
    CHECK(dark > 0.1 * both && bright > 0.1 * both);
    sc_image_free(&img);
    sc_image_free(&expect);
    sc_aov_free(&aov);
    sc_destroy_frame(gpu);
    sc_destroy_frame(ref);
    sc_destroy_renderer(renderer);
    sc_shutdown();
}

/* Deferred shading: the intersection program writes the AOVs only (its
 * key has no `shade`), a full-screen pass shades from the hit's domain
 * point and the patch's exact normal; the image matches the forward
 * render's. */
TEST(tri_gl_deferred_shading)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    sc_scene_desc sdesc = {.franke = 144};
    CHECK_INT(sc_make_scene(&sdesc, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_camera_desc camera = {.width = 128, .height = 96, .text = "1.6,-1.2,1.4,0.5,0.5,0.2,35"};
    sc_image img[2] = {{0}};
    for (int deferred = 0; deferred < 2; deferred++) {
        sc_renderer_id renderer;
        sc_renderer_desc desc = {.deferred = deferred};
        CHECK_INT(sc_make_renderer(ctx, scene, &desc, &renderer, &err), SC_OK);
        sc_key key;
        int count = 0;
        CHECK_INT(sc_query_renderer_keys(renderer, &key, 1, &count, &err), SC_OK);
        CHECK_STR(key.text, deferred ? "tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert1-out.aov"
                                     : "tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert1-out.shade");
        sc_frame_id frame;
        CHECK_INT(sc_render(renderer, &camera, &frame, &err), SC_OK);
        char png[512];
        snprintf(png, sizeof png, "%s/deferred%d.png", test_tmpdir(), deferred);
        CHECK_INT(sc_save_png(frame, png, &err), SC_OK);
        CHECK_INT(sc_png_read(png, &img[deferred], &err), SC_OK);
        sc_destroy_frame(frame);
        sc_destroy_renderer(renderer);
    }
    long n = (long)img[0].width * img[0].height, lit = 0, close = 0;
    for (long p = 0; p < n; p++) {
        int d = 0;
        for (int k = 0; k < 3; k++)
            d = abs(img[0].pixels[4 * p + k] - img[1].pixels[4 * p + k]) > d
                    ? abs(img[0].pixels[4 * p + k] - img[1].pixels[4 * p + k])
                    : d;
        close += d <= 1;
        lit += img[0].pixels[4 * p] != 51;   /* not the background grey */
    }
    printf("  %ld pixels, %ld lit, %ld within 1 level of the forward render\n", n, lit, close);
    CHECK(lit > 2000);
    CHECK(close >= n - n / 1000);
    sc_image_free(&img[0]);
    sc_image_free(&img[1]);
    sc_shutdown();
}
