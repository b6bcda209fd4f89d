/* test_install.c — the public interface: `make install` into a staging
 * tree, the example program built against the installed copy with
 * pkg-config and run on the teapot, and the calls of splinecast.h checked
 * against known values (the teapot's patches, the documented default key,
 * the register bound of Pabst et al., the CPU reference). */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <EGL/egl.h>
#include <GL/glcorearb.h>

#include "camera.h"
#include "hulls.h"
#include "image.h"
#include "io.h"
#include "refcast.h"
#include "splinecast.h"

/* Flags a program linked into this test binary's sanitizers needs. */
#if defined(__SANITIZE_ADDRESS__)
static const char sanitizer_flags[] = "-fsanitize=address,undefined";
#else
static const char sanitizer_flags[] = "";
#endif

/* The build folder the test binary belongs to: SC_BUILD from `make test`,
 * else the folder of the command line under test. */
static const char *build_folder(char *buf, size_t size)
{
    const char *env = getenv("SC_BUILD");
    if (env && env[0])
        return env;
    snprintf(buf, size, "%s", test_cli);
    char *slash = strrchr(buf, '/');
    if (!slash)
        return "build";
    *slash = 0;
    return buf;
}

static int file_size(const char *path, long *size)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return 0;
    *size = (long)st.st_size;
    return 1;
}

/* Pixels of the CPU reference of the default view that hit the scene. */
static long reference_hits(const char *scene_path, int width, int height)
{
    sc_scene scene;
    sc_error err = {0};
    if (sc_read_scene(scene_path, &scene, &err) != SC_OK)
        return -1;
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    cam.width = width;
    cam.height = height;
    sc_refcast *rc;
    sc_aov aov = {0};
    long hits = -1;
    if (sc_refcast_prepare(&scene, &rc, &err) == SC_OK) {
        if (sc_refcast_render(rc, &cam, NULL, &aov, NULL, &err) == SC_OK) {
            hits = 0;
            for (int p = 0; p < width * height; p++)
                hits += aov.surface[p] >= 0;
        }
        sc_refcast_free(rc);
    }
    sc_aov_free(&aov);
    sc_scene_free(&scene);
    return hits;
}

TEST(install_example_against_installed_copy)
{
    char buf[1024], cmd[4096];
    const char *build = build_folder(buf, sizeof buf);
    char dest[512], prefix[600], scene[600], png[600], exe[600];
    snprintf(dest, sizeof dest, "%s/install-stage", test_tmpdir());
    snprintf(prefix, sizeof prefix, "%s/opt/splinecast", dest);
    snprintf(scene, sizeof scene, "%s/examples/scenes/teapot32.bpt", test_root_dir);
    snprintf(png, sizeof png, "%s/install-teapot.png", test_tmpdir());
    snprintf(exe, sizeof exe, "%s/render_scene", test_tmpdir());

    /* The parent make's flags (jobserver, variables) are not this make's,
     * and -o keeps it from rebuilding what the test binary was built with. */
    snprintf(cmd, sizeof cmd,
             "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s -C '%s' install BUILD='%s' "
             "-o '%s/libsplinecast.a' -o '%s/splinecast' PREFIX=/opt/splinecast DESTDIR='%s'",
             test_root_dir, build, build, build, dest);
    char *out = NULL, *errs = NULL;
    int status = test_run(cmd, &out, &errs);
    if (status != 0)
        fprintf(stderr, "  %s\n%s", cmd, errs ? errs : "");
    CHECK_INT(status, 0);
    free(out);
    free(errs);

    long size;
    snprintf(buf, sizeof buf, "%s/lib/libsplinecast.a", prefix);
    CHECK(file_size(buf, &size) && size > 0);
    snprintf(buf, sizeof buf, "%s/bin/splinecast", prefix);
    CHECK(file_size(buf, &size) && size > 0);
    /* The public headers are the only headers installed: splinecast.h and
     * the two headers it includes (the base, the options' enums). */
    snprintf(cmd, sizeof cmd, "ls '%s/include'", prefix);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_STR(out, "splinecast.h\nsplinecast_base.h\nsplinecast_options.h\n");
    free(out);
    /* The .pc names the final prefix, not the staging tree. */
    snprintf(cmd, sizeof cmd, "cat '%s/lib/pkgconfig/splinecast.pc'", prefix);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "prefix=/opt/splinecast\n");
    CHECK(!strstr(out, dest));
    free(out);

    /* Only the installed copy: no -I into the source tree. */
    snprintf(cmd, sizeof cmd,
             "PKG_CONFIG_PATH='%s/lib/pkgconfig' PKG_CONFIG_SYSROOT_DIR='%s' && "
             "export PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR && "
             "cc -std=c11 -pedantic -Wall -Wextra -Werror %s '%s/examples/render_scene.c' "
             "$(pkg-config --cflags --libs splinecast) -o '%s'",
             prefix, dest, sanitizer_flags, test_root_dir, exe);
    status = test_run(cmd, NULL, &errs);
    if (status != 0)
        fprintf(stderr, "  %s\n%s", cmd, errs ? errs : "");
    CHECK_INT(status, 0);
    free(errs);

    snprintf(cmd, sizeof cmd, "'%s' '%s' '%s' 128 128", exe, scene, png);
    status = test_run(cmd, &out, &errs);
    if (status != 0 && errs && strstr(errs, "context"))
        SKIP("no GL context: %s", errs);
    if (status != 0)
        fprintf(stderr, "  %s\n%s", cmd, errs ? errs : "");
    CHECK_INT(status, 0);
    /* The teapot is 32 bicubic polynomial Bézier patches, untrimmed: one key. */
    CHECK(!strncmp(out, "renderer programs=1 ", 20));
    char *program = strstr(out, "\nprogram ");
    CHECK(program != NULL);
    CHECK(!strncmp(program, "\nprogram bez3x3-poly-", 21));
    CHECK_CONTAINS(program, "-trim0-");
    CHECK(!strstr(program + 1, "\nprogram "));
    char *wrote = strstr(out, "wrote ");
    CHECK(wrote != NULL);
    long covered = -1;
    char *cov = strstr(wrote, "128x128 covered=");
    CHECK(cov != NULL);
    covered = strtol(cov + strlen("128x128 covered="), NULL, 10);
    free(out);
    free(errs);

    sc_image img = {0};
    sc_error err = {0};
    CHECK_INT(sc_png_read(png, &img, &err), SC_OK);
    CHECK_INT(img.width, 128);
    CHECK_INT(img.height, 128);
    /* Background: sRGB 0.2 grey (shade.h). */
    long lit = 0;
    for (int p = 0; p < 128 * 128; p++) {
        const unsigned char *px = img.pixels + (size_t)img.channels * (size_t)p;
        lit += abs(px[0] - 51) > 2 || abs(px[1] - 51) > 2 || abs(px[2] - 51) > 2;
    }
    sc_image_free(&img);
    long ref = reference_hits(scene, 128, 128);
    CHECK(ref > 128 * 128 / 10);
    /* Hits agree with the reference; a shaded pixel may happen to match the
     * background grey, never the other way round. */
    CHECK(labs(covered - ref) <= ref / 100);
    CHECK(lit <= covered && lit >= covered - covered / 50);
}

TEST(install_header_compiles_as_cxx)
{
    char cmd[1024];
    if (test_run("c++ --version", NULL, NULL) != 0)
        SKIP("no C++ compiler");
    snprintf(cmd, sizeof cmd,
             "printf '#include \"splinecast.h\"\\nint main() { sc_scene_id s = {0}; "
             "sc_destroy_scene(s); return SC_OK; }\\n' | "
             "c++ -std=c++11 -Wall -Wextra -Werror -fsyntax-only -I'%s/runtime' -x c++ -",
             test_root_dir);
    char *errs = NULL;
    int status = test_run(cmd, NULL, &errs);
    if (status != 0)
        fprintf(stderr, "%s", errs ? errs : "");
    free(errs);
    CHECK_INT(status, 0);
}

TEST(install_api_scene_handles)
{
    sc_error err = {0};
    sc_scene_id teapot, patch;
    CHECK_INT(sc_make_scene(NULL, &teapot, &err), SC_OK);
    CHECK(teapot.id != 0);
    sc_scene_info info;
    CHECK_INT(sc_query_scene_info(teapot, &info, &err), SC_OK);
    CHECK_INT(info.surfaces, 32);
    CHECK_INT(info.max_degree, 3);
    CHECK_INT(info.rational_surfaces, 0);
    CHECK_INT(info.trimmed_surfaces, 0);

    /* One bilinear patch from memory: the unit square in z = 0. */
    static const char bpt[] = "1\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n";
    sc_scene_desc desc = {.text = bpt, .size = sizeof bpt - 1, .name = "square.bpt"};
    CHECK_INT(sc_make_scene(&desc, &patch, &err), SC_OK);
    CHECK(patch.id != teapot.id);
    CHECK_INT(sc_query_scene_info(patch, &info, &err), SC_OK);
    CHECK_INT(info.surfaces, 1);
    CHECK_INT(info.max_degree, 1);
    CHECK_NEAR(info.lo[0], 0, 0);
    CHECK_NEAR(info.hi[0], 1, 0);
    CHECK_NEAR(info.hi[1], 1, 0);
    CHECK_NEAR(info.hi[2], 0, 0);

    /* A destroyed handle stays invalid, even when its slot is reused. */
    sc_destroy_scene(patch);
    CHECK_INT(sc_query_scene_info(patch, &info, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "scene handle names an object that was destroyed");
    sc_scene_id again;
    CHECK_INT(sc_make_scene(&desc, &again, &err), SC_OK);
    CHECK(again.id != patch.id);
    CHECK_INT(sc_query_scene_info(patch, &info, &err), SC_FAIL);
    CHECK_INT(sc_query_scene_info((sc_scene_id){0}, &info, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "zero handle");
    sc_destroy_scene((sc_scene_id){0});  /* harmless */
    /* Handles never given: a slot not used yet, a generation not reached. */
    CHECK_INT(sc_query_scene_info((sc_scene_id){1u << 16 | 999}, &info, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "scene handle names no object ever made: 0x000103e7");
    CHECK_INT(sc_query_scene_info((sc_scene_id){((patch.id >> 16) + 5) << 16 | (patch.id & 0xffff)},
                                  &info, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "names no object ever made");
    sc_program_id never;
    /* A generation no context reaches, whatever tests ran before. */
    CHECK_INT(sc_make_program((sc_context_id){0x7ffeu << 16 | 1}, "bez3x3", &never, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.message, "context handle names no object ever made");

    /* Bad descs and bad input. */
    sc_scene_id bad = {7};
    sc_scene_desc both = {.path = "teapot", .text = bpt, .size = 4};
    CHECK_INT(sc_make_scene(&both, &bad, &err), SC_FAIL);
    CHECK_INT(bad.id, 0);
    CHECK_CONTAINS(err.message, "sc_scene_desc gives both path and text");
    sc_scene_desc unnamed = {.text = bpt, .size = sizeof bpt - 1, .name = "square.txt"};
    CHECK_INT(sc_make_scene(&unnamed, &bad, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "extension");
    static const char broken[] = "1\n3 3\n0 0 0\n";
    sc_scene_desc truncated = {.text = broken, .size = sizeof broken - 1, .name = "cut.bpt"};
    CHECK_INT(sc_make_scene(&truncated, &bad, &err), SC_FAIL);
    CHECK_STR(err.file, "cut.bpt");
    CHECK(err.line > 0);

    /* Views that cannot be rendered, and a missing AOV file. */
    sc_frame_id frame;
    sc_camera_desc same = {.eye = {1, 1, 1}, .target = {1, 1, 1}, .width = 8, .height = 8};
    CHECK_INT(sc_render_reference(teapot, &same, NULL, &frame, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_camera_desc is not a usable view");
    sc_camera_desc wide = {.fovy_deg = 180, .width = 8, .height = 8};
    CHECK_INT(sc_render_reference(teapot, &wide, NULL, &frame, &err), SC_FAIL);
    sc_camera_desc text = {.text = "1,2,3", .width = 8, .height = 8};
    CHECK_INT(sc_render_reference(teapot, &text, NULL, &frame, &err), SC_FAIL);
    char msg[1024];
    CHECK_INT(sc_load_frame("/nonexistent/frame.aov", &frame, &err), SC_FAIL);
    CHECK_CONTAINS(sc_error_text(&err, msg, sizeof msg), "/nonexistent/frame.aov");
    CHECK_INT(frame.id, 0);

    sc_shutdown();
    CHECK_INT(sc_query_scene_info(teapot, &info, &err), SC_FAIL);
}

TEST(install_api_keys_and_glsl)
{
    sc_error err = {0};
    sc_scene_id teapot;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = "teapot"}, &teapot, &err), SC_OK);
    int count = -1;
    CHECK_INT(sc_query_scene_keys(teapot, NULL, NULL, 0, &count, &err), SC_OK);
    CHECK_INT(count, 1);
    /* The documented default key (key.h, docs/variant-key.md) for bicubic
     * polynomial patches. */
    sc_key keys[4];
    CHECK_INT(sc_query_scene_keys(teapot, NULL, keys, 4, &count, &err), SC_OK);
    CHECK_STR(keys[0].text, "bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    sc_keys_desc desc = {.max_iters = 8, .tolerance_px = 0.5, .start = SC_START_CPMAP,
                         .outputs = SC_OUTPUT_SHADE | SC_OUTPUT_AOV,
                         .termination = SC_TERMINATION_NONE};
    CHECK_INT(sc_query_scene_keys(teapot, &desc, keys, 4, &count, &err), SC_OK);
    CHECK_STR(keys[0].text, "bez3x3-poly-pow-trim0-hybrid-cp-it8-tol0.5-ert0-out.shade.aov");
    desc.max_iters = 1000;
    CHECK_INT(sc_query_scene_keys(teapot, &desc, keys, 4, &count, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_keys_desc.max_iters is out of range: 1000");

    sc_glsl glsl;
    CHECK_INT(sc_generate_glsl(&(sc_glsl_desc){.key = keys[0].text, .audit = 1}, &glsl, &err),
              SC_OK);
    CHECK_STR(glsl.key, keys[0].text);
    CHECK(!strncmp(glsl.fragment, "#version 450", 12) || strstr(glsl.fragment, "\n#version 450"));
    CHECK_CONTAINS(glsl.fragment, keys[0].text);
    CHECK_INT(strlen(glsl.fragment), glsl.fragment_size);
    CHECK_INT(glsl.fragment_audit.bytes, glsl.fragment_size);
    /* Pabst et al. 4.2: M + 2N registers for orders M = N = 4. */
    CHECK_INT(glsl.fragment_audit.register_bound, 12);
    CHECK(glsl.fragment_audit.spirv_inst > 0 && glsl.vertex_audit.spirv_inst > 0);
    char prefix[200];
    snprintf(prefix, sizeof prefix, "%s - FS: ", keys[0].text);
    CHECK(!strncmp(glsl.fragment_audit.line, prefix, strlen(prefix)));
    CHECK_CONTAINS(glsl.vertex_audit.line, " - VS: ");
    sc_free_glsl(&glsl);
    CHECK(glsl.fragment == NULL);

    static const char bclip[] = "nurbs3x3-poly-dc-trim0-bclip-mid-it4-tol0.25-ert0-out.shade";
    CHECK_INT(sc_check_key(bclip, &err), SC_FAIL);
    CHECK_STR(err.key, bclip);
    CHECK_INT(sc_generate_glsl(&(sc_glsl_desc){.key = "bez3x3-nonsense"}, &glsl, &err),
              SC_FAIL);
    CHECK_STR(err.key, "bez3x3-nonsense");
    CHECK(glsl.fragment == NULL);
    sc_shutdown();
}

/* Counts the programs the library generates (one INFO line each). */
static void count_generated(sc_log_level level, const char *message, void *user)
{
    (void)level;
    if (strstr(message, ": generated in "))
        ++*(int *)user;
}

/* The default scene (the teapot) and a GL context through the public
 * calls: 1; 0 after sc_shutdown where no context can be made (the caller
 * skips); -1 where the scene cannot be made. */
static int open_teapot(sc_scene_id *scene, sc_context_id *ctx, sc_error *err)
{
    if (sc_make_scene(NULL, scene, err) != SC_OK)
        return -1;
    if (sc_make_context(NULL, ctx, err) != SC_OK) {
        sc_shutdown();
        return 0;
    }
    return 1;
}

/* A renderer made through the API takes its programs from the context's
 * cache: its keys, asked of the specialization API, are cache hits that
 * name the GL programs it draws with, and each is generated once. */
TEST(install_api_renderer_shares_programs)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    int opened = open_teapot(&scene, &ctx, &err);
    CHECK(opened >= 0);
    if (!opened)
        SKIP("no GL context: %s", err.message);
    int generated = 0;
    sc_set_logger(count_generated, &generated);
    sc_renderer_id renderer;
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.termination =
                                                                  SC_TERMINATION_NONE},
                               &renderer, &err), SC_OK);
    CHECK_INT(generated, 1);
    sc_key key;
    int count;
    CHECK_INT(sc_query_renderer_keys(renderer, &key, 1, &count, &err), SC_OK);
    CHECK_INT(count, 1);
    sc_program_id program;
    sc_program_info pinfo;
    CHECK_INT(sc_make_program(ctx, key.text, &program, &err), SC_OK);
    CHECK_INT(sc_query_program_info(program, &pinfo, &err), SC_OK);
    sc_set_logger(NULL, NULL);
    CHECK_INT(generated, 1);
    sc_renderer_info rinfo;
    CHECK_INT(sc_query_renderer_info(renderer, &rinfo, &err), SC_OK);
    CHECK_INT(rinfo.programs, 1);

    /* The program the frame was drawn with, seen through GL itself (on
     * EGL, whose entry points serve whichever context is current): the
     * drawing key's (sc_draw writes no AOVs). */
    CHECK_INT(sc_draw(renderer, &(sc_camera_desc){.width = 32, .height = 32}, &err), SC_OK);
    sc_context_info cinfo;
    CHECK_INT(sc_query_context_info(ctx, &cinfo, &err), SC_OK);
    if (cinfo.backend == SC_BACKEND_EGL) {
        PFNGLGETINTEGERVPROC get_integer =
            (PFNGLGETINTEGERVPROC)eglGetProcAddress("glGetIntegerv");
        CHECK(get_integer != NULL);
        GLint current = 0;
        get_integer(GL_CURRENT_PROGRAM, &current);
        CHECK_INT((uint32_t)current, pinfo.gl_program);
    }
    sc_shutdown();
}

TEST(install_api_render_against_reference)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    int opened = open_teapot(&scene, &ctx, &err);
    CHECK(opened >= 0);
    if (!opened)
        SKIP("no GL context: %s", err.message);
    sc_renderer_id renderer;
    sc_renderer_desc bad = {.max_iters = 65};
    CHECK_INT(sc_make_renderer(ctx, scene, &bad, &renderer, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_renderer_desc.max_iters is out of range: 65");
    bad = (sc_renderer_desc){.eval = (sc_eval)(SC_EVAL_POW + 1)};
    CHECK_INT(sc_make_renderer(ctx, scene, &bad, &renderer, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_renderer_desc.eval");
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &renderer, &err), SC_OK);

    /* The renderer's key, asked of the specialization API twice: one
     * program, the same handle. */
    sc_key key;
    int count;
    CHECK_INT(sc_query_renderer_keys(renderer, &key, 1, &count, &err), SC_OK);
    CHECK_INT(count, 1);
    sc_program_id p1, p2;
    CHECK_INT(sc_make_program(ctx, key.text, &p1, &err), SC_OK);
    CHECK_INT(sc_make_program(ctx, key.text, &p2, &err), SC_OK);
    CHECK_INT(p1.id, p2.id);
    sc_program_info pinfo;
    CHECK_INT(sc_query_program_info(p1, &pinfo, &err), SC_OK);
    CHECK_STR(pinfo.key, key.text);
    CHECK(pinfo.gl_program != 0);

    sc_camera_desc camera = {.width = 128, .height = 96};
    sc_frame_id gpu, ref;
    CHECK_INT(sc_render(renderer, &camera, &gpu, &err), SC_OK);
    CHECK_INT(sc_render_reference(scene, &camera, NULL, &ref, &err), SC_OK);
    sc_frame_info info;
    CHECK_INT(sc_query_frame_info(gpu, &info, &err), SC_OK);
    CHECK_INT(info.width, 128);
    CHECK_INT(info.height, 96);
    CHECK(info.rgba && info.surface && info.iters);
    CHECK_INT(sc_query_frame_info(ref, &info, &err), SC_OK);
    CHECK(info.iters == NULL);

    sc_comparison cmp;
    CHECK_INT(sc_compare_frames(ref, gpu, &cmp, &err), SC_OK);
    if (!(cmp.fail_pct <= 0.5 && cmp.pos_median_px < 0.1 && cmp.normal_mean_deg < 0.5))
        fprintf(stderr, "  %s\n", cmp.line);
    CHECK(cmp.reference_hits > 128 * 96 / 10);
    /* The renderer's own tests hold it to tighter figures; here the frames
     * only have to be the same view of the same scene. */
    CHECK(cmp.fail_pct <= 0.5);
    CHECK(cmp.pos_median_px < 0.1);
    CHECK(cmp.normal_mean_deg < 0.5);
    CHECK(!strncmp(cmp.line, "accuracy coverage_pct=", 22));

    /* Frames of different views cannot be compared. */
    sc_frame_id small;
    CHECK_INT(sc_render(renderer, &(sc_camera_desc){.width = 32, .height = 32}, &small, &err),
              SC_OK);
    CHECK_INT(sc_compare_frames(ref, small, &cmp, &err), SC_FAIL);

    /* An AOV file round trip gives the same pixels. */
    char path[600];
    snprintf(path, sizeof path, "%s/install-api.aov", test_tmpdir());
    CHECK_INT(sc_save_aov(gpu, path, &err), SC_OK);
    sc_frame_id loaded;
    CHECK_INT(sc_load_frame(path, &loaded, &err), SC_OK);
    CHECK_INT(sc_compare_frames(gpu, loaded, &cmp, &err), SC_OK);
    CHECK_INT(cmp.holes + cmp.false_hits + cmp.off, 0);
    CHECK_NEAR(cmp.pos_max_px, 0, 0);

    /* The scene outlives its handle while a renderer draws it; destroying
     * the context takes its renderers and programs along. */
    sc_destroy_scene(scene);
    CHECK_INT(sc_render(renderer, &camera, &small, &err), SC_OK);
    sc_destroy_context(ctx);
    CHECK_INT(sc_render(renderer, &camera, &small, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "renderer handle names an object that was destroyed");
    CHECK_INT(sc_query_program_info(p1, &pinfo, &err), SC_FAIL);
    CHECK_INT(sc_query_frame_info(gpu, &info, &err), SC_OK);
    sc_shutdown();
}

/* Vertices of the hulls of surface s of the teapot after `lift` was added
 * to the z of its control points (the renderer's default hulls). */
static int teapot_hull_vertices(int s, double lift)
{
    sc_scene scene;
    sc_error err = {0};
    if (sc_read_scene("teapot", &scene, &err) != SC_OK)
        return -1;
    sc_surface *surf = &scene.surfaces[s];
    for (int k = 0; k < surf->nu * surf->nv; k++)
        surf->cp[4 * k + 2] += lift * surf->cp[4 * k + 3];
    sc_hulls hulls;
    int n = -1;
    if (sc_hulls_build(&scene, NULL, &hulls, &err) == SC_OK) {
        n = hulls.surfaces[s].vertex_count;
        sc_hulls_free(&hulls);
    }
    sc_scene_free(&scene);
    return n;
}

/* sc_update_surface: a body patch of the teapot lifted by 0.2 through the
 * public calls; the renderer made before draws what a renderer made after
 * draws and what the reference sees, having sent that patch's data and hull
 * vertices alone; bad descs and a change of variant key refused, changing
 * nothing. */
TEST(install_api_update_surface)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    int opened = open_teapot(&scene, &ctx, &err);
    CHECK(opened >= 0);
    if (!opened)
        SKIP("no GL context: %s", err.message);
    sc_renderer_id before, after;
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &before, &err), SC_OK);
    sc_renderer_info made;
    CHECK_INT(sc_query_renderer_info(before, &made, &err), SC_OK);

    sc_surface_info info;
    CHECK_INT(sc_query_surface_info(scene, 4, &info, &err), SC_OK);
    CHECK_INT(info.deg_u, 3);
    CHECK_INT(info.deg_v, 3);
    CHECK_INT(info.nu * info.nv, 16);
    CHECK_INT(info.rational, 0);
    double points[16 * 3], weights[16], lifted[16 * 3];
    CHECK_INT(sc_query_surface_points(scene, 4, points, weights, 16, &err), SC_OK);
    CHECK_NEAR(weights[7], 1, 0);
    for (int k = 0; k < 16 * 3; k++)
        lifted[k] = points[k] + (k % 3 == 2 ? 0.2 : 0);

    /* Nothing to change: a NULL desc is the zero desc. */
    CHECK_INT(sc_update_surface(scene, NULL, &err), SC_OK);
    /* Refused, changing nothing. */
    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 4, .count = 12,
                                                          .points = lifted}, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_surface_desc.count is out of range: 12 (the surface has 4 x 4");
    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 32, .count = 16,
                                                          .points = lifted}, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "surface is out of range: 32 (0 to 31)");
    double bad_weights[16];
    for (int k = 0; k < 16; k++)
        bad_weights[k] = k == 3 ? -1 : 1;
    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 4, .count = 16,
                                                          .weights = bad_weights}, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "sc_surface_desc.weights is out of range: weight 3 is -1");
    bad_weights[3] = 2;  /* valid, but rational: a new key */
    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 4, .count = 16,
                                                          .weights = bad_weights}, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "surface 4 would become rational");
    double now[16 * 3];
    CHECK_INT(sc_query_surface_points(scene, 4, now, NULL, 16, &err), SC_OK);
    CHECK(!memcmp(now, points, sizeof now));

    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 4, .count = 16,
                                                          .points = lifted}, &err), SC_OK);
    CHECK_INT(sc_query_surface_points(scene, 4, now, NULL, 16, &err), SC_OK);
    CHECK_NEAR(now[2], points[2] + 0.2, 1e-12);
    sc_renderer_info updated;
    CHECK_INT(sc_query_renderer_info(before, &updated, &err), SC_OK);
    /* One bicubic patch: 16 points and a record of 4 texels of 16 bytes;
     * a hull vertex is 13 four-byte values. */
    int vertices = teapot_hull_vertices(4, 0.2);
    CHECK(vertices > 0);
    CHECK_INT(updated.uploaded_bytes, 16 * 16 + 4 * 16 + vertices * 13 * 4);
    CHECK(updated.uploaded_bytes * 20 < made.uploaded_bytes);

    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &after, &err), SC_OK);
    sc_camera_desc camera = {.width = 96, .height = 96};
    sc_frame_id old_frame, new_frame, ref;
    CHECK_INT(sc_render(before, &camera, &old_frame, &err), SC_OK);
    CHECK_INT(sc_render(after, &camera, &new_frame, &err), SC_OK);
    CHECK_INT(sc_render_reference(scene, &camera, NULL, &ref, &err), SC_OK);
    sc_comparison cmp;
    CHECK_INT(sc_compare_frames(new_frame, old_frame, &cmp, &err), SC_OK);
    CHECK(cmp.reference_hits > 96 * 96 / 10);
    CHECK_NEAR(cmp.fail_pct, 0, 0);
    CHECK_INT(sc_compare_frames(ref, old_frame, &cmp, &err), SC_OK);
    CHECK_NEAR(cmp.fail_pct, 0, 0);

    /* Without renderers the surface may become rational. */
    sc_destroy_renderer(before);
    sc_destroy_renderer(after);
    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 4, .count = 16,
                                                          .weights = bad_weights}, &err), SC_OK);
    CHECK_INT(sc_query_surface_info(scene, 4, &info, &err), SC_OK);
    CHECK_INT(info.rational, 1);
    sc_shutdown();
}

/* The box the default view frames, which a renderer keeps between frames
 * (a scene of 100,000 patches took 19 ms a frame to find it again), follows
 * sc_update_surface: a body patch lifted above the lid moves the box, and
 * the renderer made before frames and draws as one made after. */
TEST(install_api_update_moves_the_default_view)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    int opened = open_teapot(&scene, &ctx, &err);
    CHECK(opened >= 0);
    if (!opened)
        SKIP("no GL context: %s", err.message);
    sc_renderer_id before, after;
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &before, &err), SC_OK);
    sc_camera_desc camera = {.width = 64, .height = 64};
    sc_frame_id first, old_frame, new_frame;
    CHECK_INT(sc_render(before, &camera, &first, &err), SC_OK);
    sc_renderer_info made;
    CHECK_INT(sc_query_renderer_info(before, &made, &err), SC_OK);

    double points[16 * 3];
    CHECK_INT(sc_query_surface_points(scene, 4, points, NULL, 16, &err), SC_OK);
    for (int k = 2; k < 16 * 3; k += 3)
        points[k] += 3.0;
    CHECK_INT(sc_update_surface(scene, &(sc_surface_desc){.surface = 4, .count = 16,
                                                          .points = points}, &err), SC_OK);
    sc_renderer_info updated, fresh;
    CHECK_INT(sc_query_renderer_info(before, &updated, &err), SC_OK);
    CHECK(updated.hi[2] > made.hi[2] + 1.0);
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &after, &err), SC_OK);
    CHECK_INT(sc_query_renderer_info(after, &fresh, &err), SC_OK);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(updated.lo[c], fresh.lo[c], 0);
        CHECK_NEAR(updated.hi[c], fresh.hi[c], 0);
    }
    CHECK_INT(sc_render(before, &camera, &old_frame, &err), SC_OK);
    CHECK_INT(sc_render(after, &camera, &new_frame, &err), SC_OK);
    sc_comparison cmp;
    CHECK_INT(sc_compare_frames(new_frame, old_frame, &cmp, &err), SC_OK);
    CHECK(cmp.reference_hits > 64 * 64 / 20);
    CHECK_NEAR(cmp.fail_pct, 0, 0);
    CHECK_NEAR(cmp.coverage_pct, 0, 0);
    /* The view moved: the first frame, framed by the old box, has another
     * camera. */
    CHECK_INT(sc_compare_frames(new_frame, first, &cmp, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "the images differ in camera");
    sc_destroy_frame(first);
    sc_destroy_frame(old_frame);
    sc_destroy_frame(new_frame);
    sc_shutdown();
}

/* Whether an object of build folder `build` is up to date for make
 * (`make -q`), given HAVE_OCCT. */
static int object_up_to_date(const char *build, int have_occt)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -q -C '%s' BUILD='%s' HAVE_OCCT=%d "
             "'%s/gen/key.o'",
             test_root_dir, build, have_occt, build);
    return test_run(cmd, NULL, NULL) == 0;
}

/* Objects depend on the flags they were compiled with (Makefile,
 * config.stamp): a build after Open CASCADE was installed (HAVE_OCCT
 * turning 1) recompiles them, and the same flags again leave them be. In a
 * folder of its own, with an object newer than its source and a stamp from
 * 2000, so that only the stamp can make it stale. */
TEST(install_objects_follow_the_build_flags)
{
    char build[600], path[700], cmd[4096];
    snprintf(build, sizeof build, "%s/stamp-build", test_tmpdir());
    snprintf(cmd, sizeof cmd,
             "mkdir -p '%s/gen' && touch '%s/gen/key.o' '%s/gl_functions.h' && "
             "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s -C '%s' BUILD='%s' HAVE_OCCT=0 "
             "'%s/config.stamp' && touch -d 2000-01-01 '%s/config.stamp'",
             build, build, build, test_root_dir, build, build, build);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    snprintf(path, sizeof path, "%s/config.stamp", build);
    char *stamp = test_read_file(path);
    CHECK(stamp && !strstr(stamp, "SC_HAVE_OCCT"));
    free(stamp);
    CHECK(object_up_to_date(build, 0));
    CHECK(!object_up_to_date(build, 1));
    stamp = test_read_file(path);
    CHECK(stamp && strstr(stamp, "-DSC_HAVE_OCCT"));
    free(stamp);
    /* The same flags again: the stamp is not rewritten. */
    snprintf(cmd, sizeof cmd, "touch -d 2000-01-01 '%s'", path);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    CHECK(object_up_to_date(build, 1));
}
