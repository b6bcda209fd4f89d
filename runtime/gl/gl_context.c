/* gl_context.c — offscreen OpenGL 4.5 core contexts from EGL or OSMesa
 * (gl_context.h). EGL is linked (libEGL is the vendor-neutral dispatcher, not
 * libGL); OSMesa is opened with dlopen only when it is used. Both render into
 * framebuffer objects of their own, so neither needs a window surface. */
#include "gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { GL_MAJOR_REQUIRED = 4, GL_MINOR_REQUIRED = 5 };

/* The few OSMesa names used here (from GL/osmesa.h, whose inclusion would
 * pull the legacy GL/gl.h next to glcorearb.h). */
enum {
    OSMESA_FORMAT_ = 0x22,
    OSMESA_DEPTH_BITS_ = 0x30,
    OSMESA_STENCIL_BITS_ = 0x31,
    OSMESA_ACCUM_BITS_ = 0x32,
    OSMESA_PROFILE_ = 0x33,
    OSMESA_CORE_PROFILE_ = 0x34,
    OSMESA_CONTEXT_MAJOR_VERSION_ = 0x36,
    OSMESA_CONTEXT_MINOR_VERSION_ = 0x37,
};
typedef struct osmesa_context *osmesa_context_t;
typedef osmesa_context_t (*osmesa_create_fn)(const int *attribs, osmesa_context_t share);
typedef void (*osmesa_destroy_fn)(osmesa_context_t ctx);
typedef unsigned char (*osmesa_make_current_fn)(osmesa_context_t ctx, void *buffer,
                                                GLenum type, GLsizei width,
                                                GLsizei height);
typedef sc_gl_proc (*osmesa_get_proc_fn)(const char *name);

struct sc_gl_context {
    sc_gl gl;
    sc_backend backend;
    char description[256];
    /* EGL */
    EGLDisplay egl_display;
    EGLContext egl_context;
    /* OSMesa */
    void *osmesa_lib;
    osmesa_context_t osmesa_context;
    osmesa_destroy_fn osmesa_destroy;
    osmesa_make_current_fn osmesa_make_current;
    osmesa_get_proc_fn osmesa_get_proc;
    unsigned char osmesa_dummy[4]; /* OSMesa binds a buffer; we draw to FBOs */
    /* An application's context */
    sc_gl_app_get_proc_fn app_get_proc;
};


static int has_extension(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == 0))
            return 1;
    return 0;
}

static const char *egl_error_name(EGLint code)
{
    switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error";
    }
}

static void APIENTRY debug_message(GLenum source, GLenum type, GLuint id,
                                     GLenum severity, GLsizei length,
                                     const GLchar *message, const void *user)
{
    (void)source;
    (void)length;
    (void)user;
    sc_log_level level = SC_LOG_DEBUG;
    if (type == GL_DEBUG_TYPE_ERROR)
        level = SC_LOG_ERROR;
    else if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM)
        level = SC_LOG_WARN;
    else if (severity == GL_DEBUG_SEVERITY_LOW)
        level = SC_LOG_INFO;
    sc_log(level, "GL: %s (id %u)", message, id);
}

/* ---- EGL ---- */

static sc_gl_proc egl_get_proc(const char *name, void *user)
{
    (void)user;
    return (sc_gl_proc)eglGetProcAddress(name);
}

int sc_egl_device_wanted(const char *extensions)
{
    /* Not EGL_EXT_device_drm: NVIDIA's driver names it only where the
     * process may open the GPU's DRM node, which a server or container
     * often does not expose (/dev/nvidia* alone), and the device draws
     * all the same. */
    return extensions && !has_extension(extensions, "EGL_MESA_device_software");
}

/* A display on a hardware device when the device platform offers one that
 * initialises (sc_egl_device_wanted), else the surfaceless platform; EGL_NO_DISPLAY with err saying why when neither is there (some
 * of those reasons leave no EGL error to name). */
static EGLDisplay egl_open_display(const char **platform, sc_error *err)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!client || !get_display) {
        sc_fail(err, NULL, 0, "EGL: no platform displays (EGL_EXT_platform_base)");
        return EGL_NO_DISPLAY;
    }
    if (has_extension(client, "EGL_EXT_platform_device")) {
        PFNEGLQUERYDEVICESEXTPROC query_devices =
            (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
        PFNEGLQUERYDEVICESTRINGEXTPROC query_string =
            (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (query_devices && query_string && query_devices(16, devices, &count)) {
            for (EGLint i = 0; i < count; i++) {
                if (!sc_egl_device_wanted(query_string(devices[i], EGL_EXTENSIONS)))
                    continue;
                EGLDisplay d = get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
                if (d != EGL_NO_DISPLAY && eglInitialize(d, NULL, NULL)) {
                    *platform = "egl-device";
                    return d;
                }
            }
        }
    }
    if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
        sc_fail(err, NULL, 0, "EGL: no hardware device and no surfaceless platform "
                              "(EGL_MESA_platform_surfaceless)");
        return EGL_NO_DISPLAY;
    }
    EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (d == EGL_NO_DISPLAY || !eglInitialize(d, NULL, NULL)) {
        sc_fail(err, NULL, 0, "EGL: no surfaceless display (%s)", egl_error_name(eglGetError()));
        return EGL_NO_DISPLAY;
    }
    *platform = "egl-surfaceless";
    return d;
}

/* When the driver refused 4.5 core: the GL_VERSION of the best it offers
 * ("" when it offers nothing), from a context of the lowest core version
 * (3.2, which Mesa answers with its highest) or else of any version, made
 * current only to ask. */
static void egl_probe_version(EGLDisplay display, EGLConfig config, char *version,
                              size_t size)
{
    static const EGLint core[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    static const EGLint any[] = {EGL_NONE};
    version[0] = 0;
    EGLContext probe = eglCreateContext(display, config, EGL_NO_CONTEXT, core);
    if (probe == EGL_NO_CONTEXT)
        probe = eglCreateContext(display, config, EGL_NO_CONTEXT, any);
    if (probe == EGL_NO_CONTEXT)
        return;
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, probe)) {
        PFNGLGETSTRINGPROC get_string = (PFNGLGETSTRINGPROC)eglGetProcAddress("glGetString");
        const char *v = get_string ? (const char *)get_string(GL_VERSION) : NULL;
        snprintf(version, size, "%s", v ? v : "");
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
    eglDestroyContext(display, probe);
}

static int egl_create(sc_gl_context *ctx, int debug, sc_error *err)
{
    const char *platform = "egl";
    EGLDisplay display = egl_open_display(&platform, err);
    if (display == EGL_NO_DISPLAY)
        return SC_FAIL;
    ctx->egl_display = display;
    if (!eglBindAPI(EGL_OPENGL_API))
        return sc_fail(err, NULL, 0, "EGL: the display has no desktop OpenGL");
    const char *ext = eglQueryString(display, EGL_EXTENSIONS);
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(ext, "EGL_KHR_no_config_context")) {
        const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                               EGL_DONT_CARE, EGL_NONE};
        EGLint n = 0;
        if (!eglChooseConfig(display, want, &config, 1, &n) || n < 1)
            return sc_fail(err, NULL, 0, "EGL: no OpenGL config");
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, GL_MAJOR_REQUIRED,
                              EGL_CONTEXT_MINOR_VERSION, GL_MINOR_REQUIRED,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                              EGL_NONE};
    ctx->egl_context = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (ctx->egl_context == EGL_NO_CONTEXT) {
        const char *why = egl_error_name(eglGetError());
        char version[200];
        egl_probe_version(display, config, version, sizeof version);
        if (version[0])
            return sc_gl_fail_version(err, "EGL", version, GL_MAJOR_REQUIRED,
                                      GL_MINOR_REQUIRED);
        return sc_fail(err, NULL, 0,
                       "EGL: no OpenGL %d.%d core context (%s): the driver is too old",
                       GL_MAJOR_REQUIRED, GL_MINOR_REQUIRED, why);
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx->egl_context))
        return sc_fail(err, NULL, 0, "EGL: eglMakeCurrent failed (%s)",
                       egl_error_name(eglGetError()));
    ctx->backend = SC_BACKEND_EGL;
    snprintf(ctx->description, sizeof ctx->description, "%s", platform);
    return sc_gl_load(&ctx->gl, egl_get_proc, NULL, GL_MAJOR_REQUIRED, GL_MINOR_REQUIRED,
                      err);
}

static void egl_destroy(sc_gl_context *ctx)
{
    if (!ctx->egl_display)
        return;
    if (ctx->egl_context != EGL_NO_CONTEXT) {
        if (eglGetCurrentContext() == ctx->egl_context)
            eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE,
                           EGL_NO_CONTEXT);
        eglDestroyContext(ctx->egl_display, ctx->egl_context);
    }
    /* No eglTerminate: displays are shared per platform, so it would end
     * the other contexts on it, and Mesa unloads its driver there, which
     * leaves its leak reports without names to suppress them by. The display
     * stays initialised until the process ends. */
    ctx->egl_display = EGL_NO_DISPLAY;
}

/* ---- OSMesa ---- */

static sc_gl_proc osmesa_get_proc(const char *name, void *user)
{
    return ((sc_gl_context *)user)->osmesa_get_proc(name);
}

/* The OSMesa attributes of a core context of version major.minor. */
static void osmesa_attribs(int attribs[15], int major, int minor)
{
    const int list[15] = {OSMESA_FORMAT_, GL_RGBA,
                          OSMESA_DEPTH_BITS_, 0,
                          OSMESA_STENCIL_BITS_, 0,
                          OSMESA_ACCUM_BITS_, 0,
                          OSMESA_PROFILE_, OSMESA_CORE_PROFILE_,
                          OSMESA_CONTEXT_MAJOR_VERSION_, major,
                          OSMESA_CONTEXT_MINOR_VERSION_, minor,
                          0};
    memcpy(attribs, list, sizeof list);
}

/* As egl_probe_version: the GL_VERSION of OSMesa's best core context, or
 * else of any context; "" when it has none. */
static void osmesa_probe_version(sc_gl_context *ctx, osmesa_create_fn create, char *version,
                                 size_t size)
{
    int attribs[15];
    osmesa_attribs(attribs, 3, 2);
    static const int any[] = {OSMESA_FORMAT_, GL_RGBA, 0};
    version[0] = 0;
    osmesa_context_t probe = create(attribs, NULL);
    if (!probe)
        probe = create(any, NULL);
    if (!probe)
        return;
    if (ctx->osmesa_make_current(probe, ctx->osmesa_dummy, GL_UNSIGNED_BYTE, 1, 1)) {
        PFNGLGETSTRINGPROC get_string = (PFNGLGETSTRINGPROC)ctx->osmesa_get_proc("glGetString");
        const char *v = get_string ? (const char *)get_string(GL_VERSION) : NULL;
        snprintf(version, size, "%s", v ? v : "");
    }
    ctx->osmesa_destroy(probe);
}

static int osmesa_create(sc_gl_context *ctx, sc_error *err)
{
    static const char *const names[] = {"libOSMesa.so.8", "libOSMesa.so"};
    for (size_t i = 0; i < 2 && !ctx->osmesa_lib; i++)
        ctx->osmesa_lib = dlopen(names[i], RTLD_NOW | RTLD_LOCAL);
    if (!ctx->osmesa_lib)
        return sc_fail(err, NULL, 0, "OSMesa: cannot load libOSMesa.so.8 (%s)", dlerror());
    /* Through a union: ISO C has no cast between object and function
     * pointers, dlsym returns the former. */
    union { void *object; osmesa_create_fn fn; } create;
    union { void *object; osmesa_destroy_fn fn; } destroy;
    union { void *object; osmesa_make_current_fn fn; } make_current;
    union { void *object; osmesa_get_proc_fn fn; } get_proc;
    create.object = dlsym(ctx->osmesa_lib, "OSMesaCreateContextAttribs");
    destroy.object = dlsym(ctx->osmesa_lib, "OSMesaDestroyContext");
    make_current.object = dlsym(ctx->osmesa_lib, "OSMesaMakeCurrent");
    get_proc.object = dlsym(ctx->osmesa_lib, "OSMesaGetProcAddress");
    if (!create.object || !destroy.object || !make_current.object || !get_proc.object)
        return sc_fail(err, NULL, 0,
                       "OSMesa: libOSMesa lacks OSMesaCreateContextAttribs (too old)");
    ctx->osmesa_destroy = destroy.fn;
    ctx->osmesa_make_current = make_current.fn;
    ctx->osmesa_get_proc = get_proc.fn;
    int attribs[15];
    osmesa_attribs(attribs, GL_MAJOR_REQUIRED, GL_MINOR_REQUIRED);
    ctx->osmesa_context = create.fn(attribs, NULL);
    if (!ctx->osmesa_context) {
        char version[200];
        osmesa_probe_version(ctx, create.fn, version, sizeof version);
        if (version[0])
            return sc_gl_fail_version(err, "OSMesa", version, GL_MAJOR_REQUIRED,
                                      GL_MINOR_REQUIRED);
        return sc_fail(err, NULL, 0, "OSMesa: no OpenGL %d.%d core context",
                       GL_MAJOR_REQUIRED, GL_MINOR_REQUIRED);
    }
    if (!ctx->osmesa_make_current(ctx->osmesa_context, ctx->osmesa_dummy,
                                  GL_UNSIGNED_BYTE, 1, 1))
        return sc_fail(err, NULL, 0, "OSMesa: OSMesaMakeCurrent failed");
    ctx->backend = SC_BACKEND_OSMESA;
    snprintf(ctx->description, sizeof ctx->description, "osmesa");
    return sc_gl_load(&ctx->gl, osmesa_get_proc, ctx, GL_MAJOR_REQUIRED,
                      GL_MINOR_REQUIRED, err);
}

static void osmesa_destroy(sc_gl_context *ctx)
{
    if (ctx->osmesa_context)
        ctx->osmesa_destroy(ctx->osmesa_context);
    ctx->osmesa_context = NULL;
    if (ctx->osmesa_lib)
        dlclose(ctx->osmesa_lib);
    ctx->osmesa_lib = NULL;
}

/* ---- common ---- */

static void release(sc_gl_context *ctx)
{
    egl_destroy(ctx);
    osmesa_destroy(ctx);
    memset(ctx, 0, sizeof *ctx);
}

int sc_gl_context_create(const sc_gl_context_desc *desc, sc_gl_context **out,
                         sc_error *err)
{
    static const sc_gl_context_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    *out = NULL;
    sc_gl_context *ctx = sc_alloc(1, sizeof *ctx);
    int status = SC_FAIL;
    sc_error egl_err = {0};
    if (desc->backend != SC_BACKEND_OSMESA) {
        status = egl_create(ctx, desc->debug, &egl_err);
        if (status != SC_OK) {
            release(ctx);
            sc_log(desc->backend == SC_BACKEND_EGL ? SC_LOG_WARN : SC_LOG_INFO,
                   "%s; falling back to OSMesa", egl_err.message);
        }
    }
    if (status != SC_OK) {
        sc_error osmesa_err = {0};
        status = osmesa_create(ctx, &osmesa_err);
        if (status != SC_OK) {
            release(ctx);
            free(ctx);
            /* When EGL was tried, its reason matters as much as OSMesa's. */
            if (desc->backend == SC_BACKEND_OSMESA)
                return sc_fail(err, NULL, 0, "%s", osmesa_err.message);
            return sc_fail(err, NULL, 0, "%s; %s", egl_err.message, osmesa_err.message);
        }
    }
    size_t used = strlen(ctx->description);
    snprintf(ctx->description + used, sizeof ctx->description - used, " %s",
             (const char *)ctx->gl.GetString(GL_RENDERER));
    /* Debug output on every context (Mesa reports API errors and shader
     * compiler messages through it even without a debug context), synchronous
     * so that a message is logged next to the call that caused it. */
    ctx->gl.Enable(GL_DEBUG_OUTPUT);
    ctx->gl.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    ctx->gl.DebugMessageCallback(debug_message, ctx);
    *out = ctx;
    return SC_OK;
}

void sc_gl_context_destroy(sc_gl_context *ctx)
{
    if (!ctx)
        return;
    release(ctx);
    free(ctx);
}

static sc_gl_proc app_get_proc(const char *name, void *user)
{
    return ((sc_gl_context *)user)->app_get_proc(name);
}

int sc_gl_context_wrap(sc_gl_app_get_proc_fn get_proc, sc_gl_context **out, sc_error *err)
{
    *out = NULL;
    sc_gl_context *ctx = sc_alloc(1, sizeof *ctx);
    ctx->app_get_proc = get_proc;
    ctx->backend = SC_BACKEND_DEFAULT;
    if (sc_gl_load(&ctx->gl, app_get_proc, ctx, GL_MAJOR_REQUIRED, GL_MINOR_REQUIRED, err) !=
        SC_OK) {
        free(ctx);
        return SC_FAIL;
    }
    snprintf(ctx->description, sizeof ctx->description, "application %s",
             (const char *)ctx->gl.GetString(GL_RENDERER));
    *out = ctx;
    return SC_OK;
}

int sc_gl_context_is_app(const sc_gl_context *ctx) { return ctx->app_get_proc != NULL; }

int sc_gl_context_make_current(sc_gl_context *ctx, sc_error *err)
{
    if (ctx->app_get_proc)
        return SC_OK;   /* the application makes its context current */
    if (ctx->backend == SC_BACKEND_EGL) {
        /* EGL and OSMesa share Mesa's dispatch library, and EGL skips a
         * make-current of the context it believes current: release first, so
         * that an OSMesa context made current meanwhile cannot stay active. */
        eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (!eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE,
                            ctx->egl_context))
            return sc_fail(err, NULL, 0, "EGL: eglMakeCurrent failed (%s)",
                           egl_error_name(eglGetError()));
        return SC_OK;
    }
    if (!ctx->osmesa_make_current(ctx->osmesa_context, ctx->osmesa_dummy,
                                  GL_UNSIGNED_BYTE, 1, 1))
        return sc_fail(err, NULL, 0, "OSMesa: OSMesaMakeCurrent failed");
    return SC_OK;
}

int sc_gl_context_is_current(const sc_gl_context *ctx)
{
    /* OSMesa keeps no cheap way to ask here: its make-current is cheap. */
    return ctx->backend == SC_BACKEND_EGL && eglGetCurrentContext() == ctx->egl_context;
}

const sc_gl *sc_gl_context_gl(const sc_gl_context *ctx) { return &ctx->gl; }

sc_backend sc_gl_context_backend(const sc_gl_context *ctx) { return ctx->backend; }

const char *sc_gl_context_description(const sc_gl_context *ctx)
{
    return ctx->description;
}
