/* gl_embed.c — a renderer's draw into the application's own framebuffer
 * (gl_render.h, sc_renderer_draw_app): the application's view and
 * projection matrices instead of a camera, its bound framebuffer, viewport
 * and depth buffer instead of the renderer's target, so that the ray-cast
 * surfaces' depths (gl_FragDepth of the hit, not of the hull) meet the
 * application's own geometry in the ordinary depth test. The GL state the
 * draw changes is saved and restored (gl_state.h). */
#include "gl_render_private.h"

#include <string.h>

#include "gl_state.h"
#include "shader_contract.h"

/* eye = -A⁻¹·t for the view [A | t] (column-major), and the view direction:
 * minus the eye space's z axis in world space. Fails when A is singular. */
static int view_eye(const float v[16], double eye[3], double fwd[3])
{
    double a[3][3];
    for (int row = 0; row < 3; row++)
        for (int col = 0; col < 3; col++)
            a[row][col] = v[col * 4 + row];
    double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    if (!(fabs(det) > 1e-30) || !isfinite(det))
        return SC_FAIL;
    double inv[3][3] = {
        {c00 / det, (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det,
         (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det},
        {c01 / det, (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det,
         (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det},
        {c02 / det, (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det,
         (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det},
    };
    double t[3] = {v[12], v[13], v[14]}, len = 0;
    for (int r = 0; r < 3; r++) {
        eye[r] = -(inv[r][0] * t[0] + inv[r][1] * t[1] + inv[r][2] * t[2]);
        fwd[r] = -a[2][r];
        len += fwd[r] * fwd[r];
    }
    for (int r = 0; r < 3; r++)
        fwd[r] /= sqrt(len);
    return SC_OK;
}

/* The nearest-distance texture manual-termination programs read, far
 * everywhere (no read-back from the application's framebuffer: those
 * programs then terminate nothing early), for a viewport of w × h. */
static void far_nearest_texture(sc_renderer *r, int w, int h)
{
    const sc_gl *gl = r->gl;
    int tw = (w + SCG_NEAREST_TILE - 1) / SCG_NEAREST_TILE;
    int th = (h + SCG_NEAREST_TILE - 1) / SCG_NEAREST_TILE;
    if (!r->app_nearest || r->app_nearest_w != tw || r->app_nearest_h != th) {
        if (r->app_nearest)
            gl->DeleteTextures(1, &r->app_nearest);
        gl->CreateTextures(GL_TEXTURE_2D, 1, &r->app_nearest);
        gl->TextureStorage2D(r->app_nearest, 1, GL_R32F, tw, th);
        gl->TextureParameteri(r->app_nearest, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl->TextureParameteri(r->app_nearest, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        static const float far = 3.0e38f;
        gl->ClearTexImage(r->app_nearest, 0, GL_RED, GL_FLOAT, &far);
        r->app_nearest_w = tw;
        r->app_nearest_h = th;
    }
    gl->BindTextureUnit(SCG_UNIT_NEAREST_T, r->app_nearest);
}

int sc_renderer_draw_app(sc_renderer *r, const float view[16], const float proj[16],
                         sc_error *err)
{
    const sc_gl *gl = r->gl;
    double eye[3], fwd[3];
    if (view_eye(view, eye, fwd) != SC_OK)
        return sc_fail(err, NULL, 0, "the view matrix is singular: it has no eye");
    /* The rays start at the eye: a perspective projection (w = -z_eye, up
     * to scale), whose depth the programs write as the fixed function
     * would. */
    if (!(proj[15] == 0 && proj[11] != 0 && proj[3] == 0 && proj[7] == 0 && proj[5] != 0))
        return sc_fail(err, NULL, 0,
                       "the projection is not a perspective one (its last row must be "
                       "(0, 0, -1, 0), as gluPerspective and glFrustum make it)");
    GLint clip_depth = GL_NEGATIVE_ONE_TO_ONE;
    GLfloat range[2] = {0, 1};
    gl->GetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth);
    gl->GetFloatv(GL_DEPTH_RANGE, range);
    if (clip_depth != GL_NEGATIVE_ONE_TO_ONE || range[0] != 0 || range[1] != 1)
        return sc_fail(err, NULL, 0,
                       "the programs write depth for glClipControl's GL_NEGATIVE_ONE_TO_ONE "
                       "and glDepthRange(0, 1), the defaults; the context has %s and [%g, %g]",
                       clip_depth == GL_ZERO_TO_ONE ? "GL_ZERO_TO_ONE" : "another mode",
                       range[0], range[1]);
    GLenum complete = gl->CheckFramebufferStatus(GL_DRAW_FRAMEBUFFER);
    if (complete != GL_FRAMEBUFFER_COMPLETE)
        return sc_fail(err, NULL, 0, "the framebuffer bound for drawing is not complete (%s)",
                       complete == GL_FRAMEBUFFER_UNDEFINED
                           ? "GL_FRAMEBUFFER_UNDEFINED: the context has no default framebuffer; "
                             "bind a framebuffer object"
                           : "bind a complete one, with a depth attachment");
    sc_gl_state saved;
    sc_gl_state_save(gl, &saved);
    int vw = saved.viewport[2], vh = saved.viewport[3];
    if (vw <= 0 || vh <= 0)
        return sc_fail(err, NULL, 0, "the viewport is empty (%d x %d)", vw, vh);
    float vp[16];
    sc_render_eye_projection(view, proj, vp);
    /* One pixel at unit distance: 2·tan(fovy/2) / height, and proj[5] is
     * cot(fovy/2). */
    float footprint = (float)(2.0 / (fabs(proj[5]) * vh));
    sc_gl_state_first_draw_buffer(gl, &saved);
    gl->DepthMask(GL_TRUE);
    gl->Disable(GL_BLEND);
    gl->PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    int status;
    r->frame_aovs = !colour_frames(&r->desc);   /* the application's frame: no AOVs */
    if (r->desc.ert == SC_TERMINATION_PEEL) {
        /* Peeling needs depth buffers of its own: the frame is peeled in
         * the renderer's target at the viewport's size, then its colour
         * and depth are composed into the application's framebuffer under
         * its depth test. */
        memcpy(r->camera.eye, eye, sizeof r->camera.eye);
        r->camera.width = vw;
        r->camera.height = vh;
        status = sc_render_begin_target(r, vw, vh, err);
        if (status == SC_OK)
            status = sc_render_hulls(r, eye, fwd, vp, footprint, 1, err);
        gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)saved.draw_framebuffer);
        gl->Viewport(saved.viewport[0], saved.viewport[1], vw, vh);
        if (saved.framebuffer_srgb)
            gl->Enable(GL_FRAMEBUFFER_SRGB);
        else
            gl->Disable(GL_FRAMEBUFFER_SRGB);
        sc_gl_state_first_draw_buffer(gl, &saved);
        gl->Enable(GL_DEPTH_TEST);
        gl->DepthFunc(GL_LESS);
        gl->DepthMask(GL_TRUE);
        if (status == SC_OK)
            status = sc_peel_composite(r, saved.viewport, err);
    } else {
        if (manual_ert(r->desc.ert))
            far_nearest_texture(r, vw, vh);
        status = sc_render_hulls(r, eye, fwd, vp, footprint, 0, err);
    }
    sc_gl_state_restore(gl, &saved);
    if (status != SC_OK)
        return SC_FAIL;
    return sc_gl_check(gl, "drawing into the application's framebuffer", err);
}
