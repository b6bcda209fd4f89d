/* gl_loader.h — the OpenGL function table of one context. The entries are
 * generated from the Khronos registry's core-profile header (see
 * runtime/gl/gl_functions.awk) and resolved through the GetProcAddress of the
 * backend that made the context current (EGL or OSMesa), so the library
 * never links libGL and works the same under both backends. Calls go
 * through the table: gl->DrawArrays(...). */
#ifndef SC_GL_LOADER_H
#define SC_GL_LOADER_H

#include <GL/glcorearb.h>

#include "gl_functions.h"
#include "sc_base.h"

typedef struct sc_gl {
#define SC_GL_MEMBER_(type, name, major, minor) type name;
    SC_GL_FUNCTIONS(SC_GL_MEMBER_)
#undef SC_GL_MEMBER_
    int major, minor;     /* version of the context the table was loaded for */
    int missing;          /* entry points up to that version left NULL */
} sc_gl;

/* Looks up one entry point by its full name ("glDrawArrays"). */
typedef void (*sc_gl_proc)(void);
typedef sc_gl_proc (*sc_gl_get_proc_fn)(const char *name, void *user);

/* Resolves every entry point through get_proc and reads the context's
 * version. Fails when the version is below major.minor. Entry points the
 * driver does not give stay NULL, counted in gl->missing and logged. */
int sc_gl_load(sc_gl *gl, sc_gl_get_proc_fn get_proc, void *user, int major,
               int minor, sc_error *err);

/* "BACKEND: OpenGL 4.5 core is required, the driver offers 3.3 ("3.3 (Core
 * Profile) Mesa …")": the version found (the GL_VERSION string) and the
 * one required, from whichever step found the driver too old. backend may
 * be NULL. */
int sc_gl_fail_version(sc_error *err, const char *backend, const char *version, int major,
                       int minor);

/* In builds without NDEBUG: reads glGetError and, when it is set, logs it
 * with `what` and returns SC_FAIL (filling err). Release builds return SC_OK
 * without asking the driver, which would stall it. */
int sc_gl_check(const sc_gl *gl, const char *what, sc_error *err);

/* After an upload that allocates GPU memory: reads glGetError in every
 * build (an upload that ran out of memory must not pass silently in a
 * release build, and one query per large upload costs nothing next to
 * it). GL_OUT_OF_MEMORY fails with sc_gl_fail_memory's message naming
 * `needed`, the bytes of GPU data the whole scene needs; any other error
 * as sc_gl_check. */
int sc_gl_check_upload(const sc_gl *gl, const char *what, size_t needed, sc_error *err);

/* "out of GPU memory: the scene needs N bytes of GPU data (CAUSE)": the one
 * message for a scene the GPU could not hold, whether the driver said so
 * (GL_OUT_OF_MEMORY) or a budget refused it before anything was sent. */
int sc_gl_fail_memory(sc_error *err, size_t needed, const char *cause);

/* Name of a GL error code ("GL_INVALID_OPERATION"). */
const char *sc_gl_error_name(GLenum code);

#endif
