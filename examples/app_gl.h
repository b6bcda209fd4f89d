/* app_gl.h — what the two example applications (embed_gl.c, packed_gl.c)
 * share: an OpenGL 4.5 core context of their own (EGL, Mesa's surfaceless
 * platform), the GL functions they call from their own loader, and view
 * and projection matrices as a GL program builds them. A header of static
 * functions, so that each example stays one file for `cc` to build against
 * the installed library. Define APP_NAME (the program's name, for its
 * messages) before including it. */
#ifndef APP_GL_H
#define APP_GL_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <splinecast.h>

/* The application's GL functions, from its own loader (EGL's here). */
#define GL_FUNCS(X)                                                                        \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                           \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                           \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                         \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                         \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                                   \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                           \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                             \
    X(PFNGLVIEWPORTPROC, Viewport)                                                         \
    X(PFNGLCLEARCOLORPROC, ClearColor)                                                     \
    X(PFNGLCLEARPROC, Clear)                                                               \
    X(PFNGLENABLEPROC, Enable)                                                             \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                       \
    X(PFNGLCREATESHADERPROC, CreateShader)                                                 \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                 \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                               \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                               \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                                 \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                   \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                 \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                                     \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                     \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                         \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                           \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                           \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                                     \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                                     \
    X(PFNGLBUFFERDATAPROC, BufferData)                                                     \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                           \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                   \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                     \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                   \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                                     \
    X(PFNGLFINISHPROC, Finish)
#define DECLARE(type, name) static type gl##name;
GL_FUNCS(DECLARE)

static int fail(const char *what, const sc_error *err)
{
    char text[1024];
    fprintf(stderr, "%s: %s: %s\n", APP_NAME, what, err ? sc_error_text(err, text, sizeof text) : "");
    sc_shutdown();
    return 1;
}

/* The application's own context: EGL on Mesa's surfaceless platform. */
static int make_gl_context(void)
{
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display ? get_display(EGL_PLATFORM_SURFACELESS_MESA,
                                               EGL_DEFAULT_DISPLAY, NULL)
                                 : EGL_NO_DISPLAY;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL) || !eglBindAPI(EGL_OPENGL_API))
        return 0;
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT || !eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
        return 0;
#define LOAD(type, name) gl##name = (type)eglGetProcAddress("gl" #name);
    GL_FUNCS(LOAD)
    return 1;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize(double v[3])
{
    double n = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; c++)
        v[c] /= n;
}

/* gluLookAt with +z up and gluPerspective, column-major. */
static void matrices(const double eye[3], const double target[3], double fovy_deg, double aspect,
                     double znear, double zfar, float view[16], float proj[16])
{
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double up[3] = {0, 0, 1}, s[3], u[3];
    normalize(f);
    cross(f, up, s);
    normalize(s);
    cross(s, f, u);
    memset(view, 0, 16 * sizeof *view);
    for (int c = 0; c < 3; c++) {
        view[c * 4 + 0] = (float)s[c];
        view[c * 4 + 1] = (float)u[c];
        view[c * 4 + 2] = (float)-f[c];
    }
    view[12] = (float)-(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    view[13] = (float)-(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    view[14] = (float)(f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2]);
    view[15] = 1;
    double cot = 1 / tan(0.5 * fovy_deg * 3.14159265358979323846 / 180);
    memset(proj, 0, 16 * sizeof *proj);
    proj[0] = (float)(cot / aspect);
    proj[5] = (float)cot;
    proj[10] = (float)((zfar + znear) / (znear - zfar));
    proj[11] = -1;
    proj[14] = (float)(2 * zfar * znear / (znear - zfar));
}

/* The application's framebuffer, bound: colour and a 24-bit depth buffer,
 * w x h, and the viewport on it; its name, or 0 when it is incomplete. */
static GLuint make_framebuffer(int w, int h)
{
    GLuint fbo, rb[2];
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return 0;
    glViewport(0, 0, w, h);
    return fbo;
}

#endif
