/* gl_context_util.c — the GL tests' shared contexts (gl_context_util.h). */
#include "gl_context_util.h"

/* The context of a backend, created once; NULL (with the reason in
 * *why) when the machine cannot make one. */
sc_gl_context *test_gl_context(sc_backend backend, const char **why)
{
    if (backend == SC_BACKEND_DEFAULT) {
        sc_gl_context *ctx = test_gl_context(SC_BACKEND_EGL, why);
        return ctx ? ctx : test_gl_context(SC_BACKEND_OSMESA, why);
    }
    static sc_gl_context *contexts[3];
    static sc_error errors[3];
    static int tried[3];
    if (!tried[backend]) {
        tried[backend] = 1;
        sc_gl_context_desc desc = {.backend = backend};
        sc_gl_context_create(&desc, &contexts[backend], &errors[backend]);
    }
    *why = errors[backend].message;
    if (contexts[backend] && sc_gl_context_make_current(contexts[backend], NULL) != SC_OK)
        return NULL;
    return contexts[backend];
}
