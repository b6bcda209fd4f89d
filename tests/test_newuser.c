/* test_newuser.c — what a new user meets first: `gen --like` using every
 * field of its key, errors worded the same by `ref` and `render`, image
 * names, size limits, scenes with nothing to draw, `convert` leaving
 * nothing half-written, `--version`, progress of `render --ref`, AOV files
 * only when asked for, and a demo that does not flood the terminal. */
#include <stdlib.h>
#include <sys/stat.h>

#include "test.h"

#include "splinecast.h"

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* A key's fields, split at '-' (the key texts have no other dashes). */
static int key_field(const char *key, int index, char *out, size_t size)
{
    const char *p = key;
    for (int i = 0; i < index; i++) {
        p = strchr(p, '-');
        if (!p)
            return 0;
        p++;
    }
    size_t n = strcspn(p, "-");
    snprintf(out, size, "%.*s", (int)n, p);
    return 1;
}

/* Every field of --like's key is used except those the surface decides:
 * bern (Bézier kinds), the trim method and its cap (trimmed surfaces),
 * method, start, iterations, tolerance, ert and outputs. The surface keeps
 * its kind, degrees, rationality and trim-curve degree. */
TEST(newuser_gen_like_uses_every_field)
{
    const char *like = "bez3x3-poly-bern-clip1i8-bclip-mid-it7-tol0.1-ert0-out.shade.aov";
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = test_root("examples/scenes/trim_star.obj")},
                            &scene, &err), SC_OK);
    sc_key plain, with_like;
    CHECK_INT(sc_query_surface_key(scene, 0, NULL, &plain, &err), SC_OK);
    CHECK_INT(sc_query_surface_key(scene, 0, &(sc_keys_desc){.like = like}, &with_like, &err),
              SC_OK);
    char a[64], b[64], c[64];
    /* Kind and degrees, rationality: the surface's. */
    for (int f = 0; f < 2; f++) {
        CHECK(key_field(plain.text, f, a, sizeof a) && key_field(with_like.text, f, b, sizeof b));
        CHECK_STR(b, a);
    }
    /* Evaluation form, method … outputs: like's. */
    for (int f = 2; f < 10; f++) {
        if (f == 3)
            continue;
        CHECK(key_field(like, f, a, sizeof a) && key_field(with_like.text, f, b, sizeof b));
        CHECK_STR(b, a);
    }
    /* Trim: like's method and cap, the surface's curve degree. */
    CHECK(key_field(plain.text, 3, a, sizeof a) && key_field(with_like.text, 3, b, sizeof b));
    int deg_plain = 0, deg_like = 0, cap = 0;
    char method[16];
    CHECK(sscanf(a, "%*[a-z]%di%*d", &deg_plain) == 1);
    CHECK(sscanf(b, "%15[a-z]%di%d", method, &deg_like, &cap) == 3);
    CHECK_STR(method, "clip");
    CHECK_INT(deg_like, deg_plain);
    CHECK_INT(cap, 8);
    /* An untrimmed like leaves a trimmed surface trimmed. */
    CHECK_INT(sc_query_surface_key(scene, 0, &(sc_keys_desc){.like = "bez3x3-poly-bern-trim0-"
                                   "newton-cp-it6-tol0.05-ert1-out.shade"}, &with_like, &err), SC_OK);
    CHECK(key_field(with_like.text, 3, c, sizeof c));
    CHECK_STR(c, a);

    /* A field that cannot apply is an error naming it: bern with whole
     * NURBS surfaces. */
    CHECK_INT(sc_query_scene_keys(scene, &(sc_keys_desc){.like = like, .nurbs_direct = 1}, NULL, 0,
                                  &(int){0}, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "'bern' cannot apply");
    CHECK_STR(err.key, like);
    sc_destroy_scene(scene);

    /* The command line writes the key with like's fields. */
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s gen --scene teapot --like %s -o %s/like_gen", test_cli, like,
             test_tmpdir());
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    char path[1024];
    snprintf(path, sizeof path,
             "%s/like_gen/bez3x3-poly-bern-trim0-bclip-mid-it7-tol0.1-ert0-out.shade.aov.frag",
             test_tmpdir());
    CHECK(exists(path));
    sc_shutdown();
}

/* `diff --help` says what an empty reference scores, as the code does. */
TEST(newuser_diff_help_empty_reference)
{
    char cmd[1024], *out = NULL;
    snprintf(cmd, sizeof cmd, "%s diff --help", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "inf if TEST hits anything");
    CHECK(strstr(out, "scores 100") == NULL);
    free(out);
}

/* The stderr of one command line, with "splinecast NAME" replaced by
 * "splinecast CMD", so that two commands' messages compare. */
static char *run_err(const char *args, const char *name, int *status)
{
    char cmd[2048], *err = NULL;
    snprintf(cmd, sizeof cmd, "%s %s %s", test_cli, name, args);
    *status = test_run(cmd, NULL, &err);
    if (!err)
        return NULL;
    char pattern[64];
    snprintf(pattern, sizeof pattern, "splinecast %s", name);
    for (char *p = strstr(err, pattern); p; p = strstr(p, pattern)) {
        memmove(p + strlen("splinecast CMD"), p + strlen(pattern), strlen(p + strlen(pattern)) + 1);
        memcpy(p, "splinecast CMD", strlen("splinecast CMD"));
        p += strlen("splinecast CMD");
    }
    return err;
}

/* `ref` and `render` share their view options: the same mistake gives the
 * same message and status from both, the size limit is stated, and a name
 * that is not .png writes nothing. */
TEST(newuser_ref_and_render_word_errors_alike)
{
    char args[8][512];
    const char *dir = test_tmpdir();
    snprintf(args[0], sizeof args[0], "teapot -o %s/alike.png --size 20000x10", dir);
    snprintf(args[1], sizeof args[1], "teapot -o %s/alike.png --size big", dir);
    snprintf(args[2], sizeof args[2], "teapot -o %s/alike.png --camera 1,2,3", dir);
    snprintf(args[3], sizeof args[3], "teapot -o %s/alike.txt", dir);
    snprintf(args[4], sizeof args[4], "teapot");
    snprintf(args[5], sizeof args[5], "teapot -o %s/alike.png --frobnicate", dir);
    snprintf(args[6], sizeof args[6], "teapot -o %s/alike.png --up 0,0,0", dir);
    snprintf(args[7], sizeof args[7], "teapot -o %s/alike.png --view-from +w", dir);
    for (int i = 0; i < 8; i++) {
        int s_ref, s_render;
        char *e_ref = run_err(args[i], "ref", &s_ref);
        char *e_render = run_err(args[i], "render", &s_render);
        if (s_ref != 2 || s_render != 2 || !e_ref || !e_render || strcmp(e_ref, e_render))
            fprintf(stderr, "  for %s:\n  ref (%d): %s  render (%d): %s", args[i], s_ref,
                    e_ref ? e_ref : "", s_render, e_render ? e_render : "");
        CHECK_INT(s_ref, 2);
        CHECK_INT(s_render, 2);
        CHECK(e_ref && e_render);
        CHECK_STR(e_ref, e_render);
        if (i == 0)
            CHECK_CONTAINS(e_ref, "from 1 to 16384");
        if (i == 3)
            CHECK_CONTAINS(e_ref, "must end in .png, not");
        free(e_ref);
        free(e_render);
    }
    /* terrain writes a PNG too. */
    char cmd[2048], *err = NULL;
    snprintf(cmd, sizeof cmd, "%s terrain --franke 100 -o %s/alike.txt", test_cli, dir);
    CHECK_INT(test_run(cmd, NULL, &err), 2);
    CHECK_CONTAINS(err, "must end in .png, not");
    free(err);
    char path[1024];
    snprintf(path, sizeof path, "%s/alike.txt", dir);
    CHECK(!exists(path));
    snprintf(path, sizeof path, "%s/alike.png", dir);
    CHECK(!exists(path));
}

/* A scene without a surface: a message naming the file, exit 1, no image. */
TEST(newuser_nothing_to_draw)
{
    const char *scene = test_write_tmp("only_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const char *cmds[] = {"ref", "render"};
    for (int c = 0; c < 2; c++) {
        char cmd[2048], *err = NULL, path[1024];
        snprintf(path, sizeof path, "%s/nothing_%s.png", test_tmpdir(), cmds[c]);
        snprintf(cmd, sizeof cmd, "%s %s %s -o %s --size 16x16", test_cli, cmds[c], scene, path);
        CHECK_INT(test_run(cmd, NULL, &err), 1);
        CHECK_CONTAINS(err, "only_faces.obj: nothing to draw");
        free(err);
        CHECK(!exists(path));
    }
}

/* A convert that cannot put its .obj in place leaves no .mtl behind. */
TEST(newuser_failed_convert_leaves_nothing)
{
    char dir[1024], cmd[2048], mtl[1024];
    snprintf(dir, sizeof dir, "%s/folder.obj", test_tmpdir());
    mkdir(dir, 0755);
    snprintf(cmd, sizeof cmd, "%s convert teapot -o %s", test_cli, dir);
    char *err = NULL;
    CHECK_INT(test_run(cmd, NULL, &err), 1);
    CHECK_CONTAINS(err, "folder.obj");
    free(err);
    snprintf(mtl, sizeof mtl, "%s/folder.mtl", test_tmpdir());
    CHECK(!exists(mtl));
}

TEST(newuser_version)
{
    char cmd[1024], *out = NULL, want[64];
    snprintf(cmd, sizeof cmd, "%s --version", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    snprintf(want, sizeof want, "splinecast %s\n", SPLINECAST_VERSION);
    CHECK_STR(out, want);
    free(out);
}

/* `render` writes the AOV file only with --aov; with --ref it says how the
 * reference goes on stderr; and the AOV it writes compares with `ref`'s
 * of the same view. */
TEST(newuser_render_aov_only_when_asked)
{
    const char *dir = test_tmpdir();
    char cmd[2048], *out = NULL, *err = NULL, path[1024];
    snprintf(cmd, sizeof cmd, "%s render teapot -o %s/plain.png --size 40x32 --frames 1 --ref",
             test_cli, dir);
    int status = test_run(cmd, &out, &err);
    if (status == 1 && err && strstr(err, "OSMesa")) {
        free(out);
        free(err);
        SKIP("no GL context");
    }
    CHECK_INT(status, 0);
    CHECK_CONTAINS(err, "render: reference 100%");
    CHECK_CONTAINS(out, "accuracy coverage_pct=");
    free(out);
    free(err);
    snprintf(path, sizeof path, "%s/plain.aov", dir);
    CHECK(!exists(path));
    snprintf(cmd, sizeof cmd, "(%s render teapot -o %s/plain.png --size 40x32 --frames 1 "
             "--aov %s/asked.aov && %s ref teapot -o %s/asked_ref.png --size 40x32 && "
             "%s diff %s/asked_ref.aov %s/asked.aov)", test_cli, dir, dir, test_cli, dir, test_cli,
             dir, dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "accuracy coverage_pct=");
    free(out);
}

/* The demo shows info's summary, not a line per surface (run small:
 * DEMO_SIZE). */
TEST(newuser_demo_is_quiet)
{
    char cmd[2048], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "DEMO_SIZE=48x48 sh %s %s %s/demo 2>&1", test_root("examples/demo.sh"), test_cli,
             test_tmpdir());
    int status = test_run(cmd, &out, &err);
    if (status != 0 && out && strstr(out, "OSMesa")) {
        free(out);
        free(err);
        SKIP("no GL context");
    }
    CHECK_INT(status, 0);
    CHECK_CONTAINS(out, "surfaces 32\n");
    CHECK(strstr(out, "\nsurface 0 ") == NULL);
    free(out);
    free(err);
}

/* `audit --compare --match`: two audits of one scene under different
 * methods pair shader for shader once the method (and what goes with it)
 * is left out; without --match nothing pairs; an ambiguous pairing and an
 * unknown field are refused by name. */
TEST(newuser_audit_compare_match)
{
    const char *dir = test_tmpdir();
    char cmd[4096], *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd,
             "(%s audit --family 3..3 --like bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert1-"
             "out.shade.aov > %s/a_newton.txt && %s audit --family 3..3 --like bez3x3-poly-dc-"
             "trim0-bclip-mid-it32-tol0.05-ert1-out.shade.aov > %s/a_bclip.txt)", test_cli, dir,
             test_cli, dir);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    snprintf(cmd, sizeof cmd, "%s audit --compare %s/a_newton.txt %s/a_bclip.txt", test_cli, dir,
             dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "of 0 shaders in both");
    free(out);
    snprintf(cmd, sizeof cmd, "%s audit --compare %s/a_newton.txt %s/a_bclip.txt "
             "--match method,start,iters", test_cli, dir, dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    /* The 2 fragment programs (3x3, poly and rat) pair; the two vertex
     * programs (cp and mid) have different names. */
    CHECK_CONTAINS(out, "of 2 shaders in both");
    CHECK_CONTAINS(out, "(was bez3x3-rat-dc-trim0-newton-cp-it6-tol0.05-ert1-out.shade.aov)");
    free(out);
    snprintf(cmd, sizeof cmd, "%s audit --compare %s/a_newton.txt %s/a_bclip.txt "
             "--match method,start,iters,rational", test_cli, dir, dir);
    CHECK_INT(test_run(cmd, NULL, &err), 1);
    CHECK_CONTAINS(err, "both match");
    free(err);
    snprintf(cmd, sizeof cmd, "%s audit --compare %s/a_newton.txt %s/a_bclip.txt --match colour",
             test_cli, dir, dir);
    CHECK_INT(test_run(cmd, NULL, &err), 1);
    CHECK_CONTAINS(err, "unknown key field 'colour'");
    free(err);
}

/* Every debug view shows misses in the shaded view's background grey and
 * carries a legend strip (white text on a dark strip along the bottom);
 * the shaded view is left as it is. */
TEST(newuser_debug_views_background_and_legend)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_destroy_scene(scene);
        SKIP("no GL context: %s", err.message);
    }
    static const sc_show views[] = {SC_SHOW_SHADE, SC_SHOW_UV, SC_SHOW_ITERS, SC_SHOW_NORMAL,
                                    SC_SHOW_DEPTH, SC_SHOW_HULL};
    enum { W = 128, H = 96 };
    for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
        sc_renderer_id r;
        sc_frame_id frame;
        sc_frame_info info;
        CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.show = views[v]}, &r, &err),
                  SC_OK);
        CHECK_INT(sc_render(r, &(sc_camera_desc){.width = W, .height = H}, &frame, &err), SC_OK);
        CHECK_INT(sc_query_frame_info(frame, &info, &err), SC_OK);
        /* The top left corner is a miss in the default view: background. */
        CHECK_INT(info.surface[0], -1);
        for (int c = 0; c < 3; c++)
            CHECK_INT(info.rgba[c], 51);
        CHECK_INT(info.rgba[3], 255);
        int misses = 0, grey = 0, strip = 0, text = 0;
        for (int p = 0; p < W * (H - 14); p++)
            if (info.surface[p] < 0) {
                misses++;
                grey += info.rgba[4 * p] == 51 && info.rgba[4 * p + 1] == 51 &&
                        info.rgba[4 * p + 2] == 51;
            }
        for (int p = W * (H - 14); p < W * H; p++) {
            strip += info.rgba[4 * p] == 20;
            text += info.rgba[4 * p] == 230;
        }
        if (views[v] == SC_SHOW_HULL) {
            CHECK(grey > 0);  /* the proxies cover some misses */
        } else {
            CHECK_INT(grey, misses);
        }
        if (views[v] == SC_SHOW_SHADE) {
            CHECK_INT(text, 0);
        } else {
            CHECK(strip > W * 14 / 2);
            CHECK(text > 20);
        }
        sc_destroy_frame(frame);
        sc_destroy_renderer(r);
    }
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    sc_shutdown();
}
