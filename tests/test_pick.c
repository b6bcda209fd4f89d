/* test_pick.c — sc_pick and `splinecast pick` against the CPU reference:
 * on a grid of image points over the tea set and a trimmed IGES part, the
 * picked point lies within 1e-6 of the scene's size of the reference's hit
 * for the same ray, sc_eval_surface at the picked (u, v) gives the picked
 * point, and the command line prints the same answer. */
#include <stdlib.h>

#include "test.h"

#include "camera.h"
#include "io.h"
#include "refcast.h"
#include "splinecast.h"

enum { PICK_SIZE = 96, PICK_GRID = 12 };

typedef struct pick_counts {
    int both, misses, disagree;
    double worst;          /* largest point distance / scene size */
    int no_gl;
} pick_counts;

/* Picks a grid of points of the default view (with `up`) of one scene and
 * compares each with the reference ray; n->no_gl when GL is missing. */
static void pick_against_reference(const char *path, const double up[3], pick_counts *n)
{
    memset(n, 0, sizeof *n);
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    sc_renderer_id r;
    if (sc_make_scene(&(sc_scene_desc){.path = path}, &scene, &err) != SC_OK) {
        TEST_FAIL_("%s: %s", path, err.message);
        return;
    }
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_destroy_scene(scene);
        n->no_gl = 1;
        return;
    }
    sc_camera_desc view = {.width = PICK_SIZE, .height = PICK_SIZE};
    memcpy(view.up, up, sizeof view.up);
    sc_frame_id frame;
    sc_frame_info info;
    if (sc_make_renderer(ctx, scene, NULL, &r, &err) != SC_OK ||
        sc_render(r, &view, &frame, &err) != SC_OK || sc_query_frame_info(frame, &info, &err)) {
        TEST_FAIL_("%s: %s", path, err.message);
        return;
    }
    sc_camera cam = {.width = PICK_SIZE, .height = PICK_SIZE};
    CHECK_INT(sc_camera_parse(info.camera, &cam, &err), SC_OK);
    sc_destroy_frame(frame);
    sc_scene model;
    CHECK_INT(sc_read_scene(path, &model, &err), SC_OK);
    sc_refcast *rc;
    CHECK_INT(sc_refcast_prepare(&model, &rc, &err), SC_OK);
    double lo[3], hi[3], size = 0;
    sc_scene_bounds(&model, lo, hi);
    for (int k = 0; k < 3; k++)
        size += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    size = sqrt(size);
    for (int gy = 0; gy < PICK_GRID; gy++)
        for (int gx = 0; gx < PICK_GRID; gx++) {
            /* Off the pixel centres too: the ray goes through (x, y). */
            double x = (gx + 0.5) * PICK_SIZE / PICK_GRID + 0.13;
            double y = (gy + 0.5) * PICK_SIZE / PICK_GRID + 0.31;
            sc_pick_result pick;
            CHECK_INT(sc_pick(r, x, y, &pick, &err), SC_OK);
            double dir[3];
            sc_camera_ray(&cam, x, y, dir);
            sc_ref_hit ref;
            sc_refcast_trace(rc, cam.eye, dir, &ref);
            if (!pick.hit && ref.surface < 0) {
                n->misses++;
                continue;
            }
            if (!pick.hit || ref.surface < 0) {
                n->disagree++;
                fprintf(stderr, "  %s (%g, %g): pick %s, reference %s\n", path, x, y,
                        pick.hit ? "hits" : "misses", ref.surface >= 0 ? "hits" : "misses");
                continue;
            }
            n->both++;
            double dist = 0;
            for (int k = 0; k < 3; k++)
                dist += (pick.point[k] - ref.point[k]) * (pick.point[k] - ref.point[k]);
            dist = sqrt(dist);
            n->worst = fmax(n->worst, dist / size);
            if (dist > 1e-6 * size)
                fprintf(stderr, "  %s (%g, %g): surface %d (%.17g, %.17g) vs reference %d "
                        "(%.17g, %.17g)\n", path, x, y, pick.surface, pick.u, pick.v,
                        ref.surface, ref.u, ref.v);
            CHECK_NEAR(dist / size, 0, 1e-6);
            CHECK_NEAR(pick.t, ref.t, 1e-6 * size);
            /* A different surface only at a seam, where both hold the point. */
            if (pick.surface == ref.surface) {
                CHECK_NEAR(pick.u, ref.u, 1e-6 * (1 + fabs(ref.u)));
                CHECK_NEAR(pick.v, ref.v, 1e-6 * (1 + fabs(ref.v)));
            }
            double cosine = 0;
            for (int k = 0; k < 3; k++)
                cosine += pick.normal[k] * ref.normal[k];
            CHECK(cosine > 0.999 || pick.surface != ref.surface);
            /* eval at the picked (u, v) gives the picked point. */
            sc_surface_point at;
            CHECK_INT(sc_eval_surface(scene, pick.surface, pick.u, pick.v, &at, &err), SC_OK);
            for (int k = 0; k < 3; k++)
                CHECK_NEAR(at.point[k], pick.point[k], 1e-12 * size);
        }
    sc_refcast_free(rc);
    sc_scene_free(&model);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
}

TEST(pick_tea_set_against_reference)
{
    static const struct {
        const char *file;
        double up[3];
    } sets[] = {{"teaset/teapot32.bpt", {0, 0, 0}}, {"teaset/teapot.bpt", {0, 1, 0}},
                {"teaset/teacup.bpt", {0, 1, 0}}, {"teaset/teaspoon.bpt", {0, 0, 0}}};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        REQUIRE_DATA(sets[i].file);
        pick_counts n;
        int failed_before = test_failed_flag;
        pick_against_reference(test_data(sets[i].file), sets[i].up, &n);
        if (n.no_gl)
            SKIP("no GL context");
        if (test_failed_flag && !failed_before)
            return;
        fprintf(stderr, "  %s: %d both hit, %d both miss, %d disagree, worst %.3g of the size\n",
                sets[i].file, n.both, n.misses, n.disagree, n.worst);
        /* Enough of the grid hits; at most one silhouette point may differ. */
        CHECK(n.both >= 5);
        CHECK(n.disagree <= 1);
    }
    sc_shutdown();
}

TEST(pick_trimmed_iges_against_reference)
{
    const char *files[] = {"iges/bug24012_face.igs", "iges/gpucast_part.igs"};
    for (int i = 0; i < 2; i++) {
        REQUIRE_DATA(files[i]);
        pick_counts n;
        int failed_before = test_failed_flag;
        pick_against_reference(test_data(files[i]), (double[3]){0, 0, 0}, &n);
        if (n.no_gl)
            SKIP("no GL context");
        if (test_failed_flag && !failed_before)
            return;
        fprintf(stderr, "  %s: %d both hit, %d both miss, %d disagree, worst %.3g of the size\n",
                files[i], n.both, n.misses, n.disagree, n.worst);
        CHECK(n.both >= 5);
        CHECK(n.disagree <= 1);
    }
    sc_shutdown();
}

/* The command line: the documented line, the same numbers sc_eval_surface
 * gives at the printed (u, v), a miss in a corner, and bad points refused. */
TEST(pick_cli_line)
{
    char cmd[2048], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "%s pick teapot --at 48.5,40.5 --size 96x96", test_cli);
    int status = test_run(cmd, &out, &err);
    if (status == 1 && err && strstr(err, "OSMesa")) {
        free(out);
        free(err);
        SKIP("no GL context");
    }
    CHECK_INT(status, 0);
    int surface;
    double u, v, p[3], nrm[3], t;
    CHECK(out && sscanf(out, "pick surface=%d u=%lf v=%lf point=%lf,%lf,%lf normal=%lf,%lf,%lf "
                        "t=%lf", &surface, &u, &v, &p[0], &p[1], &p[2], &nrm[0], &nrm[1], &nrm[2],
                        &t) == 10);
    free(out);
    free(err);
    snprintf(cmd, sizeof cmd, "%s eval teapot --surface %d --uv %.17g,%.17g", test_cli, surface,
             u, v);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    double e[3];
    CHECK(out && sscanf(strstr(out, "point "), "point %lf %lf %lf", &e[0], &e[1], &e[2]) == 3);
    for (int k = 0; k < 3; k++)
        CHECK_NEAR(e[k], p[k], 1e-9 * 4);
    free(out);
    snprintf(cmd, sizeof cmd, "%s pick teapot --at 0.5,0.5 --size 96x96", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_STR(out, "pick miss\n");
    free(out);
    snprintf(cmd, sizeof cmd, "%s pick teapot --at 96,3 --size 96x96", test_cli);
    CHECK_INT(test_run(cmd, NULL, &err), 2);
    CHECK_CONTAINS(err, "outside the 96x96 image");
    free(err);
}
