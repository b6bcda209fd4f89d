/* gl_deferred.h — deferred shading of a terrain (gl_deferred.c). */
#ifndef SC_GL_DEFERRED_H
#define SC_GL_DEFERRED_H

#include "gl_render_private.h"

/* Shades every pixel the renderer's target hits from its AOVs (the domain
 * point gives the patch and its barycentric point; the normal is the
 * patch's own) into the colour attachment, in linear light (the caller
 * has GL_FRAMEBUFFER_SRGB on). eye: the frame's, world space. */
int sc_deferred_shade(sc_renderer *r, const double eye[3], sc_error *err);

#endif
