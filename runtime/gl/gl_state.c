/* gl_state.c — saving and restoring the GL state a renderer changes in an
 * application's context (gl_state.h). Queries stall nothing on these
 * drivers: they read the context's own records. */
#include "gl_state.h"

#include <string.h>

#include "shader_contract.h"

static GLboolean enabled(const sc_gl *gl, GLenum cap) { return gl->IsEnabled(cap); }

static void set_enabled(const sc_gl *gl, GLenum cap, GLboolean on)
{
    if (on)
        gl->Enable(cap);
    else
        gl->Disable(cap);
}

void sc_gl_state_save(const sc_gl *gl, sc_gl_state *s)
{
    memset(s, 0, sizeof *s);
    gl->GetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    gl->GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vertex_array);
    gl->GetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    for (int u = 0; u < SC_GL_STATE_UNITS; u++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        gl->GetIntegerv(GL_TEXTURE_BINDING_BUFFER, &s->unit_buffer[u]);
        gl->GetIntegerv(GL_TEXTURE_BINDING_2D, &s->unit_2d[u]);
    }
    gl->ActiveTexture((GLenum)s->active_texture);
    s->depth_test = enabled(gl, GL_DEPTH_TEST);
    s->cull_face = enabled(gl, GL_CULL_FACE);
    s->blend = enabled(gl, GL_BLEND);
    s->framebuffer_srgb = enabled(gl, GL_FRAMEBUFFER_SRGB);
    gl->GetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    gl->GetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    gl->GetIntegerv(GL_CULL_FACE_MODE, &s->cull_mode);
    gl->GetIntegerv(GL_FRONT_FACE, &s->front_face);
    gl->GetIntegerv(GL_POLYGON_MODE, s->polygon_mode);
    gl->GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_framebuffer);
    gl->GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_framebuffer);
    gl->GetIntegerv(GL_VIEWPORT, s->viewport);
    gl->GetInteger64i_v(GL_SHADER_STORAGE_BUFFER_BINDING, SCG_BUFFER_COUNTERS, &s->counters_buffer);
    gl->GetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, SCG_BUFFER_COUNTERS, &s->counters_start);
    gl->GetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, SCG_BUFFER_COUNTERS, &s->counters_size);
    gl->GetIntegerv(GL_PACK_ALIGNMENT, &s->pack_alignment);
    gl->GetIntegerv(GL_UNPACK_ALIGNMENT, &s->unpack_alignment);
    if (s->draw_framebuffer) {
        GLint max = 0;
        gl->GetIntegerv(GL_MAX_DRAW_BUFFERS, &max);
        s->ndraw_buffers = max < SC_GL_STATE_DRAW_BUFFERS ? max : SC_GL_STATE_DRAW_BUFFERS;
        for (int i = 0; i < s->ndraw_buffers; i++)
            gl->GetIntegerv(GL_DRAW_BUFFER0 + (GLenum)i, &s->draw_buffers[i]);
    }
}

void sc_gl_state_first_draw_buffer(const sc_gl *gl, const sc_gl_state *s)
{
    int more = 0;
    for (int i = 1; i < s->ndraw_buffers; i++)
        more |= s->draw_buffers[i] != GL_NONE;
    if (more) {
        GLenum first = (GLenum)s->draw_buffers[0];
        gl->DrawBuffers(1, &first);
    }
}

void sc_gl_state_restore(const sc_gl *gl, const sc_gl_state *s)
{
    gl->UseProgram((GLuint)s->program);
    gl->BindVertexArray((GLuint)s->vertex_array);
    for (int u = 0; u < SC_GL_STATE_UNITS; u++) {
        gl->ActiveTexture(GL_TEXTURE0 + (GLenum)u);
        gl->BindTexture(GL_TEXTURE_BUFFER, (GLuint)s->unit_buffer[u]);
        gl->BindTexture(GL_TEXTURE_2D, (GLuint)s->unit_2d[u]);
    }
    gl->ActiveTexture((GLenum)s->active_texture);
    set_enabled(gl, GL_DEPTH_TEST, s->depth_test);
    set_enabled(gl, GL_CULL_FACE, s->cull_face);
    set_enabled(gl, GL_BLEND, s->blend);
    set_enabled(gl, GL_FRAMEBUFFER_SRGB, s->framebuffer_srgb);
    gl->DepthMask(s->depth_mask);
    gl->DepthFunc((GLenum)s->depth_func);
    gl->CullFace((GLenum)s->cull_mode);
    gl->FrontFace((GLenum)s->front_face);
    /* Core profiles keep one mode for both faces. */
    gl->PolygonMode(GL_FRONT_AND_BACK, (GLenum)s->polygon_mode[0]);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_framebuffer);
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_framebuffer);
    gl->Viewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    /* A size of 0 is a whole-buffer binding (or none). */
    if (s->counters_size > 0)
        gl->BindBufferRange(GL_SHADER_STORAGE_BUFFER, SCG_BUFFER_COUNTERS,
                            (GLuint)s->counters_buffer, (GLintptr)s->counters_start,
                            (GLsizeiptr)s->counters_size);
    else
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, SCG_BUFFER_COUNTERS,
                           (GLuint)s->counters_buffer);
    gl->PixelStorei(GL_PACK_ALIGNMENT, s->pack_alignment);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, s->unpack_alignment);
    if (s->ndraw_buffers) {
        GLenum buffers[SC_GL_STATE_DRAW_BUFFERS];
        for (int i = 0; i < s->ndraw_buffers; i++)
            buffers[i] = (GLenum)s->draw_buffers[i];
        gl->DrawBuffers(s->ndraw_buffers, buffers);
    }
}
