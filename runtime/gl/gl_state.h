/* gl_state.h — the GL state a renderer changes when it draws in a context
 * that is not its own (an application's), saved before and put back after,
 * so that the application's next draw finds what it left. The list is the
 * one docs/api.md gives ("Drawing into the application's GL"). */
#ifndef SC_GL_STATE_H
#define SC_GL_STATE_H

#include "gl_loader.h"

enum { SC_GL_STATE_UNITS = 7, SC_GL_STATE_DRAW_BUFFERS = 8 };

typedef struct sc_gl_state {
    GLint program, vertex_array, active_texture;
    GLint unit_buffer[SC_GL_STATE_UNITS];  /* GL_TEXTURE_BUFFER binding per unit */
    GLint unit_2d[SC_GL_STATE_UNITS];      /* GL_TEXTURE_2D binding per unit */
    GLboolean depth_test, depth_mask, cull_face, blend, framebuffer_srgb;
    GLint depth_func, cull_mode, front_face, polygon_mode[2];
    GLint draw_framebuffer, read_framebuffer, viewport[4];
    GLint pack_alignment, unpack_alignment;
    int ndraw_buffers;                     /* of a bound framebuffer object */
    GLint draw_buffers[SC_GL_STATE_DRAW_BUFFERS];
    /* the shader storage binding the programs count in, and its range */
    GLint64 counters_buffer, counters_start, counters_size;
} sc_gl_state;

void sc_gl_state_save(const sc_gl *gl, sc_gl_state *s);
void sc_gl_state_restore(const sc_gl *gl, const sc_gl_state *s);

/* With a framebuffer object bound that draws to more than one buffer,
 * limits it to its first (the programs' colour is location 0, their AOVs
 * must not land in the application's other attachments); restored by
 * sc_gl_state_restore. */
void sc_gl_state_first_draw_buffer(const sc_gl *gl, const sc_gl_state *s);

#endif
