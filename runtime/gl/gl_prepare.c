/* gl_prepare.c — what a renderer prepares before any frame (gl_render.h):
 * a key per surface, one program per distinct key (programs.h), the patch
 * data (gl_data.h) and the hulls (hulls.h) in one vertex buffer; and the
 * update of one surface's share of them. Frames are drawn in gl_render.c. */
#include "gl_render_private.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_layout.h"
#include "programs.h"
#include "scene_keys.h"
#include "tri_prisms.h"

/* The key of one surface (scene_keys.h): its degrees, rationality and
 * trims, the render's start, iterations and outputs (iterations and
 * tolerance from the accuracy target's choice when there is one); the
 * generic program above the unrolling limit, or everywhere when asked. */
void sc_prepare_surface_key(const sc_surface *s, const sc_render_desc *desc,
                            const sc_accuracy_choice *choice, scg_key *key)
{
    sc_key_options opts = {
        .generic_above = desc->unroll_max_degree,
        .max_iters = choice ? choice->max_iters : desc->max_iters,
        .tol_milli = choice ? choice->tol_milli : desc->tol_milli,
        .start = desc->start,
        .trim_method = desc->trim_method,
        .trim_iters = desc->trim_iters,
        .termination = desc->ert,
        .outputs = view_outputs(desc),
        .method = desc->method,
        .eval = desc->eval,
    };
    sc_surface_key(s, &opts, key);
    if (desc->generic && key->eval != SCG_EVAL_LOOP) {
        key->eval = SCG_EVAL_LOOP;
        key->deg_u = key->deg_v = 0;
    }
}


/* Surfaces that share a program under the defaults share one under an
 * accuracy target too: each takes the most iterations and the smallest
 * tolerance chosen for any of them, so that a target never compiles more
 * programs, nor switches between more, than the defaults (their hulls stay
 * their own). */
static void share_programs(sc_renderer *r)
{
    int n = r->scene->nsurfaces, ngroups = 0;
    scg_key *base = sc_alloc((size_t)(n ? n : 1), sizeof *base);
    int *group_of = sc_alloc((size_t)(n ? n : 1), sizeof *group_of);
    sc_accuracy_choice *shared = sc_alloc((size_t)(n ? n : 1), sizeof *shared);
    for (int s = 0; s < n; s++) {
        if (sc_surface_drawable(r->scene, s, NULL) != SC_OK) {
            group_of[s] = -1;
            continue;
        }
        scg_key key;
        sc_prepare_surface_key(&r->scene->surfaces[s], &r->desc, NULL, &key);
        int g = 0;
        while (g < ngroups && !scg_key_equal(&base[g], &key))
            g++;
        const sc_accuracy_choice *c = &r->choices[s];
        if (g == ngroups) {
            base[ngroups++] = key;
            shared[g] = *c;
        }
        if (c->max_iters > shared[g].max_iters)
            shared[g].max_iters = c->max_iters;
        if (c->tol_milli < shared[g].tol_milli)
            shared[g].tol_milli = c->tol_milli;
        group_of[s] = g;
    }
    for (int s = 0; s < n; s++)
        if (group_of[s] >= 0) {
            r->choices[s].max_iters = shared[group_of[s]].max_iters;
            r->choices[s].tol_milli = shared[group_of[s]].tol_milli;
        }
    free(base);
    free(group_of);
    free(shared);
}

/* The origin hulls are rasterised relative to: the middle of their box
 * when the renderer is made, kept thereafter, so that a surface update
 * rewrites the vertices of that surface alone. */
void sc_prepare_raster_origin(sc_renderer *r)
{
    const sc_hulls *h = &r->hulls;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < h->count; k++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], h->subpatches[k].lo[c]);
            hi[c] = fmax(hi[c], h->subpatches[k].hi[c]);
        }
    for (int c = 0; c < 3; c++)
        r->raster_origin[c] = h->count ? 0.5 * (lo[c] + hi[c]) : 0;
}

/* The GPU vertices of hulls [first, first + count), whose vertices start at
 * verts[0]: relative to their record's centre (hull.vert), in the
 * parameters of their record's program: local [0, 1]² of the Bézier patch
 * for `bez` records, the surface's own for `nurbs`. */
void sc_prepare_fill_vertices(const sc_renderer *r, int first, int count, gpu_vertex *verts)
{
    const sc_hulls *h = &r->hulls;
    int base = count ? h->subpatches[first].first_vertex : 0;
    for (int k = first; k < first + count; k++) {
        const sc_subpatch *s = &h->subpatches[k];
        int nurbs = r->kinds[s->surface] == SCG_PATCH_NURBS;
        double du = nurbs ? (s->domain[1] - s->domain[0]) / (s->local[1] - s->local[0]) : 1;
        double dv = nurbs ? (s->domain[3] - s->domain[2]) / (s->local[3] - s->local[2]) : 1;
        double ou = nurbs ? s->domain[0] - du * s->local[0] : 0;
        double ov = nurbs ? s->domain[2] - dv * s->local[2] : 0;
        const double *rect = nurbs ? s->domain : s->local;
        int record = sc_gpu_data_record(&r->data, s->surface, s->patch);
        const double *centre = sc_gpu_data_record_centre(&r->data, record);
        for (int v = s->first_vertex; v < s->first_vertex + s->vertex_count; v++) {
            gpu_vertex *g = &verts[v - base];
            for (int c = 0; c < 3; c++) {
                g->pos[c] = (float)(h->vertices[v].pos[c] - centre[c]);
                g->raster_pos[c] = (float)(h->vertices[v].pos[c] - r->raster_origin[c]);
            }
            g->uv[0] = (float)(ou + du * h->vertices[v].uv[0]);
            g->uv[1] = (float)(ov + dv * h->vertices[v].uv[1]);
            for (int c = 0; c < 4; c++)
                g->domain[c] = (float)rect[c];
            g->record = record;
        }
    }
}

/* GPU bytes of the hulls' vertex and index buffers (neither is ever
 * empty). */
static void hull_buffer_bytes(const sc_hulls *h, size_t *vbytes, size_t *ibytes)
{
    *vbytes = (size_t)(h->nvertices ? h->nvertices : 1) * sizeof(gpu_vertex);
    *ibytes = (size_t)(h->nindices ? h->nindices : 1) * sizeof(uint32_t);
}

static size_t colour_buffer_bytes(const sc_scene *scene)
{
    return (size_t)(scene->nsurfaces ? scene->nsurfaces : 1) * 4 * sizeof(float);
}

/* The GPU data the whole scene needs: patch data (built, r->data.bytes),
 * hulls and colours; what an out-of-memory message names. */
size_t sc_prepare_gpu_bytes(const sc_renderer *r)
{
    size_t vbytes, ibytes;
    hull_buffer_bytes(&r->hulls, &vbytes, &ibytes);
    return r->data.bytes + vbytes + ibytes + colour_buffer_bytes(r->scene);
}

/* The per-hull scratch of a frame, sized for r->hulls. */
static void size_scratch(sc_renderer *r)
{
    const sc_hulls *h = &r->hulls;
    r->frame_indices = sc_realloc(r->frame_indices, (size_t)(h->nindices ? h->nindices : 1),
                                  sizeof(uint32_t));
    size_t count = (size_t)(h->count ? h->count : 1);
    r->distance = sc_realloc(r->distance, count, sizeof(double));
    r->items = sc_realloc(r->items, count, sizeof *r->items);
    r->inside = sc_realloc(r->inside, count, sizeof *r->inside);
    /* At most one run per hull, plus the inside hulls' runs per group. */
    r->runs = sc_realloc(r->runs, 2 * count, sizeof *r->runs);
}

/* Every hull into new vertex and index buffers, and the per-hull scratch
 * of a frame sized for them. */
static int upload_hulls(sc_renderer *r, sc_error *err)
{
    const sc_hulls *h = &r->hulls;
    gpu_vertex *verts = sc_alloc((size_t)(h->nvertices ? h->nvertices : 1), sizeof *verts);
    sc_prepare_fill_vertices(r, 0, h->count, verts);
    int status = sc_prepare_upload_hull_buffers(r, verts, err);
    free(verts);
    return status;
}

int sc_prepare_upload_hull_buffers(sc_renderer *r, const gpu_vertex *verts, sc_error *err)
{
    const sc_gl *gl = r->gl;
    const sc_hulls *h = &r->hulls;
    if (r->vertex_buffer)
        gl->DeleteBuffers(1, &r->vertex_buffer);
    if (r->index_buffer)
        gl->DeleteBuffers(1, &r->index_buffer);
    gl->CreateBuffers(1, &r->vertex_buffer);
    gl->CreateBuffers(1, &r->index_buffer);
    size_t vbytes, ibytes;
    hull_buffer_bytes(h, &vbytes, &ibytes);
    /* Dynamic: a surface update rewrites its range. */
    gl->NamedBufferStorage(r->vertex_buffer, (GLsizeiptr)vbytes, verts, GL_DYNAMIC_STORAGE_BIT);
    /* Rewritten every frame in drawing order. */
    gl->NamedBufferStorage(r->index_buffer, (GLsizeiptr)ibytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    r->hull_bytes = vbytes + ibytes;
    r->hull_bytes_uploaded = vbytes;
    r->vertex_capacity = h->nvertices;
    r->index_capacity = h->nindices;
    GLuint vao = r->vertex_array;
    gl->VertexArrayVertexBuffer(vao, 0, r->vertex_buffer, 0, sizeof(gpu_vertex));
    gl->VertexArrayElementBuffer(vao, r->index_buffer);
    size_scratch(r);
    return sc_gl_check_upload(gl, "uploading the hulls", sc_prepare_gpu_bytes(r), err);
}

/* The hull vertices of surfaces [first, end) — contiguous in the vertex
 * buffer — rewritten in their range; returns the bytes sent. */
static size_t send_surfaces(sc_renderer *r, int first, int end)
{
    const sc_hull_range *a = &r->hulls.surfaces[first], *z = &r->hulls.surfaces[end - 1];
    int nverts = z->first_vertex + z->vertex_count - a->first_vertex;
    int nsub = z->first_subpatch + z->subpatch_count - a->first_subpatch;
    if (nverts <= 0)
        return 0;
    gpu_vertex *verts = sc_alloc((size_t)nverts, sizeof *verts);
    sc_prepare_fill_vertices(r, a->first_subpatch, nsub, verts);
    size_t bytes = (size_t)nverts * sizeof(gpu_vertex);
    r->gl->NamedBufferSubData(r->vertex_buffer,
                              (GLintptr)((size_t)a->first_vertex * sizeof(gpu_vertex)),
                              (GLsizeiptr)bytes, verts);
    free(verts);
    return bytes;
}

int sc_renderer_send_updates(sc_renderer *r, sc_error *err)
{
    if (!r->pending)
        return SC_OK;
    const sc_hulls *h = &r->hulls;
    int n = r->scene->nsurfaces;
    size_t sent = 0;
    if (r->recount) {
        sc_prepare_group_hulls(r);
        size_scratch(r);
    }
    if (h->nvertices > r->vertex_capacity || h->nindices > r->index_capacity) {
        /* More than the buffers hold: new ones, every vertex sent. */
        if (upload_hulls(r, err) != SC_OK)
            return SC_FAIL;
        sent = r->hull_bytes_uploaded;
        memset(r->stale, 0, (size_t)n);
    }
    for (int s = 0; s < n; s++) {
        if (!r->stale[s])
            continue;
        int end = s;
        while (end < n && r->stale[end])
            r->stale[end++] = 0;
        sent += send_surfaces(r, s, end);
        s = end;
    }
    r->pending = r->recount = 0;
    r->counting_afresh = 1;
    r->bytes_uploaded += sent;
    r->bytes_uploaded_total += sent;
    return sc_gl_check(r->gl, "sending the updated surfaces' hulls", err);
}

/* One group per distinct program the surfaces are drawn with, in the order
 * the surfaces first ask for it (the keys never change: a surface that
 * would change its key needs a new renderer). */
void sc_prepare_groups(sc_renderer *r)
{
    int n = r->scene->nsurfaces;
    r->groups = sc_alloc((size_t)(n ? n : 1), sizeof *r->groups);
    r->surface_group = sc_alloc((size_t)(n ? n : 1), sizeof *r->surface_group);
    for (int s = 0; s < n; s++) {
        int g = 0;
        while (g < r->ngroups && r->groups[g].program.id != r->surface_program[s].id)
            g++;
        if (g == r->ngroups)
            r->groups[r->ngroups++].program = r->surface_program[s];
        r->surface_group[s] = g;
    }
    r->group_seen = sc_alloc((size_t)(r->ngroups ? r->ngroups : 1), sizeof(double));
}

/* Each hull's group, after the hulls were (re)built. */
void sc_prepare_group_hulls(sc_renderer *r)
{
    r->hull_group = sc_realloc(r->hull_group, (size_t)(r->hulls.count ? r->hulls.count : 1),
                               sizeof(int));
    for (int k = 0; k < r->hulls.count; k++)
        r->hull_group[k] = r->surface_group[r->hulls.subpatches[k].surface];
}

/* One attribute of the contract, read from its field of gpu_vertex. */
static void vertex_attrib(const sc_gl *gl, GLuint vao, GLuint location, int components,
                          GLenum type)
{
    GLuint offset = (GLuint)gpu_vertex_fields[location].offset;
    gl->EnableVertexArrayAttrib(vao, location);
    if (type == GL_INT)
        gl->VertexArrayAttribIFormat(vao, location, components, type, offset);
    else
        gl->VertexArrayAttribFormat(vao, location, components, type, GL_FALSE, offset);
    gl->VertexArrayAttribBinding(vao, location, 0);
}

void sc_prepare_vertex_array(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    gl->CreateVertexArrays(1, &r->vertex_array);
#define X(ID, location, name, type, components, component_type) \
    vertex_attrib(gl, r->vertex_array, location, components, GL_##component_type);
    SCG_ATTRIBS(X)
#undef X
}

int sc_prepare_upload_colours(sc_renderer *r, sc_error *err)
{
    const sc_gl *gl = r->gl;
    int n = r->scene->nsurfaces ? r->scene->nsurfaces : 1;
    float *colours = sc_alloc((size_t)n * 4, sizeof(float));
    for (int s = 0; s < r->scene->nsurfaces; s++) {
        memcpy(colours + 4 * s, r->scene->surfaces[s].color, 3 * sizeof(float));
        colours[4 * s + 3] = 1;
    }
    gl->CreateBuffers(1, &r->colour_buffer);
    r->colour_bytes = colour_buffer_bytes(r->scene);
    gl->NamedBufferStorage(r->colour_buffer, (GLsizeiptr)r->colour_bytes, colours, 0);
    gl->CreateTextures(GL_TEXTURE_BUFFER, 1, &r->colour_texture);
    gl->TextureBuffer(r->colour_texture, GL_RGBA32F, r->colour_buffer);
    free(colours);
    return sc_gl_check_upload(gl, "uploading the colours", sc_prepare_gpu_bytes(r), err);
}

void sc_prepare_defaults(sc_renderer *r)
{
    if (!r->desc.ert)
        r->desc.ert = SC_DEFAULT_TERMINATION;
    /* Hull faces drawn where a ray misses would read as hits nearby. */
    if (r->desc.view == SC_SHOW_HULL)
        r->desc.ert = SC_TERMINATION_NONE;
    if (!r->desc.order)
        r->desc.order = SC_RENDER_DEFAULT_ORDER;
    if (r->desc.batch_hulls <= 0)
        r->desc.batch_hulls = SC_RENDER_DEFAULT_BATCH_HULLS;
    if (!r->desc.list_below_px)
        r->desc.list_below_px = SC_RENDER_DEFAULT_LIST_BELOW_PX;
}

int sc_renderer_create(const sc_gl *gl, const sc_scene *scene, const sc_render_desc *desc,
                       sc_renderer **out, sc_error *err)
{
    static const sc_render_desc defaults = {0};
    *out = NULL;
    sc_renderer *r = sc_alloc(1, sizeof *r);
    r->gl = gl;
    r->scene = scene;
    r->desc = desc ? *desc : defaults;
    r->manhattan = scene->terrain && !r->desc.order;
    sc_prepare_defaults(r);
    int n = scene->nsurfaces;
    r->keys = sc_alloc((size_t)(n ? n : 1), sizeof *r->keys);
    r->kinds = sc_alloc((size_t)(n ? n : 1), sizeof *r->kinds);
    r->surface_program = sc_alloc((size_t)(n ? n : 1), sizeof *r->surface_program);
    r->own_programs = !r->desc.programs;
    r->programs = r->own_programs ? sc_program_cache_create(gl) : r->desc.programs;
    /* Each surface is cut into Bézier patches once; hull i and the record
     * it names come from the same patch, and an accuracy target measures
     * them. */
    r->patches = sc_alloc((size_t)(n ? n : 1), sizeof *r->patches);
    if (scene->terrain)
        sc_tri_patch_list(scene->terrain, &r->patches[0]);
    else
        for (int s = 0; s < n; s++)
            sc_surface_world_patches(&scene->surfaces[s], s, &r->patches[s]);
    if (r->desc.accuracy.px > 0 && !scene->terrain) {
        r->choices = sc_alloc((size_t)(n ? n : 1), sizeof *r->choices);
        sc_accuracy_choose(scene, r->patches, &r->desc.accuracy, r->desc.method, r->choices);
        share_programs(r);
    }
    double t0 = sc_now();
    for (int s = 0; s < n; s++) {
        if (sc_surface_drawable(scene, s, err) != SC_OK)
            goto fail;
        sc_prepare_surface_key(&scene->surfaces[s], &r->desc, r->choices ? &r->choices[s] : NULL,
                               &r->keys[s]);
        if (scene->terrain) {   /* its stand-in surface: the terrain's key */
            scg_key like = r->keys[s];
            sc_tri_key(scene->terrain, &like, &r->keys[s]);
            if (r->desc.deferred && r->desc.view == SC_SHOW_SHADE)
                r->keys[s].outputs &= ~SCG_OUTPUT_SHADE;   /* gl_deferred.c shades */
        }
        r->kinds[s] = r->keys[s].kind;
        /* Drawn without AOVs: the AOV set is compiled when first asked
         * for (gl_render.c). */
        if (colour_frames(&r->desc))
            r->keys[s].outputs &= ~SCG_OUTPUT_AOV;
        if (sc_program_for_key(r->programs, &r->keys[s], &r->surface_program[s], err) != SC_OK)
            goto fail;
    }
    r->compile_ms = 1e3 * (sc_now() - t0);
    if (scene->terrain) {
        /* One record and one prism per triangular patch (tri_prisms.h). */
        sc_tri_prisms(scene->terrain, &r->hulls);
    } else {
        sc_hull_desc hulls = r->desc.hulls;
        double *tolerance = NULL;
        if (r->choices) {
            tolerance = sc_alloc((size_t)(n ? n : 1), sizeof *tolerance);
            for (int s = 0; s < n; s++)
                tolerance[s] = r->choices[s].hull_tolerance;
            hulls.mode = SC_SPLIT_ADAPTIVE;
            hulls.surface_tolerance = tolerance;
        }
        int status = sc_hulls_build_from(scene, r->patches, &hulls, &r->hulls, err);
        free(tolerance);
        if (status != SC_OK)
            goto fail;
    }
    if (sc_gpu_data_build_from(gl, scene, r->patches, r->keys, &r->data, err) != SC_OK)
        goto fail;
    /* Weighed before anything is sent, so that a refused scene leaves no
     * buffer behind, half filled or not. */
    size_t needed = sc_prepare_gpu_bytes(r);
    if (r->desc.gpu_memory_budget && needed > r->desc.gpu_memory_budget) {
        char cause[96];
        snprintf(cause, sizeof cause, "the GPU memory budget is %zu bytes",
                 r->desc.gpu_memory_budget);
        sc_gl_fail_memory(err, needed, cause);
        goto fail;
    }
    if (sc_gpu_data_send(gl, &r->data, needed, err) != SC_OK)
        goto fail;
    sc_prepare_vertex_array(r);
    sc_prepare_raster_origin(r);
    if (sc_prepare_upload_colours(r, err) != SC_OK || upload_hulls(r, err) != SC_OK)
        goto fail;
    sc_prepare_groups(r);
    sc_prepare_group_hulls(r);
    r->bytes_uploaded = r->data.bytes_uploaded + r->hull_bytes_uploaded + r->colour_bytes;
    r->bytes_uploaded_total = r->bytes_uploaded;
    r->stale = sc_alloc((size_t)(n ? n : 1), 1);
    r->counting_afresh = 1;
    *out = r;
    return SC_OK;
fail:
    sc_renderer_destroy(r);
    return SC_FAIL;
}

void sc_renderer_destroy(sc_renderer *r)
{
    if (!r)
        return;
    const sc_gl *gl = r->gl;
    if (r->nearest_texture)
        gl->DeleteTextures(1, &r->nearest_texture);
    if (r->app_nearest)
        gl->DeleteTextures(1, &r->app_nearest);
    if (r->counter_buffer)
        gl->DeleteBuffers(1, &r->counter_buffer);
    if (r->time_query)
        gl->DeleteQueries(1, &r->time_query);
    sc_gl_target_destroy(gl, &r->target);
    sc_gpu_data_free(gl, &r->data);
    GLuint buffers[3] = {r->vertex_buffer, r->index_buffer, r->colour_buffer};
    for (int i = 0; i < 3; i++)
        if (buffers[i])
            gl->DeleteBuffers(1, &buffers[i]);
    if (r->colour_texture)
        gl->DeleteTextures(1, &r->colour_texture);
    if (r->vertex_array)
        gl->DeleteVertexArrays(1, &r->vertex_array);
    if (r->deferred_program)
        gl->DeleteProgram(r->deferred_program);
    sc_peel_destroy(r);
    sc_lists_destroy(r);
    if (r->own_programs)
        sc_program_cache_destroy(r->programs);
    sc_hulls_free(&r->hulls);
    for (int s = 0; r->patches && s < r->scene->nsurfaces; s++)
        sc_patch_list_free(&r->patches[s]);
    if (r->own_scene) {
        sc_scene_free(r->own_scene);
        free(r->own_scene);
    }
    free(r->patches);
    free(r->groups);
    free(r->surface_group);
    free(r->hull_group);
    free(r->keys);
    free(r->kinds);
    free(r->choices);
    free(r->surface_program);
    free(r->frame_indices);
    free(r->distance);
    free(r->items);
    free(r->inside);
    free(r->runs);
    free(r->group_seen);
    free(r->stale);
    free(r->uvt);
    free(r->nearest);
    free(r->tile_far);
    free(r->cosine);
    free(r);
}

int sc_renderer_update_surface(sc_renderer *r, int surface, sc_error *err)
{
    if (surface < 0 || surface >= r->scene->nsurfaces)
        return sc_fail(err, NULL, 0, "no surface %d in the scene", surface);
    if (r->scene->terrain)
        return sc_fail(err, NULL, 0, "a terrain has no surfaces to update; make a new scene");
    if (sc_surface_drawable(r->scene, surface, err) != SC_OK)
        return SC_FAIL;
    scg_key key;
    sc_prepare_surface_key(&r->scene->surfaces[surface], &r->desc,
                           r->choices ? &r->choices[surface] : NULL, &key);
    if (colour_frames(&r->desc))
        key.outputs &= ~SCG_OUTPUT_AOV;
    if (!scg_key_equal(&key, &r->keys[surface]))
        return sc_fail(err, NULL, 0, "surface %d changed its key; make a new renderer", surface);
    r->view_known = 0;
    sc_patch_list old = r->patches[surface];
    sc_surface_world_patches(&r->scene->surfaces[surface], surface, &r->patches[surface]);
    int hulls_moved, records_moved;
    if (sc_hulls_update_surface_from(&r->hulls, r->scene, surface, &r->patches[surface],
                                     &hulls_moved, err) != SC_OK ||
        sc_gpu_data_update_surface_from(r->gl, &r->data, r->scene, r->patches, surface, r->keys,
                                        &records_moved, err) != SC_OK) {
        sc_patch_list_free(&r->patches[surface]);
        r->patches[surface] = old;
        return SC_FAIL;
    }
    sc_patch_list_free(&old);
    if (r->counting_afresh)
        r->bytes_uploaded = 0;
    r->counting_afresh = 0;
    r->bytes_uploaded += r->data.bytes_uploaded;
    r->bytes_uploaded_total += r->data.bytes_uploaded;
    /* Vertices carry their record's number and centre: when records moved,
     * every vertex is stale; when this surface's hull counts changed, the
     * vertices after its own moved. They are sent with the next frame. */
    int n = r->scene->nsurfaces;
    int from = records_moved ? 0 : surface, to = records_moved || hulls_moved ? n : surface + 1;
    memset(r->stale + from, 1, (size_t)(to - from));
    r->recount |= hulls_moved;
    r->pending = 1;
    return SC_OK;
}

void sc_renderer_stats(const sc_renderer *r, sc_render_stats *stats)
{
    stats->programs = r->ngroups;
    for (int g = 0; g < r->ngroups; g++)
        stats->programs += (r->groups[g].inside.id != 0) + (r->groups[g].aov.id != 0) +
                           (r->groups[g].aov_inside.id != 0);
    stats->hulls = r->hulls.count;
    stats->triangles = r->hulls.nindices / 3;
    stats->gpu_bytes = r->data.bytes + r->hull_bytes + r->colour_bytes;
    stats->bytes_uploaded = r->bytes_uploaded;
    stats->bytes_uploaded_total = r->bytes_uploaded_total;
    stats->qhull_hulls = r->hulls.qhull_pieces;
    stats->compile_ms = r->compile_ms;
    stats->draw_calls = r->draw_calls;
    stats->program_switches = r->program_switches;
    stats->culled_hulls = r->culled;
    stats->readbacks = r->readbacks;
    stats->peel_layers = r->peel_layers;
    stats->threads = r->frame_threads;
    stats->intersections = -1;
    if (r->frame_aovs && r->counter_buffer) {
        GLuint count = 0;
        r->gl->GetNamedBufferSubData(r->counter_buffer, 0, sizeof count, &count);
        stats->intersections = count;
    }
    stats->intersect_ms = stats->intersect_query_ms = -1;
    if (r->timed) {
        GLuint64 ns = 0;
        r->gl->GetQueryObjectui64v(r->time_query, GL_QUERY_RESULT, &ns);
        stats->intersect_query_ms = 1e-6 * (double)ns;
        stats->intersect_ms = r->intersect_ms;
    }
}

const scg_key *sc_renderer_surface_key(const sc_renderer *r, int surface)
{
    return &r->keys[surface];
}

const sc_accuracy_choice *sc_renderer_surface_choice(const sc_renderer *r, int surface)
{
    return r->choices ? &r->choices[surface] : NULL;
}

void sc_renderer_surface_hulls(const sc_renderer *r, int surface, int *count,
                               double *tolerance)
{
    *count = r->hulls.surfaces ? r->hulls.surfaces[surface].subpatch_count : 0;
    *tolerance = 0;
    if (r->choices)
        *tolerance = r->choices[surface].hull_tolerance;
    else if (!r->scene->terrain && r->hulls.desc.mode != SC_SPLIT_UNIFORM)
        *tolerance = r->hulls.desc.tolerance;
}
