/* gl_target.c — offscreen framebuffer: creation, clearing, read-back
 * (gl_target.h). */
#include "gl_target.h"

#include <stdlib.h>
#include <string.h>

static GLuint make_texture(const sc_gl *gl, GLenum format, int width, int height)
{
    GLuint tex = 0;
    gl->CreateTextures(GL_TEXTURE_2D, 1, &tex);
    gl->TextureStorage2D(tex, 1, format, width, height);
    /* Read texel for texel: no filtering, no mipmaps. */
    gl->TextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

static int is_integer_format(GLenum format)
{
    return format == GL_R32I || format == GL_RG32I || format == GL_RGBA32I ||
           format == GL_R32UI || format == GL_RGBA32UI;
}

int sc_gl_target_create(const sc_gl *gl, const sc_gl_target_desc *desc,
                        sc_gl_target *target, sc_error *err)
{
    memset(target, 0, sizeof *target);
    if (desc->width <= 0 || desc->height <= 0)
        return sc_fail(err, NULL, 0, "framebuffer size %dx%d is not positive", desc->width,
                       desc->height);
    GLint max_size = 0, max_draw = 0;
    gl->GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    gl->GetIntegerv(GL_MAX_DRAW_BUFFERS, &max_draw);
    if (desc->width > max_size || desc->height > max_size)
        return sc_fail(err, NULL, 0, "framebuffer size %dx%d exceeds the driver's %d",
                       desc->width, desc->height, max_size);
    target->width = desc->width;
    target->height = desc->height;
    gl->CreateFramebuffers(1, &target->framebuffer);
    GLenum draw_buffers[SC_GL_TARGET_MAX_COLOURS];
    int count = 0;
    for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS; i++) {
        draw_buffers[i] = GL_NONE;
        if (!desc->formats[i])
            continue;
        if (i >= max_draw) {
            sc_gl_target_destroy(gl, target);
            return sc_fail(err, NULL, 0, "framebuffer: the driver has %d draw buffers, "
                                         "output %d needs more", max_draw, i);
        }
        target->formats[i] = desc->formats[i];
        target->colour[i] = make_texture(gl, desc->formats[i], desc->width, desc->height);
        gl->NamedFramebufferTexture(target->framebuffer, GL_COLOR_ATTACHMENT0 + i,
                                    target->colour[i], 0);
        draw_buffers[i] = GL_COLOR_ATTACHMENT0 + i;
        count = i + 1;
    }
    target->depth = make_texture(gl, GL_DEPTH_COMPONENT32F, desc->width, desc->height);
    gl->NamedFramebufferTexture(target->framebuffer, GL_DEPTH_ATTACHMENT, target->depth, 0);
    gl->NamedFramebufferDrawBuffers(target->framebuffer, count, draw_buffers);
    GLenum status = gl->CheckNamedFramebufferStatus(target->framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        sc_gl_target_destroy(gl, target);
        /* Each texture is allocated here: an attachment left incomplete
         * is nearly always one the driver had no memory for. */
        return sc_fail(err, NULL, 0, "a %dx%d framebuffer is incomplete (status 0x%x%s): "
                       "the image is too large for this driver; try a smaller size",
                       desc->width, desc->height, status,
                       status == GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT ?
                           ", an attachment the driver could not allocate" : "");
    }
    if (sc_gl_check(gl, "creating the framebuffer", err) != SC_OK) {
        sc_gl_target_destroy(gl, target);
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_gl_target_destroy(const sc_gl *gl, sc_gl_target *target)
{
    if (target->framebuffer)
        gl->DeleteFramebuffers(1, &target->framebuffer);
    for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS; i++)
        if (target->colour[i])
            gl->DeleteTextures(1, &target->colour[i]);
    if (target->depth)
        gl->DeleteTextures(1, &target->depth);
    memset(target, 0, sizeof *target);
}

void sc_gl_target_begin(const sc_gl *gl, const sc_gl_target *target,
                        const float clear[SC_GL_TARGET_MAX_COLOURS][4], unsigned uncleared)
{
    gl->BindFramebuffer(GL_FRAMEBUFFER, target->framebuffer);
    gl->Viewport(0, 0, target->width, target->height);
    for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS; i++) {
        if (!target->colour[i] || (uncleared >> i & 1))
            continue;
        if (is_integer_format(target->formats[i])) {
            GLint value[4] = {(GLint)clear[i][0], (GLint)clear[i][1], (GLint)clear[i][2],
                              (GLint)clear[i][3]};
            gl->ClearNamedFramebufferiv(target->framebuffer, GL_COLOR, i, value);
        } else {
            gl->ClearNamedFramebufferfv(target->framebuffer, GL_COLOR, i, clear[i]);
        }
    }
    const float far_depth = 1.0f;
    gl->ClearNamedFramebufferfv(target->framebuffer, GL_DEPTH, 0, &far_depth);
}

/* Reads a whole texture and flips it to top-down rows. */
static int read_texture(const sc_gl *gl, const sc_gl_target *target, GLuint tex,
                        GLenum format, GLenum type, size_t pixel_bytes, void *out,
                        sc_error *err)
{
    size_t row = pixel_bytes * (size_t)target->width;
    size_t size = row * (size_t)target->height;
    unsigned char *tmp = sc_alloc(size, 1);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->GetTextureImage(tex, 0, format, type, (GLsizei)size, tmp);
    if (sc_gl_check(gl, "reading back the framebuffer", err) != SC_OK) {
        free(tmp);
        return SC_FAIL;
    }
    unsigned char *dst = out;
    for (int y = 0; y < target->height; y++)
        memcpy(dst + row * (size_t)y, tmp + row * (size_t)(target->height - 1 - y), row);
    free(tmp);
    return SC_OK;
}

int sc_gl_target_read(const sc_gl *gl, const sc_gl_target *target, int attachment,
                      GLenum format, GLenum type, size_t pixel_bytes, void *out,
                      sc_error *err)
{
    if (attachment < 0 || attachment >= SC_GL_TARGET_MAX_COLOURS || !target->colour[attachment])
        return sc_fail(err, NULL, 0, "framebuffer has no attachment %d", attachment);
    return read_texture(gl, target, target->colour[attachment], format, type, pixel_bytes, out,
                        err);
}

int sc_gl_target_read_attachment(const sc_gl *gl, const sc_gl_target *target, int attachment,
                                 void *out, sc_error *err)
{
    if (attachment < 0 || attachment >= SC_GL_TARGET_MAX_COLOURS)
        return sc_fail(err, NULL, 0, "framebuffer has no attachment %d", attachment);
    switch (target->formats[attachment]) {
    case GL_R32I:
        return sc_gl_target_read(gl, target, attachment, GL_RED_INTEGER, GL_INT, 4, out, err);
    case GL_RGBA32F:
        return sc_gl_target_read(gl, target, attachment, GL_RGBA, GL_FLOAT, 16, out, err);
    case GL_RGBA8:
    case GL_SRGB8_ALPHA8:
        return sc_gl_target_read(gl, target, attachment, GL_RGBA, GL_UNSIGNED_BYTE, 4, out, err);
    default:
        return sc_fail(err, NULL, 0, "framebuffer attachment %d: no read-back for format 0x%x",
                       attachment, target->formats[attachment]);
    }
}

int sc_gl_target_read_image(const sc_gl *gl, const sc_gl_target *target, int attachment,
                            sc_image *img, sc_error *err)
{
    sc_image_alloc(img, target->width, target->height, 4);
    int status = sc_gl_target_read(gl, target, attachment, GL_RGBA, GL_UNSIGNED_BYTE, 4,
                                   img->pixels, err);
    if (status != SC_OK)
        sc_image_free(img);
    return status;
}

int sc_gl_target_read_depth(const sc_gl *gl, const sc_gl_target *target, float *depth,
                            sc_error *err)
{
    return read_texture(gl, target, target->depth, GL_DEPTH_COMPONENT, GL_FLOAT,
                        sizeof(float), depth, err);
}
