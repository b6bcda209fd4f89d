/* gl_target.h — the offscreen framebuffer every render draws into: colour
 * attachments at the fragment output locations the programs write (8-bit
 * colour, integer and float AOVs — gen/shader_contract.h fixes which is
 * where)
 * and a float depth texture (a texture rather than a renderbuffer, so that
 * it can be read back). Read-back turns the GL's bottom-up rows into the
 * library's top-down ones. */
#ifndef SC_GL_TARGET_H
#define SC_GL_TARGET_H

#include "gl_loader.h"
#include "image.h"

enum { SC_GL_TARGET_MAX_COLOURS = 8 };

typedef struct sc_gl_target_desc {
    int width, height;
    /* Internal format of the attachment at fragment output location i
     * (GL_SRGB8_ALPHA8, GL_RGBA8, GL_R32I, GL_RGBA32F, …); 0: none. */
    GLenum formats[SC_GL_TARGET_MAX_COLOURS];
} sc_gl_target_desc;

typedef struct sc_gl_target {
    int width, height;
    GLenum formats[SC_GL_TARGET_MAX_COLOURS];
    GLuint colour[SC_GL_TARGET_MAX_COLOURS];
    GLuint depth;             /* GL_DEPTH_COMPONENT32F */
    GLuint framebuffer;
} sc_gl_target;

int sc_gl_target_create(const sc_gl *gl, const sc_gl_target_desc *desc,
                        sc_gl_target *target, sc_error *err);
void sc_gl_target_destroy(const sc_gl *gl, sc_gl_target *target);
/* Binds the framebuffer, sets the viewport, clears attachment i to clear[i]
 * (integer attachments to its values truncated) unless bit i of `uncleared`
 * is set, and depth to 1. */
void sc_gl_target_begin(const sc_gl *gl, const sc_gl_target *target,
                        const float clear[SC_GL_TARGET_MAX_COLOURS][4], unsigned uncleared);
/* Attachment i as width × height pixels of `format`/`type` (pixel_bytes
 * each), row 0 at the top. */
int sc_gl_target_read(const sc_gl *gl, const sc_gl_target *target, int attachment,
                      GLenum format, GLenum type, size_t pixel_bytes, void *out,
                      sc_error *err);
/* Attachment i whole, in the pixel format its internal format reads back
 * as without conversion: 4 ints (GL_R32I: 1), 4 floats (GL_RGBA32F) or 4
 * bytes (8-bit formats) per pixel, row 0 at the top. */
int sc_gl_target_read_attachment(const sc_gl *gl, const sc_gl_target *target, int attachment,
                                 void *out, sc_error *err);
/* An 8-bit attachment as an RGBA image (allocated here). */
int sc_gl_target_read_image(const sc_gl *gl, const sc_gl_target *target, int attachment,
                            sc_image *img, sc_error *err);
/* width × height window-space depths in [0, 1], row 0 at the top. */
int sc_gl_target_read_depth(const sc_gl *gl, const sc_gl_target *target, float *depth,
                            sc_error *err);

#endif
