/* test_accuracy.c — settings from an accuracy target (accuracy.h,
 * docs/accuracy.md): the choice is monotone (a looser target never asks
 * for finer hulls, more iterations or a smaller tolerance), a render at a
 * target meets it against the CPU reference, and bad targets are refused
 * with a message that names what is wrong. */
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy.h"
#include "hulls.h"
#include "io.h"
#include "key.h"
#include "nurbs.h"
#include "options.h"
#include "splinecast.h"

static const double targets[] = {0.005, 0.05, 0.1, 0.5, 1, 5, 100};
#define NTARGETS ((int)(sizeof targets / sizeof targets[0]))

/* Every surface, every pair of neighbouring targets, for one view and
 * normal bound: hulls never finer, iterations never more, tolerance never
 * smaller; and the hulls built from the loosest target's choices no more
 * than from the tightest's (the adaptive split is monotone in its
 * tolerance, so the targets between need no build). Returns the cost of
 * the loosest and the tightest target: hulls and iterations of all
 * surfaces, [0] and [1]. */
static void check_monotone(const sc_scene *scene, const sc_patch_list *patches,
                           const sc_camera *view, double normal_deg, int loosest[2],
                           int tightest[2])
{
    int n = scene->nsurfaces;
    sc_accuracy_choice *prev = calloc((size_t)n, sizeof *prev);
    sc_accuracy_choice *cur = calloc((size_t)n, sizeof *cur);
    double *tol = calloc((size_t)n, sizeof *tol);
    int prev_hulls = 0, iters = 0;
    for (int t = 0; t < NTARGETS; t++) {
        sc_accuracy_target target = {.px = targets[t], .normal_deg = normal_deg, .view = *view};
        sc_accuracy_choose(scene, patches, &target, SC_METHOD_DEFAULT, cur);
        for (int s = 0; s < n; s++) {
            CHECK(cur[s].hull_tolerance > 0);
            CHECK(cur[s].max_iters >= 1 && cur[s].max_iters <= SCG_DEFAULT_ITERS);
            CHECK(cur[s].tol_milli >= 1);
            if (t > 0) {
                CHECK(cur[s].hull_tolerance >= prev[s].hull_tolerance);
                CHECK(cur[s].max_iters <= prev[s].max_iters);
                CHECK(cur[s].tol_milli >= prev[s].tol_milli);
            }
            tol[s] = cur[s].hull_tolerance;
            iters += cur[s].max_iters;
        }
        if (t == 0)
            tightest[1] = iters;
        loosest[1] = iters;
        iters = 0;
        if (t == 0 || t == NTARGETS - 1) {
            sc_hulls hulls;
            sc_error err = {0};
            CHECK_INT(sc_hulls_build_from(scene, patches,
                                          &(sc_hull_desc){.surface_tolerance = tol}, &hulls,
                                          &err), SC_OK);
            if (t > 0)
                CHECK(hulls.count <= prev_hulls);
            prev_hulls = hulls.count;
            if (t == 0)
                tightest[0] = hulls.count;
            loosest[0] = hulls.count;
            sc_hulls_free(&hulls);
        }
        memcpy(prev, cur, (size_t)n * sizeof *cur);
    }
    free(prev);
    free(cur);
    free(tol);
}

TEST(accuracy_choice_is_monotone)
{
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(TEST_TEAPOT32, &scene, &err), SC_OK);
    int n = scene.nsurfaces;
    sc_patch_list *patches = calloc((size_t)n, sizeof *patches);
    for (int s = 0; s < n; s++)
        sc_surface_world_patches(&scene.surfaces[s], s, &patches[s]);
    sc_camera view = {.width = 256, .height = 256};
    sc_camera_default(&scene, &view);
    int loose[2], tight[2];
    check_monotone(&scene, patches, &view, 0, loose, tight);
    CHECK(tight[0] > loose[0] || tight[1] > loose[1]);
    check_monotone(&scene, patches, &view, 2, loose, tight);
    /* A close-up from 8 % of the default distance: the tightest target
     * asks for the most there too. */
    sc_camera close = view;
    for (int c = 0; c < 3; c++)
        close.eye[c] = view.target[c] + 0.08 * (view.eye[c] - view.target[c]);
    close.width = close.height = 1024;
    check_monotone(&scene, patches, &close, 0, loose, tight);
    CHECK(tight[0] > loose[0] || tight[1] > loose[1]);
    /* Looser than the defaults costs less: at 1 px every surface takes
     * fewer iterations than the defaults' and hulls no finer. */
    sc_accuracy_choice *c = calloc((size_t)n, sizeof *c);
    sc_accuracy_choose(&scene, patches, &(sc_accuracy_target){.px = 1, .view = view},
                       SC_METHOD_DEFAULT, c);
    for (int s = 0; s < n; s++) {
        CHECK(c[s].max_iters < SCG_DEFAULT_ITERS);
        CHECK(c[s].tol_milli > SCG_DEFAULT_TOL_MILLI);
        CHECK(c[s].hull_tolerance >= SC_HULL_DEFAULT_TOLERANCE);
    }
    /* subdiv and bclip keep their own step counts. */
    sc_accuracy_choose(&scene, patches, &(sc_accuracy_target){.px = 1, .view = view},
                       SC_METHOD_SUBDIV, c);
    CHECK_INT(c[0].max_iters, 0);
    free(c);
    for (int s = 0; s < n; s++)
        sc_patch_list_free(&patches[s]);
    free(patches);
    sc_scene_free(&scene);
}

/* Renders the teapot at a target and at the defaults, compares both with
 * the reference: the target's 99th percentile of the position error is
 * within it, and the renderer reports choices no costlier than the
 * defaults'. */
TEST(accuracy_render_meets_target)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = TEST_TEAPOT32}, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_destroy_scene(scene);
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_camera_desc view = {.width = 160, .height = 160};
    sc_frame_id ref;
    CHECK_INT(sc_render_reference(scene, &view, NULL, &ref, &err), SC_OK);
    const double px[] = {0.1, 1};
    for (int t = 0; t < 2; t++) {
        sc_renderer_desc desc = {.accuracy_px = px[t], .accuracy_view = &view};
        sc_renderer_id r;
        CHECK_INT(sc_make_renderer(ctx, scene, &desc, &r, &err), SC_OK);
        sc_frame_id frame;
        CHECK_INT(sc_render(r, &view, &frame, &err), SC_OK);
        sc_comparison acc;
        CHECK_INT(sc_compare_frames(ref, frame, &acc, &err), SC_OK);
        CHECK(acc.both_hit > 1000);
        CHECK(acc.pos_p99_px <= px[t]);
        CHECK(acc.fail_pct < 0.5);
        sc_renderer_surface_info si;
        CHECK_INT(sc_query_renderer_surface(r, 0, &si, &err), SC_OK);
        CHECK(si.max_iters <= SCG_DEFAULT_ITERS);
        CHECK(si.tolerance_px >= 0.05);
        CHECK(si.hulls > 0 && si.footprint > 0 && si.radius > 0);
        CHECK_CONTAINS(si.key.text, "-hybrid-");
        CHECK_INT(sc_query_renderer_surface(r, 1 << 20, &si, &err), SC_FAIL);
        sc_destroy_frame(frame);
        sc_destroy_renderer(r);
    }
    sc_destroy_frame(ref);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    sc_shutdown();
}

TEST(accuracy_bad_targets_refused)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_destroy_scene(scene);
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    const struct {
        double px, deg;
        const char *says;
    } bad[] = {
        {-1, 0, "sc_renderer_desc.accuracy_px"},
        {1e-4, 0, "0.001 to 100 pixel footprints"},
        {1000, 0, "0.001 to 100 pixel footprints"},
        {NAN, 0, "sc_renderer_desc.accuracy_px"},
        {0.1, 91, "0 (none) to 90 degrees"},
        {0.1, -2, "0 (none) to 90 degrees"},
        {0, 5, "needs a position bound"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        sc_renderer_id r = {0};
        sc_renderer_desc desc = {.accuracy_px = bad[i].px, .accuracy_normal_deg = bad[i].deg};
        CHECK_INT(sc_make_renderer(ctx, scene, &desc, &r, &err), SC_FAIL);
        CHECK_INT((int)r.id, 0);
        CHECK_CONTAINS(err.message, bad[i].says);
    }
    /* A bad view for the target is the view's error. */
    sc_renderer_id r;
    sc_renderer_desc desc = {.accuracy_px = 0.1,
                             .accuracy_view = &(sc_camera_desc){.text = "1,2,3"}};
    CHECK_INT(sc_make_renderer(ctx, scene, &desc, &r, &err), SC_FAIL);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    sc_shutdown();
    /* The command line's spelling. */
    double px, deg;
    CHECK_INT(cli_accuracy_parse("0.25,3", &px, &deg, &err), SC_OK);
    CHECK_NEAR(px, 0.25, 0);
    CHECK_NEAR(deg, 3, 0);
    CHECK_INT(cli_accuracy_parse("2", &px, &deg, &err), SC_OK);
    CHECK_NEAR(deg, 0, 0);
    const char *texts[] = {"", "px", "0.1,", "0.1;2", "0", "0.1,95", "500"};
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        CHECK_INT(cli_accuracy_parse(texts[i], &px, &deg, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, "--accuracy");
    }
    char cmd[1024], *out = NULL;
    snprintf(cmd, sizeof cmd, "%s render teapot -o %s/acc.png --accuracy 0.1,x", test_cli,
             test_tmpdir());
    CHECK(test_run(cmd, NULL, &out) != 0);
    CHECK_CONTAINS(out, "--accuracy takes PX or PX,DEG");
    free(out);
}

/* `render --accuracy` keeps the lines scripts read and adds its summary
 * before the program lines; its keys carry the chosen cap and tolerance. */
TEST(accuracy_render_prints_choice)
{
    char cmd[1024], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "%s render teapot -o %s/acc_cli.png --size 48x48 --frames 1 "
             "--accuracy 1", test_cli, test_tmpdir());
    int rc = test_run(cmd, &out, &err);
    if (rc != 0 && err && strstr(err, "no GL context")) {
        free(out);
        free(err);
        SKIP("no GL context");
    }
    CHECK_INT(rc, 0);
    CHECK(!strncmp(out, "stats programs=", 15));
    char *chosen = strstr(out, "\nchosen accuracy_px=1 normal_deg=0 surfaces=");
    CHECK(chosen != NULL);
    char *program = strstr(out, "\nprogram ");
    CHECK(program != NULL && program > chosen);
    int iters_min = 0, iters_max = 0;
    CHECK(sscanf(strstr(chosen, "iters_min="), "iters_min=%d iters_max=%d", &iters_min,
                 &iters_max) == 2);
    CHECK(iters_max < SCG_DEFAULT_ITERS);
    char want[32];
    snprintf(want, sizeof want, "-it%d-tol1-", iters_max);
    CHECK_CONTAINS(program, want);
    CHECK_CONTAINS(err, "render: surface 0: hull_tol=");
    free(out);
    free(err);
}
