/* test_peel.c — depth peeling of the hulls' entries (SC_TERMINATION_PEEL,
 * runtime/gl/gl_peel.c) on real Mesa: its images and AOVs against the CPU
 * reference and against the manual mode's on the teapot, the trimmed
 * scenes and the stacks; fewer intersections per covered pixel than the
 * manual mode on the teapot, with no read-back; the depth its resolve pass
 * writes; the fall-backs (a hull holding the eye, an application's
 * framebuffer); the command line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"
#include "gl_context_util.h"
#include "gl_render_private.h"
#include "emit_glsl.h"
#include "imgdiff.h"
#include "io.h"
#include "refcast.h"
#include "splinecast.h"
#include "test.h"

static const char *scene_path(const char *name)
{
    static char path[4][1024];
    static int next;
    char *p = path[next++ % 4];
    snprintf(p, sizeof path[0], "%s/examples/scenes/%s", test_root_dir, name);
    return p;
}

static long covered(const sc_aov *aov)
{
    long n = 0;
    for (int p = 0; p < aov->width * aov->height; p++)
        n += aov->surface[p] >= 0;
    return n;
}

/* Draws one frame; the AOVs, the stats and (depth, when not NULL) the
 * depth buffer, rows bottom-up. */
static int render(sc_gl_context *ctx, const sc_scene *scene, const sc_render_desc *desc,
                  const sc_camera *cam, sc_aov *aov, sc_render_stats *stats, float *depth)
{
    sc_error err = {0};
    sc_renderer *r;
    int ok = sc_renderer_create(sc_gl_context_gl(ctx), scene, desc, &r, &err) == SC_OK;
    if (ok) {
        ok = sc_renderer_draw(r, cam, &err) == SC_OK &&
             sc_renderer_read(r, NULL, aov, &err) == SC_OK;
        if (ok && depth) {
            const sc_gl *gl = sc_gl_context_gl(ctx);
            gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
            gl->GetTextureImage(r->target.depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                                (GLsizei)((size_t)cam->width * (size_t)cam->height * 4), depth);
            ok = sc_gl_check(gl, "reading the depth", &err) == SC_OK;
        }
        sc_renderer_stats(r, stats);
        sc_renderer_destroy(r);
    }
    if (!ok)
        fprintf(stderr, "  render: %s\n", err.message);
    return ok;
}

/* The accuracy targets of the GL tests (test_gl.c): at most 0.1 % failing
 * pixels, median position error below 0.1 pixel footprint, mean normal
 * error below half a degree. */
static int meets_targets(const sc_aov *ref, const sc_aov *test, const char *what)
{
    sc_accuracy acc;
    sc_error err = {0};
    if (sc_accuracy_compare(ref, test, &acc, &err) != SC_OK) {
        fprintf(stderr, "  %s: %s\n", what, err.message);
        return 0;
    }
    int ok = acc.ref_hits > 500 && acc.fail_pct <= 0.1 && acc.pos_median_px < 0.1 &&
             acc.normal_mean_deg < 0.5;
    if (!ok)
        fprintf(stderr, "  %s: ref_hits %ld fail_pct %g pos_median_px %g normal_mean_deg %g\n", what,
                (long)acc.ref_hits, acc.fail_pct, acc.pos_median_px, acc.normal_mean_deg);
    return ok;
}

/* The teapot at 256×256: peeling meets the accuracy targets against the
 * reference, draws the manual mode's image (the same surface at every
 * pixel but a few seam pixels), runs fewer intersections per covered pixel,
 * reads nothing back, and its resolve pass leaves the hits' depth in the
 * depth buffer, as the programs that write gl_FragDepth do. */
TEST(peel_teapot_against_reference_and_manual)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const char *path = TEST_TEAPOT32;
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    cam.width = cam.height = 256;
    int n = cam.width * cam.height;
    float *depth_manual = sc_alloc((size_t)n, sizeof(float));
    float *depth_peel = sc_alloc((size_t)n, sizeof(float));
    sc_aov ref, manual, peel;
    sc_render_stats sm, sp;
    CHECK_INT(sc_refcast_cached(path, &cam, test_tmpdir(), &ref, &err), SC_OK);
    /* The manual mode with every hull drawn as a hull, as depth peeling
     * draws them: the same starts, so the same hits to the depth buffer's
     * precision. (Candidate lists start elsewhere, and their hits differ
     * within the tolerance: up to 1e-5 in window depth here.) */
    sc_render_desc desc = {.ert = SC_TERMINATION_MANUAL, .list_below_px = SC_LISTS_OFF};
    CHECK(render(ctx, &scene, &desc, &cam, &manual, &sm, depth_manual));
    desc.ert = SC_TERMINATION_PEEL;
    CHECK(render(ctx, &scene, &desc, &cam, &peel, &sp, depth_peel));
    CHECK(meets_targets(&ref, &peel, "teapot, peel"));
    CHECK(meets_targets(&ref, &manual, "teapot, manual"));
    sc_accuracy acc;
    CHECK_INT(sc_accuracy_compare(&manual, &peel, &acc, &err), SC_OK);
    CHECK(acc.fail_pct <= 0.01);
    long other = 0, depth_off = 0, both = 0;
    for (int p = 0; p < n; p++) {
        other += manual.surface[p] != peel.surface[p];
        /* The depth buffer's rows are bottom-up, the AOVs' top-down. */
        int q = (cam.height - 1 - p / cam.width) * cam.width + p % cam.width;
        if (manual.surface[p] >= 0 && peel.surface[p] >= 0) {
            both++;
            depth_off += fabsf(depth_manual[q] - depth_peel[q]) > 1e-6f;
        } else if (peel.surface[p] < 0) {
            depth_off += depth_peel[q] != 1.0f;
        }
    }
    CHECK(other <= n / 1000);
    CHECK(both > n / 8);
    CHECK(depth_off <= n / 1000);
    /* One intersection per covered pixel and a few more, fewer than the
     * manual mode's; nothing read back; several layers. */
    long c = covered(&peel);
    double rays_peel = (double)sp.intersections / (double)c;
    double rays_manual = (double)sm.intersections / (double)covered(&manual);
    if (!(rays_peel < rays_manual && rays_peel >= 1))
        fprintf(stderr, "  rays per covered pixel: peel %.3f, manual %.3f\n", rays_peel,
                rays_manual);
    CHECK(rays_peel >= 1);
    CHECK(rays_peel < rays_manual);
    CHECK(sm.readbacks > 0);
    CHECK_INT(sp.readbacks, 0);
    CHECK_INT(sp.culled_hulls, 0);
    CHECK(sp.peel_layers >= 2);
    CHECK_INT(sm.peel_layers, 0);
    sc_aov_free(&ref);
    sc_aov_free(&manual);
    sc_aov_free(&peel);
    free(depth_manual);
    free(depth_peel);
    sc_scene_free(&scene);
}

/* The trimmed example scenes (their default views) and the stacks (from
 * above, as seed 000's Table 3 is measured; stack_16 also from its default
 * view) of examples/scenes at 96×96: peeling meets the accuracy targets
 * against the reference and draws the manual mode's surfaces. */
TEST(peel_trimmed_and_stacks_against_reference)
{
    TEST_NEED_GL_CONTEXT(ctx);
    static const char *const names[] = {"trim_hole.obj", "trim_nested.obj", "trim_nine.obj",
                                        "trim_star.obj", "trim_touch.obj",  "trimmed_hole.obj",
                                        "stack_2.obj",   "stack_16.obj",    "stack_128.obj"};
    const sc_camera above = {.eye = {0, 0, 4.5}, .target = {0, 0, 0}, .fovy_deg = 22.6,
                             .width = 96, .height = 96};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *path = scene_path(names[i]);
        int stack = !strncmp(names[i], "stack_", 6);
        sc_scene scene;
        sc_error err = {0};
        CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
        int views = stack ? (strcmp(names[i], "stack_16.obj") ? 1 : 2) : 1;
        for (int view = 0; view < views; view++) {
            sc_camera cam = above;
            if (stack == view) {
                sc_camera_default(&scene, &cam);
                cam.width = cam.height = 96;
            }
            sc_aov ref, manual, peel;
            sc_render_stats sm, sp;
            CHECK_INT(sc_refcast_cached(path, &cam, test_tmpdir(), &ref, &err), SC_OK);
            sc_render_desc desc = {.ert = SC_TERMINATION_MANUAL};
            CHECK(render(ctx, &scene, &desc, &cam, &manual, &sm, NULL));
            desc.ert = SC_TERMINATION_PEEL;
            CHECK(render(ctx, &scene, &desc, &cam, &peel, &sp, NULL));
            char what[128];
            snprintf(what, sizeof what, "%s, %s, peel", names[i],
                     stack == view ? "default view" : "above");
            CHECK(meets_targets(&ref, &peel, what));
            long other = 0;
            for (int p = 0; p < cam.width * cam.height; p++)
                other += manual.surface[p] != peel.surface[p];
            if (other > cam.width * cam.height / 1000)
                fprintf(stderr, "  %s: %ld pixels on another surface than manual's\n", what,
                        other);
            CHECK(other <= cam.width * cam.height / 1000);
            CHECK_INT(sp.readbacks, 0);
            CHECK(sp.peel_layers >= 1);
            /* From above, the top layer hides every other everywhere: one
             * intersection a covered pixel (a few more at the bumps' seams),
             * where the manual mode runs the top four layers. */
            if (stack && stack != view) {
                long c = covered(&peel);
                if (!(sp.intersections >= c && sp.intersections <= c + c / 100))
                    fprintf(stderr, "  %s: %lld intersections, %ld covered\n", what,
                            sp.intersections, c);
                CHECK(sp.intersections >= c && sp.intersections <= c + c / 100);
            }
            sc_aov_free(&ref);
            sc_aov_free(&manual);
            sc_aov_free(&peel);
        }
        sc_scene_free(&scene);
    }
}

/* A hull holding the eye (uniform:1 hulls, the eye between the surface
 * and its hull's top): the frame falls back to drawing every hull with the
 * ert0 programs, and its image is the reference's and the one without
 * early termination. */
TEST(peel_eye_inside_hull_falls_back)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const char *path = scene_path("stack_4.obj");
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
    sc_camera cam = {.eye = {0.2, 0.1, 0.025}, .target = {0.2, 0.1, -1}, .fovy_deg = 60,
                     .width = 64, .height = 64};
    sc_render_desc desc = {.ert = SC_TERMINATION_NONE,
                           .hulls = {.mode = SC_SPLIT_UNIFORM, .divisions = 1}};
    sc_aov ref, none, peel;
    sc_render_stats stats;
    CHECK_INT(sc_refcast_cached(path, &cam, test_tmpdir(), &ref, &err), SC_OK);
    CHECK(render(ctx, &scene, &desc, &cam, &none, &stats, NULL));
    desc.ert = SC_TERMINATION_PEEL;
    CHECK(render(ctx, &scene, &desc, &cam, &peel, &stats, NULL));
    CHECK_INT(stats.programs, 2);   /* ert4, and ert0 for the frame's fall-back */
    CHECK_INT(stats.peel_layers, 0);
    CHECK_INT(stats.readbacks, 0);
    sc_accuracy acc;
    CHECK_INT(sc_accuracy_compare(&ref, &peel, &acc, &err), SC_OK);
    CHECK_INT(acc.ref_hits, 64 * 64);
    CHECK(acc.fail_pct <= 0.1);
    CHECK_INT(sc_accuracy_compare(&none, &peel, &acc, &err), SC_OK);
    CHECK(acc.fail_pct == 0);
    sc_aov_free(&ref);
    sc_aov_free(&none);
    sc_aov_free(&peel);
    sc_scene_free(&scene);
}

/* Into an application's framebuffer (sc_renderer_draw_app) a peeling
 * renderer peels in its own target and composes colour and depth into the
 * application's under its depth test: the manual mode's picture (within
 * the rounding of the target's sRGB colour, 2 levels) and depth, and in
 * front of the application's own depth only where it is nearer; no ert0
 * program was needed. */
TEST(peel_draw_app_composes)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(TEST_TEAPOT32, &scene, &err), SC_OK);
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    cam.width = cam.height = 96;
    int n = cam.width * cam.height;
    float view[16], proj[16];
    sc_camera_gl_matrices(&cam, 1.0, 100.0, view, proj);
    /* The application's own state: no program of an earlier test's
     * renderer (deleted with it) current. */
    gl->UseProgram(0);
    GLuint fb, tex[2];
    gl->CreateFramebuffers(1, &fb);
    gl->CreateTextures(GL_TEXTURE_2D, 2, tex);
    gl->TextureStorage2D(tex[0], 1, GL_RGBA8, cam.width, cam.height);
    gl->TextureStorage2D(tex[1], 1, GL_DEPTH_COMPONENT32F, cam.width, cam.height);
    gl->NamedFramebufferTexture(fb, GL_COLOR_ATTACHMENT0, tex[0], 0);
    gl->NamedFramebufferTexture(fb, GL_DEPTH_ATTACHMENT, tex[1], 0);
    /* manual, peel; the same two over the application's geometry. */
    static const sc_ray_termination modes[4] = {SC_TERMINATION_MANUAL, SC_TERMINATION_PEEL,
                                                SC_TERMINATION_MANUAL, SC_TERMINATION_PEEL};
    unsigned char *colour[4];
    float *depth[4];
    float split = 1;
    for (int m = 0; m < 4; m++) {
        colour[m] = sc_alloc((size_t)n, 4);
        depth[m] = sc_alloc((size_t)n, sizeof(float));
    }
    for (int m = 0; m < 4; m++) {
        sc_render_desc desc = {.ert = modes[m]};
        sc_renderer *r;
        CHECK_INT(sc_renderer_create(gl, &scene, &desc, &r, &err), SC_OK);
        gl->BindFramebuffer(GL_FRAMEBUFFER, fb);
        gl->Viewport(0, 0, cam.width, cam.height);
        static const float black[4] = {0, 0, 0, 1}, far = 1;
        gl->ClearNamedFramebufferfv(fb, GL_COLOR, 0, black);
        gl->ClearNamedFramebufferfv(fb, GL_DEPTH, 0, &far);
        /* The application's geometry: the left half of the view at a
         * depth in the middle of the teapot's. */
        if (m >= 2) {
            gl->Enable(GL_SCISSOR_TEST);
            gl->Scissor(0, 0, cam.width / 2, cam.height);
            gl->ClearNamedFramebufferfv(fb, GL_DEPTH, 0, &split);
            gl->Disable(GL_SCISSOR_TEST);
        }
        CHECK_INT(sc_renderer_draw_app(r, view, proj, &err), SC_OK);
        gl->Finish();
        gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
        gl->GetTextureImage(tex[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, n * 4, colour[m]);
        gl->GetTextureImage(tex[1], 0, GL_DEPTH_COMPONENT, GL_FLOAT, n * 4, depth[m]);
        sc_render_stats stats;
        sc_renderer_stats(r, &stats);
        CHECK_INT(stats.programs, 1);   /* no ert0 sibling: peeled, not fallen back */
        gl->UseProgram(0);
        sc_renderer_destroy(r);
        gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
        if (m == 1) {
            /* The middle of the teapot's depths, for the geometry. */
            float lo = 1, hi = 0;
            for (int p = 0; p < n; p++)
                if (depth[0][p] < 1) {
                    lo = fminf(lo, depth[0][p]);
                    hi = fmaxf(hi, depth[0][p]);
                }
            split = 0.5f * (lo + hi);
        }
    }
    for (int pair = 0; pair < 2; pair++) {
        const int a = 2 * pair, b = 2 * pair + 1;
        long drawn = 0, differ = 0, hidden = 0;
        for (int p = 0; p < n; p++) {
            drawn += depth[a][p] < (pair ? split : 1);
            int off = fabsf(depth[a][p] - depth[b][p]) > 1e-6f;
            for (int c = 0; c < 4; c++)
                off |= abs(colour[a][4 * p + c] - colour[b][4 * p + c]) > 2;
            differ += off;
            /* Over the geometry's half, nothing behind it was drawn. */
            hidden += pair && p % cam.width < cam.width / 2 && depth[b][p] > split;
        }
        if (differ > n / 1000)
            fprintf(stderr, "  draw_app %s: %ld of %d pixels differ\n", pair ? "over geometry" : "alone",
                    differ, n);
        CHECK(drawn > n / 16);
        CHECK(differ <= n / 1000);
        CHECK_INT(hidden, 0);
    }
    gl->DeleteFramebuffers(1, &fb);
    gl->DeleteTextures(2, tex);
    for (int m = 0; m < 4; m++) {
        free(colour[m]);
        free(depth[m]);
    }
    sc_scene_free(&scene);
}

/* The command line: `render --ert peel` prints no read-back and its
 * layers, `bench --ert manual,peel` one line each. */
TEST(peel_cli)
{
    char cmd[2048], *out = NULL, *err_text = NULL;
    snprintf(cmd, sizeof cmd, "%s render %s -o %s/peel.png --size 64x64 --frames 1 --ert peel",
             test_cli, TEST_TEAPOT32, test_tmpdir());
    int status = test_run(cmd, &out, &err_text);
    if (status == 1 && err_text && strstr(err_text, "OSMesa")) {
        free(out);
        free(err_text);
        SKIP("no GL context");
    }
    CHECK_INT(status, 0);
    CHECK_CONTAINS(out, " readbacks=0 ");
    CHECK_CONTAINS(out, " peel_layers=");
    CHECK(!strstr(out, " peel_layers=0\n"));
    free(out);
    free(err_text);
    snprintf(cmd, sizeof cmd, "%s bench %s --ert manual,peel --size 48x48 --frames 1", test_cli,
             TEST_TEAPOT32);
    CHECK_INT(test_run(cmd, &out, &err_text), 0);
    CHECK_CONTAINS(out, " ert=manual ");
    CHECK_CONTAINS(out, " ert=peel ");
    free(out);
    free(err_text);
}

/* What the ert4 key asks of the generated program (scg_generate checks it
 * with glslang): no gl_FragDepth anywhere, the early fragment tests, the
 * image of the best hits, the hit kept only when nearer, after the
 * intersection; and a key asking for the hull view (which writes the
 * hull's depth where rays miss) refused. */
TEST(peel_generated_program)
{
    scg_key key;
    sc_error err = {0};
    CHECK_INT(scg_key_parse("bez3x3-poly-dc-trim0-hybrid-cp-it6-tol0.05-ert4-out.shade.aov", &key,
                            &err),
              SC_OK);
    CHECK_INT(key.ert, SCG_ERT_PEEL);
    scg_generated gen;
    CHECK_INT(scg_generate(&key, &gen, &err), SC_OK);
    const char *frag = scg_text_str(&gen.fragment);
    const char *early = strstr(frag, "layout(early_fragment_tests) in;");
    const char *image = strstr(frag, "uniform coherent image2D sc_best_depth;");
    const char *call = strstr(frag, "sc_intersect(hit");
    const char *test = strstr(frag, "if (sc_depth >= imageLoad(sc_best_depth");
    const char *store = strstr(frag, "imageStore(sc_best_depth");
    int ok = early && image && call && test && store && call < test && test < store &&
             !strstr(frag, "gl_FragDepth") && !strstr(frag, "sc_nearest_t");
    scg_generated_free(&gen);
    CHECK(ok);
    /* The same key with ert0 writes gl_FragDepth and has none of it. */
    key.ert = SCG_ERT_NONE;
    CHECK_INT(scg_generate(&key, &gen, &err), SC_OK);
    frag = scg_text_str(&gen.fragment);
    ok = strstr(frag, "gl_FragDepth = ") && !strstr(frag, "early_fragment_tests") &&
         !strstr(frag, "sc_best_depth");
    scg_generated_free(&gen);
    CHECK(ok);
    CHECK_INT(scg_key_parse("bez3x3-poly-dc-trim0-newton-cp-it4-tol0.05-ert4-out.hull", &key, &err),
              SC_OK);
    CHECK_INT(scg_key_check(&key, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "ert4");
}

/* Through the public API (sc_make_renderer, sc_render: sc_draw and
 * sc_read_frame), Franke's C2 terrain (288 prisms, the tri4 program at
 * ert4) from an oblique view and from inside the prisms' box: the
 * reference's image within the targets, with no read-back. */
TEST(peel_terrain_public_api)
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
    static const char *const views[] = {"1.6,-1.2,1.4,0.5,0.5,0.2,35", "0.5,0.02,1.1,0.5,0.6,0.3,60"};
    for (int v = 0; v < 2; v++) {
        sc_renderer_id renderer;
        sc_renderer_desc desc = {.termination = SC_TERMINATION_PEEL};
        CHECK_INT(sc_make_renderer(ctx, scene, &desc, &renderer, &err), SC_OK);
        sc_key key;
        int count = 0;
        CHECK_INT(sc_query_renderer_keys(renderer, &key, 1, &count, &err), SC_OK);
        /* Drawn without the AOVs unless read back (sc_renderer_desc.aovs). */
        CHECK_STR(key.text, "tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert4-out.shade");
        sc_camera_desc camera = {.width = 128, .height = 96, .text = views[v]};
        sc_frame_id gpu, ref;
        sc_comparison cmp;
        CHECK_INT(sc_render(renderer, &camera, &gpu, &err), SC_OK);
        CHECK_INT(sc_render_reference(scene, &camera, NULL, &ref, &err), SC_OK);
        CHECK_INT(sc_compare_frames(ref, gpu, &cmp, &err), SC_OK);
        sc_renderer_info info;
        CHECK_INT(sc_query_renderer_info(renderer, &info, &err), SC_OK);
        if (!(cmp.fail_pct <= 0.1))
            printf("  %s: %s\n", views[v], cmp.line);
        CHECK(cmp.reference_hits > 2000);
        CHECK(cmp.fail_pct <= 0.1);
        CHECK_INT(info.readbacks, 0);
        CHECK(info.peel_layers >= 1);
        CHECK(info.intersections >= cmp.test_hits);
        sc_destroy_frame(gpu);
        sc_destroy_frame(ref);
        sc_destroy_renderer(renderer);
    }
    sc_shutdown();
}

/* A pack saved for depth peeling (sc_save_pack with SC_TERMINATION_PEEL)
 * draws, through the packed renderer, the image a peeling renderer of the
 * scene draws: the trimmed nine-hole patch at 96×96. */
TEST(peel_packed_renderer)
{
    const char *scene_path = test_root("examples/scenes/trim_nine.obj");
    char pack[1024];
    snprintf(pack, sizeof pack, "%s/peel_nine.pack", test_tmpdir());
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    sc_renderer_desc desc = {.termination = SC_TERMINATION_PEEL};
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err), SC_OK);
    CHECK_INT(sc_save_pack(scene, &desc, pack, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_renderer_id direct, packed;
    CHECK_INT(sc_make_renderer(ctx, scene, &desc, &direct, &err), SC_OK);
    CHECK_INT(sc_make_renderer(ctx, (sc_scene_id){0}, &(sc_renderer_desc){.pack = pack}, &packed,
                               &err),
              SC_OK);
    sc_key key;
    int count = 0;
    CHECK_INT(sc_query_renderer_keys(packed, &key, 1, &count, &err), SC_OK);
    CHECK(strstr(key.text, "-ert4-") != NULL);
    sc_camera_desc view = {.width = 96, .height = 96};
    sc_frame_id fa, fb;
    CHECK_INT(sc_render(direct, &view, &fa, &err), SC_OK);
    CHECK_INT(sc_render(packed, &view, &fb, &err), SC_OK);
    sc_frame_info ia, ib;
    CHECK_INT(sc_query_frame_info(fa, &ia, &err), SC_OK);
    CHECK_INT(sc_query_frame_info(fb, &ib, &err), SC_OK);
    long hits = 0, differ = 0;
    for (int p = 0; p < 96 * 96; p++) {
        hits += ia.surface[p] >= 0;
        differ += ia.surface[p] != ib.surface[p] || ia.t[p] != ib.t[p] ||
                  memcmp(ia.rgba + 4 * p, ib.rgba + 4 * p, 4) != 0;
    }
    CHECK(hits > 96 * 96 / 10);
    CHECK_INT(differ, 0);
    sc_renderer_info info;
    CHECK_INT(sc_query_renderer_info(packed, &info, &err), SC_OK);
    CHECK(info.peel_layers >= 1);
    CHECK_INT(info.readbacks, 0);
    sc_destroy_frame(fa);
    sc_destroy_frame(fb);
    sc_shutdown();
}
