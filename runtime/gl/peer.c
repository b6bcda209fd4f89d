/* peer.c — the tessellation peers' entry points (peer.h): making,
 * updating, drawing and destroying a peer, handed to GLU's half
 * (peer_glu.c) or the tessellation shaders' (peer_tess.c), which share
 * peer_common.c. */
#include "peer_private.h"

#include <stdlib.h>

int sc_peer_create(const sc_gl *gl, const sc_scene *scene, const sc_peer_config *config,
                   sc_peer **out, sc_error *err)
{
    *out = NULL;
    if (!(config->tolerance_px > 0))
        return sc_fail(err, NULL, 0, "peer tolerance %g px is not positive", config->tolerance_px);
    if (scene->terrain)
        return sc_fail(err, NULL, 0, "the tessellation peers draw NURBS surfaces, not terrains");
    sc_peer *p = sc_alloc(1, sizeof *p);
    p->gl = gl;
    p->scene = scene;
    p->config = *config;
    sc_peer_upload_colours(p);
    gl->CreateVertexArrays(1, &p->vertex_array);
    int status = config->type == SC_PEER_TYPE_GLU ? sc_peer_glu_create(p, err)
                                                  : sc_peer_tess_create(p, err);
    if (status != SC_OK) {
        sc_peer_destroy(p);
        return SC_FAIL;
    }
    *out = p;
    return SC_OK;
}

void sc_peer_destroy(sc_peer *p)
{
    if (!p)
        return;
    const sc_gl *gl = p->gl;
    if (p->config.type == SC_PEER_TYPE_GLU)
        sc_peer_glu_destroy(p);
    else
        sc_peer_tess_destroy(p);
    sc_gl_target_destroy(gl, &p->target);
    GLuint buffers[3] = {p->vertex_buffer, p->index_buffer, p->colour_buffer};
    gl->DeleteBuffers(3, buffers);
    if (p->colour_texture)
        gl->DeleteTextures(1, &p->colour_texture);
    if (p->vertex_array)
        gl->DeleteVertexArrays(1, &p->vertex_array);
    if (p->aov_program)
        gl->DeleteProgram(p->aov_program);
    if (p->colour_program)
        gl->DeleteProgram(p->colour_program);
    if (p->query)
        gl->DeleteQueries(1, &p->query);
    free(p);
}

int sc_peer_update(sc_peer *p, const sc_camera *cam, sc_error *err)
{
    return p->config.type == SC_PEER_TYPE_GLU ? sc_peer_glu_update(p, cam, err)
                                              : sc_peer_tess_update(p, err);
}

int sc_peer_draw(sc_peer *p, const sc_camera *cam, int aovs, sc_error *err)
{
    const sc_gl *gl = p->gl;
    double t0 = sc_now();
    float vp[16];
    if (sc_peer_begin(p, cam, aovs || !p->config.aovs_on_demand, vp, err) != SC_OK)
        return SC_FAIL;
    int status = p->config.type == SC_PEER_TYPE_GLU ? sc_peer_glu_draw(p, err)
                                                    : sc_peer_tess_draw(p, cam, vp, err);
    gl->Disable(GL_FRAMEBUFFER_SRGB);
    gl->BindVertexArray(0);
    gl->UseProgram(0);
    gl->Finish();
    p->stats.draw_ms = 1e3 * (sc_now() - t0);
    return status == SC_OK ? sc_gl_check(gl, "drawing a peer's frame", err) : SC_FAIL;
}

int sc_peer_read(sc_peer *p, sc_image *img, sc_aov *aov, sc_error *err)
{
    if (!p->target.framebuffer)
        return sc_fail(err, NULL, 0, "nothing drawn yet");
    /* A frame drawn without the AOVs: drawn again with them, at its camera. */
    if (!p->frame_aovs) {
        sc_camera cam = p->camera;
        if (sc_peer_draw(p, &cam, 1, err) != SC_OK)
            return SC_FAIL;
    }
    return sc_peer_read_target(p, img, aov, err);
}

void sc_peer_stats_get(const sc_peer *p, sc_peer_stats *stats)
{
    *stats = p->stats;
}
