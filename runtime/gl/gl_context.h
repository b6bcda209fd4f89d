/* gl_context.h — an offscreen OpenGL 4.5 core context from EGL (the device
 * platform when a real GPU is present, the surfaceless platform otherwise)
 * or from OSMesa, loaded at run time with dlopen so that libGL and
 * libOSMesa never end up in one program. The context owns its GL function
 * table and routes the driver's debug output to sc_log. Contexts are created,
 * made current and destroyed from one thread. */
#ifndef SC_GL_CONTEXT_H
#define SC_GL_CONTEXT_H

#include "gl_loader.h"
#include "splinecast_options.h"

typedef struct sc_gl_context_desc {
    sc_backend backend;
    int debug;        /* ask for a debug context (more driver messages) */
} sc_gl_context_desc;

typedef struct sc_gl_context sc_gl_context;

/* An application's GetProcAddress (eglGetProcAddress, glXGetProcAddressARB,
 * glfwGetProcAddress, SDL's with a cast, …). */
typedef sc_gl_proc (*sc_gl_app_get_proc_fn)(const char *name);

/* The application's context, current now, its GL table resolved through
 * get_proc: the library never makes it current, installs no debug callback
 * in it and does not destroy it. Its backend is SC_BACKEND_DEFAULT. */
int sc_gl_context_wrap(sc_gl_app_get_proc_fn get_proc, sc_gl_context **out, sc_error *err);
/* Whether ctx is an application's (sc_gl_context_wrap). */
int sc_gl_context_is_app(const sc_gl_context *ctx);

/* Creates the context and makes it current. */
int sc_gl_context_create(const sc_gl_context_desc *desc, sc_gl_context **out,
                         sc_error *err);
void sc_gl_context_destroy(sc_gl_context *ctx);
/* 1 when ctx is the thread's current context in fact (a program's own
 * window context may have been made current since the library's). */
int sc_gl_context_is_current(const sc_gl_context *ctx);
int sc_gl_context_make_current(sc_gl_context *ctx, sc_error *err);

const sc_gl *sc_gl_context_gl(const sc_gl_context *ctx);
/* The backend that was actually used (EGL or OSMESA, never DEFAULT). */
sc_backend sc_gl_context_backend(const sc_gl_context *ctx);
/* "egl-surfaceless", "egl-device" or "osmesa", then GL_RENDERER. */
const char *sc_gl_context_description(const sc_gl_context *ctx);

/* Whether EGL's device platform tries the device whose extension string
 * (eglQueryDeviceStringEXT's EGL_EXTENSIONS) is `extensions`: any device
 * but Mesa's software rasteriser, which the surfaceless platform reaches
 * too; 0 for NULL. */
int sc_egl_device_wanted(const char *extensions);


#endif
