/* test_embed.c — splinecast in an application's own GL (docs/api.md,
 * "Drawing into the application's GL"): examples/embed_gl.c built against
 * an installed copy (make install, pkg-config) draws a ray-cast scene and a
 * triangle mesh of its own into its framebuffer; where the two intersect,
 * the pixels the depth test gives each must be those the CPU reference's
 * distances give, and the argument checks of sc_draw_gl. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include "camera.h"
#include "embed_util.h"
#include "io.h"
#include "refcast.h"
#include "splinecast.h"

/* A binary PPM as RGB bytes, rows top-down; NULL when it is not one. */
static unsigned char *read_ppm(const char *path, int *w, int *h)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *px = NULL;
    int maxval;
    if (fscanf(f, "P6 %d %d %d", w, h, &maxval) == 3 && maxval == 255 && fgetc(f) == '\n') {
        size_t n = (size_t)*w * (size_t)*h * 3;
        px = malloc(n);
        if (px && fread(px, 1, n, f) != n) {
            free(px);
            px = NULL;
        }
    }
    fclose(f);
    return px;
}

/* Distance along the unit ray dir from eye to the square (centre c, half
 * sides a and b, orthogonal), or INFINITY. */
static double square_distance(const double eye[3], const double dir[3], const double c[3],
                              const double a[3], const double b[3])
{
    double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    double denom = n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2];
    if (fabs(denom) < 1e-12)
        return INFINITY;
    double t = (n[0] * (c[0] - eye[0]) + n[1] * (c[1] - eye[1]) + n[2] * (c[2] - eye[2])) / denom;
    if (!(t > 0))
        return INFINITY;
    double s = 0, u = 0, aa = 0, bb = 0;
    for (int k = 0; k < 3; k++) {
        double d = eye[k] + t * dir[k] - c[k];
        s += d * a[k];
        u += d * b[k];
        aa += a[k] * a[k];
        bb += b[k] * b[k];
    }
    return fabs(s / aa) <= 1 && fabs(u / bb) <= 1 ? t : INFINITY;
}

/* Per pixel, who wins: 0 nothing, 1 the surfaces, 2 the mesh. */
enum { NOTHING, SURFACE, MESH };

TEST(embed_gl_example_intersection_line)
{
    char exe[1024], out_ppm[1024], cmd[3000];
    if (test_build_example("embed_gl", exe, sizeof exe) != 0)
        return;
    snprintf(out_ppm, sizeof out_ppm, "%s/embed.ppm", test_tmpdir());
    const int W = 160, H = 160;
    snprintf(cmd, sizeof cmd, "'%s' teapot '%s' %d %d", exe, out_ppm, W, H);
    char *out = NULL, *errs = NULL;
    int status = test_run(cmd, &out, &errs);
    if (status != 0 && errs && strstr(errs, "context"))
        SKIP("no GL context: %s", errs);
    if (status != 0)
        fprintf(stderr, "  %s\n%s", cmd, errs ? errs : "");
    CHECK_INT(status, 0);
    free(errs);
    if (status != 0) {
        free(out);
        return;
    }
    CHECK_CONTAINS(out, "\nstate restored\n");
    /* Drawing the surfaces before or after the mesh makes the same image:
     * the depth test decides, not the order. */
    CHECK_CONTAINS(out, " order_diff=0\n");
    char camera_text[512] = "";
    double c[3], a[3], b[3];
    const char *cam_line = strstr(out, "camera "), *mesh_line = strstr(out, "mesh ");
    CHECK(cam_line && mesh_line);
    CHECK(sscanf(cam_line, "camera %511s", camera_text) == 1);
    CHECK(sscanf(mesh_line, "mesh %lf,%lf,%lf %lf,%lf,%lf %lf,%lf,%lf", &c[0], &c[1], &c[2], &a[0],
                 &a[1], &a[2], &b[0], &b[1], &b[2]) == 9);
    free(out);

    int w = 0, h = 0;
    unsigned char *px = read_ppm(out_ppm, &w, &h);
    CHECK(px != NULL);
    CHECK_INT(w, W);
    CHECK_INT(h, H);
    if (!px || w != W || h != H) {
        free(px);
        return;
    }

    /* The reference: the CPU ray caster's distances to the teapot, and the
     * square's along the same rays. */
    sc_scene scene;
    sc_error err = {0};
    sc_camera cam = {0};   /* up zero: the default up; the text has none */
    CHECK_INT(sc_read_scene(test_root("examples/scenes/teapot32.bpt"), &scene, &err), SC_OK);
    CHECK_INT(sc_camera_parse(camera_text, &cam, &err), SC_OK);
    cam.width = W;
    cam.height = H;
    sc_refcast *rc;
    sc_aov aov = {0};
    CHECK_INT(sc_refcast_prepare(&scene, &rc, &err), SC_OK);
    CHECK_INT(sc_refcast_render(rc, &cam, NULL, &aov, NULL, &err), SC_OK);
    sc_refcast_free(rc);
    int *ref = calloc((size_t)W * H, sizeof *ref), *gpu = calloc((size_t)W * H, sizeof *gpu);
    double *gap = calloc((size_t)W * H, sizeof *gap);
    double footprint = 2 * tan(0.5 * cam.fovy_deg * M_PI / 180) / H;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int p = y * W + x;
            double dir[3];
            sc_camera_ray(&cam, x + 0.5, y + 0.5, dir);
            double tm = square_distance(cam.eye, dir, c, a, b);
            double ts = aov.surface[p] >= 0 ? aov.t[p] : INFINITY;
            ref[p] = isinf(tm) && isinf(ts) ? NOTHING : ts < tm ? SURFACE : MESH;
            /* How far apart the two are, in pixel footprints there. */
            gap[p] = isinf(tm) || isinf(ts) ? INFINITY : fabs(ts - tm) / (footprint * fmin(ts, tm));
            const unsigned char *q = px + 3 * p;
            gpu[p] = q[0] == 255 && q[1] == 0 && q[2] == 255 ? MESH
                     : q[0] || q[1] || q[2]                  ? SURFACE
                                                             : NOTHING;
        }

    /* The intersection line: pixels whose neighbour to the right or below
     * has the other winner of the two, by the reference. Each must be met
     * by such a switch in the GPU's image within a pixel, and no pixel
     * away from the line (and from the surfaces' outline, where coverage
     * may differ by a pixel as in every accuracy test) may change hands. */
    long line = 0, met = 0, wrong = 0, both = 0;
    for (int y = 1; y < H - 1; y++)
        for (int x = 1; x < W - 1; x++) {
            int p = y * W + x;
            both += ref[p] != NOTHING;
            int switches = 0, gpu_switch = 0, near_edge = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int q = p + dy * W + dx;
                    near_edge |= ref[q] != ref[p] && (ref[q] == NOTHING || ref[p] == NOTHING);
                    near_edge |= aov.surface[q] != aov.surface[p] &&
                                 (aov.surface[q] < 0 || aov.surface[p] < 0);
                    gpu_switch |= (gpu[q] == SURFACE && gpu[p] == MESH) ||
                                  (gpu[q] == MESH && gpu[p] == SURFACE);
                }
            int q = p + 1, r = p + W;
            switches = (ref[p] == SURFACE && (ref[q] == MESH || ref[r] == MESH)) ||
                       (ref[p] == MESH && (ref[q] == SURFACE || ref[r] == SURFACE));
            if (switches && !near_edge) {
                line++;
                met += gpu_switch;
            }
            if (gpu[p] != ref[p] && !near_edge && !(gap[p] < 2))
                wrong++;
        }
    /* The teapot's body, spout and handle cross the square: a line of
     * some length, all of it found. */
    CHECK(line > 40);
    CHECK_INT(met, line);
    CHECK_INT(wrong, 0);
    CHECK(both > W * H / 4);
    free(ref);
    free(gpu);
    free(gap);
    free(px);
    sc_aov_free(&aov);
    sc_scene_free(&scene);
}

TEST(embed_draw_gl_refused_on_own_context)
{
    sc_error err = {0};
    sc_context_id ctx;
    if (sc_make_context(NULL, &ctx, &err) != SC_OK)
        SKIP("no GL context: %s", err.message);
    sc_scene_id scene;
    sc_renderer_id r;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &r, &err), SC_OK);
    sc_gl_draw_desc d = {.view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -10, 1},
                         .projection = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -1, 0, 0, -1, 0}};
    CHECK_INT(sc_draw_gl(r, &d, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "renderer is not on an application's context");
    CHECK_INT(sc_draw_gl(r, NULL, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "desc is NULL");
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
}

/* The application's own EGL context, current; NULL when there is none. */
static EGLContext app_context(EGLDisplay *dpy)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    *dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL)
                       : EGL_NO_DISPLAY;
    if (*dpy == EGL_NO_DISPLAY || !eglInitialize(*dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_API))
        return EGL_NO_CONTEXT;
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(*dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx != EGL_NO_CONTEXT && !eglMakeCurrent(*dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        eglDestroyContext(*dpy, ctx);
        ctx = EGL_NO_CONTEXT;
    }
    return ctx;
}

/* In the application's context: sc_render draws what it draws on the
 * library's own context and leaves the application's state as it was;
 * sc_draw_gl refuses what it cannot draw with, saying why. */
TEST(embed_app_context_state_and_refusals)
{
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    sc_context_id own;
    if (sc_make_context(NULL, &own, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_renderer_id r_own;
    sc_frame_id f_own;
    sc_camera_desc view = {.width = 64, .height = 64};
    CHECK_INT(sc_make_renderer(own, scene, NULL, &r_own, &err), SC_OK);
    CHECK_INT(sc_render(r_own, &view, &f_own, &err), SC_OK);

    EGLDisplay dpy;
    EGLContext egl = app_context(&dpy);
    if (egl == EGL_NO_CONTEXT) {
        sc_shutdown();
        SKIP("no EGL context of the test's own");
    }
    PFNGLGETINTEGERVPROC get_integer = (PFNGLGETINTEGERVPROC)eglGetProcAddress("glGetIntegerv");
    PFNGLDEPTHFUNCPROC depth_func = (PFNGLDEPTHFUNCPROC)eglGetProcAddress("glDepthFunc");
    PFNGLENABLEPROC enable = (PFNGLENABLEPROC)eglGetProcAddress("glEnable");
    PFNGLISENABLEDPROC is_enabled = (PFNGLISENABLEDPROC)eglGetProcAddress("glIsEnabled");
    PFNGLVIEWPORTPROC viewport = (PFNGLVIEWPORTPROC)eglGetProcAddress("glViewport");
    PFNGLCLIPCONTROLPROC clip_control = (PFNGLCLIPCONTROLPROC)eglGetProcAddress("glClipControl");
    depth_func(GL_GEQUAL);
    enable(GL_BLEND);
    viewport(3, 4, 50, 60);

    sc_context_id app;
    CHECK_INT(sc_make_context(&(sc_context_desc){.get_proc_address = eglGetProcAddress}, &app,
                              &err),
              SC_OK);
    sc_context_info info;
    CHECK_INT(sc_query_context_info(app, &info, &err), SC_OK);
    CHECK_INT(info.backend, SC_BACKEND_DEFAULT);
    CHECK(!strncmp(info.description, "application ", 12));
    sc_renderer_id r_app;
    sc_frame_id f_app;
    CHECK_INT(sc_make_renderer(app, scene, NULL, &r_app, &err), SC_OK);
    CHECK_INT(sc_render(r_app, &view, &f_app, &err), SC_OK);
    GLint func = 0, vp[4] = {0};
    get_integer(GL_DEPTH_FUNC, &func);
    get_integer(GL_VIEWPORT, vp);
    CHECK_INT(func, GL_GEQUAL);
    CHECK(is_enabled(GL_BLEND));
    CHECK(vp[0] == 3 && vp[1] == 4 && vp[2] == 50 && vp[3] == 60);
    sc_frame_info a, b;
    CHECK_INT(sc_query_frame_info(f_own, &a, &err), SC_OK);
    CHECK_INT(sc_query_frame_info(f_app, &b, &err), SC_OK);
    long differ = 0;
    for (int p = 0; p < 64 * 64; p++)
        differ += a.surface[p] != b.surface[p] || memcmp(a.rgba + 4 * p, b.rgba + 4 * p, 4);
    CHECK_INT(differ, 0);

    sc_gl_draw_desc d = {.view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -10, 1},
                         .projection = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -1, 0, 0, -1, 0}};
    sc_gl_draw_desc ortho = d, singular = d, nan_view = d;
    ortho.projection[11] = 0;
    ortho.projection[15] = 1;
    memset(singular.view, 0, sizeof singular.view);
    nan_view.view[0] = NAN;
    CHECK_INT(sc_draw_gl(r_app, &ortho, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "not a perspective one");
    CHECK_INT(sc_draw_gl(r_app, &singular, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "singular");
    CHECK_INT(sc_draw_gl(r_app, &nan_view, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "view[0] is not finite");
    clip_control(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    CHECK_INT(sc_draw_gl(r_app, &d, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "GL_ZERO_TO_ONE");
    clip_control(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    /* A surfaceless context has no default framebuffer to draw into. */
    CHECK_INT(sc_draw_gl(r_app, &d, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "GL_FRAMEBUFFER_UNDEFINED");

    sc_destroy_context(app);
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, egl);
    /* The library's own context is made current again for its next call. */
    sc_frame_id again;
    CHECK_INT(sc_render(r_own, &view, &again, &err), SC_OK);
    sc_shutdown();
}
