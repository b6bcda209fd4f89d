/* viewer.c — `viewer SCENE`: a window (GLFW) onto a ray-cast scene, built
 * on the public API alone. The library draws offscreen into its own
 * context; each frame is read back (sc_render) and shown as a texture in
 * the window's context, so the viewer needs nothing from the library but
 * frames. Left drag orbits, right (or shift-left) drag pans, the wheel
 * zooms, a click without drag picks (sc_pick). Keys: M method, S start,
 * + / - iterations, V view, T trim method, R reset, Q or Esc quit. The
 * window title carries the live stats.
 *
 * For tests and demos it runs a script instead of waiting for input:
 * `--script FILE` (orbit DX DY, pan DX DY, zoom F, key C, click X Y,
 * screenshot PATH, one per line) or `--frames N --screenshot PATH`. Every
 * frame prints `viewer frame=N camera=… ` on stdout with the camera in
 * `--camera` syntax, so that `splinecast render` can draw the same view. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "splinecast.h"

static const char usage[] =
    "usage: viewer SCENE [--size WxH] [--up X,Y,Z] [--script FILE]\n"
    "              [--frames N --screenshot PATH]\n"
    "\n"
    "Mouse: left drag orbits, right or shift-left drag pans, the wheel zooms,\n"
    "a click picks (prints a `pick` line). Keys: M method, S start (cpmap,\n"
    "mid, view), + / - iterations, V view (shade, iters, uv, normal, hull,\n"
    "depth), T trim method (fast, clip, left), A accuracy target (off, 1, 0.1,\n"
    "0.01 px: settings chosen per surface for the current view), R reset the\n"
    "view, Q or Esc quit.\n"
    "\n"
    "--script FILE runs one command per line and exits: orbit DEG_X DEG_Y,\n"
    "pan FX FY (fractions of the view), zoom F, key C, click X Y, screenshot PATH.\n";

static const double pi = 3.14159265358979323846;

typedef struct view_state {
    sc_context_id ctx;
    sc_scene_id scene;
    sc_renderer_id renderer;
    sc_renderer_desc desc;
    int width, height;
    double eye[3], target[3], up[3], fovy;
    double home_eye[3], home_target[3];
    int has_up;
    int frame_count;
    double frame_ms;
    GLFWwindow *window;
    GLuint texture;
    int dirty, renderer_dirty;
    /* Mouse */
    int dragging, moved, button;
    double last_x, last_y, press_x, press_y;
} view_state;

static const sc_method methods[] = {SC_METHOD_HYBRID, SC_METHOD_NEWTON, SC_METHOD_BROYDEN,
                                    SC_METHOD_BCLIP, SC_METHOD_SUBDIV};
static const char *const method_names[] = {"hybrid", "newton", "broyden", "bclip", "subdiv"};
static const sc_start starts[] = {SC_START_CPMAP, SC_START_MID, SC_START_VIEW};
static const char *const start_names[] = {"cpmap", "mid", "view"};
/* Accuracy targets in pixels (0: off, the renderer's own settings). */
static const double accuracies[] = {0, 1, 0.1, 0.01};
static const sc_show shows[] = {SC_SHOW_SHADE, SC_SHOW_ITERS, SC_SHOW_UV, SC_SHOW_NORMAL,
                                SC_SHOW_HULL, SC_SHOW_DEPTH};
static const char *const show_names[] = {"shade", "iters", "uv", "normal", "hull", "depth"};
static const sc_trim_method trims[] = {SC_TRIM_FAST, SC_TRIM_CLIP, SC_TRIM_LEFT};
static const char *const trim_names[] = {"fast", "clip", "left"};
static int method_at, start_at, show_at, trim_at, accuracy_at;

static void report(const sc_error *err)
{
    char buf[1024];
    fprintf(stderr, "viewer: %s\n", sc_error_text(err, buf, sizeof buf));
}

static void camera_text(const view_state *v, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", v->eye[0], v->eye[1],
                     v->eye[2], v->target[0], v->target[1], v->target[2], v->fovy);
    if (v->has_up && n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, ",%.17g,%.17g,%.17g", v->up[0], v->up[1], v->up[2]);
}

/* The library made its own context current behind GLFW's back: GLFW still
 * believes the window's is, so it is released first to be made current
 * for real. */
static void make_window_current(view_state *v)
{
    glfwMakeContextCurrent(NULL);
    glfwMakeContextCurrent(v->window);
}

static int make_renderer(view_state *v)
{
    sc_error err = {0};
    if (v->renderer.id)
        sc_destroy_renderer(v->renderer);
    v->renderer.id = 0;
    v->desc.method = methods[method_at];
    v->desc.start = starts[start_at];
    v->desc.show = shows[show_at];
    v->desc.trim = trims[trim_at];
    /* A target is met for the view the renderer is made in. */
    char cam[400];
    camera_text(v, cam, sizeof cam);
    sc_camera_desc accuracy_view = {.width = v->width, .height = v->height, .text = cam};
    v->desc.accuracy_px = accuracies[accuracy_at];
    v->desc.accuracy_view = accuracies[accuracy_at] > 0 ? &accuracy_view : NULL;
    if (sc_make_renderer(v->ctx, v->scene, &v->desc, &v->renderer, &err) != SC_OK) {
        report(&err);
        return 0;
    }
    v->renderer_dirty = 0;
    return 1;
}

/* Renders the current view offscreen and uploads it to the window's
 * texture. */
static int render(view_state *v)
{
    sc_error err = {0};
    if (v->renderer_dirty && !make_renderer(v))
        return 0;
    char cam[400];
    camera_text(v, cam, sizeof cam);
    sc_camera_desc view = {.width = v->width, .height = v->height, .text = cam};
    sc_frame_id frame;
    sc_frame_info info;
    double t0 = sc_now();
    if (sc_render(v->renderer, &view, &frame, &err) != SC_OK ||
        sc_query_frame_info(frame, &info, &err) != SC_OK) {
        report(&err);
        return 0;
    }
    v->frame_ms = 1e3 * (sc_now() - t0);
    make_window_current(v);
    glBindTexture(GL_TEXTURE_2D, v->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, info.width, info.height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, info.rgba);
    sc_destroy_frame(frame);
    sc_renderer_info stats;
    sc_query_renderer_info(v->renderer, &stats, &err);
    char title[512];
    snprintf(title, sizeof title,
             "splinecast viewer: %s start=%s iters=%d view=%s trim=%s | %.1f ms, %d programs, "
             "%d hulls, %d draw calls, accuracy %g px", method_names[method_at], start_names[start_at],
             v->desc.max_iters ? v->desc.max_iters : 6, show_names[show_at], trim_names[trim_at],
             v->frame_ms, stats.programs, stats.hulls, stats.draw_calls, accuracies[accuracy_at]);
    glfwSetWindowTitle(v->window, title);
    printf("viewer frame=%d camera=%s method=%s start=%s iters=%d view=%s trim=%s frame_ms=%.2f "
           "programs=%d hulls=%d accuracy=%g\n", v->frame_count++, cam, method_names[method_at],
           start_names[start_at], v->desc.max_iters ? v->desc.max_iters : 6, show_names[show_at],
           trim_names[trim_at], v->frame_ms, stats.programs, stats.hulls, accuracies[accuracy_at]);
    fflush(stdout);
    v->dirty = 0;
    return 1;
}

/* Draws the texture over the whole window, row 0 of the frame at the top. */
static void present(view_state *v)
{
    make_window_current(v);
    int fw, fh;
    glfwGetFramebufferSize(v->window, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glEnable(GL_TEXTURE_2D);
    glBindTexture(GL_TEXTURE_2D, v->texture);
    glBegin(GL_QUADS);
    glTexCoord2f(0, 1); glVertex2f(-1, -1);
    glTexCoord2f(1, 1); glVertex2f(1, -1);
    glTexCoord2f(1, 0); glVertex2f(1, 1);
    glTexCoord2f(0, 0); glVertex2f(-1, 1);
    glEnd();
    glDisable(GL_TEXTURE_2D);
}

static void sub3(const double a[3], const double b[3], double o[3])
{
    for (int k = 0; k < 3; k++)
        o[k] = a[k] - b[k];
}

static void cross3(const double a[3], const double b[3], double o[3])
{
    double r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                   a[0] * b[1] - a[1] * b[0]};
    memcpy(o, r, sizeof r);
}

static double norm3(double a[3])
{
    double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    if (l > 0)
        for (int k = 0; k < 3; k++)
            a[k] /= l;
    return l;
}

/* Rodrigues: v rotated by angle about the unit axis. */
static void rotate(double v[3], const double axis[3], double angle)
{
    double c = cos(angle), s = sin(angle), d = v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2];
    double x[3];
    cross3(axis, v, x);
    for (int k = 0; k < 3; k++)
        v[k] = v[k] * c + x[k] * s + axis[k] * d * (1 - c);
}

static void world_up(const view_state *v, double up[3])
{
    if (v->has_up) {
        memcpy(up, v->up, 3 * sizeof *up);
    } else {
        up[0] = up[1] = 0;
        up[2] = 1;
    }
    norm3(up);
}

/* Turns the eye about the target: dx degrees about the up axis, dy about
 * the view's right axis (stopping short of the poles). */
static void orbit(view_state *v, double dx, double dy)
{
    double up[3], off[3], right[3];
    world_up(v, up);
    sub3(v->eye, v->target, off);
    rotate(off, up, -dx * pi / 180);
    cross3(off, up, right);
    if (norm3(right) > 0) {
        double trial[3] = {off[0], off[1], off[2]};
        rotate(trial, right, dy * pi / 180);
        double len = sqrt(trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2]);
        double along = (trial[0] * up[0] + trial[1] * up[1] + trial[2] * up[2]) / len;
        if (fabs(along) < 0.995)
            memcpy(off, trial, sizeof off);
    }
    for (int k = 0; k < 3; k++)
        v->eye[k] = v->target[k] + off[k];
    v->dirty = 1;
}

/* Moves eye and target by fx, fy of the view's height at the target. */
static void pan(view_state *v, double fx, double fy)
{
    double up[3], off[3], right[3], cam_up[3];
    world_up(v, up);
    sub3(v->target, v->eye, off);
    double dist = norm3(off);
    cross3(off, up, right);
    if (norm3(right) == 0)
        return;
    cross3(right, off, cam_up);
    double h = 2 * dist * tan(0.5 * v->fovy * pi / 180);
    for (int k = 0; k < 3; k++) {
        double d = -fx * h * right[k] + fy * h * cam_up[k];
        v->eye[k] += d;
        v->target[k] += d;
    }
    v->dirty = 1;
}

static void zoom(view_state *v, double f)
{
    if (!(f > 0))
        return;
    for (int k = 0; k < 3; k++)
        v->eye[k] = v->target[k] + (v->eye[k] - v->target[k]) * f;
    v->dirty = 1;
}

static void pick(view_state *v, double x, double y)
{
    sc_error err = {0};
    sc_pick_result hit;
    if (sc_pick(v->renderer, x, y, &hit, &err) != SC_OK) {
        report(&err);
        return;
    }
    if (!hit.hit)
        printf("pick miss\n");
    else
        printf("pick surface=%d u=%.12g v=%.12g point=%.12g,%.12g,%.12g normal=%.12g,%.12g,%.12g "
               "t=%.12g\n", hit.surface, hit.u, hit.v, hit.point[0], hit.point[1], hit.point[2],
               hit.normal[0], hit.normal[1], hit.normal[2], hit.t);
    fflush(stdout);
}

static void key(view_state *v, int c)
{
    switch (c) {
    case 'M': method_at = (method_at + 1) % 5; v->renderer_dirty = 1; break;
    case 'S': start_at = (start_at + 1) % 3; v->renderer_dirty = 1; break;
    case 'A': accuracy_at = (accuracy_at + 1) % 4; v->renderer_dirty = 1; break;
    case 'V': show_at = (show_at + 1) % 6; v->renderer_dirty = 1; break;
    case 'T': trim_at = (trim_at + 1) % 3; v->renderer_dirty = 1; break;
    case '+': case '=':
        v->desc.max_iters = (v->desc.max_iters ? v->desc.max_iters : 6) + 1;
        if (v->desc.max_iters > SC_MAX_ITERS)
            v->desc.max_iters = SC_MAX_ITERS;
        v->renderer_dirty = 1;
        break;
    case '-':
        v->desc.max_iters = (v->desc.max_iters ? v->desc.max_iters : 6) - 1;
        if (v->desc.max_iters < 1)
            v->desc.max_iters = 1;
        v->renderer_dirty = 1;
        break;
    case 'R':
        memcpy(v->eye, v->home_eye, sizeof v->eye);
        memcpy(v->target, v->home_target, sizeof v->target);
        break;
    case 'Q':
        glfwSetWindowShouldClose(v->window, 1);
        break;
    default:
        return;
    }
    v->dirty = 1;
}

static void on_key(GLFWwindow *w, int k, int scancode, int action, int mods)
{
    (void)scancode;
    view_state *v = glfwGetWindowUserPointer(w);
    if (action != GLFW_PRESS && action != GLFW_REPEAT)
        return;
    if (k == GLFW_KEY_ESCAPE)
        key(v, 'Q');
    else if (k == GLFW_KEY_KP_ADD || (k == GLFW_KEY_EQUAL && (mods & GLFW_MOD_SHIFT)))
        key(v, '+');
    else if (k == GLFW_KEY_KP_SUBTRACT || k == GLFW_KEY_MINUS)
        key(v, '-');
    else if (k >= GLFW_KEY_A && k <= GLFW_KEY_Z)
        key(v, 'A' + (k - GLFW_KEY_A));
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    view_state *v = glfwGetWindowUserPointer(w);
    double x, y;
    glfwGetCursorPos(w, &x, &y);
    if (action == GLFW_PRESS) {
        v->dragging = 1;
        v->moved = 0;
        v->button = (button == GLFW_MOUSE_BUTTON_RIGHT || (mods & GLFW_MOD_SHIFT)) ? 1 : 0;
        v->last_x = v->press_x = x;
        v->last_y = v->press_y = y;
    } else if (action == GLFW_RELEASE && v->dragging) {
        v->dragging = 0;
        if (!v->moved && x >= 0 && y >= 0 && x < v->width && y < v->height)
            pick(v, x, y);
    }
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    view_state *v = glfwGetWindowUserPointer(w);
    if (!v->dragging)
        return;
    if (fabs(x - v->press_x) + fabs(y - v->press_y) > 3)
        v->moved = 1;
    if (!v->moved)
        return;
    if (v->button)
        pan(v, (x - v->last_x) / v->height, (y - v->last_y) / v->height);
    else
        orbit(v, 0.4 * (x - v->last_x), 0.4 * (y - v->last_y));
    v->last_x = x;
    v->last_y = y;
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    zoom(glfwGetWindowUserPointer(w), pow(0.9, dy));
}

/* The window's back buffer as an RGB PNG, row 0 at the top. */
static int screenshot(view_state *v, const char *path)
{
    present(v);
    int fw, fh;
    glfwGetFramebufferSize(v->window, &fw, &fh);
    unsigned char *pixels = malloc((size_t)fw * (size_t)fh * 4);
    unsigned char *flipped = malloc((size_t)fw * (size_t)fh * 4);
    glFinish();
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, fw, fh, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
    for (int y = 0; y < fh; y++)
        memcpy(flipped + (size_t)y * fw * 4, pixels + (size_t)(fh - 1 - y) * fw * 4,
               (size_t)fw * 4);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    img.width = (png_uint_32)fw;
    img.height = (png_uint_32)fh;
    img.format = PNG_FORMAT_RGBA;
    int ok = png_image_write_to_file(&img, path, 0, flipped, 0, NULL) != 0;
    free(pixels);
    free(flipped);
    if (!ok) {
        fprintf(stderr, "viewer: %s: cannot write the screenshot (%s)\n", path, img.message);
        return 0;
    }
    printf("viewer screenshot=%s size=%dx%d\n", path, fw, fh);
    fflush(stdout);
    return 1;
}

/* Runs one script line; 0 on a bad line or a failure. */
static int script_line(view_state *v, const char *line, const char *file, int no)
{
    double a, b;
    char word[32], path[1024];
    if (line[0] == '#' || line[strspn(line, " \t\r\n")] == 0)
        return 1;
    if (sscanf(line, "orbit %lf %lf", &a, &b) == 2)
        orbit(v, a, b);
    else if (sscanf(line, "pan %lf %lf", &a, &b) == 2)
        pan(v, a, b);
    else if (sscanf(line, "zoom %lf", &a) == 1)
        zoom(v, a);
    else if (sscanf(line, "key %31s", word) == 1 && strlen(word) == 1)
        key(v, word[0] >= 'a' && word[0] <= 'z' ? word[0] - 32 : word[0]);
    else if (sscanf(line, "click %lf %lf", &a, &b) == 2) {
        if (v->dirty && !render(v))
            return 0;
        pick(v, a, b);
        return 1;
    } else if (sscanf(line, "screenshot %1023s", path) == 1) {
        if (v->dirty && !render(v))
            return 0;
        return screenshot(v, path);
    } else {
        fprintf(stderr, "%s:%d: expected orbit DX DY, pan FX FY, zoom F, key C, click X Y or "
                "screenshot PATH\n", file, no);
        return 0;
    }
    /* Each step is a frame, as it would be on screen. */
    if (!render(v))
        return 0;
    present(v);
    glfwSwapBuffers(v->window);
    glfwPollEvents();
    return 1;
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *script = NULL, *shot = NULL;
    view_state v;
    memset(&v, 0, sizeof v);
    v.width = 640;
    v.height = 480;
    int frames = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            fputs(usage, stdout);
            return 0;
        } else if (!strcmp(a, "--size") && next) {
            if (sscanf(argv[++i], "%dx%d", &v.width, &v.height) != 2 || v.width < 16 ||
                v.height < 16 || v.width > 8192 || v.height > 8192) {
                fprintf(stderr, "viewer: --size takes WxH from 16 to 8192, not '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--up") && next) {
            if (sscanf(argv[++i], "%lf,%lf,%lf", &v.up[0], &v.up[1], &v.up[2]) != 3 ||
                norm3(v.up) == 0) {
                fprintf(stderr, "viewer: --up takes a non-zero X,Y,Z, not '%s'\n", argv[i]);
                return 2;
            }
            v.has_up = 1;
        } else if (!strcmp(a, "--script") && next) {
            script = argv[++i];
        } else if (!strcmp(a, "--frames") && next) {
            frames = atoi(argv[++i]);
        } else if (!strcmp(a, "--screenshot") && next) {
            shot = argv[++i];
        } else if (a[0] != '-' && !scene_path) {
            scene_path = a;
        } else {
            fprintf(stderr, "viewer: unexpected argument '%s'\n%s", a, usage);
            return 2;
        }
    }
    if (!scene_path) {
        fputs(usage, stderr);
        return 2;
    }
    sc_error err = {0};
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &v.scene, &err) != SC_OK ||
        sc_make_context(NULL, &v.ctx, &err) != SC_OK) {
        report(&err);
        return 1;
    }
    if (!glfwInit()) {
        fprintf(stderr, "viewer: no window system (GLFW could not start; under no display, "
                "run it with xvfb-run)\n");
        return 1;
    }
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    /* EGL, as the library's own context: one GL entry point (libglvnd's
     * EGL) for both, and it works where GLX is refused (Xvfb). */
    glfwWindowHint(GLFW_CONTEXT_CREATION_API, GLFW_EGL_CONTEXT_API);
    glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
    v.window = glfwCreateWindow(v.width, v.height, "splinecast viewer", NULL, NULL);
    if (!v.window) {
        fprintf(stderr, "viewer: could not open a %dx%d window\n", v.width, v.height);
        glfwTerminate();
        return 1;
    }
    glfwSetWindowUserPointer(v.window, &v);
    glfwMakeContextCurrent(v.window);
    glfwSwapInterval(script || frames ? 0 : 1);
    glGenTextures(1, &v.texture);
    glBindTexture(GL_TEXTURE_2D, v.texture);
    /* One texel per pixel: no filtering, so the window shows the frame's
     * very bytes. */
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glfwSetKeyCallback(v.window, on_key);
    glfwSetMouseButtonCallback(v.window, on_button);
    glfwSetCursorPosCallback(v.window, on_cursor);
    glfwSetScrollCallback(v.window, on_scroll);

    /* The default view of the scene (with --up), as `render` frames it. */
    int status = 1;
    if (!make_renderer(&v))
        goto done;
    {
        sc_camera_desc first = {.width = v.width, .height = v.height};
        memcpy(first.up, v.up, sizeof first.up);
        sc_frame_id frame;
        sc_frame_info info;
        if (sc_render(v.renderer, &first, &frame, &err) != SC_OK ||
            sc_query_frame_info(frame, &info, &err) != SC_OK) {
            report(&err);
            goto done;
        }
        memcpy(v.eye, info.eye, sizeof v.eye);
        memcpy(v.target, info.target, sizeof v.target);
        v.fovy = info.fovy_deg;
        sc_destroy_frame(frame);
        memcpy(v.home_eye, v.eye, sizeof v.eye);
        memcpy(v.home_target, v.target, sizeof v.target);
    }
    if (!render(&v))
        goto done;
    if (script) {
        FILE *f = fopen(script, "r");
        if (!f) {
            fprintf(stderr, "viewer: %s: cannot open the script\n", script);
            goto done;
        }
        char line[1200];
        int no = 0, ok = 1;
        while (ok && fgets(line, sizeof line, f))
            ok = script_line(&v, line, script, ++no);
        fclose(f);
        status = ok ? 0 : 1;
        goto done;
    }
    if (frames > 0) {
        for (int f = 1; f < frames; f++) {
            present(&v);
            glfwSwapBuffers(v.window);
            glfwPollEvents();
            v.dirty = 1;
            if (!render(&v))
                goto done;
        }
        status = shot && !screenshot(&v, shot) ? 1 : 0;
        goto done;
    }
    while (!glfwWindowShouldClose(v.window)) {
        if ((v.dirty || v.renderer_dirty) && !render(&v))
            break;
        present(&v);
        glfwSwapBuffers(v.window);
        glfwWaitEvents();
    }
    status = 0;
done:
    if (v.texture) {
        make_window_current(&v);
        glDeleteTextures(1, &v.texture);
    }
    glfwDestroyWindow(v.window);
    glfwTerminate();
    sc_destroy_context(v.ctx);
    sc_destroy_scene(v.scene);
    sc_shutdown();
    return status;
}
