/* test_outputs.c — outputs on demand: a colour-only renderer draws the
 * same work as one that writes the AOVs, drops the AOVs its termination
 * does not read, and says so when asked for a frame. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"
#include "gl_context_util.h"
#include "gl_render_private.h"
#include "io.h"
#include "shader_contract.h"
#include "splinecast.h"
#include "test.h"

static long long intersections_of(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                                  const sc_camera_desc *cam, sc_key *key, sc_error *err)
{
    sc_renderer_id r;
    sc_renderer_info info = {0};
    int count = 0;
    if (sc_make_renderer(ctx, scene, &desc, &r, err) != SC_OK)
        return -1;
    int ok = sc_draw(r, cam, err) == SC_OK && sc_query_renderer_info(r, &info, err) == SC_OK &&
             sc_query_renderer_keys(r, key, 1, &count, err) == SC_OK;
    if (ok && desc.colour_only) {
        sc_frame_id frame = {0};
        sc_error read_err = {0};
        ok = sc_read_frame(r, &frame, &read_err) == SC_FAIL &&
             strstr(read_err.message, "colour-only") && strstr(read_err.message, "no AOVs");
        if (!ok)
            snprintf(err->message, sizeof err->message, "read: %.400s", read_err.message);
    }
    sc_destroy_renderer(r);
    return ok ? info.intersections : -1;
}

TEST(outputs_colour_only_frames)
{
    sc_error err = {0};
    sc_context_id ctx;
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = "teapot"}, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_destroy_scene(scene);
        SKIP("no GL context: %s", err.message);
    }
    sc_camera_desc cam = {.width = 96, .height = 72};
    static const sc_ray_termination modes[] = {SC_TERMINATION_DEFAULT, SC_TERMINATION_NONE};
    for (int m = 0; m < 2; m++) {
        sc_key full, colour;
        long long a = intersections_of(ctx, scene, (sc_renderer_desc){.termination = modes[m]},
                                       &cam, &full, &err);
        CHECK(a > 0);
        long long b = intersections_of(
            ctx, scene, (sc_renderer_desc){.termination = modes[m], .colour_only = 1}, &cam,
            &colour, &err);
        if (b < 0)
            TEST_FAIL_("colour-only: %s", err.message);
        /* The programs drop the AOVs. Without termination the same rays
         * run; under manual termination the nearest distances come from
         * the depth buffer, made a little larger than it rounds them, so
         * a few more rays may run, never fewer than a handful less. */
        if (modes[m] == SC_TERMINATION_NONE)
            CHECK_INT(a, b);
        else
            CHECK(b >= a - a / 1000 && b <= a + a / 50);
        size_t n = strlen(colour.text);
        CHECK(n > 10 && !strcmp(full.text + strlen(full.text) - 4, ".aov"));
        CHECK(!strcmp(colour.text + n - 10, "-out.shade"));
    }
    sc_renderer_id r;
    CHECK_INT(sc_make_renderer(ctx, scene,
                               &(sc_renderer_desc){.colour_only = 1, .show = SC_SHOW_NORMAL}, &r,
                               &err),
              SC_FAIL);
    CHECK_CONTAINS(err.message, "colour_only");
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
}

/* The colour-only frame's picture is the full frame's: its colour
 * attachment, read by the runtime's own means, against the shaded image
 * of a renderer that writes the AOVs, under the default (manual)
 * termination, whose nearest distances then come from the depth buffer. */
TEST(outputs_colour_only_image_matches)
{
    const char *why = "";
    sc_gl_context *ctx = test_gl_context(SC_BACKEND_DEFAULT, &why);
    if (!ctx)
        SKIP("no GL context: %s", why);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    sc_camera cam = {.eye = {0, -8, 3}, .target = {0, 0, 0.8}, .fovy_deg = 30,
                     .width = 160, .height = 120};
    sc_image full = {0}, colour = {0};
    sc_render_desc desc = {0};
    sc_renderer *r;
    CHECK_INT(sc_renderer_create(gl, &scene, &desc, &r, &err), SC_OK);
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    CHECK_INT(sc_renderer_read(r, &full, NULL, &err), SC_OK);
    sc_renderer_destroy(r);
    desc.colour_only = 1;
    CHECK_INT(sc_renderer_create(gl, &scene, &desc, &r, &err), SC_OK);
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    CHECK(r->readbacks > 0);   /* the depth buffer's nearest distances were read */
    CHECK(r->target.colour[SCG_FRAG_OUT_SURFACE] == 0 && r->target.colour[SCG_FRAG_OUT_UVT] == 0);
    CHECK_INT(sc_gl_target_read_image(gl, &r->target, SCG_FRAG_OUT_COLOUR, &colour, &err), SC_OK);
    sc_renderer_destroy(r);
    int n = cam.width * cam.height, differ = 0;
    CHECK(full.pixels && colour.pixels && full.channels == colour.channels);
    for (int p = 0; full.pixels && colour.pixels && p < n; p++) {
        int worst = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs(full.pixels[p * full.channels + c] - colour.pixels[p * colour.channels + c]);
            worst = d > worst ? d : worst;
        }
        differ += worst > 2;
    }
    if (differ)
        fprintf(stderr, "  %d of %d pixels differ by more than 2 levels\n", differ, n);
    CHECK(differ <= n / 1000);
    sc_image_free(&full);
    sc_image_free(&colour);
    sc_scene_free(&scene);
}
