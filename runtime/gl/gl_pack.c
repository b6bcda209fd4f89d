/* gl_pack.c — a renderer's GPU data as a pack (pack_file.h): built from a
 * scene without a GL context (`splinecast pack`, at build time), and a
 * renderer made from one (at run time) that uploads it as it is, with the
 * programs of its keys from the context's program cache — which reads
 * them from a `splinecast gen` folder when it has one — so that a program
 * shipping a pack and generated GLSL needs neither the scene's readers
 * and preparation nor the compiler. */
#include "gl_render_private.h"

#include <stdlib.h>
#include <string.h>

#include "gl_pack.h"
#include "scene_keys.h"
#include "gpu_layout.h"

_Static_assert(sizeof(gpu_vertex) == SC_PACK_VERTEX_BYTES, "a pack's vertex is the GPU's");
_Static_assert((int)SCG_RECORD_TEXELS == (int)SC_PACK_RECORD_TEXELS, "a pack's records are the GPU's");
_Static_assert(SCG_KEY_MAX <= SC_PACK_KEY_BYTES, "a pack holds any key");

/* A renderer's preparation without GL: keys, patches, hulls, staged data. */
static void free_unsent(sc_renderer *r)
{
    sc_gpu_data_free(NULL, &r->data);
    sc_hulls_free(&r->hulls);
    for (int s = 0; r->patches && s < r->scene->nsurfaces; s++)
        sc_patch_list_free(&r->patches[s]);
    free(r->patches);
    free(r->keys);
    free(r->kinds);
    free(r);
}

int sc_pack_build(const sc_scene *scene, const sc_render_desc *desc, sc_pack *out,
                  sc_error *err)
{
    static const sc_render_desc defaults = {0};
    memset(out, 0, sizeof *out);
    if (scene->terrain)
        return sc_fail(err, NULL, 0, "a terrain cannot be packed yet (its prisms are made per "
                                     "frame order): draw it from the scene");
    sc_renderer *r = sc_alloc(1, sizeof *r);
    r->scene = scene;
    r->desc = desc ? *desc : defaults;
    sc_prepare_defaults(r);
    int n = scene->nsurfaces;
    r->keys = sc_alloc((size_t)(n ? n : 1), sizeof *r->keys);
    r->kinds = sc_alloc((size_t)(n ? n : 1), sizeof *r->kinds);
    r->patches = sc_alloc((size_t)(n ? n : 1), sizeof *r->patches);
    for (int s = 0; s < n; s++) {
        if (sc_surface_drawable(scene, s, err) != SC_OK) {
            free_unsent(r);
            return SC_FAIL;
        }
        sc_prepare_surface_key(&scene->surfaces[s], &r->desc, NULL, &r->keys[s]);
        r->kinds[s] = r->keys[s].kind;
        sc_surface_world_patches(&scene->surfaces[s], s, &r->patches[s]);
    }
    if (sc_hulls_build_from(scene, r->patches, &r->desc.hulls, &r->hulls, err) != SC_OK ||
        sc_gpu_data_build_from(NULL, scene, r->patches, r->keys, &r->data, err) != SC_OK) {
        free_unsent(r);
        return SC_FAIL;
    }
    sc_prepare_raster_origin(r);
    const sc_hulls *h = &r->hulls;
    out->nsurfaces = n;
    out->keys = sc_alloc((size_t)(n ? n : 1), SC_PACK_KEY_BYTES);
    out->colours = sc_alloc((size_t)(n ? n : 1), 4 * sizeof(float));
    for (int s = 0; s < n; s++) {
        scg_key_format(&r->keys[s], out->keys[s], SC_PACK_KEY_BYTES);
        memcpy(out->colours + 4 * s, scene->surfaces[s].color, 3 * sizeof(float));
        out->colours[4 * s + 3] = 1;
    }
    /* The staged arrays move into the pack. */
    out->npoints = r->data.npoints;
    out->nknots = r->data.nknots;
    out->nrecords = r->data.nrecords;
    out->ntrim_texels = r->data.ntrim_texels;
    out->points = r->data.staged[SCG_TEX_POINTS];
    out->knots = r->data.staged[SCG_TEX_KNOTS];
    out->records = r->data.staged[SCG_TEX_RECORDS];
    for (int t = 0; t < SCG_TEXTURE_COUNT; t++)
        r->data.staged[t] = NULL;
    out->nvertices = h->nvertices;
    out->vertices = sc_alloc((size_t)(h->nvertices ? h->nvertices : 1), sizeof(gpu_vertex));
    sc_prepare_fill_vertices(r, 0, h->count, (gpu_vertex *)out->vertices);
    out->nindices = h->nindices;
    out->indices = sc_alloc((size_t)(h->nindices ? h->nindices : 1), sizeof(uint32_t));
    if (h->nindices)
        memcpy(out->indices, h->indices, (size_t)h->nindices * sizeof(uint32_t));
    out->nhulls = h->count;
    out->hulls = sc_alloc((size_t)(h->count ? h->count : 1), sizeof *out->hulls);
    for (int k = 0; k < h->count; k++) {
        const sc_subpatch *s = &h->subpatches[k];
        out->hulls[k] = (sc_pack_hull){s->surface, s->patch, s->first_vertex, s->vertex_count,
                                       s->first_index, s->index_count, {0}, {0}};
        memcpy(out->hulls[k].lo, s->lo, sizeof s->lo);
        memcpy(out->hulls[k].hi, s->hi, sizeof s->hi);
    }
    out->view = (uint32_t)r->desc.view;
    out->termination = (uint32_t)r->desc.ert;
    memcpy(out->raster_origin, r->raster_origin, sizeof out->raster_origin);
    /* What the default view of the scene frames, so that a packed
     * renderer's default view is the scene's (trimmed faces by what they
     * keep). */
    if (!sc_scene_view_bounds(scene, out->lo, out->hi))
        sc_scene_bounds(scene, out->lo, out->hi);
    free_unsent(r);
    return SC_OK;
}

/* The stand-in scene of a packed renderer: its surfaces' colours, and
 * control points on the scene's box so that the default view frames it. */
static sc_scene *stand_in_scene(const sc_pack *pack)
{
    sc_scene *scene = sc_alloc(1, sizeof *scene);
    sc_scene_init(scene);
    for (int i = 0; i < pack->nsurfaces; i++) {
        sc_surface *s = sc_scene_add_surface(scene);
        memcpy(s->color, pack->colours + 4 * i, sizeof s->color);
        sc_surface_alloc(s, 1, 1, 2, 2);
        for (int k = 0; k < 4; k++) {
            s->knots_u[k] = s->knots_v[k] = k < 2 ? 0 : 1;
            const double *corner = k == 3 ? pack->hi : pack->lo;
            memcpy(s->cp + 4 * k, corner, 3 * sizeof(double));
            s->cp[4 * k + 3] = 1;
        }
    }
    return scene;
}

int sc_renderer_create_packed(const sc_gl *gl, const sc_pack *pack, const sc_render_desc *desc,
                              sc_renderer **out, sc_error *err)
{
    static const sc_render_desc defaults = {0};
    *out = NULL;
    if (pack->view > SC_SHOW_REFLECT || pack->termination > SC_TERMINATION_LISTS)
        return sc_fail(err, NULL, 0, "the pack's view or termination is not one this library "
                                     "knows");
    sc_renderer *r = sc_alloc(1, sizeof *r);
    r->gl = gl;
    r->desc = desc ? *desc : defaults;
    r->desc.view = (sc_show)pack->view;
    r->desc.ert = (sc_ray_termination)pack->termination;
    sc_prepare_defaults(r);
    r->own_scene = stand_in_scene(pack);
    r->scene = r->own_scene;
    int n = pack->nsurfaces;
    r->keys = sc_alloc((size_t)(n ? n : 1), sizeof *r->keys);
    r->kinds = sc_alloc((size_t)(n ? n : 1), sizeof *r->kinds);
    r->surface_program = sc_alloc((size_t)(n ? n : 1), sizeof *r->surface_program);
    r->own_programs = !r->desc.programs;
    r->programs = r->own_programs ? sc_program_cache_create(gl) : r->desc.programs;
    double t0 = sc_now();
    for (int s = 0; s < n; s++) {
        if (scg_key_parse(pack->keys[s], &r->keys[s], err) != SC_OK ||
            r->keys[s].kind == SCG_PATCH_TRIANGLE) {
            if (r->keys[s].kind == SCG_PATCH_TRIANGLE)
                sc_fail(err, NULL, 0, "surface %d: a terrain's key in a pack", s);
            goto fail;
        }
        r->kinds[s] = r->keys[s].kind;
        if (colour_frames(&r->desc))   /* drawn without AOVs (gl_render_private.h) */
            r->keys[s].outputs &= ~SCG_OUTPUT_AOV;
        if (sc_program_for_key(r->programs, &r->keys[s], &r->surface_program[s], err) != SC_OK)
            goto fail;
    }
    r->compile_ms = 1e3 * (sc_now() - t0);

    sc_hulls *h = &r->hulls;
    h->count = pack->nhulls;
    h->subpatches = sc_alloc((size_t)(h->count ? h->count : 1), sizeof *h->subpatches);
    for (int k = 0; k < h->count; k++) {
        const sc_pack_hull *p = &pack->hulls[k];
        sc_subpatch *s = &h->subpatches[k];
        *s = (sc_subpatch){.surface = p->surface, .patch = p->patch,
                           .first_vertex = p->first_vertex, .vertex_count = p->vertex_count,
                           .first_index = p->first_index, .index_count = p->index_count};
        memcpy(s->lo, p->lo, sizeof s->lo);
        memcpy(s->hi, p->hi, sizeof s->hi);
    }
    /* World positions, for the test of hulls holding the eye. */
    const gpu_vertex *verts = (const gpu_vertex *)pack->vertices;
    h->nvertices = pack->nvertices;
    h->vertices = sc_alloc((size_t)(h->nvertices ? h->nvertices : 1), sizeof *h->vertices);
    for (int v = 0; v < h->nvertices; v++)
        for (int c = 0; c < 3; c++)
            h->vertices[v].pos[c] = verts[v].raster_pos[c] + pack->raster_origin[c];
    h->nindices = pack->nindices;
    h->indices = sc_alloc((size_t)(h->nindices ? h->nindices : 1), sizeof *h->indices);
    if (h->nindices)
        memcpy(h->indices, pack->indices, (size_t)h->nindices * sizeof *h->indices);
    h->nsurfaces = n;
    memcpy(r->raster_origin, pack->raster_origin, sizeof r->raster_origin);

    sc_gpu_data *d = &r->data;
    d->nsurfaces = n;
    d->npoints = pack->npoints;
    d->nknots = pack->nknots;
    d->nrecords = pack->nrecords;
    d->ntrim_texels = pack->ntrim_texels;
    size_t texels[SCG_TEXTURE_COUNT] = {
        [SCG_TEX_POINTS] = (size_t)pack->npoints * 4,
        [SCG_TEX_KNOTS] = (size_t)pack->nknots,
        [SCG_TEX_RECORDS] = ((size_t)pack->nrecords * SCG_RECORD_TEXELS +
                             (size_t)pack->ntrim_texels) * 4};
    const float *arrays[SCG_TEXTURE_COUNT] = {
        [SCG_TEX_POINTS] = pack->points, [SCG_TEX_KNOTS] = pack->knots,
        [SCG_TEX_RECORDS] = pack->records};
    GLint max_texels = 0;
    gl->GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    for (int t = 0; t < SCG_TEXTURE_COUNT; t++) {
        /* As sc_gpu_data_build_from's: a buffer is never empty. */
        d->staged[t] = sc_alloc(texels[t] ? texels[t] : 4, sizeof(float));
        if (texels[t])
            memcpy(d->staged[t], arrays[t], texels[t] * sizeof(float));
        d->bytes += (texels[t] ? texels[t] : 4) * sizeof(float);
        if ((long long)texels[t] / (t == SCG_TEX_KNOTS ? 1 : 4) > max_texels) {
            sc_fail(err, NULL, 0, "the pack's %s need more texels than the driver's buffer "
                                  "textures hold (%d)", t == SCG_TEX_POINTS ? "points" :
                                  t == SCG_TEX_KNOTS ? "knots" : "records", max_texels);
            goto fail;
        }
    }
    size_t needed = sc_prepare_gpu_bytes(r);
    if (r->desc.gpu_memory_budget && needed > r->desc.gpu_memory_budget) {
        char cause[96];
        snprintf(cause, sizeof cause, "the GPU memory budget is %zu bytes",
                 r->desc.gpu_memory_budget);
        sc_gl_fail_memory(err, needed, cause);
        goto fail;
    }
    if (sc_gpu_data_send(gl, d, needed, err) != SC_OK)
        goto fail;
    sc_prepare_vertex_array(r);
    if (sc_prepare_upload_colours(r, err) != SC_OK ||
        sc_prepare_upload_hull_buffers(r, verts, err) != SC_OK)
        goto fail;
    sc_prepare_groups(r);
    sc_prepare_group_hulls(r);
    r->bytes_uploaded = r->data.bytes_uploaded + r->hull_bytes_uploaded + r->colour_bytes;
    r->bytes_uploaded_total = r->bytes_uploaded;
    *out = r;
    return SC_OK;
fail:
    sc_renderer_destroy(r);
    return SC_FAIL;
}

const sc_scene *sc_renderer_scene(const sc_renderer *r) { return r->scene; }

int sc_renderer_view_bounds(sc_renderer *r, double lo[3], double hi[3])
{
    if (!r->view_known) {
        r->view_any = sc_scene_view_bounds(r->scene, r->view_lo, r->view_hi);
        r->view_known = 1;
    }
    memcpy(lo, r->view_lo, sizeof r->view_lo);
    memcpy(hi, r->view_hi, sizeof r->view_hi);
    return r->view_any;
}
