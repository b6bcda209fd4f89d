/* test_api_cli.c — the public calls the command line needs beyond the
 * three uses of test_install.c: what `info` prints (trim curves, skipped
 * entities, surfaces no program draws), `eval`'s surface evaluation,
 * `convert`'s OBJ writer, the reference's statistics and progress,
 * `render`'s timing calls (draw without read back, per-frame counts) and
 * the view checked without a scene, the audit's lines and comparison. Each
 * is checked against the internal module it wraps or against known values.
 * A test that makes objects ends with sc_shutdown, so that the handle
 * checks of test_install.c see fresh pools. */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "image.h"
#include "io.h"
#include "nurbs.h"
#include "splinecast.h"
#include "trim_pack.h"

/* A bilinear patch (the square [0, 2]² in z = 0), a polygon face the
 * reader skips, and no trims. */
static const char square_obj[] =
    "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 2 2 0\n"
    "cstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\n"
    "parm u 0 0 1 1\nparm v 0 0 1 1\nend\n"
    "f 1 2 3\n";

TEST(api_cli_scene_and_surface_queries)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_scene_desc desc = {.text = square_obj, .size = sizeof square_obj - 1, .name = "sq.obj"};
    test_warnings w = {0};
    sc_set_logger(test_gather_warnings, &w);   /* the reader's note on the polygon */
    CHECK_INT(sc_make_scene(&desc, &scene, &err), SC_OK);
    sc_set_logger(NULL, NULL);
    sc_scene_info info;
    CHECK_INT(sc_query_scene_info(scene, &info, &err), SC_OK);
    CHECK_INT(info.surfaces, 1);
    CHECK_INT(info.skipped_kinds, 1);
    CHECK_INT(info.skipped, 1);
    CHECK_INT(info.dropped_loops, 0);
    sc_skipped_info k;
    CHECK_INT(sc_query_scene_skipped(scene, 0, &k, &err), SC_OK);
    CHECK_STR(k.type, "polygon");
    CHECK_INT(k.count, 1);
    CHECK(k.reason[0] != 0);
    CHECK_INT(sc_query_scene_skipped(scene, 1, &k, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "index is out of range: 1 (0 to 0)");

    sc_surface_info s;
    CHECK_INT(sc_query_surface_info(scene, 0, &s, &err), SC_OK);
    CHECK_INT(s.trim_curves, 0);
    CHECK_NEAR(s.u_min, 0, 0);
    CHECK_NEAR(s.u_max, 1, 0);
    CHECK_NEAR(s.v_max, 1, 0);

    /* The middle of the square: point (1, 1, 0), partials (2, 0, 0) and
     * (0, 2, 0), normal +z. */
    sc_surface_point at;
    CHECK_INT(sc_eval_surface(scene, 0, 0.5, 0.5, &at, &err), SC_OK);
    CHECK_NEAR(at.point[0], 1, 1e-15);
    CHECK_NEAR(at.point[1], 1, 1e-15);
    CHECK_NEAR(at.du[0], 2, 1e-15);
    CHECK_NEAR(at.dv[1], 2, 1e-15);
    CHECK_INT(at.has_normal, 1);
    CHECK_NEAR(fabs(at.normal[2]), 1, 1e-15);
    CHECK_INT(sc_eval_surface(scene, 0, 1.5, 0.5, &at, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "(u, v) is out of range");
    CHECK_INT(sc_eval_surface(scene, 1, 0.5, 0.5, &at, &err), SC_FAIL);
    sc_destroy_scene(scene);

    /* A trimmed scene: its curves counted over its loops, as the reader
     * holds them. */
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = test_root("examples/scenes/trim_nine.obj")},
                            &scene, &err), SC_OK);
    sc_scene internal;
    CHECK_INT(sc_read_scene(test_root("examples/scenes/trim_nine.obj"), &internal, &err), SC_OK);
    int curves = 0;
    for (int l = 0; l < internal.surfaces[0].nloops; l++)
        curves += internal.surfaces[0].loops[l].ncurves;
    CHECK_INT(sc_query_surface_info(scene, 0, &s, &err), SC_OK);
    CHECK_INT(s.trim_curves, curves);
    CHECK_INT(curves, 9);
    sc_scene_free(&internal);
    sc_destroy_scene(scene);
    sc_shutdown();
}

/* `bench --trim-table`'s figures: every trimmed example's block as
 * sc_trim_pack packs it at the surface's trim degree, which the surface's
 * key names; zeros for an untrimmed surface. */
TEST(api_cli_surface_trim_matches_the_packed_block)
{
    static const char *const files[] = {"trim_nine.obj", "trim_star.obj", "trim_nested.obj",
                                        "trim_touch.obj", "trimmed_hole.obj"};
    sc_error err = {0};
    for (size_t f = 0; f < sizeof files / sizeof files[0]; f++) {
        char path[256];
        snprintf(path, sizeof path, "examples/scenes/%s", files[f]);
        sc_scene_id scene;
        sc_scene internal;
        CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = test_root(path)}, &scene, &err), SC_OK);
        CHECK_INT(sc_read_scene(test_root(path), &internal, &err), SC_OK);
        const sc_surface *surf = &internal.surfaces[0];
        sc_trim_block block;
        CHECK_INT(sc_trim_pack(surf, sc_surface_trim_degree(surf), &block, &err), SC_OK);
        sc_surface_trim_info t;
        CHECK_INT(sc_query_surface_trim(scene, 0, &t, &err), SC_OK);
        CHECK_INT(t.degree, sc_surface_trim_degree(surf));
        CHECK_INT(t.loops, block.nloops);
        CHECK_INT(t.pieces, block.npieces);
        CHECK_INT(t.grid_u, block.grid_u);
        CHECK_INT(t.grid_v, block.grid_v);
        CHECK_INT(t.entries, block.nentries);
        CHECK_INT(t.texels, block.ntexels);
        CHECK_INT((long)t.bytes, 16L * block.ntexels);
        CHECK(t.pieces > 0 && t.loops > 0);
        sc_key key;
        char fast[32];
        snprintf(fast, sizeof fast, "-fast%di", t.degree);
        CHECK_INT(sc_query_surface_key(scene, 0, NULL, &key, &err), SC_OK);
        CHECK_CONTAINS(key.text, fast);
        sc_trim_block_free(&block);
        sc_scene_free(&internal);
        sc_destroy_scene(scene);
    }

    sc_scene_id square;
    test_warnings w = {0};
    sc_set_logger(test_gather_warnings, &w);   /* the reader's note on the polygon */
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.text = square_obj, .size = sizeof square_obj - 1,
                                             .name = "sq.obj"}, &square, &err), SC_OK);
    sc_set_logger(NULL, NULL);
    sc_surface_trim_info t, zero = {0};
    memset(&t, 0xff, sizeof t);
    CHECK_INT(sc_query_surface_trim(square, 0, &t, &err), SC_OK);
    CHECK(!memcmp(&t, &zero, sizeof t));
    CHECK_INT(sc_query_surface_trim(square, 1, &t, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "surface is out of range: 1 (0 to 0)");
    CHECK_INT(sc_query_surface_trim(square, 0, NULL, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "info");
    sc_destroy_scene(square);
    sc_shutdown();
}

TEST(api_cli_eval_matches_the_nurbs_core)
{
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    sc_scene teapot;
    CHECK_INT(sc_read_scene("teapot", &teapot, &err), SC_OK);
    const sc_surface *s = &teapot.surfaces[7];
    double p[3], su[3], sv[3], n[3];
    sc_surface_eval_world(s, 0.3, 0.6, p, su, sv);
    CHECK_INT(sc_surface_normal(s, 0.3, 0.6, n), 0);
    sc_xform_normal(s->xform, n, n);
    sc_surface_point at;
    CHECK_INT(sc_eval_surface(scene, 7, 0.3, 0.6, &at, &err), SC_OK);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(at.point[c], p[c], 0);
        CHECK_NEAR(at.du[c], su[c], 0);
        CHECK_NEAR(at.dv[c], sv[c], 0);
        CHECK_NEAR(at.normal[c], n[c], 0);
    }
    sc_scene_free(&teapot);
    sc_destroy_scene(scene);
    sc_shutdown();
}

TEST(api_cli_keys_skip_undrawable)
{
    /* One patch of degree 17 in u: above what a program draws. */
    char bpt[4096];
    int len = snprintf(bpt, sizeof bpt, "2\n17 1\n");
    for (int j = 0; j < 2; j++)
        for (int i = 0; i <= 17; i++)
            len += snprintf(bpt + len, sizeof bpt - (size_t)len, "%d %d 0\n", i, j);
    len += snprintf(bpt + len, sizeof bpt - (size_t)len, "1 1\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n");
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.text = bpt, .size = (size_t)len, .name = "d.bpt"},
                            &scene, &err), SC_OK);
    sc_key keys[4];
    int n = -1;
    CHECK_INT(sc_query_scene_keys(scene, NULL, keys, 4, &n, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "17");
    test_warnings w = {0};
    sc_set_logger(test_gather_warnings, &w);
    CHECK_INT(sc_query_scene_keys(scene, &(sc_keys_desc){.skip_undrawable = 1}, keys, 4, &n, &err),
              SC_OK);
    sc_set_logger(NULL, NULL);
    CHECK_INT(w.count, 1);
    CHECK_CONTAINS(w.text, "no variant key");
    CHECK_INT(n, 1);
    CHECK_CONTAINS(keys[0].text, "bez1x1-poly");
    sc_destroy_scene(scene);
    sc_shutdown();
}

TEST(api_cli_save_obj_round_trip)
{
    sc_error err = {0};
    sc_scene_id scene, back;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = test_root("examples/scenes/trim_hole.obj")},
                            &scene, &err), SC_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/api_save.obj", test_tmpdir());
    CHECK_INT(sc_save_obj(scene, path, &err), SC_OK);
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = path}, &back, &err), SC_OK);
    sc_scene_info a, b;
    CHECK_INT(sc_query_scene_info(scene, &a, &err), SC_OK);
    CHECK_INT(sc_query_scene_info(back, &b, &err), SC_OK);
    CHECK_INT(b.surfaces, a.surfaces);
    CHECK_INT(b.trimmed_surfaces, a.trimmed_surfaces);
    for (int c = 0; c < 3; c++)
        CHECK_NEAR(b.hi[c], a.hi[c], 1e-12);
    CHECK_INT(sc_save_obj(scene, "out.igs", &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "a name ending in .obj");
    sc_destroy_scene(back);
    sc_destroy_scene(scene);
    sc_shutdown();
}

static void count_progress(double fraction, void *user)
{
    int *calls = user;
    (*calls)++;
    (void)fraction;
}

TEST(api_cli_reference_stats_and_camera)
{
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    CHECK_INT(sc_check_camera(&(sc_camera_desc){.text = "0,0,0,1,2,3"}, &err), SC_FAIL);
    CHECK_INT(sc_check_camera(&(sc_camera_desc){.text = "1,1,1,1,1,1,30"}, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "eye and target are the same point");
    CHECK_INT(sc_check_camera(&(sc_camera_desc){.width = 20000}, &err), SC_FAIL);
    sc_camera_desc view = {.width = 64, .height = 48, .text = "8,-6,5,0,0,1.2,30"};
    CHECK_INT(sc_check_camera(&view, &err), SC_OK);
    CHECK_INT(sc_check_camera(NULL, &err), SC_OK);

    int calls = 0;
    sc_reference_desc desc = {.threads = 2, .progress = count_progress, .progress_user = &calls};
    sc_frame_id frame;
    CHECK_INT(sc_render_reference(scene, &view, &desc, &frame, &err), SC_OK);
    CHECK(calls > 0);
    sc_frame_info info;
    CHECK_INT(sc_query_frame_info(frame, &info, &err), SC_OK);
    CHECK_STR(info.camera, "8,-6,5,0,0,1.2,30");
    CHECK_INT(info.reference.rays, 64 * 48);
    CHECK_INT(info.reference.threads, 2);
    long hits = 0;
    for (int p = 0; p < 64 * 48; p++)
        hits += info.surface[p] >= 0;
    CHECK_INT(info.reference.hits, hits);
    CHECK(hits > 0 && info.reference.subdivisions > 0);
    CHECK_INT(info.reference.over_budget, 0);

    /* A reference frame's PNG is RGB, as `ref` writes it. */
    char path[1024];
    snprintf(path, sizeof path, "%s/api_ref.png", test_tmpdir());
    CHECK_INT(sc_save_png(frame, path, &err), SC_OK);
    sc_image img;
    CHECK_INT(sc_png_read(path, &img, &err), SC_OK);
    CHECK_INT(img.channels, 3);
    CHECK_INT(img.pixels[0], info.rgba[0]);
    sc_image_free(&img);
    sc_destroy_frame(frame);
    sc_destroy_scene(scene);
    sc_shutdown();
}

TEST(api_cli_draw_then_read_frame)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_renderer_id r;
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &r, &err), SC_OK);
    sc_frame_id none;
    sc_camera_desc view = {.width = 96, .height = 96};
    /* sc_draw then sc_read_frame gives the frame sc_render gives. */
    CHECK_INT(sc_draw(r, &view, &err), SC_OK);
    sc_renderer_info info;
    CHECK_INT(sc_query_renderer_info(r, &info, &err), SC_OK);
    CHECK(info.draw_calls > 0);
    CHECK(info.program_switches > 0);
    CHECK(info.readbacks >= 0 && info.culled_hulls >= 0);
    sc_frame_id a, b;
    CHECK_INT(sc_read_frame(r, &a, &err), SC_OK);
    CHECK_INT(sc_render(r, &view, &b, &err), SC_OK);
    sc_frame_info fa, fb;
    CHECK_INT(sc_query_frame_info(a, &fa, &err), SC_OK);
    CHECK_INT(sc_query_frame_info(b, &fb, &err), SC_OK);
    CHECK_INT(fa.width, 96);
    CHECK_INT(memcmp(fa.surface, fb.surface, 96 * 96 * sizeof *fa.surface), 0);
    CHECK_INT(memcmp(fa.rgba, fb.rgba, 96 * 96 * 4), 0);
    CHECK_STR(fa.camera, fb.camera);
    CHECK_INT((int)fa.reference.rays, 0);
    CHECK_INT(sc_read_frame((sc_renderer_id){0}, &none, &err), SC_FAIL);
    /* A renderer of the same scene shares the context's program; one with
     * programs of its own compiles it again. */
    sc_renderer_id shared, own;
    sc_renderer_info si, oi;
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &shared, &err), SC_OK);
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.own_programs = 1}, &own, &err),
              SC_OK);
    CHECK_INT(sc_query_renderer_info(shared, &si, &err), SC_OK);
    CHECK_INT(sc_query_renderer_info(own, &oi, &err), SC_OK);
    CHECK(oi.compile_ms > si.compile_ms);
    CHECK_INT(sc_draw(own, &view, &err), SC_OK);
    CHECK_INT(sc_draw(r, &(sc_camera_desc){.text = "bad"}, &err), SC_FAIL);
    sc_destroy_frame(a);
    sc_destroy_frame(b);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    sc_shutdown();   /* fresh pools for the tests after this one */
}

TEST(api_cli_audit_lines_and_compare)
{
    const char *key = "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade";
    sc_error err = {0};
    sc_glsl glsl;
    CHECK_INT(sc_generate_glsl(&(sc_glsl_desc){.key = key, .audit = 1}, &glsl, &err), SC_OK);
    /* The vertex line names the vertex program the key shares. */
    char want[128];
    snprintf(want, sizeof want, "%s - VS: ", glsl.vertex_name);
    CHECK(!strncmp(glsl.vertex_audit.line, want, strlen(want)));
    CHECK(glsl.ir_kinds && !strncmp(glsl.ir_kinds, key, strlen(key)));
    CHECK_CONTAINS(glsl.ir_kinds, " - FS by kind: ");

    /* An audit compared with itself changes nothing; a bad line is named. */
    char text[1024];
    snprintf(text, sizeof text, "# saved\n%s\n  %s\n%s\n", glsl.fragment_audit.line, glsl.ir_kinds,
             glsl.vertex_audit.line);
    sc_free_glsl(&glsl);
    CHECK(glsl.ir_kinds == NULL);
    sc_audit_text a = {.name = "a.audit", .text = text, .size = strlen(text)};
    char path[1024];
    snprintf(path, sizeof path, "%s/api_compare.txt", test_tmpdir());
    FILE *out = fopen(path, "w+");
    CHECK(out != NULL);
    CHECK_INT(sc_compare_audits(&a, &a, out, &err), SC_OK);
    long size = ftell(out);
    CHECK(size > 0);
    fclose(out);
    sc_audit_text bad = {.name = "b.audit", .text = "x\nnot an audit line\n", .size = 20};
    CHECK_INT(sc_compare_audits(&a, &bad, stdout, &err), SC_FAIL);
    CHECK_STR(err.file, "b.audit");
    CHECK_INT(err.line, 1);
    sc_audit_text twice = {.name = "c.audit", .text = text, .size = 0};
    char doubled[2048];
    snprintf(doubled, sizeof doubled, "%s%s", text, text);
    twice.text = doubled;
    twice.size = strlen(doubled);
    CHECK_INT(sc_compare_audits(&twice, &a, stdout, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "already audited on line 2");
    CHECK_INT(sc_compare_audits(NULL, &a, stdout, &err), SC_FAIL);
}

TEST(api_cli_keys_made_and_per_surface)
{
    sc_error err = {0};
    sc_key key;
    /* Zero desc: the documented default key; then varied as gen --family. */
    CHECK_INT(sc_make_key(NULL, &key, &err), SC_OK);
    CHECK_STR(key.text, "bez3x3-poly-pow-trim0-newton-cp-it6-tol0.05-ert1-out.shade.aov");
    /* The evaluation form follows the degrees: pow up to 4, dc above. */
    CHECK_INT(sc_make_key(&(sc_key_desc){.deg_u = 5}, &key, &err), SC_OK);
    CHECK_STR(key.text, "bez5x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert1-out.shade.aov");
    const char *generic = "bezdyn-poly-loop-trim0-newton-mid-it4-tol0.25-ert0-out.shade";
    sc_key_desc desc = {.like = generic, .deg_u = 5, .deg_v = 2, .rational = 1, .max_iters = 9};
    CHECK_INT(sc_make_key(&desc, &key, &err), SC_OK);
    CHECK_STR(key.text, "bez5x2-rat-dc-trim0-newton-mid-it9-tol0.25-ert0-out.shade");
    CHECK_INT(sc_make_key(&(sc_key_desc){.like = key.text, .rational = 2}, &key, &err), SC_OK);
    CHECK_STR(key.text, "bez5x2-poly-dc-trim0-newton-mid-it9-tol0.25-ert0-out.shade");
    CHECK_INT(sc_make_key(&(sc_key_desc){.like = "bez3x3"}, &key, &err), SC_FAIL);
    CHECK_STR(err.key, "bez3x3");
    CHECK_INT(sc_make_key(&(sc_key_desc){.deg_u = 17}, &key, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_key_desc.deg_u is out of range: 17");
    /* The program candidate lists draw a key's hulls with: ert5, each
     * candidate started on its control net (mid), the rest as it is. */
    const char *drawn = "bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade";
    CHECK_INT(sc_make_key(&(sc_key_desc){.like = drawn, .lists = 1}, &key, &err), SC_OK);
    CHECK_STR(key.text, "bez3x3-poly-pow-trim0-hybrid-mid-it6-tol0.05-ert5-out.shade");
    CHECK_INT(sc_make_key(&(sc_key_desc){.like = drawn, .lists = 2}, &key, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_key_desc.lists is out of range: 2");

    /* Per surface, with like's options: as sc_query_scene_keys with the
     * same desc, ertN taken as it is. */
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    sc_keys_desc like = {.like = generic, .max_iters = 3};
    CHECK_INT(sc_query_surface_key(scene, 5, &like, &key, &err), SC_OK);
    CHECK_STR(key.text, "bez3x3-poly-pow-trim0-newton-mid-it3-tol0.25-ert0-out.shade");
    sc_key all[2];
    int n;
    CHECK_INT(sc_query_scene_keys(scene, &like, all, 2, &n, &err), SC_OK);
    CHECK_INT(n, 1);
    CHECK_STR(all[0].text, key.text);
    CHECK_INT(sc_query_surface_key(scene, 32, NULL, &key, &err), SC_FAIL);
    CHECK_INT(sc_query_surface_key(scene, 0, &(sc_keys_desc){.like = "x"}, &key, &err), SC_FAIL);
    sc_destroy_scene(scene);
    sc_shutdown();
}

TEST(api_cli_dump_ir_and_save_text)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/api_dump.txt", test_tmpdir());
    FILE *out = fopen(path, "w+");
    CHECK(out != NULL);
    sc_error err = {0};
    CHECK_INT(sc_dump_ir("bez1x1-poly-dc-trim0-newton-cp-it2-tol0.05-ert0-out.shade", out, &err),
              SC_OK);
    fclose(out);
    char *text = test_read_file(path);
    CHECK(text != NULL);
    CHECK(text && !strncmp(text, "# after ", 8));
    free(text);
    CHECK_INT(sc_dump_ir("nope", stdout, &err), SC_FAIL);

    snprintf(path, sizeof path, "%s/api_saved.txt", test_tmpdir());
    CHECK_INT(sc_save_text(path, "abc\n", 4, &err), SC_OK);
    text = test_read_file(path);
    CHECK_STR(text, "abc\n");
    free(text);
    CHECK_INT(sc_save_text("/nonexistent/dir/x.txt", "a", 1, &err), SC_FAIL);
    CHECK_STR(err.file, "/nonexistent/dir/x.txt");
}
