/* test_view.c — camera habits: an up vector (`--up`, the 10-number camera
 * text), the default view seen from an axis (`--view-from`), and the
 * default framing of trimmed surfaces by what their trims keep. */
#include <stdlib.h>

#include "test.h"

#include "camera.h"
#include "io.h"
#include "refcast.h"
#include "splinecast.h"

TEST(view_camera_text_with_up)
{
    sc_camera cam = {.width = 8, .height = 8};
    sc_error err = {0};
    CHECK_INT(sc_camera_parse("1,2,3,0,0,0,40,0,1,0", &cam, &err), SC_OK);
    CHECK_NEAR(cam.up[1], 1, 0);
    char text[400];
    sc_camera_format(&cam, text, sizeof text);
    CHECK_STR(text, "1,2,3,0,0,0,40,0,1,0");
    /* The frame's up follows it: the image's up is the world's +y, made
     * orthogonal to the view. */
    double f[3], r[3], u[3];
    sc_camera_frame(&cam, f, r, u);
    CHECK(u[1] > 0.9 * sqrt(1 - f[1] * f[1]));
    CHECK_NEAR(u[0] * f[0] + u[1] * f[1] + u[2] * f[2], 0, 1e-12);
    /* Without an up vector: 7 numbers, as before. */
    sc_camera plain = {.width = 8, .height = 8};
    CHECK_INT(sc_camera_parse("1,2,3,0,0,0,40", &plain, &err), SC_OK);
    sc_camera_format(&plain, text, sizeof text);
    CHECK_STR(text, "1,2,3,0,0,0,40");
    CHECK_INT(sc_camera_parse("1,2,3,0,0,0,40,0,0,0", &cam, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "up vector is zero");
    CHECK_INT(sc_camera_parse("1,2,3,0,0,0,40,0,1", &cam, &err), SC_FAIL);
    /* Up along the view: the old rule applies. */
    sc_camera along = {.eye = {0, 5, 0}, .target = {0, 0, 0}, .fovy_deg = 30, .up = {0, 1, 0},
                       .width = 8, .height = 8};
    sc_camera_frame(&along, f, r, u);
    CHECK_NEAR(u[2], 1, 1e-12);
}

/* `--up 0,1,0` stands a y-up model up: the reference and the GPU agree on
 * the view (diff compares), the files record the up vector, and the
 * default view looks from above along +y. `--view-from +x` looks along -x. */
TEST(view_up_and_view_from_cli)
{
    const char *dir = test_tmpdir();
    char cmd[4096], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "(%s ref teapot -o %s/up_ref.png --size 48x48 --up 0,1,0 && "
             "%s render teapot -o %s/up_gpu.png --size 48x48 --up 0,1,0 --frames 1 --aov "
             "%s/up_gpu.aov && %s diff %s/up_ref.aov %s/up_gpu.aov)", test_cli, dir, test_cli,
             dir, dir, test_cli, dir, dir);
    int status = test_run(cmd, &out, &err);
    if (status == 1 && err && strstr(err, "OSMesa")) {
        free(out);
        free(err);
        SKIP("no GL context");
    }
    CHECK_INT(status, 0);
    CHECK_CONTAINS(out, ",0,1,0 hit_pixels=");
    CHECK_CONTAINS(out, "accuracy coverage_pct=");
    double fail = -1;
    CHECK(sscanf(strstr(out, "fail_pct="), "fail_pct=%lf", &fail) == 1);
    CHECK(fail < 1.0);
    /* The default direction for +y up is (1, 1.2, 2): above along +y. */
    double e[3], t[3], fovy;
    CHECK(sscanf(strstr(out, "camera="), "camera=%lf,%lf,%lf,%lf,%lf,%lf,%lf", &e[0], &e[1],
                 &e[2], &t[0], &t[1], &t[2], &fovy) == 7);
    CHECK_NEAR((e[1] - t[1]) / (e[0] - t[0]), 1.2, 1e-9);
    CHECK_NEAR((e[2] - t[2]) / (e[0] - t[0]), 2.0, 1e-9);
    free(out);
    free(err);
    snprintf(cmd, sizeof cmd, "%s ref teapot -o %s/from_x.png --size 16x16 --view-from +x",
             test_cli, dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK(sscanf(strstr(out, "camera="), "camera=%lf,%lf,%lf,%lf,%lf,%lf,%lf", &e[0], &e[1],
                 &e[2], &t[0], &t[1], &t[2], &fovy) == 7);
    CHECK(e[0] - t[0] > 0);
    CHECK_NEAR(e[1], t[1], 1e-9);
    CHECK_NEAR(e[2], t[2], 1e-9);
    free(out);
    snprintf(cmd, sizeof cmd, "%s ref teapot -o %s/from_x.png --view-from +x --camera "
             "1,2,3,0,0,0,30", test_cli, dir);
    CHECK_INT(test_run(cmd, NULL, &err), 2);
    CHECK_CONTAINS(err, "cannot go with --camera");
    free(err);
}

/* The hit pixels of a reference image: count and the centre of their box
 * in image fractions. */
static long hits_of(const sc_scene *scene, const sc_camera *cam, double centre[2])
{
    sc_refcast *rc;
    sc_error err = {0};
    if (sc_refcast_prepare(scene, &rc, &err) != SC_OK)
        return -1;
    sc_aov aov;
    if (sc_refcast_render(rc, cam, NULL, &aov, NULL, &err) != SC_OK) {
        sc_refcast_free(rc);
        return -1;
    }
    long n = 0;
    int lo[2] = {aov.width, aov.height}, hi[2] = {-1, -1};
    for (int j = 0; j < aov.height; j++)
        for (int i = 0; i < aov.width; i++)
            if (aov.surface[j * aov.width + i] >= 0) {
                n++;
                lo[0] = i < lo[0] ? i : lo[0];
                hi[0] = i > hi[0] ? i : hi[0];
                lo[1] = j < lo[1] ? j : lo[1];
                hi[1] = j > hi[1] ? j : hi[1];
            }
    centre[0] = 0.5 * (lo[0] + hi[0] + 1) / aov.width;
    centre[1] = 0.5 * (lo[1] + hi[1] + 1) / aov.height;
    sc_aov_free(&aov);
    sc_refcast_free(rc);
    return n;
}

/* A face that keeps a small piece of a large surface (OCC26138_Torus.igs)
 * is framed by what it keeps: centred, and several times larger than the
 * framing of its control points' box (the default before). */
TEST(view_default_frames_trimmed_faces)
{
    REQUIRE_DATA("iges/OCC26138_Torus.igs");
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene(test_data("iges/OCC26138_Torus.igs"), &scene, &err), SC_OK);
    sc_camera now = {.width = 64, .height = 64}, before;
    sc_camera_default(&scene, &now);
    /* The old framing: the same rule over the control points' box. */
    double lo[3], hi[3], kept_lo[3], kept_hi[3];
    CHECK(sc_scene_bounds(&scene, lo, hi));
    CHECK(sc_scene_view_bounds(&scene, kept_lo, kept_hi));
    for (int k = 0; k < 3; k++)
        CHECK(kept_lo[k] >= lo[k] - 1e-9 && kept_hi[k] <= hi[k] + 1e-9);
    before = now;
    double radius_now = 0, radius_before = 0;
    for (int k = 0; k < 3; k++) {
        radius_now += (kept_hi[k] - kept_lo[k]) * (kept_hi[k] - kept_lo[k]);
        radius_before += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    double scale = sqrt(radius_before / radius_now);
    for (int k = 0; k < 3; k++) {
        before.target[k] = 0.5 * (lo[k] + hi[k]);
        before.eye[k] = before.target[k] + scale * (now.eye[k] - now.target[k]);
    }
    double c_now[2], c_before[2];
    long n_now = hits_of(&scene, &now, c_now), n_before = hits_of(&scene, &before, c_before);
    CHECK(n_now > 0 && n_before > 0);
    fprintf(stderr, "  %ld hit pixels framed by the kept region, %ld by the control points\n",
            n_now, n_before);
    CHECK(n_now > 3 * n_before);
    CHECK_NEAR(c_now[0], 0.5, 0.1);
    CHECK_NEAR(c_now[1], 0.5, 0.1);
    sc_scene_free(&scene);

    /* Untrimmed scenes frame exactly as before. */
    CHECK_INT(sc_read_scene(TEST_TEAPOT32, &scene, &err), SC_OK);
    CHECK(sc_scene_bounds(&scene, lo, hi) && sc_scene_view_bounds(&scene, kept_lo, kept_hi));
    for (int k = 0; k < 3; k++) {
        CHECK_NEAR(kept_lo[k], lo[k], 0);
        CHECK_NEAR(kept_hi[k], hi[k], 0);
    }
    sc_scene_free(&scene);
}
