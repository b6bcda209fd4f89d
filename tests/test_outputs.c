/* test_outputs.c — outputs on demand: the default renderer's sc_draw
 * writes colour and depth alone, running the rays a renderer that always
 * writes the AOVs runs, and a read or a pick after it draws the frame again
 * with them, the always-AOV frame; the tessellation peers' frames the
 * same. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"
#include "gl_context_util.h"
#include "gl_render_private.h"
#include "io.h"
#include "peer_private.h"
#include "shader_contract.h"
#include "splinecast.h"
#include "test.h"

/* A renderer's last sc_draw: its intersections and keys; then, read back
 * (drawn again with the AOVs where the frame had none), its image; the
 * programs and intersections before and after. */
typedef struct drawn {
    long long intersections, intersections_read;
    int programs, programs_read;
    sc_key key;
    sc_frame_id frame;
    sc_pick_result pick[4];
} drawn;

static const double pick_at[4][2] = {{48.5, 36.5}, {40.5, 30.5}, {60.5, 44.5}, {2.5, 2.5}};

static int draw_and_read(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                         const sc_camera_desc *cam, drawn *out, sc_error *err)
{
    sc_renderer_id r;
    sc_renderer_info info = {0}, after = {0};
    int count = 0;
    memset(out, 0, sizeof *out);
    if (sc_make_renderer(ctx, scene, &desc, &r, err) != SC_OK)
        return SC_FAIL;
    int ok = sc_draw(r, cam, err) == SC_OK && sc_query_renderer_info(r, &info, err) == SC_OK &&
             sc_query_renderer_keys(r, &out->key, 1, &count, err) == SC_OK &&
             sc_read_frame(r, &out->frame, err) == SC_OK &&
             sc_query_renderer_info(r, &after, err) == SC_OK;
    /* Picking after a draw: each pick reads the frame (the first drawn
     * again with the AOVs where it had none). */
    for (int i = 0; ok && i < 4; i++)
        ok = sc_draw(r, cam, err) == SC_OK &&
             sc_pick(r, pick_at[i][0], pick_at[i][1], &out->pick[i], err) == SC_OK;
    sc_destroy_renderer(r);
    out->intersections = info.intersections;
    out->intersections_read = after.intersections;
    out->programs = info.programs;
    out->programs_read = after.programs;
    return ok ? SC_OK : SC_FAIL;
}

/* Pixels whose colour differs by more than 2 levels. */
static int differing(sc_frame_id a, sc_frame_id b)
{
    sc_frame_info fa, fb;
    sc_error err = {0};
    if (sc_query_frame_info(a, &fa, &err) != SC_OK || sc_query_frame_info(b, &fb, &err) != SC_OK ||
        fa.width != fb.width || fa.height != fb.height)
        return -1;
    int differ = 0;
    for (int p = 0; p < fa.width * fa.height; p++)
        for (int c = 0; c < 3; c++)
            if (abs(fa.rgba[4 * p + c] - fb.rgba[4 * p + c]) > 2) {
                differ++;
                break;
            }
    return differ;
}

TEST(outputs_on_demand_frames)
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
        drawn always, demand;
        if (draw_and_read(ctx, scene,
                          (sc_renderer_desc){.termination = modes[m], .aovs = SC_AOVS_ALWAYS},
                          &cam, &always, &err) != SC_OK)
            TEST_FAIL_("always: %s", err.message);
        if (draw_and_read(ctx, scene, (sc_renderer_desc){.termination = modes[m]}, &cam, &demand,
                          &err) != SC_OK)
            TEST_FAIL_("on demand: %s", err.message);
        CHECK(always.intersections > 0);
        CHECK(always.intersections_read == always.intersections);
        /* The default's sc_draw ran programs without the AOVs, which count
         * nothing; the read drew the frame again with them, the rays of
         * the frame that wrote them from the start. */
        CHECK(demand.intersections == -1);
        CHECK(demand.intersections_read == always.intersections);
        size_t n = strlen(demand.key.text);
        CHECK(n > 10 && !strcmp(always.key.text + strlen(always.key.text) - 4, ".aov"));
        CHECK(!strcmp(demand.key.text + n - 10, "-out.shade"));
        /* The AOV programs were compiled for the read, not before. */
        CHECK_INT(always.programs_read, always.programs);
        CHECK(demand.programs_read > demand.programs);
        /* The frame read back is the always-AOV frame's. */
        CHECK_INT(differing(always.frame, demand.frame), 0);
        for (int i = 0; i < 4; i++) {
            const sc_pick_result *x = &always.pick[i], *y = &demand.pick[i];
            CHECK_INT(x->hit, y->hit);
            CHECK_INT(x->surface, y->surface);
            CHECK_INT(x->gpu_surface, y->gpu_surface);
            CHECK_NEAR(x->u, y->u, 1e-9);
            CHECK_NEAR(x->v, y->v, 1e-9);
            CHECK_NEAR(x->t, y->t, 1e-9);
        }
        CHECK(always.pick[0].hit);   /* the middle of the default view */
        CHECK(!always.pick[3].hit);  /* its corner */
        sc_destroy_frame(always.frame);
        sc_destroy_frame(demand.frame);
    }
    sc_renderer_id r;
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.aovs = 2}, &r, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "aovs");
    sc_peer_id peer;
    CHECK_INT(sc_make_peer(ctx, scene, &(sc_peer_desc){.aovs = 2}, &peer, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_peer_desc.aovs");
    CHECK_INT(peer.id, 0);
    /* A debug view is drawn from the AOVs: its renderer keeps them. */
    drawn normal;
    CHECK_INT(draw_and_read(ctx, scene, (sc_renderer_desc){.show = SC_SHOW_NORMAL}, &cam, &normal,
                            &err),
              SC_OK);
    CHECK_INT(normal.programs_read, normal.programs);
    CHECK(strcmp(normal.key.text + strlen(normal.key.text) - 10, "-out.shade"));
    sc_destroy_frame(normal.frame);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
}

/* The teapot from its side, a little above, filling most of the image. */
static const sc_camera teapot_side_view = {.eye = {0, -8, 3}, .target = {0, 0, 0.8},
                                           .fovy_deg = 30, .width = 160, .height = 120};

/* The colour-only frame's picture is the full frame's: its colour
 * attachment, read by the runtime's own means, against the shaded image
 * of a renderer that writes the AOVs, under the default (manual)
 * termination, whose nearest distances then come from the depth buffer.
 * The colour-only target has no AOV attachment; a read after the frame
 * draws it again with them, at the same camera, and gets the same image. */
TEST(outputs_colour_only_image_matches)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    sc_camera cam = teapot_side_view;
    sc_image full = {0}, colour = {0}, again = {0};
    sc_aov aov = {0};
    sc_render_desc desc = {0};
    sc_renderer *r;
    CHECK_INT(sc_renderer_create(gl, &scene, &desc, &r, &err), SC_OK);
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    CHECK(r->target.colour[SCG_FRAG_OUT_SURFACE] != 0);
    CHECK_INT(sc_renderer_read(r, &full, NULL, &err), SC_OK);
    sc_renderer_destroy(r);
    desc.aovs_on_demand = 1;
    CHECK_INT(sc_renderer_create(gl, &scene, &desc, &r, &err), SC_OK);
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    CHECK(r->readbacks > 0);   /* the depth buffer's nearest distances were read */
    CHECK(r->target.colour[SCG_FRAG_OUT_SURFACE] == 0 && r->target.colour[SCG_FRAG_OUT_UVT] == 0);
    CHECK(r->groups[0].aov.id == 0);   /* not compiled yet */
    CHECK_INT(sc_gl_target_read_image(gl, &r->target, SCG_FRAG_OUT_COLOUR, &colour, &err), SC_OK);
    CHECK_INT(sc_renderer_read(r, &again, &aov, &err), SC_OK);
    CHECK(r->target.colour[SCG_FRAG_OUT_SURFACE] != 0 && r->groups[0].aov.id != 0);
    int covered = 0;
    for (int p = 0; aov.surface && p < cam.width * cam.height; p++)
        covered += aov.surface[p] >= 0;
    CHECK(covered > cam.width * cam.height / 10);
    /* The next sc_renderer_draw writes the colour alone again. */
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    CHECK(r->target.colour[SCG_FRAG_OUT_SURFACE] == 0);
    sc_renderer_destroy(r);
    int n = cam.width * cam.height, differ = 0, differ_again = 0;
    CHECK(full.pixels && colour.pixels && again.pixels && full.channels == colour.channels &&
          full.channels == again.channels);
    for (int p = 0; full.pixels && colour.pixels && again.pixels && p < n; p++) {
        int worst = 0, worst_again = 0;
        for (int c = 0; c < 3; c++) {
            int d = abs(full.pixels[p * full.channels + c] - colour.pixels[p * colour.channels + c]);
            int e = abs(full.pixels[p * full.channels + c] - again.pixels[p * again.channels + c]);
            worst = d > worst ? d : worst;
            worst_again = e > worst_again ? e : worst_again;
        }
        differ += worst > 2;
        differ_again += worst_again > 0;
    }
    if (differ)
        fprintf(stderr, "  %d of %d pixels differ by more than 2 levels\n", differ, n);
    CHECK(differ <= n / 1000);
    CHECK_INT(differ_again, 0);
    sc_image_free(&full);
    sc_image_free(&colour);
    sc_image_free(&again);
    sc_aov_free(&aov);
    sc_scene_free(&scene);
}

/* A peer's frame without the AOVs: the colour attachment alone drawn, with
 * the picture of the frame that writes them (the same triangles and
 * shading); a read draws it again with the AOVs, and gets what a peer
 * that always writes them reads. For GLU's triangles and the tessellation
 * shaders. */
TEST(outputs_peer_colour_only_frames)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    sc_camera cam = teapot_side_view;
    for (int type = 0; type < 2; type++) {
        sc_image images[2] = {{0}}, colour = {0};
        sc_aov aovs[2] = {{0}};
        for (int on_demand = 0; on_demand < 2; on_demand++) {
            sc_peer_config config = {.type = type ? SC_PEER_TYPE_TESS : SC_PEER_TYPE_GLU,
                                     .tolerance_px = 0.5, .aovs_on_demand = on_demand};
            sc_peer *p;
            CHECK_INT(sc_peer_create(gl, &scene, &config, &p, &err), SC_OK);
            CHECK_INT(sc_peer_update(p, &cam, &err), SC_OK);
            CHECK_INT(sc_peer_draw(p, &cam, 0, &err), SC_OK);
            CHECK_INT(p->frame_aovs, !on_demand);
            /* Without the AOVs the target has the colour attachment alone. */
            CHECK_INT(p->target.colour[SCG_FRAG_OUT_SURFACE] != 0, !on_demand);
            CHECK_INT(p->target.colour[SCG_FRAG_OUT_NORMAL] != 0, !on_demand);
            if (on_demand)
                CHECK_INT(sc_gl_target_read_image(gl, &p->target, SCG_FRAG_OUT_COLOUR, &colour,
                                                  &err),
                          SC_OK);
            CHECK_INT(sc_peer_read(p, &images[on_demand], &aovs[on_demand], &err), SC_OK);
            CHECK_INT(p->frame_aovs, 1);
            CHECK(p->target.colour[SCG_FRAG_OUT_SURFACE] != 0);
            sc_peer_destroy(p);
        }
        int n = cam.width * cam.height, differ = 0, differ_read = 0, covered = 0, surfaces = 0;
        CHECK(images[0].pixels && images[1].pixels && colour.pixels);
        for (int q = 0; images[0].pixels && images[1].pixels && colour.pixels && q < n; q++) {
            differ += memcmp(images[0].pixels + 4 * q, colour.pixels + 4 * q, 3) != 0;
            differ_read += memcmp(images[0].pixels + 4 * q, images[1].pixels + 4 * q, 3) != 0;
            covered += aovs[0].surface[q] >= 0;
            surfaces += aovs[0].surface[q] != aovs[1].surface[q];
        }
        CHECK(covered > n / 10);
        CHECK_INT(differ, 0);
        CHECK_INT(differ_read, 0);
        CHECK_INT(surfaces, 0);
        for (int i = 0; i < 2; i++) {
            sc_image_free(&images[i]);
            sc_aov_free(&aovs[i]);
        }
        sc_image_free(&colour);
    }
    sc_scene_free(&scene);
}
