/* gl_loader.c — fills the generated GL function table from a context's
 * GetProcAddress and checks the context's version (gl_loader.h). */
#include "gl_loader.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "4.6 (Core Profile) Mesa 22.3.6", "OpenGL ES 3.2 Mesa …": the first
 * number pair. */
static void parse_version(const char *version, int *major, int *minor)
{
    const char *digits = version;
    while (*digits && (*digits < '0' || *digits > '9'))
        digits++;
    char *end;
    *major = (int)strtol(digits, &end, 10);
    *minor = *end == '.' ? (int)strtol(end + 1, NULL, 10) : 0;
}

int sc_gl_fail_version(sc_error *err, const char *backend, const char *version, int major,
                       int minor)
{
    int have_major, have_minor;
    parse_version(version, &have_major, &have_minor);
    return sc_fail(err, NULL, 0,
                   "%s%sOpenGL %d.%d core is required, the driver offers %d.%d (\"%s\")",
                   backend ? backend : "", backend ? ": " : "", major, minor, have_major,
                   have_minor, version);
}

int sc_gl_load(sc_gl *gl, sc_gl_get_proc_fn get_proc, void *user, int major,
               int minor, sc_error *err)
{
    memset(gl, 0, sizeof *gl);
    /* glGetIntegerv(GL_MAJOR_VERSION) is 3.0+: read the version string
     * first, so that an old context gets a clear message, not a crash. */
    gl->GetString = (PFNGLGETSTRINGPROC)get_proc("glGetString", user);
    if (!gl->GetString)
        return sc_fail(err, NULL, 0, "OpenGL: no glGetString (no current context?)");
    const char *version = (const char *)gl->GetString(GL_VERSION);
    if (!version)
        return sc_fail(err, NULL, 0, "OpenGL: glGetString(GL_VERSION) failed (no current context?)");
    int have_major, have_minor;
    parse_version(version, &have_major, &have_minor);
    if (have_major * 100 + have_minor < major * 100 + minor)
        return sc_gl_fail_version(err, NULL, version, major, minor);
    gl->major = have_major;
    gl->minor = have_minor;

    /* A driver may lack an entry point of its version that nobody calls
     * (Mesa's OSMesa has no glGetnCompressedTexImage once EGL has set up the
     * shared dispatch): leave it NULL and say so, rather than refuse. */
    const char *first_missing = NULL;
#define SC_GL_RESOLVE_(type, name, fmajor, fminor)                                  \
    gl->name = (type)get_proc("gl" #name, user);                                    \
    if (!gl->name && fmajor * 100 + fminor <= major * 100 + minor) {                \
        gl->missing++;                                                              \
        if (!first_missing)                                                         \
            first_missing = "gl" #name;                                             \
    }
    SC_GL_FUNCTIONS(SC_GL_RESOLVE_)
#undef SC_GL_RESOLVE_
    if (gl->missing)
        sc_log(SC_LOG_INFO, "OpenGL %s: %d entry points missing (first %s)", version,
               gl->missing, first_missing);
    return SC_OK;
}

const char *sc_gl_error_name(GLenum code)
{
    switch (code) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: return "unknown GL error";
    }
}

int sc_gl_fail_memory(sc_error *err, size_t needed, const char *cause)
{
    return sc_fail(err, NULL, 0, "out of GPU memory: the scene needs %zu bytes of GPU data (%s)",
                   needed, cause);
}

/* glGetError, drained so that the next check reports its own error; an
 * error found is logged and returned in err, GL_OUT_OF_MEMORY with the
 * scene's size when `needed` is known. */
static int check_error(const sc_gl *gl, const char *what, size_t needed, sc_error *err)
{
    GLenum code = gl->GetError();
    if (code == GL_NO_ERROR)
        return SC_OK;
    for (int i = 0; i < 16 && gl->GetError() != GL_NO_ERROR; i++)
        ;
    sc_log(SC_LOG_ERROR, "OpenGL error %s after %s", sc_gl_error_name(code), what);
    if (code == GL_OUT_OF_MEMORY && needed) {
        char cause[160];
        snprintf(cause, sizeof cause, "GL_OUT_OF_MEMORY after %s", what);
        return sc_gl_fail_memory(err, needed, cause);
    }
    return sc_fail(err, NULL, 0, "OpenGL error %s after %s", sc_gl_error_name(code), what);
}

int sc_gl_check(const sc_gl *gl, const char *what, sc_error *err)
{
#ifdef NDEBUG
    (void)gl;
    (void)what;
    (void)err;
    return SC_OK;
#else
    return check_error(gl, what, 0, err);
#endif
}

int sc_gl_check_upload(const sc_gl *gl, const char *what, size_t needed, sc_error *err)
{
    return check_error(gl, what, needed, err);
}
