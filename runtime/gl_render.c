/* gl_render.c — the render path (gl_render.h). Preparation: a key per
 * surface, one program per distinct key (programs.h), the patch data
 * (gl_data.h), the hulls (hulls.h) in one vertex buffer. A frame: sort the
 * hulls of each program front to back, draw each program's hulls with one
 * call (hulls holding the eye by their back faces, so that their rays still
 * start), then read back. Programs are switched once per key, not per hull:
 * the order is front to back within a program, which is what early ray
 * termination needs, and the depth test keeps the image exact whatever the
 * order. */
#include "gl_render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "emit_glsl.h"
#include "gl_data.h"
#include "gl_target.h"
#include "gpu_layout.h"
#include "programs.h"
#include "scene_keys.h"

/* Fragment-stage uniform and vertex-stage uniform locations (templates/hull.vert). */
enum { LOC_VIEW_PROJECTION = 16, LOC_EYE = 17 };
/* Texture unit of the per-surface colours (emit_glsl.c, hull.vert). */
enum { COLOUR_UNIT = 3 };

/* One vertex of a hull as the vertex program reads it (templates/hull.vert:
 * locations 0 position, 1 start (u, v), 2 sub-patch domain, 3 record). */
typedef struct gpu_vertex {
    float pos[3];
    float uv[2];
    float domain[4];
    int32_t record;
} gpu_vertex;

typedef struct group {
    sc_program program;
    int nhulls;
    int *hulls;              /* indices into r->hulls.subpatches */
} group;

struct sc_renderer {
    const sc_gl *gl;
    const sc_scene *scene;
    sc_render_desc desc;
    scg_key *keys;           /* per surface */
    scg_patch_kind *kinds;   /* per surface */
    sc_program *surface_program;
    sc_program_cache *programs;
    sc_gpu_data data;
    sc_hulls hulls;
    int ngroups;
    group *groups;
    GLuint vertex_array, vertex_buffer, index_buffer, colour_buffer, colour_texture;
    size_t hull_bytes, colour_bytes;
    sc_gl_target target;
    sc_camera camera;        /* of the last frame */
    double compile_ms;
    /* per frame scratch */
    uint32_t *frame_indices;
    double *distance;
};

int sc_view_parse(const char *text, sc_view *view, sc_error *err)
{
    static const char *const names[] = {"shade", "uv", "iters", "normal", "depth"};
    for (int i = 0; i < 5; i++)
        if (!strcmp(text, names[i])) {
            *view = (sc_view)i;
            return SC_OK;
        }
    return sc_fail(err, NULL, 0, "unknown view '%s' (shade, uv, iters, normal or depth)", text);
}

/* The key of one surface (scene_keys.h): its degrees, rationality and
 * trims, the render's start, iterations and outputs; the generic program
 * above the unrolling limit, or everywhere when asked. */
static void surface_key(const sc_surface *s, const sc_render_desc *desc, scg_key *key)
{
    sc_key_options opts = {
        .generic_above =
            desc->unroll_max_degree > 0 ? desc->unroll_max_degree : SC_UNROLL_MAX_DEGREE,
        .max_iters = desc->max_iters > 0 ? desc->max_iters : SC_RENDER_DEFAULT_ITERS,
        .tol_milli = desc->tol_milli > 0 ? desc->tol_milli : SC_RENDER_DEFAULT_TOL_MILLI,
        .start = desc->start_set ? desc->start : SCG_START_CP,
        .outputs = SCG_OUTPUT_SHADE | SCG_OUTPUT_AOV |
                   (desc->view == SC_VIEW_ITERS ? SCG_OUTPUT_ITERS : 0) |
                   (desc->view == SC_VIEW_UV ? SCG_OUTPUT_UVVIEW : 0),
    };
    sc_surface_key(s, &opts, key);
    if (desc->generic && key->eval != SCG_EVAL_LOOP) {
        key->eval = SCG_EVAL_LOOP;
        key->deg_u = key->deg_v = 0;
    }
}

/* sRGB 0.2, the reference images' background (shade.c), in linear light:
 * the colour attachment is sRGB, so the GL encodes it on the way in. */
static float background_linear(void) { return (float)pow((0.2 + 0.055) / 1.055, 2.4); }

/* Hull vertices in the parameters of their record's program: local [0, 1]²
 * of the Bézier patch for `bez` records, the surface's own for `nurbs`. */
static int upload_hulls(sc_renderer *r, sc_error *err)
{
    const sc_gl *gl = r->gl;
    const sc_hulls *h = &r->hulls;
    gpu_vertex *verts = sc_alloc((size_t)h->nvertices, sizeof *verts);
    for (int k = 0; k < h->count; k++) {
        const sc_subpatch *s = &h->subpatches[k];
        int nurbs = r->kinds[s->surface] == SCG_PATCH_NURBS;
        double du = nurbs ? (s->domain[1] - s->domain[0]) / (s->local[1] - s->local[0]) : 1;
        double dv = nurbs ? (s->domain[3] - s->domain[2]) / (s->local[3] - s->local[2]) : 1;
        double ou = nurbs ? s->domain[0] - du * s->local[0] : 0;
        double ov = nurbs ? s->domain[2] - dv * s->local[2] : 0;
        const double *rect = nurbs ? s->domain : s->local;
        int record = sc_gpu_data_record(&r->data, s->surface, s->patch);
        for (int v = s->first_vertex; v < s->first_vertex + s->vertex_count; v++) {
            gpu_vertex *g = &verts[v];
            for (int c = 0; c < 3; c++)
                g->pos[c] = (float)h->vertices[v].pos[c];
            g->uv[0] = (float)(ou + du * h->vertices[v].uv[0]);
            g->uv[1] = (float)(ov + dv * h->vertices[v].uv[1]);
            for (int c = 0; c < 4; c++)
                g->domain[c] = (float)rect[c];
            g->record = record;
        }
    }
    if (r->vertex_buffer)
        gl->DeleteBuffers(1, &r->vertex_buffer);
    if (r->index_buffer)
        gl->DeleteBuffers(1, &r->index_buffer);
    gl->CreateBuffers(1, &r->vertex_buffer);
    gl->CreateBuffers(1, &r->index_buffer);
    size_t vbytes = (size_t)(h->nvertices ? h->nvertices : 1) * sizeof *verts;
    size_t ibytes = (size_t)(h->nindices ? h->nindices : 1) * sizeof(uint32_t);
    gl->NamedBufferStorage(r->vertex_buffer, (GLsizeiptr)vbytes, verts, 0);
    /* Rewritten every frame in drawing order. */
    gl->NamedBufferStorage(r->index_buffer, (GLsizeiptr)ibytes, NULL, GL_DYNAMIC_STORAGE_BIT);
    free(verts);
    r->hull_bytes = vbytes + ibytes;
    GLuint vao = r->vertex_array;
    gl->VertexArrayVertexBuffer(vao, 0, r->vertex_buffer, 0, sizeof(gpu_vertex));
    gl->VertexArrayElementBuffer(vao, r->index_buffer);
    r->frame_indices = sc_realloc(r->frame_indices, (size_t)(h->nindices ? h->nindices : 1),
                                  sizeof(uint32_t));
    r->distance = sc_realloc(r->distance, (size_t)(h->count ? h->count : 1), sizeof(double));
    return sc_gl_check(gl, "uploading the hulls", err);
}

/* Hulls by program: group g holds the hulls of the surfaces drawn with
 * program g. */
static void build_groups(sc_renderer *r)
{
    for (int g = 0; g < r->ngroups; g++)
        free(r->groups[g].hulls);
    free(r->groups);
    r->ngroups = sc_program_count(r->programs);
    r->groups = sc_alloc((size_t)r->ngroups, sizeof *r->groups);
    for (int g = 0; g < r->ngroups; g++) {
        r->groups[g].program.id = (uint32_t)g + 1;
        r->groups[g].hulls = sc_alloc((size_t)(r->hulls.count ? r->hulls.count : 1), sizeof(int));
    }
    for (int k = 0; k < r->hulls.count; k++) {
        group *g = &r->groups[r->surface_program[r->hulls.subpatches[k].surface].id - 1];
        g->hulls[g->nhulls++] = k;
    }
}

static void setup_vertex_array(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    gl->CreateVertexArrays(1, &r->vertex_array);
    GLuint vao = r->vertex_array;
    gl->EnableVertexArrayAttrib(vao, 0);
    gl->VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(gpu_vertex, pos));
    gl->EnableVertexArrayAttrib(vao, 1);
    gl->VertexArrayAttribFormat(vao, 1, 2, GL_FLOAT, GL_FALSE, offsetof(gpu_vertex, uv));
    gl->EnableVertexArrayAttrib(vao, 2);
    gl->VertexArrayAttribFormat(vao, 2, 4, GL_FLOAT, GL_FALSE, offsetof(gpu_vertex, domain));
    gl->EnableVertexArrayAttrib(vao, 3);
    gl->VertexArrayAttribIFormat(vao, 3, 1, GL_INT, offsetof(gpu_vertex, record));
    for (int a = 0; a < 4; a++)
        gl->VertexArrayAttribBinding(vao, (GLuint)a, 0);
}

static void upload_colours(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    int n = r->scene->nsurfaces ? r->scene->nsurfaces : 1;
    float *colours = sc_alloc((size_t)n * 4, sizeof(float));
    for (int s = 0; s < r->scene->nsurfaces; s++) {
        memcpy(colours + 4 * s, r->scene->surfaces[s].color, 3 * sizeof(float));
        colours[4 * s + 3] = 1;
    }
    gl->CreateBuffers(1, &r->colour_buffer);
    r->colour_bytes = (size_t)n * 4 * sizeof(float);
    gl->NamedBufferStorage(r->colour_buffer, (GLsizeiptr)r->colour_bytes, colours, 0);
    gl->CreateTextures(GL_TEXTURE_BUFFER, 1, &r->colour_texture);
    gl->TextureBuffer(r->colour_texture, GL_RGBA32F, r->colour_buffer);
    free(colours);
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
    int n = scene->nsurfaces;
    r->keys = sc_alloc((size_t)(n ? n : 1), sizeof *r->keys);
    r->kinds = sc_alloc((size_t)(n ? n : 1), sizeof *r->kinds);
    r->surface_program = sc_alloc((size_t)(n ? n : 1), sizeof *r->surface_program);
    r->programs = sc_program_cache_create(gl);
    double t0 = sc_now();
    for (int s = 0; s < n; s++) {
        surface_key(&scene->surfaces[s], &r->desc, &r->keys[s]);
        r->kinds[s] = r->keys[s].kind;
        if (sc_program_for_key(r->programs, &r->keys[s], &r->surface_program[s], err) != SC_OK)
            goto fail;
    }
    r->compile_ms = 1e3 * (sc_now() - t0);
    if (sc_hulls_build(scene, &r->desc.hulls, &r->hulls, err) != SC_OK ||
        sc_gpu_data_upload(gl, scene, r->keys, &r->data, err) != SC_OK)
        goto fail;
    setup_vertex_array(r);
    upload_colours(r);
    if (upload_hulls(r, err) != SC_OK)
        goto fail;
    build_groups(r);
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
    sc_program_cache_destroy(r->programs);
    sc_hulls_free(&r->hulls);
    for (int g = 0; g < r->ngroups; g++)
        free(r->groups[g].hulls);
    free(r->groups);
    free(r->keys);
    free(r->kinds);
    free(r->surface_program);
    free(r->frame_indices);
    free(r->distance);
    free(r);
}

/* The attachments the programs write (emit_glsl.h). */
static void target_formats(sc_view view, GLenum formats[SC_GL_TARGET_MAX_COLOURS])
{
    memset(formats, 0, sizeof(GLenum) * SC_GL_TARGET_MAX_COLOURS);
    formats[SCG_FRAG_OUT_COLOUR] = GL_SRGB8_ALPHA8;
    formats[SCG_FRAG_OUT_SURFACE] = GL_R32I;
    formats[SCG_FRAG_OUT_UVT] = GL_RGBA32F;
    formats[SCG_FRAG_OUT_POINT] = GL_RGBA32F;
    formats[SCG_FRAG_OUT_NORMAL] = GL_RGBA32F;
    if (view == SC_VIEW_ITERS)
        formats[SCG_FRAG_OUT_ITERS] = GL_RGBA8;
    if (view == SC_VIEW_UV)
        formats[SCG_FRAG_OUT_UV] = GL_RGBA8;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Depth range that holds every hull: nearest and farthest bounding-box
 * corner along the view direction. */
static void depth_range(const sc_renderer *r, const double eye[3], const double fwd[3],
                        double *znear, double *zfar)
{
    double lo = INFINITY, hi = 0;
    for (int k = 0; k < r->hulls.count; k++) {
        const sc_subpatch *s = &r->hulls.subpatches[k];
        for (int c = 0; c < 8; c++) {
            double p[3] = {c & 1 ? s->hi[0] : s->lo[0], c & 2 ? s->hi[1] : s->lo[1],
                           c & 4 ? s->hi[2] : s->lo[2]};
            double d[3] = {p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]};
            double z = dot3(d, fwd);
            lo = fmin(lo, z);
            hi = fmax(hi, z);
        }
    }
    if (!(hi > 0))
        hi = 1;  /* nothing in front: any range draws nothing */
    *zfar = hi * 1.01;
    *znear = fmax(lo * 0.99, *zfar * 1e-5);
}

/* Distance from p to the box [lo, hi] (0 inside). */
static double box_distance(const double lo[3], const double hi[3], const double p[3])
{
    double d2 = 0;
    for (int c = 0; c < 3; c++) {
        double d = p[c] < lo[c] ? lo[c] - p[c] : p[c] > hi[c] ? p[c] - hi[c] : 0;
        d2 += d * d;
    }
    return sqrt(d2);
}

typedef struct ranked {
    double distance;
    int index;
} ranked;

static int by_distance(const void *a, const void *b)
{
    double x = ((const ranked *)a)->distance, y = ((const ranked *)b)->distance;
    return x < y ? -1 : x > y;
}

/* Sorts `items` (indices) by their distances, nearest first. */
static void sort_by_distance(int *items, int n, const double *distance, ranked *scratch)
{
    for (int k = 0; k < n; k++)
        scratch[k] = (ranked){distance[items[k]], items[k]};
    qsort(scratch, (size_t)n, sizeof *scratch, by_distance);
    for (int k = 0; k < n; k++)
        items[k] = scratch[k].index;
}

int sc_renderer_draw(sc_renderer *r, const sc_camera *cam, sc_error *err)
{
    const sc_gl *gl = r->gl;
    GLenum formats[SC_GL_TARGET_MAX_COLOURS];
    target_formats(r->desc.view, formats);
    if (r->target.width != cam->width || r->target.height != cam->height) {
        sc_gl_target_destroy(gl, &r->target);
        sc_gl_target_desc td = {.width = cam->width, .height = cam->height};
        memcpy(td.formats, formats, sizeof td.formats);
        if (sc_gl_target_create(gl, &td, &r->target, err) != SC_OK)
            return SC_FAIL;
    }
    r->camera = *cam;
    double fwd[3], right[3], up[3];
    sc_camera_frame(cam, fwd, right, up);
    double znear, zfar;
    depth_range(r, cam->eye, fwd, &znear, &zfar);
    float view[16], proj[16], vp[16];
    sc_camera_gl_matrices(cam, znear, zfar, view, proj);
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += (double)proj[k * 4 + row] * view[col * 4 + k];
            vp[col * 4 + row] = (float)sum;
        }
    float footprint = (float)(2.0 * tan(0.5 * cam->fovy_deg * M_PI / 180.0) / cam->height);
    float eye[3] = {(float)cam->eye[0], (float)cam->eye[1], (float)cam->eye[2]};

    float bg = background_linear();
    float clear[SC_GL_TARGET_MAX_COLOURS][4] = {{bg, bg, bg, 1}, {-1, -1, -1, -1}};
    /* uvt.z is the distance to the nearest surface so far: far away. */
    clear[SCG_FRAG_OUT_UVT][2] = 3.0e38f;
    /* Before the clear, so that the background is encoded like the rest. */
    gl->Enable(GL_FRAMEBUFFER_SRGB);
    sc_gl_target_begin(gl, &r->target, clear);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->Enable(GL_CULL_FACE);
    gl->FrontFace(GL_CCW);
    gl->BindVertexArray(r->vertex_array);
    sc_gpu_data_bind(gl, &r->data);
    gl->BindTextureUnit(COLOUR_UNIT, r->colour_texture);

    /* Front to back within each program; the programs in the order of their
     * nearest hull. Hulls holding the eye go by their back faces. */
    const sc_hulls *h = &r->hulls;
    for (int k = 0; k < h->count; k++)
        r->distance[k] = box_distance(h->subpatches[k].lo, h->subpatches[k].hi, cam->eye);
    int ngroups = r->ngroups;
    int *group_order = sc_alloc((size_t)(ngroups ? ngroups : 1), sizeof(int));
    double *group_near = sc_alloc((size_t)(ngroups ? ngroups : 1), sizeof(double));
    ranked *scratch = sc_alloc((size_t)(h->count > ngroups ? h->count : ngroups) + 1,
                               sizeof *scratch);
    for (int g = 0; g < ngroups; g++) {
        group *gr = &r->groups[g];
        sort_by_distance(gr->hulls, gr->nhulls, r->distance, scratch);
        group_near[g] = gr->nhulls ? r->distance[gr->hulls[0]] : INFINITY;
        group_order[g] = g;
    }
    sort_by_distance(group_order, ngroups, group_near, scratch);
    free(scratch);

    /* Index ranges: per group, the hulls around the eye, then the others. */
    int nidx = 0;
    int *inside_start = sc_alloc((size_t)(2 * ngroups + 1), sizeof(int));
    for (int gi = 0; gi < ngroups; gi++) {
        group *gr = &r->groups[group_order[gi]];
        for (int pass = 0; pass < 2; pass++) {
            inside_start[2 * gi + pass] = nidx;
            for (int k = 0; k < gr->nhulls; k++) {
                const sc_subpatch *s = &h->subpatches[gr->hulls[k]];
                int inside = r->distance[gr->hulls[k]] == 0 &&
                             sc_hull_contains(h, gr->hulls[k], cam->eye);
                if (inside != (pass == 0))
                    continue;
                memcpy(r->frame_indices + nidx, h->indices + s->first_index,
                       (size_t)s->index_count * sizeof(uint32_t));
                nidx += s->index_count;
            }
        }
    }
    inside_start[2 * ngroups] = nidx;
    if (nidx)
        gl->NamedBufferSubData(r->index_buffer, 0, (GLsizeiptr)nidx * 4, r->frame_indices);
    for (int gi = 0; gi < ngroups; gi++) {
        GLuint program = sc_program_gl_name(r->programs, r->groups[group_order[gi]].program);
        gl->UseProgram(program);
        gl->ProgramUniformMatrix4fv(program, LOC_VIEW_PROJECTION, 1, GL_FALSE, vp);
        gl->ProgramUniform3fv(program, LOC_EYE, 1, eye);
        gl->ProgramUniform1f(program, SCG_UNI_FOOTPRINT, footprint);
        for (int pass = 0; pass < 2; pass++) {
            int first = inside_start[2 * gi + pass], count = inside_start[2 * gi + pass + 1] - first;
            if (!count)
                continue;
            gl->CullFace(pass == 0 ? GL_FRONT : GL_BACK);
            gl->DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT,
                             (const void *)((size_t)first * sizeof(uint32_t)));
        }
    }
    free(inside_start);
    free(group_order);
    free(group_near);
    gl->Disable(GL_FRAMEBUFFER_SRGB);
    gl->Finish();
    return sc_gl_check(gl, "drawing the hulls", err);
}

/* A float channel to an 8-bit grey level, black for misses. */
static void grey_view(const sc_aov *aov, const float *values, int stride, int normal_view,
                      sc_image *img)
{
    int n = aov->width * aov->height;
    double lo = INFINITY, hi = -INFINITY;
    for (int p = 0; p < n && !normal_view; p++)
        if (aov->surface[p] >= 0) {
            lo = fmin(lo, values[p * stride]);
            hi = fmax(hi, values[p * stride]);
        }
    double span = hi > lo ? hi - lo : 1;
    for (int p = 0; p < n; p++) {
        unsigned char *px = img->pixels + 4 * p;
        px[3] = 255;
        if (aov->surface[p] < 0) {
            px[0] = px[1] = px[2] = 0;
            continue;
        }
        for (int c = 0; c < 3; c++) {
            /* normal: (n + 1) / 2 per axis; depth: near white, far dark */
            double x = normal_view ? 0.5 * (values[p * stride + c] + 1)
                                   : 1 - 0.8 * (values[p * stride] - lo) / span;
            px[c] = (unsigned char)lround(255 * fmin(fmax(x, 0), 1));
        }
    }
}

int sc_renderer_read(sc_renderer *r, sc_image *img, sc_aov *aov, sc_error *err)
{
    const sc_gl *gl = r->gl;
    const sc_gl_target *t = &r->target;
    if (!t->framebuffer)
        return sc_fail(err, NULL, 0, "nothing drawn yet");
    int n = t->width * t->height;
    sc_aov own;
    sc_aov *a = aov ? aov : &own;
    sc_aov_alloc(a, &r->camera, 1);
    float *uvt = sc_alloc((size_t)n * 4, sizeof(float));
    float *point = sc_alloc((size_t)n * 4, sizeof(float));
    float *normal = sc_alloc((size_t)n * 4, sizeof(float));
    int status = SC_OK;
    if (sc_gl_target_read(gl, t, SCG_FRAG_OUT_SURFACE, GL_RED_INTEGER, GL_INT, 4, a->surface,
                          err) != SC_OK ||
        sc_gl_target_read(gl, t, SCG_FRAG_OUT_UVT, GL_RGBA, GL_FLOAT, 16, uvt, err) != SC_OK ||
        sc_gl_target_read(gl, t, SCG_FRAG_OUT_POINT, GL_RGBA, GL_FLOAT, 16, point, err) != SC_OK ||
        sc_gl_target_read(gl, t, SCG_FRAG_OUT_NORMAL, GL_RGBA, GL_FLOAT, 16, normal, err) != SC_OK)
        status = SC_FAIL;
    for (int p = 0; p < n && status == SC_OK; p++) {
        if (a->surface[p] < 0) {
            a->surface[p] = -1;
            continue;
        }
        a->uv[2 * p] = uvt[4 * p];
        a->uv[2 * p + 1] = uvt[4 * p + 1];
        a->t[p] = uvt[4 * p + 2];
        a->iters[p] = uvt[4 * p + 3];
        memcpy(a->point + 3 * p, point + 4 * p, 3 * sizeof(float));
        memcpy(a->normal + 3 * p, normal + 4 * p, 3 * sizeof(float));
    }
    free(uvt);
    free(point);
    if (status == SC_OK && img) {
        switch (r->desc.view) {
        case SC_VIEW_SHADE:
            status = sc_gl_target_read_image(gl, t, SCG_FRAG_OUT_COLOUR, img, err);
            break;
        case SC_VIEW_UV:
            status = sc_gl_target_read_image(gl, t, SCG_FRAG_OUT_UV, img, err);
            break;
        case SC_VIEW_ITERS:
            status = sc_gl_target_read_image(gl, t, SCG_FRAG_OUT_ITERS, img, err);
            break;
        case SC_VIEW_NORMAL:
        case SC_VIEW_DEPTH:
            sc_image_alloc(img, t->width, t->height, 4);
            if (r->desc.view == SC_VIEW_NORMAL)
                grey_view(a, a->normal, 3, 1, img);
            else
                grey_view(a, a->t, 1, 0, img);
            break;
        }
    }
    free(normal);
    if (!aov || status != SC_OK)
        sc_aov_free(a);
    return status;
}

int sc_renderer_update_surface(sc_renderer *r, int surface, sc_error *err)
{
    if (surface < 0 || surface >= r->scene->nsurfaces)
        return sc_fail(err, NULL, 0, "no surface %d in the scene", surface);
    scg_key key;
    surface_key(&r->scene->surfaces[surface], &r->desc, &key);
    if (!scg_key_equal(&key, &r->keys[surface]))
        return sc_fail(err, NULL, 0, "surface %d changed its key; make a new renderer", surface);
    if (sc_gpu_data_update_surface(r->gl, &r->data, r->scene, surface, r->keys, err) != SC_OK)
        return SC_FAIL;
    /* Hulls are cheap to build and their count may change: all of them are
     * rebuilt, the patch data of the other surfaces stays. */
    sc_hulls_free(&r->hulls);
    if (sc_hulls_build(r->scene, &r->desc.hulls, &r->hulls, err) != SC_OK ||
        upload_hulls(r, err) != SC_OK)
        return SC_FAIL;
    build_groups(r);
    return SC_OK;
}

void sc_renderer_stats(const sc_renderer *r, sc_render_stats *stats)
{
    stats->programs = sc_program_count(r->programs);
    stats->hulls = r->hulls.count;
    stats->triangles = r->hulls.nindices / 3;
    stats->gpu_bytes = r->data.bytes + r->hull_bytes + r->colour_bytes;
    stats->compile_ms = r->compile_ms;
}

const scg_key *sc_renderer_surface_key(const sc_renderer *r, int surface)
{
    return &r->keys[surface];
}
