/* test_chart.c — `splinecast bench --chart` end to end on a small image
 * (the CSV's header and rows, both pictures), and the tessellation peers
 * through the public API against the CPU reference: GLU on a trimmed scene
 * (its trims reach GLU the right way round), the tessellation shaders on
 * the teapot, both refined by a finer tolerance. */
#include <stdlib.h>

#include "splinecast.h"
#include "test.h"

/* Splits one CSV line into at most `max` fields (in place). */
static int split_fields(char *line, char **fields, int max)
{
    int n = 0;
    for (char *p = line; p && n < max;) {
        fields[n++] = p;
        p = strchr(p, ',');
        if (p)
            *p++ = 0;
    }
    return n;
}

TEST(chart_small_end_to_end)
{
    char dir[512], cmd[2048], *out = NULL, *errors = NULL;
    snprintf(dir, sizeof dir, "%s/chart", test_tmpdir());
    snprintf(cmd, sizeof cmd,
             "%s bench %s --chart %s --size 48x48 --frames 1 "
             "--configs default,newton-mid,hull-uniform1,glu-1,tess-1,tess-0.1",
             test_cli, TEST_TEAPOT32, dir);
    int status = test_run(cmd, &out, &errors);
    if (status != 0)
        fprintf(stderr, "%s\n", errors ? errors : "");
    CHECK_INT(status, 0);
    /* Progress on stderr, a line per row. */
    CHECK_CONTAINS(errors, "chart: [1/");
    free(out);
    free(errors);

    char path[600];
    snprintf(path, sizeof path, "%s/points.csv", dir);
    char *csv = test_read_file(path);
    CHECK(csv != NULL);
    char *save = NULL, *line = strtok_r(csv, "\n", &save);
    CHECK_STR(line, "scene,view,config,frame_ms,image_ms,fail_pct,pos_p99_px,normal_mean_deg,"
                    "normal_p99_deg,gpu_bytes,triangles,compile_ms");
    /* Per view: which rows came, and GLU's and the shaders' accuracy at
     * the two tolerances. */
    const char *views[3] = {"whole", "closeup8", "deforming"};
    int seen[3][7] = {{0}};
    const char *configs[7] = {"default", "newton-mid", "hull-uniform1", "glu-1", "glu-0.1",
                              "tess-1", "tess-0.1"};
    double pos[3][7] = {{0}};
    int rows = 0;
    while ((line = strtok_r(NULL, "\n", &save))) {
        char *f[16];
        CHECK_INT(split_fields(line, f, 16), 12);
        CHECK_CONTAINS(f[0], "teapot32");
        int v = -1, c = -1;
        for (int i = 0; i < 3; i++)
            if (!strcmp(f[1], views[i]))
                v = i;
        for (int i = 0; i < 7; i++)
            if (!strcmp(f[2], configs[i]))
                c = i;
        CHECK(v >= 0);
        CHECK(c >= 0);
        seen[v][c]++;
        double frame_ms = atof(f[3]), image_ms = atof(f[4]), fail = atof(f[5]);
        double p99 = atof(f[6]), nmean = atof(f[7]), n99 = atof(f[8]);
        CHECK(frame_ms > 0 && frame_ms < 60000);
        CHECK(image_ms > 0 && image_ms < 60000);
        CHECK(fail >= 0 && fail <= 100);
        CHECK(p99 >= 0 && isfinite(p99));
        CHECK(nmean >= 0 && nmean <= 180 && n99 >= 0 && n99 <= 180);
        CHECK(atol(f[9]) > 0);   /* gpu_bytes */
        CHECK(atol(f[10]) > 0);  /* triangles */
        CHECK(atof(f[11]) >= 0); /* compile_ms */
        pos[v][c] = p99;
        rows++;
    }
    free(csv);
    CHECK_INT(rows, 3 * 7);
    for (int v = 0; v < 3; v++)
        for (int c = 0; c < 7; c++)
            CHECK_INT(seen[v][c], 1);
    /* The ray caster's default lands within a pixel; each peer is more
     * exact at the finer tolerance (whole view). */
    CHECK(pos[0][0] < 1);
    CHECK(pos[0][4] < pos[0][3]);
    CHECK(pos[0][6] < pos[0][5]);

    const char *pictures[2] = {"chart.png", "chart.svg"};
    for (int i = 0; i < 2; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, pictures[i]);
        char *text = test_read_file(path);
        CHECK(text != NULL);
        if (i == 0)
            CHECK(!memcmp(text, "\x89PNG", 4));
        else
            CHECK_CONTAINS(text, "<svg");
        free(text);
    }
}

/* A peer's frame of `scene` at `tol` px against the reference `ref`. */
static int peer_accuracy(sc_context_id ctx, sc_scene_id scene, sc_peer_kind kind, double tol,
                         const sc_camera_desc *cam, sc_frame_id ref, sc_comparison *out,
                         sc_peer_info *info)
{
    sc_error err = {0};
    sc_peer_id peer;
    sc_frame_id frame = {0};
    sc_peer_desc desc = {.kind = kind, .tolerance_px = tol};
    int status = sc_make_peer(ctx, scene, &desc, &peer, &err);
    if (status == SC_OK)
        status = sc_update_peer(peer, cam, &err);
    if (status == SC_OK)
        status = sc_draw_peer(peer, cam, &err);
    if (status == SC_OK)
        status = sc_read_peer_frame(peer, &frame, &err);
    if (status == SC_OK)
        status = sc_compare_frames(ref, frame, out, &err);
    if (status == SC_OK)
        status = sc_query_peer_info(peer, info, &err);
    if (status != SC_OK)
        fprintf(stderr, "  %s\n", err.message);
    sc_destroy_frame(frame);
    sc_destroy_peer(peer);
    return status;
}

TEST(chart_peers_against_reference)
{
    sc_error err = {0};
    sc_context_id ctx;
    CHECK_INT(sc_make_context(NULL, &ctx, &err), SC_OK);
    sc_camera_desc cam = {.width = 96, .height = 96};
    sc_comparison coarse, fine;
    sc_peer_info info;

    /* A patch with a circular hole and no outer loop, and nested loops:
     * GLU must keep what the reference keeps. */
    const char *trimmed[2] = {"examples/scenes/trim_hole.obj", "examples/scenes/trim_nested.obj"};
    for (int i = 0; i < 2; i++) {
        sc_scene_id scene;
        sc_frame_id ref;
        CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = test_root(trimmed[i])}, &scene, &err),
                  SC_OK);
        CHECK_INT(sc_render_reference(scene, &cam, NULL, &ref, &err), SC_OK);
        CHECK_INT(peer_accuracy(ctx, scene, SC_PEER_GLU, 0.1, &cam, ref, &fine, &info), SC_OK);
        CHECK_INT(info.tessellator_errors, 0);
        CHECK(info.triangles > 0);
        /* Edge pixels of the trims may go either way; nothing more. */
        CHECK(fine.fail_pct < 3);
        CHECK(fine.pos_p99_px < 0.5);
        /* The shaders leave trimmed surfaces out. */
        CHECK_INT(peer_accuracy(ctx, scene, SC_PEER_TESS_SHADER, 0.5, &cam, ref, &coarse, &info),
                  SC_OK);
        CHECK_INT(info.skipped_surfaces, 1);
        sc_destroy_frame(ref);
        sc_destroy_scene(scene);
    }

    sc_scene_id teapot;
    sc_frame_id ref;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = TEST_TEAPOT32}, &teapot, &err), SC_OK);
    CHECK_INT(sc_render_reference(teapot, &cam, NULL, &ref, &err), SC_OK);
    long coarse_triangles = 0;
    for (int kind = 0; kind < 2; kind++) {
        sc_peer_kind k = kind ? SC_PEER_TESS_SHADER : SC_PEER_GLU;
        CHECK_INT(peer_accuracy(ctx, teapot, k, 1, &cam, ref, &coarse, &info), SC_OK);
        coarse_triangles = info.triangles;
        CHECK_INT(peer_accuracy(ctx, teapot, k, 0.1, &cam, ref, &fine, &info), SC_OK);
        CHECK_INT(info.skipped_surfaces, 0);
        CHECK(info.triangles > coarse_triangles);
        CHECK(fine.pos_p99_px < coarse.pos_p99_px);
        CHECK(fine.fail_pct < 1);
        /* The tolerance bounds the chordal error; p99 of the position
         * error stays within a small multiple of it. */
        CHECK(fine.pos_p99_px < 0.5);
    }
    sc_destroy_frame(ref);
    sc_destroy_scene(teapot);
    sc_destroy_context(ctx);
}
