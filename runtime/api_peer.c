/* api_peer.c — the public interface of the tessellation peers
 * (splinecast.h, runtime/gl/peer.h): handles, argument checks, and frames
 * made from what a peer drew. */
#include "api_private.h"

typedef struct peer_object {
    context_object *context;
    scene_object *scene;
    sc_peer *peer;
} peer_object;

static void destroy_peer_object(peer_object *p)
{
    if (sc_api_make_current(p->context, NULL) == SC_OK)
        sc_peer_destroy(p->peer);
    sc_api_release_scene(p->scene);
    free(p);
}

int sc_make_peer(sc_context_id ctx, sc_scene_id scene, const sc_peer_desc *desc,
                 sc_peer_id *out, sc_error *err)
{
    static const sc_peer_desc defaults = {0};
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!desc)
        desc = &defaults;
    context_object *c = sc_api_pool_get(&sc_api_contexts, ctx.id, err);
    scene_object *s = c ? sc_api_pool_get(&sc_api_scenes, scene.id, err) : NULL;
    if (!s || sc_api_check_enum(desc->kind, SC_PEER_TESS_SHADER + 1, "sc_peer_desc.kind", err))
        return SC_FAIL;
    if (!(desc->tolerance_px == 0 || (desc->tolerance_px >= 0.001 && desc->tolerance_px <= 100)))
        return sc_api_invalid(err, "sc_peer_desc.tolerance_px", PROBLEM_RANGE,
                              "%g (0 for the default, or 0.001 to 100 pixels)", desc->tolerance_px);
    if (desc->aovs != SC_AOVS_ON_DEMAND && desc->aovs != SC_AOVS_ALWAYS)
        return sc_api_invalid(err, "sc_peer_desc.aovs", PROBLEM_RANGE,
                              "SC_AOVS_ON_DEMAND (0) or SC_AOVS_ALWAYS (1)");
    if (sc_api_make_current(c, err) != SC_OK)
        return SC_FAIL;
    sc_peer_config config = {
        .type = desc->kind == SC_PEER_GLU ? SC_PEER_TYPE_GLU : SC_PEER_TYPE_TESS,
        .tolerance_px = desc->tolerance_px ? desc->tolerance_px : 0.1,
        .aovs_on_demand = desc->aovs == SC_AOVS_ON_DEMAND,
    };
    peer_object *p = sc_alloc(1, sizeof *p);
    p->context = c;
    p->scene = s;
    if (sc_peer_create(sc_gl_context_gl(c->gl), &s->scene, &config, &p->peer, err) != SC_OK) {
        free(p);
        return SC_FAIL;
    }
    s->users++;
    if ((out->id = sc_api_pool_insert(&sc_api_peers, p, err)) == 0) {
        destroy_peer_object(p);
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_destroy_peer(sc_peer_id peer)
{
    peer_object *p = sc_api_pool_get(&sc_api_peers, peer.id, NULL);
    if (!p)
        return;
    sc_api_pool_remove(&sc_api_peers, peer.id);
    destroy_peer_object(p);
}

void sc_api_destroy_peers(const context_object *c)
{
    for (int i = 0; i < sc_api_peers.count; i++) {
        peer_object *p = sc_api_peers.slots[i].object;
        if (p && (!c || p->context == c)) {
            sc_api_pool_remove(&sc_api_peers, sc_api_slot_id(&sc_api_peers, i));
            destroy_peer_object(p);
        }
    }
    if (!c) {
        free(sc_api_peers.slots);
        sc_api_peers.slots = NULL;
        sc_api_peers.count = 0;
    }
}

/* The peer of a handle, current, and the camera for its scene. */
static peer_object *peer_and_camera(sc_peer_id peer, const sc_camera_desc *camera,
                                    sc_camera *cam, sc_error *err)
{
    peer_object *p = sc_api_pool_get(&sc_api_peers, peer.id, err);
    if (!p || (cam && sc_api_make_camera(camera, &p->scene->scene, cam, err) != SC_OK) ||
        sc_api_make_current(p->context, err) != SC_OK)
        return NULL;
    return p;
}

int sc_update_peer(sc_peer_id peer, const sc_camera_desc *camera, sc_error *err)
{
    sc_camera cam;
    peer_object *p = peer_and_camera(peer, camera, &cam, err);
    return p ? sc_peer_update(p->peer, &cam, err) : SC_FAIL;
}

int sc_draw_peer(sc_peer_id peer, const sc_camera_desc *camera, sc_error *err)
{
    sc_camera cam;
    peer_object *p = peer_and_camera(peer, camera, &cam, err);
    return p ? sc_peer_draw(p->peer, &cam, 0, err) : SC_FAIL;
}

int sc_read_peer_frame(sc_peer_id peer, sc_frame_id *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    peer_object *p = peer_and_camera(peer, NULL, NULL, err);
    if (!p)
        return SC_FAIL;
    frame_object *f = sc_alloc(1, sizeof *f);
    if (sc_peer_read(p->peer, &f->rgba, &f->aov, err) != SC_OK) {
        free(f);
        return SC_FAIL;
    }
    sc_peer_stats st;
    sc_peer_stats_get(p->peer, &st);
    f->render_ms = st.draw_ms;
    if ((out->id = sc_api_pool_insert(&sc_api_frames, f, err)) != 0)
        return SC_OK;
    sc_image_free(&f->rgba);
    sc_aov_free(&f->aov);
    free(f);
    return SC_FAIL;
}

int sc_query_peer_info(sc_peer_id peer, sc_peer_info *info, sc_error *err)
{
    peer_object *p = sc_api_pool_get(&sc_api_peers, peer.id, err);
    if (!p)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    sc_peer_stats st;
    sc_peer_stats_get(p->peer, &st);
    *info = (sc_peer_info){
        .tessellate_ms = st.tessellate_ms,
        .upload_ms = st.upload_ms,
        .draw_ms = st.draw_ms,
        .vertices = st.vertices,
        .triangles = st.triangles,
        .gpu_bytes = st.gpu_bytes,
        .compile_ms = st.compile_ms,
        .skipped_surfaces = st.skipped_surfaces,
        .tessellator_errors = st.tessellator_errors,
    };
    return SC_OK;
}
