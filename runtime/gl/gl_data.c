/* gl_data.c — patch data in buffer textures (gl_data.h, layout in
 * gen/gpu_layout.h). Data is built on the CPU surface by surface into
 * float arrays, so that one surface can be rebuilt and written back into its
 * own ranges. Trim blocks (trim_pack.h) follow the records in sc_records;
 * each record names its surface's block by texel index, fixed up once the
 * records' total is known. */
#include "gl_data.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs.h"
#include "trim_pack.h"

/* Growable float arrays of the three textures. */
typedef struct arrays {
    float *points, *knots, *records, *trims; /* 4, 1, 4, 4 floats per texel */
    int npoints, nknots, nrecords, ntrims;   /* texels */
    int cap_points, cap_knots, cap_records, cap_trims;
} arrays;

static float *grow(float **data, int *count, int *cap, int add, int floats_per_texel)
{
    if (*count + add > *cap || !*data) {
        while (*count + add > *cap || *cap == 0)
            *cap = *cap ? 2 * *cap : 256;
        *data = sc_realloc(*data, (size_t)*cap * (size_t)floats_per_texel, sizeof(float));
    }
    float *at = *data + (size_t)*count * (size_t)floats_per_texel;
    *count += add;
    return at;
}

static void arrays_free(arrays *a)
{
    free(a->points);
    free(a->knots);
    free(a->records);
    free(a->trims);
    memset(a, 0, sizeof *a);
}

/* One record: homogeneous points (4 doubles each, world space) re-centred on
 * the middle of their Euclidean bounding box, rounded to float so that the
 * record holds the centre exactly. */
static void add_record(arrays *a, int surface_id, int deg_u, int deg_v, int nu, int nv,
                       const double *cp, int knot_u, int knot_v, const double rect[4])
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    int n = nu * nv;
    for (int k = 0; k < n; k++)
        for (int c = 0; c < 3; c++) {
            double x = cp[4 * k + c] / cp[4 * k + 3];
            lo[c] = fmin(lo[c], x);
            hi[c] = fmax(hi[c], x);
        }
    double centre[3];
    for (int c = 0; c < 3; c++)
        centre[c] = (float)(0.5 * (lo[c] + hi[c]));
    int first_point = a->npoints;
    float *pt = grow(&a->points, &a->npoints, &a->cap_points, n, 4);
    for (int k = 0; k < n; k++) {
        double w = cp[4 * k + 3];
        /* (x - c)·w = x·w - c·w: relative to the centre, still homogeneous */
        for (int c = 0; c < 3; c++)
            pt[4 * k + c] = (float)(cp[4 * k + c] - centre[c] * w);
        pt[4 * k + 3] = (float)w;
    }
    float *r = grow(&a->records, &a->nrecords, &a->cap_records, SCG_RECORD_TEXELS, 4);
    float rec[4 * SCG_RECORD_TEXELS] = {
        (float)first_point, (float)nu, (float)nv, (float)surface_id,
        (float)knot_u, (float)knot_v, (float)deg_u, (float)deg_v,
        (float)rect[0], (float)rect[1], (float)rect[2], (float)rect[3],
        (float)centre[0], (float)centre[1], (float)centre[2], 0.0f};
    memcpy(r, rec, sizeof rec);
}

static int add_knots(arrays *a, const double *knots, int n)
{
    int first = a->nknots;
    float *k = grow(&a->knots, &a->nknots, &a->cap_knots, n, 1);
    for (int i = 0; i < n; i++)
        k[i] = (float)knots[i];
    return first;
}

/* Appends surface s's data and fills its range: `bez` surfaces one record
 * per patch of `list`, their world-space Bézier patches. The records'
 * trim-block field holds the block's offset among the trim texels for now
 * (-1 when untrimmed); place_trim_blocks makes it a texel index. */
static int build_surface(arrays *a, const sc_surface *surf, int surface_id,
                         const sc_patch_list *list, const scg_key *key, sc_gpu_surface *range,
                         sc_error *err)
{
    sc_trim_block block = {0};
    if (key->trim != SC_TRIM_NONE && surf->nloops > 0 &&
        sc_trim_pack(surf, key->trim_degree, &block, err) != SC_OK)
        return SC_FAIL;
    range->first_trim = a->ntrims;
    if (block.ntexels) {
        float *t = grow(&a->trims, &a->ntrims, &a->cap_trims, block.ntexels, 4);
        memcpy(t, block.texels, (size_t)block.ntexels * 4 * sizeof(float));
    }
    range->trim_count = a->ntrims - range->first_trim;
    sc_trim_block_free(&block);

    range->kind = key->kind;
    range->first_record = a->nrecords / SCG_RECORD_TEXELS;
    range->first_point = a->npoints;
    range->first_knot = a->nknots;
    if (key->kind == SCG_PATCH_NURBS) {
        sc_surface world;
        sc_surface_copy(&world, surf);
        sc_surface_bake_xform(&world);
        int ku = add_knots(a, world.knots_u, world.nu + world.deg_u + 1);
        int kv = add_knots(a, world.knots_v, world.nv + world.deg_v + 1);
        double rect[4];
        sc_surface_domain(&world, &rect[0], &rect[1], &rect[2], &rect[3]);
        add_record(a, surface_id, world.deg_u, world.deg_v, world.nu, world.nv, world.cp, ku,
                   kv, rect);
        sc_surface_free(&world);
    } else if (key->kind == SCG_PATCH_TRIANGLE) {
        /* A terrain's patches (tri_prisms.h): the (n+1)(n+2)/2 points of a
         * triangular patch in one row. */
        for (int p = 0; p < list->count; p++) {
            const sc_bezier_patch *bp = &list->patches[p];
            double rect[4] = {bp->u0, bp->u1, bp->v0, bp->v1};
            int ncoef = (bp->deg_u + 1) * (bp->deg_u + 2) / 2;
            add_record(a, surface_id, bp->deg_u, bp->deg_v, ncoef, 1, bp->cp, 0, 0, rect);
        }
    } else {
        for (int p = 0; p < list->count; p++) {
            const sc_bezier_patch *bp = &list->patches[p];
            double rect[4] = {bp->u0, bp->u1, bp->v0, bp->v1};
            add_record(a, surface_id, bp->deg_u, bp->deg_v, bp->deg_u + 1, bp->deg_v + 1, bp->cp,
                       0, 0, rect);
        }
    }
    range->record_count = a->nrecords / SCG_RECORD_TEXELS - range->first_record;
    range->point_count = a->npoints - range->first_point;
    range->knot_count = a->nknots - range->first_knot;
    for (int r = range->first_record; r < range->first_record + range->record_count; r++)
        a->records[4 * (SCG_RECORD_TEXELS * r + 3) + 3] =
            range->trim_count ? (float)range->first_trim : -1.0f;
    return SC_OK;
}

/* Trim blocks go after all `total_records` records: turns the records'
 * block offsets of one surface into texel indices in sc_records (0 for
 * none, which no block can have, records coming first). */
static void place_trim_blocks(arrays *a, const sc_gpu_surface *range, int total_records)
{
    for (int r = range->first_record; r < range->first_record + range->record_count; r++) {
        float *w = &a->records[4 * (SCG_RECORD_TEXELS * r + 3) + 3];
        *w = *w < 0 ? 0.0f : (float)(total_records * SCG_RECORD_TEXELS) + *w;
    }
}

/* Records [first, first + count) of the arrays: their centres (texel +3). */
static void copy_centres(sc_gpu_data *data, const arrays *a, int first, int count)
{
    for (int r = first; r < first + count; r++)
        for (int c = 0; c < 3; c++)
            data->centres[3 * r + c] = a->records[4 * (SCG_RECORD_TEXELS * r + 3) + c];
}

static const GLenum texture_formats[SCG_TEXTURE_COUNT] = {
    [SCG_TEX_POINTS] = GL_RGBA32F,
    [SCG_TEX_KNOTS] = GL_R32F,
    [SCG_TEX_RECORDS] = GL_RGBA32F,
};

/* Bytes of texture t's buffer: never empty (scenes drawn by bez programs
 * alone have no knots), one zero texel then. */
static size_t texture_bytes(const sc_gpu_data *data, int t)
{
    size_t texels[SCG_TEXTURE_COUNT] = {
        [SCG_TEX_POINTS] = (size_t)data->npoints * 16,
        [SCG_TEX_KNOTS] = (size_t)data->nknots * 4,
        [SCG_TEX_RECORDS] = ((size_t)data->nrecords * SCG_RECORD_TEXELS +
                             (size_t)data->ntrim_texels) * 16,
    };
    return texels[t] ? texels[t] : 16;
}

int sc_gpu_data_build_from(const sc_gl *gl, const sc_scene *scene,
                           const sc_patch_list *patches, const scg_key *keys,
                           sc_gpu_data *data, sc_error *err)
{
    memset(data, 0, sizeof *data);
    arrays a = {0};
    data->nsurfaces = scene->nsurfaces;
    data->surfaces = sc_alloc((size_t)(scene->nsurfaces ? scene->nsurfaces : 1),
                              sizeof *data->surfaces);
    for (int s = 0; s < scene->nsurfaces; s++)
        if (build_surface(&a, &scene->surfaces[s], s, &patches[s], &keys[s], &data->surfaces[s],
                          err) != SC_OK) {
            arrays_free(&a);
            sc_gpu_data_free(gl, data);
            return SC_FAIL;
        }
    data->nrecords = a.nrecords / SCG_RECORD_TEXELS;
    data->npoints = a.npoints;
    data->nknots = a.nknots;
    data->ntrim_texels = a.ntrims;
    data->centres = sc_alloc((size_t)(data->nrecords ? data->nrecords : 1), 3 * sizeof(double));
    copy_centres(data, &a, 0, data->nrecords);
    for (int s = 0; s < scene->nsurfaces; s++)
        place_trim_blocks(&a, &data->surfaces[s], data->nrecords);
    if (a.ntrims) {
        float *t = grow(&a.records, &a.nrecords, &a.cap_records, a.ntrims, 4);
        memcpy(t, a.trims, (size_t)a.ntrims * 4 * sizeof(float));
    }
    GLint max_texels = 0;
    /* Without a context (a pack written at build time) the layout's own limit. */
    if (gl)
        gl->GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    else
        max_texels = 1 << 24;
    int most = a.npoints > a.nrecords ? a.npoints : a.nrecords;
    if (a.nknots > most)
        most = a.nknots;
    /* Offsets travel as floats: exact below 2^24 (gpu_layout.h). */
    if (most > max_texels || most >= (1 << 24)) {
        arrays_free(&a);
        sc_gpu_data_free(gl, data);
        return sc_fail(err, NULL, 0,
                       "scene too large for the GPU layout: %d texels in one texture "
                       "(limit %d)", most, max_texels < (1 << 24) ? max_texels : (1 << 24));
    }
    /* The arrays move into the staged data; the trims were copied. */
    data->staged[SCG_TEX_POINTS] = a.points;
    data->staged[SCG_TEX_KNOTS] = a.knots;
    data->staged[SCG_TEX_RECORDS] = a.records;
    free(a.trims);
    for (int t = 0; t < SCG_TEXTURE_COUNT; t++)
        data->bytes += texture_bytes(data, t);
    return SC_OK;
}

int sc_gpu_data_send(const sc_gl *gl, sc_gpu_data *data, size_t needed, sc_error *err)
{
    gl->CreateBuffers(SCG_TEXTURE_COUNT, data->buffers);
    gl->CreateTextures(GL_TEXTURE_BUFFER, SCG_TEXTURE_COUNT, data->textures);
    for (int t = 0; t < SCG_TEXTURE_COUNT; t++) {
        static const float zero[4];
        gl->NamedBufferStorage(data->buffers[t], (GLsizeiptr)texture_bytes(data, t),
                               data->staged[t] ? (const void *)data->staged[t] : zero,
                               GL_DYNAMIC_STORAGE_BIT);
        gl->TextureBuffer(data->textures[t], texture_formats[t], data->buffers[t]);
        free(data->staged[t]);
        data->staged[t] = NULL;
    }
    data->bytes_uploaded = data->bytes;
    if (sc_gl_check_upload(gl, "uploading the patch data", needed, err) != SC_OK) {
        sc_gpu_data_free(gl, data);
        return SC_FAIL;
    }
    return SC_OK;
}

int sc_gpu_data_upload_from(const sc_gl *gl, const sc_scene *scene,
                            const sc_patch_list *patches, const scg_key *keys,
                            sc_gpu_data *data, sc_error *err)
{
    if (sc_gpu_data_build_from(gl, scene, patches, keys, data, err) != SC_OK)
        return SC_FAIL;
    return sc_gpu_data_send(gl, data, data->bytes, err);
}

int sc_gpu_data_update_surface_from(const sc_gl *gl, sc_gpu_data *data, const sc_scene *scene,
                                    const sc_patch_list *patches, int surface,
                                    const scg_key *keys, int *moved, sc_error *err)
{
    if (moved)
        *moved = 0;
    if (surface < 0 || surface >= data->nsurfaces || scene->nsurfaces != data->nsurfaces)
        return sc_fail(err, NULL, 0, "surface %d is not in the uploaded scene", surface);
    sc_gpu_surface *old = &data->surfaces[surface];
    /* Build at the surface's own offsets: start the arrays' counts there, so
     * that the offsets written into its records match the textures'. */
    arrays a = {0};
    a.npoints = old->first_point;
    a.nknots = old->first_knot;
    a.nrecords = old->first_record * SCG_RECORD_TEXELS;
    a.ntrims = old->first_trim;
    grow(&a.points, &a.npoints, &a.cap_points, 0, 4);
    grow(&a.knots, &a.nknots, &a.cap_knots, 0, 1);
    grow(&a.records, &a.nrecords, &a.cap_records, 0, 4);
    grow(&a.trims, &a.ntrims, &a.cap_trims, 0, 4);
    sc_gpu_surface fresh;
    if (build_surface(&a, &scene->surfaces[surface], surface, &patches[surface], &keys[surface],
                      &fresh, err) != SC_OK) {
        arrays_free(&a);
        return SC_FAIL;
    }
    if (fresh.kind != old->kind || fresh.record_count != old->record_count ||
        fresh.point_count != old->point_count || fresh.knot_count != old->knot_count ||
        fresh.trim_count != old->trim_count) {
        /* The surface's data changed size: everything after it moves. */
        arrays_free(&a);
        if (moved)
            *moved = 1;
        sc_gpu_data_free(gl, data);
        return sc_gpu_data_upload_from(gl, scene, patches, keys, data, err);
    }
    place_trim_blocks(&a, &fresh, data->nrecords);
    copy_centres(data, &a, old->first_record, old->record_count);
    GLuint records = data->buffers[SCG_TEX_RECORDS];
    gl->NamedBufferSubData(data->buffers[SCG_TEX_POINTS], (GLintptr)old->first_point * 16,
                           (GLsizeiptr)old->point_count * 16,
                           a.points + (size_t)old->first_point * 4);
    if (old->knot_count)
        gl->NamedBufferSubData(data->buffers[SCG_TEX_KNOTS], (GLintptr)old->first_knot * 4,
                               (GLsizeiptr)old->knot_count * 4, a.knots + old->first_knot);
    size_t record_floats = (size_t)old->first_record * SCG_RECORD_TEXELS * 4;
    gl->NamedBufferSubData(records, (GLintptr)(record_floats * sizeof(float)),
                           (GLsizeiptr)old->record_count * SCG_RECORD_TEXELS * 16,
                           a.records + record_floats);
    if (old->trim_count) {
        size_t at = (size_t)data->nrecords * SCG_RECORD_TEXELS + (size_t)old->first_trim;
        gl->NamedBufferSubData(records, (GLintptr)(at * 16), (GLsizeiptr)old->trim_count * 16,
                               a.trims + (size_t)old->first_trim * 4);
    }
    data->bytes_uploaded = (size_t)old->point_count * 16 + (size_t)old->knot_count * 4 +
                           (size_t)old->record_count * SCG_RECORD_TEXELS * 16 +
                           (size_t)old->trim_count * 16;
    arrays_free(&a);
    return sc_gl_check(gl, "updating a surface's patch data", err);
}

/* The old entry points decompose the scene themselves, the same way. */
static sc_patch_list *scene_patches(const sc_scene *scene)
{
    int n = scene->nsurfaces;
    sc_patch_list *patches = sc_alloc((size_t)(n ? n : 1), sizeof *patches);
    for (int s = 0; s < n; s++)
        sc_surface_world_patches(&scene->surfaces[s], s, &patches[s]);
    return patches;
}

static void scene_patches_free(const sc_scene *scene, sc_patch_list *patches)
{
    for (int s = 0; s < scene->nsurfaces; s++)
        sc_patch_list_free(&patches[s]);
    free(patches);
}

int sc_gpu_data_upload(const sc_gl *gl, const sc_scene *scene, const scg_key *keys,
                       sc_gpu_data *data, sc_error *err)
{
    sc_patch_list *patches = scene_patches(scene);
    int status = sc_gpu_data_upload_from(gl, scene, patches, keys, data, err);
    scene_patches_free(scene, patches);
    return status;
}

int sc_gpu_data_update_surface(const sc_gl *gl, sc_gpu_data *data, const sc_scene *scene,
                               int surface, const scg_key *keys, int *moved, sc_error *err)
{
    sc_patch_list *patches = scene_patches(scene);
    int status = sc_gpu_data_update_surface_from(gl, data, scene, patches, surface, keys, moved,
                                                 err);
    scene_patches_free(scene, patches);
    return status;
}

void sc_gpu_data_bind(const sc_gl *gl, const sc_gpu_data *data)
{
    gl->BindTextures(SCG_UNIT_POINTS, SCG_TEXTURE_COUNT, data->textures);
}

void sc_gpu_data_free(const sc_gl *gl, sc_gpu_data *data)
{
    if (data->textures[0] && gl)
        gl->DeleteTextures(SCG_TEXTURE_COUNT, data->textures);
    if (data->buffers[0] && gl)
        gl->DeleteBuffers(SCG_TEXTURE_COUNT, data->buffers);
    for (int t = 0; t < SCG_TEXTURE_COUNT; t++)
        free(data->staged[t]);
    free(data->surfaces);
    free(data->centres);
    memset(data, 0, sizeof *data);
}

int sc_gpu_data_record(const sc_gpu_data *data, int surface, int patch)
{
    const sc_gpu_surface *s = &data->surfaces[surface];
    return s->kind == SCG_PATCH_NURBS ? s->first_record : s->first_record + patch;
}

const double *sc_gpu_data_record_centre(const sc_gpu_data *data, int record)
{
    return data->centres + 3 * record;
}
