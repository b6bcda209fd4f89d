/* api_pack.c — the public interface of packs (splinecast.h): a scene's GPU
 * data written at build time (sc_save_pack) and a renderer drawing it at
 * run time (sc_make_renderer with sc_renderer_desc.pack). */
#include "api_private.h"

int sc_save_pack(sc_scene_id scene, const sc_renderer_desc *desc, const char *path,
                 sc_error *err)
{
    static const sc_renderer_desc defaults = {0};
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    if (!path)
        return sc_api_invalid(err, "path", PROBLEM_NULL, NULL);
    sc_render_desc internal;
    if (desc && desc->pack)
        return sc_api_invalid(err, "sc_renderer_desc.pack", PROBLEM_RANGE,
                              "a pack is written from a scene, not from another pack");
    if (sc_api_render_desc(desc ? desc : &defaults, &internal, err) != SC_OK)
        return SC_FAIL;
    /* The choices of an accuracy target depend on a view; a pack holds
     * explicit settings only. */
    if (desc && (desc->accuracy_px != 0 || desc->accuracy_normal_deg != 0))
        return sc_api_invalid(err, "sc_renderer_desc.accuracy_px", PROBLEM_RANGE,
                              "a pack holds explicit settings (hulls, iterations, tolerance), "
                              "not an accuracy target");
    sc_pack pack;
    if (sc_pack_build(&s->scene, &internal, &pack, err) != SC_OK)
        return SC_FAIL;
    int status = sc_pack_write(path, &pack, err);
    sc_pack_free(&pack);
    return status;
}

/* The fields a pack decided when it was written. */
static int check_packed_desc(const sc_renderer_desc *d, sc_error *err)
{
    const char *fixed = d->hull_split ? "hull_split" : d->hull_divisions ? "hull_divisions"
                      : d->hull_tolerance != 0 ? "hull_tolerance" : d->hull_max_depth ? "hull_max_depth"
                      : d->start ? "start" : d->max_iters ? "max_iters"
                      : d->tolerance_px != 0 ? "tolerance_px" : d->show ? "show"
                      : d->generic ? "generic" : d->unroll_max_degree ? "unroll_max_degree"
                      : d->trim ? "trim" : d->trim_iters ? "trim_iters"
                      : d->termination ? "termination" : d->method ? "method" : d->eval ? "eval"
                      : d->accuracy_px != 0 || d->accuracy_normal_deg != 0 ? "accuracy_px"
                      : NULL;
    if (fixed)
        return sc_api_invalid(err, "sc_renderer_desc", PROBLEM_RANGE,
                              "%s is fixed by the pack (give it to `splinecast pack`)", fixed);
    return SC_OK;
}

int sc_api_make_packed_renderer(context_object *c, sc_scene_id scene,
                                const sc_renderer_desc *desc, sc_renderer_id *out,
                                sc_error *err)
{
    if (scene.id != 0)
        return sc_api_invalid(err, "scene", PROBLEM_RANGE,
                              "give the zero handle with sc_renderer_desc.pack");
    sc_render_desc internal;
    if (check_packed_desc(desc, err) != SC_OK ||
        sc_api_render_desc(desc, &internal, err) != SC_OK ||
        sc_api_make_current(c, err) != SC_OK)
        return SC_FAIL;
    internal.programs = desc->own_programs ? NULL : c->programs;
    sc_pack pack;
    if (sc_pack_read(desc->pack, &pack, err) != SC_OK)
        return SC_FAIL;
    renderer_object *r = sc_alloc(1, sizeof *r);
    r->context = c;
    int status = sc_renderer_create_packed(sc_gl_context_gl(c->gl), &pack, &internal,
                                           &r->renderer, err);
    sc_pack_free(&pack);
    if (status != SC_OK) {
        free(r);
        return SC_FAIL;
    }
    if ((out->id = sc_api_pool_insert(&sc_api_renderers, r, err)) == 0) {
        sc_api_destroy_renderer_object(r);
        return SC_FAIL;
    }
    return SC_OK;
}
