/* gl_context_util.h — the GL contexts the GL tests share (gl_context_util.c):
 * one per backend, made on first use and kept for the whole run, since
 * making a context costs more than most GL tests. */
#ifndef SC_TEST_GL_CONTEXT_UTIL_H
#define SC_TEST_GL_CONTEXT_UTIL_H

#include "gl_context.h"

/* The context of a backend, made current; NULL (with the reason in *why)
 * when the machine cannot make one. SC_BACKEND_DEFAULT: EGL, else OSMesa. */
sc_gl_context *test_gl_context(sc_backend backend, const char **why);

/* The first line of a GL test: the default backend's context as `name`,
 * or the test skipped with the reason (test.h's SKIP). */
#define TEST_NEED_GL_CONTEXT(name)                                                \
    const char *name##_why = "";                                                  \
    sc_gl_context *name = test_gl_context(SC_BACKEND_DEFAULT, &name##_why);       \
    if (!name)                                                                    \
        SKIP("no GL context: %s", name##_why)

#endif
