/* gl_render.c — one frame of the render path (gl_render.h): order the
 * hulls by the draw-order policy, cut the order into draw calls (one per
 * run of hulls with the same program) and, for the manual early ray
 * termination, into batches, each reading the nearest distances the
 * batches before it left (refreshed between batches); hulls holding
 * the eye go first, by their back faces, so that their rays still start.
 * The depth test keeps the image exact whatever the order and whatever
 * early termination skips: termination only drops work whose result the
 * depth test would reject. Then the read-back of the image and its AOVs.
 * Preparation is in gl_prepare.c. */
#include "gl_render_private.h"

#include <stdlib.h>
#include <string.h>

#include "gl_deferred.h"
#include "programs.h"
#include "shader_contract.h"
#include "tri_prisms.h"
#include "view_legend.h"

/* The attachments the programs write: the contract's fragment outputs
 * that the view's keys declare, at their locations. */
static void target_formats(const sc_renderer *r, GLenum formats[SC_GL_TARGET_MAX_COLOURS])
{
    unsigned outputs = view_outputs(&r->desc);
    memset(formats, 0, sizeof(GLenum) * SC_GL_TARGET_MAX_COLOURS);
#define X(ID, location, name, type, output, format, miss, clear) \
    if (outputs & SCG_OUTPUT_##output)                          \
        formats[location] = GL_##format;
    SCG_FRAG_OUTS(X)
#undef X
    /* A frame without AOVs: the colour attachment alone (manual early
     * termination then reads the depth buffer). */
    if (!r->frame_aovs)
        for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS; i++)
            if (i != SCG_FRAG_OUT_COLOUR)
                formats[i] = 0;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Depth range that holds every hull: nearest and farthest bounding-box
 * corner along the view direction, the corners that the direction's
 * signs pick (a frame of 100,352 hulls spent 2 % of its time in fmin and
 * fmax over all eight). */
static void depth_range(const sc_renderer *r, const double eye[3], const double fwd[3],
                        double *znear, double *zfar)
{
    double lo = INFINITY, hi = 0;
    for (int k = 0; k < r->hulls.count; k++) {
        const sc_subpatch *s = &r->hulls.subpatches[k];
        double nearest[3], farthest[3];
        for (int c = 0; c < 3; c++) {
            nearest[c] = (fwd[c] < 0 ? s->hi[c] : s->lo[c]) - eye[c];
            farthest[c] = (fwd[c] < 0 ? s->lo[c] : s->hi[c]) - eye[c];
        }
        double z_near = dot3(nearest, fwd), z_far = dot3(farthest, fwd);
        lo = z_near < lo ? z_near : lo;
        hi = z_far > hi ? z_far : hi;
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

static int by_order(const void *a, const void *b)
{
    const sort_item *x = a, *y = b;
    if (x->major != y->major)
        return x->major < y->major ? -1 : 1;
    if (x->minor != y->minor)
        return x->minor < y->minor ? -1 : 1;
    if (x->group != y->group)
        return x->group < y->group ? -1 : 1;
    if (x->distance != y->distance)
        return x->distance < y->distance ? -1 : 1;
    return (x->hull > y->hull) - (x->hull < y->hull);
}

/* Puts r->items[0, n) — hulls not holding the eye, distances filled in —
 * in the order of the draw-order policy. */
static void order_hulls(sc_renderer *r, int n)
{
    sort_item *items = r->items;
    qsort(items, (size_t)n, sizeof *items, by_order);
    /* Manhattan sets (major: the set) are in order already: one program. */
    /* Depth peeling draws in batches front to back (gl_peel.c) and groups
     * each batch's hulls by program on the GPU. */
    if (r->desc.order == SC_HULL_ORDER_FRONT_TO_BACK || r->desc.ert == SC_TERMINATION_PEEL ||
        r->manhattan)
        return;
    /* By program: the programs in the order of their nearest hull, front to
     * back within one. Hybrid: the same within each bucket of batch_hulls
     * hulls taken front to back. In depth order, a group's first hull in a
     * range is its nearest there. */
    int bucket = r->desc.order == SC_HULL_ORDER_HYBRID ? r->desc.batch_hulls : (n ? n : 1);
    for (int start = 0; start < n; start += bucket) {
        int end = start + bucket < n ? start + bucket : n;
        for (int g = 0; g < r->ngroups; g++)
            r->group_seen[g] = INFINITY;
        for (int k = start; k < end; k++) {
            int g = r->hull_group[items[k].hull];
            if (r->group_seen[g] == INFINITY)
                r->group_seen[g] = items[k].distance;
            items[k].major = start;
            items[k].minor = r->group_seen[g];
            items[k].group = g;
        }
    }
    qsort(items, (size_t)n, sizeof *items, by_order);
}

/* The program for hulls of group g that hold the eye (see `group`), of
 * the frame's set. */
static int inside_program(sc_renderer *r, int g, sc_error *err)
{
    group *gr = &r->groups[g];
    int aov = colour_frames(&r->desc) && r->frame_aovs;
    sc_program *inside = aov ? &gr->aov_inside : &gr->inside;
    if (inside->id)
        return SC_OK;
    scg_key key = *sc_program_key(r->programs, aov ? gr->aov : gr->program);
    key.ert = SCG_ERT_NONE;
    return sc_program_for_key(r->programs, &key, inside, err);
}

/* colour_frames: the programs that write the AOVs too, compiled when a
 * frame first asks for the AOVs (reading back, picking), so that a viewer
 * that only draws never compiles them. */
static int aov_programs(sc_renderer *r, sc_error *err)
{
    double t0 = sc_now();
    for (int g = 0; g < r->ngroups; g++) {
        group *gr = &r->groups[g];
        if (gr->aov.id)
            continue;
        scg_key key = *sc_program_key(r->programs, gr->program);
        key.outputs |= SCG_OUTPUT_AOV;
        if (sc_program_for_key(r->programs, &key, &gr->aov, err) != SC_OK)
            return SC_FAIL;
    }
    r->compile_ms += 1e3 * (sc_now() - t0);
    return SC_OK;
}

/* Appends hull k to the frame's index list and to the last draw call when
 * it continues it, else to a new one. */
static void append_hull(sc_renderer *r, int *nruns, int *nidx, int k, int inside)
{
    const sc_subpatch *s = &r->hulls.subpatches[k];
    int g = r->hull_group[k];
    draw_run *last = *nruns ? &r->runs[*nruns - 1] : NULL;
    if (!last || last->group != g || last->inside != inside) {
        last = &r->runs[(*nruns)++];
        *last = (draw_run){.group = g, .inside = inside, .first = *nidx};
    }
    memcpy(r->frame_indices + *nidx, r->hulls.indices + s->first_index,
           (size_t)s->index_count * sizeof(uint32_t));
    *nidx += s->index_count;
    last->count += s->index_count;
}

/* Uploads the indices of runs [0, nruns) (from index `first` on) and draws
 * them. */
static void submit_runs(sc_renderer *r, int nruns, int first, int nidx, GLuint *current)
{
    const sc_gl *gl = r->gl;
    if (nidx > first)
        gl->NamedBufferSubData(r->index_buffer, (GLintptr)first * 4,
                               (GLsizeiptr)(nidx - first) * 4, r->frame_indices + first);
    for (int i = 0; i < nruns; i++) {
        const draw_run *run = &r->runs[i];
        GLuint program =
            sc_program_gl_name(r->programs, sc_render_group_program(r, run->group, run->inside));
        if (program != *current) {
            gl->UseProgram(program);
            *current = program;
            r->program_switches++;
        }
        gl->CullFace(run->inside == 1 ? GL_FRONT : GL_BACK);
        gl->DrawElements(GL_TRIANGLES, run->count, GL_UNSIGNED_INT,
                         (const void *)((size_t)run->first * sizeof(uint32_t)));
        r->draw_calls++;
    }
}

/* Between batches in the manual modes the uvt attachment (the depth buffer
 * in a colour-only frame) is read back. Its distances (.z, along the unit
 * ray) go, as their largest value over each tile of SCG_NEAREST_TILE²
 * pixels, to sc_nearest_t, which the ert1/ert2 programs read instead of
 * the attachment they write: GL leaves a fragment's read of a texel that
 * fragments of the same draw write undefined, and hulls of one batch
 * overlap on screen. A tile's largest distance never lies in front of the
 * nearest hit of any of its pixels, and the upload is a 16th of the
 * image's (on llvmpipe the frame time is the same as with every pixel's
 * distance). They also become depth along the view direction (which,
 * unlike the distance, a box's corners bound), kept as its largest value
 * per tile for culling whole hulls.
 *
 * Both figures only ever err large (a tile's value at or behind every hit
 * in it), which only discards and culls less. So the pixels give only
 * their largest value per tile, a plain maximum the compiler vectorises,
 * and the conversions run once a tile: depth = distance × the cosine
 * between the pixel's ray and the view direction, bounded with the tile's
 * largest cosine, and back with its smallest. Converting every pixel in
 * double precision took 13.7 % of the CPU samples of the teapot's manual
 * frames at 1024² (`perf record`, `bench --ert manual`), while the
 * rasteriser's threads waited on it. */
enum { NEAREST_TILE = SCG_NEAREST_TILE };

/* Per tile the smallest and largest cosine between its pixels' rays
 * (sx, sy, 1) in the camera's frame and the view direction: they depend
 * only on the size and the field of view. */
static void tile_cosines(sc_renderer *r, int w, int h, int tw, int th)
{
    if (r->cosine_fovy == r->camera.fovy_deg)
        return;
    r->cosine = sc_realloc(r->cosine, 2 * (size_t)tw * (size_t)th, sizeof(float));
    float *lo = r->cosine, *hi = r->cosine + (size_t)tw * (size_t)th;
    for (int t = 0; t < tw * th; t++) {
        lo[t] = 1;
        hi[t] = 0;
    }
    double tan_half = tan(0.5 * r->camera.fovy_deg * M_PI / 180.0);
    double aspect = (double)w / h;
    for (int y = 0; y < h; y++) {
        double sy = (2.0 * (y + 0.5) / h - 1) * tan_half;
        for (int x = 0; x < w; x++) {
            double sx = (2.0 * (x + 0.5) / w - 1) * tan_half * aspect;
            float c = (float)(1 / sqrt(1 + sx * sx + sy * sy));
            size_t t = (size_t)(y / NEAREST_TILE) * (size_t)tw + (size_t)(x / NEAREST_TILE);
            lo[t] = fminf(lo[t], c);
            hi[t] = fmaxf(hi[t], c);
        }
    }
    r->cosine_fovy = r->camera.fovy_deg;
}

/* The later rows of one tile row into the first, each value the larger.
 * In runs of 8 with the rows distinct (restrict), which GCC vectorises at
 * -O2 without knowing n: the plain loop it leaves scalar (0.54 against
 * 0.26 ms for the whole reduction of 1024², measured alone). */
static void max_rows(float *restrict first, const float *restrict row, size_t n)
{
    enum { RUN = 8 };
    size_t x = 0;
    for (; x + RUN <= n; x += RUN)
        for (int k = 0; k < RUN; k++)
            first[x + k] = row[x + k] > first[x + k] ? row[x + k] : first[x + k];
    for (; x < n; x++)
        first[x] = row[x] > first[x] ? row[x] : first[x];
}

/* Each tile row's maxima go down the columns into the row's first line,
 * then across each tile. */
void sc_tile_maxima(float *pixels, int w, int h, int tw, float *out)
{
    for (int y0 = 0; y0 < h; y0 += NEAREST_TILE) {
        float *first = pixels + (size_t)y0 * (size_t)w;
        int y1 = y0 + NEAREST_TILE < h ? y0 + NEAREST_TILE : h;
        for (int y = y0 + 1; y < y1; y++)
            max_rows(first, pixels + (size_t)y * (size_t)w, (size_t)w);
        float *row = out + (size_t)(y0 / NEAREST_TILE) * (size_t)tw;
        for (int tx = 0; tx < tw; tx++) {
            int x1 = (tx + 1) * NEAREST_TILE < w ? (tx + 1) * NEAREST_TILE : w;
            float m = 0;
            for (int x = tx * NEAREST_TILE; x < x1; x++)
                m = first[x] > m ? first[x] : m;
            row[tx] = m;
        }
    }
}

static void refresh_nearest(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    int w = r->target.width, h = r->target.height;
    int tw = (w + NEAREST_TILE - 1) / NEAREST_TILE, th = (h + NEAREST_TILE - 1) / NEAREST_TILE;
    size_t tiles = (size_t)tw * (size_t)th;
    int channels = r->frame_aovs ? 4 : 1;
    r->uvt = sc_realloc(r->uvt, (size_t)channels * (size_t)w * (size_t)h, sizeof(float));
    r->nearest = sc_realloc(r->nearest, tiles, sizeof(float));
    r->tile_far = sc_realloc(r->tile_far, tiles, sizeof(float));
    tile_cosines(r, w, h, tw, th);
    const float *cos_lo = r->cosine, *cos_hi = r->cosine + tiles;
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    /* Rows bottom-up, as the window, and so back into sc_nearest_t. */
    if (!r->frame_aovs) {
        gl->GetTextureImage(r->target.depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                            (GLsizei)((size_t)w * (size_t)h * sizeof(float)), r->uvt);
        /* The largest window depth per tile, back to the depth along the
         * view (the inverse of the projection, which keeps the order),
         * made larger by more than the buffer's rounding there (relative
         * 2^-24 · f/n), so that nothing in front of a hit is ever culled;
         * a tile with background stays far. */
        sc_tile_maxima(r->uvt, w, h, tw, r->tile_far);
        double n = r->znear, f = r->zfar;
        for (size_t t = 0; t < tiles; t++) {
            double d = r->tile_far[t];
            if (d >= 1) {
                r->tile_far[t] = r->nearest[t] = 3.0e38f;
                continue;
            }
            double z = 2 * f * n / ((f + n) - (2 * d - 1) * (f - n));
            z *= 1 + 1e-6 * f / n + 1e-5;
            r->tile_far[t] = (float)z;
            r->nearest[t] = (float)(z / cos_lo[t]);
        }
    } else {
        gl->GetTextureImage(r->target.colour[SCG_FRAG_OUT_UVT], 0, GL_RGBA, GL_FLOAT,
                            (GLsizei)(4 * (size_t)w * (size_t)h * sizeof(float)), r->uvt);
        /* The distances (.z) packed in place, ahead of where they are read. */
        for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
            r->uvt[i] = r->uvt[4 * i + 2];
        sc_tile_maxima(r->uvt, w, h, tw, r->nearest);
        for (size_t t = 0; t < tiles; t++)
            r->tile_far[t] = r->nearest[t] * cos_hi[t];
    }
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TextureSubImage2D(r->nearest_texture, 0, 0, 0, tw, th, GL_RED, GL_FLOAT, r->nearest);
    r->readbacks++;
}

/* Whether hull k lies behind the nearest surface so far at every pixel it
 * can cover: its box, projected (vp, column-major, the camera at the
 * origin) and widened by a pixel,
 * touches only tiles whose largest depth so far is nearer than the box's
 * nearest corner (along the view direction fwd). Along any ray of those
 * pixels every point of the hull then lies behind the hit already there, so
 * no hit of the hull can pass the depth test. */
static int hull_hidden(const sc_renderer *r, const float vp[16], const double fwd[3], int k)
{
    const sc_subpatch *s = &r->hulls.subpatches[k];
    int w = r->target.width, h = r->target.height;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, near = INFINITY;
    for (int c = 0; c < 8; c++) {
        double p[3] = {c & 1 ? s->hi[0] : s->lo[0], c & 2 ? s->hi[1] : s->lo[1],
                       c & 4 ? s->hi[2] : s->lo[2]};
        double d[3] = {p[0] - r->camera.eye[0], p[1] - r->camera.eye[1], p[2] - r->camera.eye[2]};
        near = fmin(near, dot3(d, fwd));
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = vp[row] * d[0] + vp[4 + row] * d[1] + vp[8 + row] * d[2] + vp[12 + row];
        if (!(clip[3] > 1e-9))
            return 0;  /* a corner at or behind the eye: no bounded rectangle */
        double x = (0.5 * clip[0] / clip[3] + 0.5) * w, y = (0.5 * clip[1] / clip[3] + 0.5) * h;
        x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
    }
    int tw = (w + NEAREST_TILE - 1) / NEAREST_TILE;
    int tx0 = (int)fmax(floor(x0 - 1), 0) / NEAREST_TILE;
    int tx1 = (int)fmin(ceil(x1 + 1), w - 1) / NEAREST_TILE;
    int ty0 = (int)fmax(floor(y0 - 1), 0) / NEAREST_TILE;
    int ty1 = (int)fmin(ceil(y1 + 1), h - 1) / NEAREST_TILE;
    if (x1 < 0 || y1 < 0 || x0 >= w || y0 >= h)
        return 1;  /* off screen */
    /* A margin for the float distances the programs write. */
    near *= 1 - 1e-5;
    for (int ty = ty0; ty <= ty1; ty++)
        for (int tx = tx0; tx <= tx1; tx++)
            if (!(r->tile_far[ty * tw + tx] < near))
                return 0;
    return 1;
}

/* Whether hull k's box lies wholly outside one plane of the view frustum
 * (vp as in hull_hidden): then none of its fragments is drawn, and it is
 * left out of the frame before any batch, so that a view with nothing in it
 * draws nothing and reads nothing back. Behind the eye counts as outside
 * (w ≤ 0 at every corner, which hull_hidden cannot bound). */
static int hull_outside(const sc_subpatch *s, const float vp[16], const double eye[3])
{
    unsigned all_out = 0x7f;
    for (int c = 0; c < 8 && all_out; c++) {
        double d[3] = {(c & 1 ? s->hi[0] : s->lo[0]) - eye[0],
                       (c & 2 ? s->hi[1] : s->lo[1]) - eye[1],
                       (c & 4 ? s->hi[2] : s->lo[2]) - eye[2]};
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = vp[row] * d[0] + vp[4 + row] * d[1] + vp[8 + row] * d[2] + vp[12 + row];
        double w = clip[3];
        unsigned out = (clip[0] < -w) | (clip[0] > w) << 1 | (clip[1] < -w) << 2 |
                       (clip[1] > w) << 3 | (clip[2] < -w) << 4 | (clip[2] > w) << 5 |
                       (w <= 0) << 6;
        all_out &= out;
    }
    return all_out != 0;
}

/* sc_nearest_t for a target of the current size. */
static int make_nearest_texture(sc_renderer *r, sc_error *err)
{
    const sc_gl *gl = r->gl;
    if (r->nearest_texture)
        gl->DeleteTextures(1, &r->nearest_texture);
    gl->CreateTextures(GL_TEXTURE_2D, 1, &r->nearest_texture);
    int tw = (r->target.width + NEAREST_TILE - 1) / NEAREST_TILE;
    int th = (r->target.height + NEAREST_TILE - 1) / NEAREST_TILE;
    gl->TextureStorage2D(r->nearest_texture, 1, GL_R32F, tw, th);
    gl->TextureParameteri(r->nearest_texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TextureParameteri(r->nearest_texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return sc_gl_check(gl, "creating the nearest distances", err);
}

int sc_render_begin_target(sc_renderer *r, int width, int height, sc_error *err)
{
    const sc_gl *gl = r->gl;
    int manual = manual_ert(r->desc.ert);
    GLenum formats[SC_GL_TARGET_MAX_COLOURS];
    target_formats(r, formats);
    if (r->target.width != width || r->target.height != height ||
        memcmp(r->target.formats, formats, sizeof formats)) {
        sc_gl_target_destroy(gl, &r->target);
        sc_gl_target_desc td = {.width = width, .height = height};
        memcpy(td.formats, formats, sizeof td.formats);
        if (sc_gl_target_create(gl, &td, &r->target, err) != SC_OK ||
            (manual && make_nearest_texture(r, err) != SC_OK))
            return SC_FAIL;
        r->cosine_fovy = 0;
    }
    float bg = background_linear();
    float clear[SC_GL_TARGET_MAX_COLOURS][4] = {{0}};
    unsigned uncleared = 0;  /* read only at hits: 32 of the 56 bytes a pixel */
    for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++) {
        const scg_frag_out_info *o = &scg_frag_outs[i];
        const float background[4] = {bg, bg, bg, 1};
        memcpy(clear[o->location], o->clear_background ? background : o->clear, sizeof clear[0]);
        uncleared |= (unsigned)o->not_cleared << o->location;
    }
    /* Before the clear, so that the background is encoded like the rest. */
    gl->Enable(GL_FRAMEBUFFER_SRGB);
    sc_gl_target_begin(gl, &r->target, clear, uncleared);
    return SC_OK;
}

/* One frame for cam, writing the AOVs when aovs is 1. */
static int draw_frame(sc_renderer *r, const sc_camera *cam, int aovs, sc_error *err)
{
    const sc_gl *gl = r->gl;
    r->frame_aovs = aovs || !colour_frames(&r->desc);
    if (colour_frames(&r->desc) && r->frame_aovs && aov_programs(r, err) != SC_OK)
        return SC_FAIL;
    if (sc_render_begin_target(r, cam->width, cam->height, err) != SC_OK)
        return SC_FAIL;
    r->camera = *cam;
    double fwd[3], right[3], up[3];
    sc_camera_frame(cam, fwd, right, up);
    double znear, zfar;
    depth_range(r, cam->eye, fwd, &znear, &zfar);
    r->znear = znear;
    r->zfar = zfar;
    float view[16], proj[16], vp[16];
    sc_camera_gl_matrices(cam, znear, zfar, view, proj);
    sc_render_eye_projection(view, proj, vp);
    float footprint = (float)(2.0 * tan(0.5 * cam->fovy_deg * M_PI / 180.0) / cam->height);
    r->time_hulls = r->desc.time_intersection;
    int status = sc_render_hulls(r, cam->eye, fwd, vp, footprint, 1, err);
    r->time_hulls = 0;
    if (status == SC_OK && r->desc.deferred && r->scene->terrain &&
        r->desc.view == SC_SHOW_SHADE)
        status = sc_deferred_shade(r, cam->eye, err);
    gl->Disable(GL_FRAMEBUFFER_SRGB);
    gl->Finish();
    if (status != SC_OK)
        return SC_FAIL;
    sc_peel_finish(r);
    if (r->peel_pending)
        sc_log(SC_LOG_WARN, "depth peeling stopped after %d layers with %lld hull fragments "
               "still in front of their pixels' hits: those pixels keep the best hit found",
               SC_PEEL_MAX_LAYERS, r->peel_pending);
    return sc_gl_check(gl, "drawing the hulls", err);
}

int sc_renderer_draw(sc_renderer *r, const sc_camera *cam, sc_error *err)
{
    return draw_frame(r, cam, 0, err);
}

int sc_renderer_draw_aovs(sc_renderer *r, const sc_camera *cam, sc_error *err)
{
    return draw_frame(r, cam, 1, err);
}

void sc_render_eye_projection(const float view[16], const float proj[16], float vp[16])
{
    /* The camera moved to the origin: the programs project points relative
     * to the eye (hull.vert), never world coordinates. For a rigid view
     * [R | -R·eye], R·(p - eye) is the view of p. */
    float rot[16];
    memcpy(rot, view, sizeof rot);
    rot[12] = rot[13] = rot[14] = 0;
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += (double)proj[k * 4 + row] * rot[col * 4 + k];
            vp[col * 4 + row] = (float)sum;
        }
}

/* One thread's share of a frame's pass over the hulls: hulls [from, to),
 * sorted into those holding the eye (r->inside from index `from` on),
 * those outside the view (counted), those candidate lists take (into
 * take) and the rest (r->items from `from` on). */
typedef struct hull_share {
    sc_renderer *r;
    const float *vp;
    const double *eye;
    int listing;          /* as in sc_render_hulls */
    int from, to;
    list_take *take;
    int ninside, nitems, outside;
} hull_share;

static void *pass_share(void *arg)
{
    hull_share *w = arg;
    const sc_renderer *r = w->r;
    const sc_hulls *h = &r->hulls;
    for (int k = w->from; k < w->to; k++) {
        double d = box_distance(h->subpatches[k].lo, h->subpatches[k].hi, w->eye);
        if (d == 0 && sc_hull_contains(h, k, w->eye))
            r->inside[w->from + w->ninside++] = k;
        else if (hull_outside(&h->subpatches[k], w->vp, w->eye))
            w->outside++;
        else if (!w->listing || !sc_lists_take(r, w->take, k, d, w->vp, w->eye, w->listing == 2))
            r->items[w->from + w->nitems++] = (sort_item){.distance = d, .hull = k};
    }
    return NULL;
}

/* The pass is the frame's CPU work that grows with the hulls (the box
 * distance, the view test, the candidate lists' projection and outline):
 * about 35 ms of the 100,352-patch grid's frame at 1024² on one thread. */
#define PASS_MIN_SHARE 1024

/* The frame's pass over the hulls, in contiguous shares on several threads
 * where there are many; each share's results are then moved up behind the
 * share before it, so that every array is in hull order, as one thread
 * would have left it, and the frame the same whatever the count. */
static void pass_hulls(sc_renderer *r, const float vp[16], const double eye[3], int listing,
                       int *ninside, int *nitems)
{
    int count = r->hulls.count, threads = sc_frame_shares(r->desc.threads, count, PASS_MIN_SHARE);
    hull_share shares[SC_FRAME_MAX_THREADS];
    for (int t = 0; t < threads; t++)
        shares[t] = (hull_share){.r = r, .vp = vp, .eye = eye, .listing = listing,
                                 .from = (int)((long long)count * t / threads),
                                 .to = (int)((long long)count * (t + 1) / threads),
                                 .take = &r->take[t]};
    sc_run_shares(pass_share, shares, sizeof shares[0], threads);
    *ninside = *nitems = 0;
    r->outside = 0;
    for (int t = 0; t < threads; t++) {
        const hull_share *w = &shares[t];
        memmove(r->inside + *ninside, r->inside + w->from, (size_t)w->ninside * sizeof *r->inside);
        memmove(r->items + *nitems, r->items + w->from, (size_t)w->nitems * sizeof *r->items);
        *ninside += w->ninside;
        *nitems += w->nitems;
        r->outside += w->outside;
    }
    if (listing)
        sc_lists_merge(r, threads);
    r->frame_threads = threads;
}

int sc_render_hulls(sc_renderer *r, const double eye_world[3], const double fwd[3],
                    const float vp[16], float footprint, int own_target, sc_error *err)
{
    const sc_gl *gl = r->gl;
    if (sc_renderer_send_updates(r, err) != SC_OK)
        return SC_FAIL;
    int manual = own_target && manual_ert(r->desc.ert);
    float eye[3], eye_low[3], raster_eye[3];
    for (int c = 0; c < 3; c++) {
        eye[c] = (float)eye_world[c];
        eye_low[c] = (float)(eye_world[c] - eye[c]);
        raster_eye[c] = (float)(eye_world[c] - r->raster_origin[c]);
    }
    /* Hulls holding the eye go first (their hits may lie anywhere in front
     * of the other hulls), grouped by program; then the others in the
     * order of the policy. */
    const sc_hulls *h = &r->hulls;
    int ninside, n;
    /* Candidate lists (gl_lists.c) need the renderer's own target, whose
     * pixels they are built over: 2, every hull they can take; 1, in the
     * manual modes, the small ones. A terrain keeps its Manhattan sets. */
    int listing = 0;
    /* A packed renderer (own_scene) keeps no sub-patch domains on the CPU. */
    if (own_target && !r->manhattan && !r->scene->terrain && !r->desc.deferred && !r->own_scene)
        listing = r->desc.ert == SC_TERMINATION_LISTS                       ? 2
                  : manual_ert(r->desc.ert) && r->desc.list_below_px > 0 ? 1
                                                                          : 0;
    if (listing)
        sc_lists_begin(r);
    else
        r->take[0].nlisted = 0;
    pass_hulls(r, vp, eye_world, listing, &ninside, &n);
    /* A terrain's prisms in sets of one Manhattan distance from the
     * square under the eye (seed 004, section VII): a set's prisms do not
     * overlap on screen, and each set is one batch that sees the hits of
     * the sets in front of it. */
    for (int i = 0; r->manhattan && i < n; i++)
        r->items[i].major =
            sc_tri_manhattan(r->scene->terrain, h->subpatches[r->items[i].hull].patch, eye_world);
    order_hulls(r, n);
    for (int i = 0; i < ninside; i++)
        if (r->desc.ert != SC_TERMINATION_NONE &&
            inside_program(r, r->hull_group[r->inside[i]], err) != SC_OK)
            return SC_FAIL;
    /* Depth peeling needs the renderer's own target and no hull holding the
     * eye (whose entry is the eye itself, behind every other hull's); else
     * the frame falls back to drawing every hull with the `inside`
     * programs (ert0): no early termination, the same image. */
    int peeling = r->desc.ert == SC_TERMINATION_PEEL;
    int peel = peeling && own_target && !ninside;
    r->peel_fallback = peeling && !peel;
    r->peel_batches = r->peel_layers = 0;
    r->peel_pending = 0;
    /* The lists' programs draw no hull: hulls the lists did not take are
     * drawn like depth peeling's fallback, front faces, `inside` programs. */
    int ert0_hulls = r->peel_fallback || r->desc.ert == SC_TERMINATION_LISTS;
    for (int i = 0; ert0_hulls && i < n; i++)
        if (inside_program(r, r->hull_group[r->items[i].hull], err) != SC_OK)
            return SC_FAIL;

    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->Enable(GL_CULL_FACE);
    gl->FrontFace(GL_CCW);
    gl->BindVertexArray(r->vertex_array);
    sc_gpu_data_bind(gl, &r->data);
    gl->BindTextureUnit(SCG_UNIT_COLOURS, r->colour_texture);
    /* The intersections of this frame, counted from zero by the programs
     * that write the AOVs (the others count nothing). */
    if (r->frame_aovs) {
        if (!r->counter_buffer) {
            gl->CreateBuffers(1, &r->counter_buffer);
            gl->NamedBufferData(r->counter_buffer, sizeof(GLuint), NULL, GL_DYNAMIC_READ);
        }
        static const GLuint zero = 0;
        gl->ClearNamedBufferData(r->counter_buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                 &zero);
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, SCG_BUFFER_COUNTERS, r->counter_buffer);
    }
    if (manual) {
        static const float far = 3.0e38f;
        gl->ClearTexImage(r->nearest_texture, 0, GL_RED, GL_FLOAT, &far);
        gl->BindTextureUnit(SCG_UNIT_NEAREST_T, r->nearest_texture);
    }
    for (int g = 0; g < r->ngroups; g++) {
        sc_program programs[2] = {sc_render_group_program(r, g, 0),
                                  sc_render_group_program(r, g, 1)};
        for (int i = 0; i < 2; i++) {
            GLuint program = sc_program_gl_name(r->programs, programs[i]);
            /* A list program's uniforms are set where it draws (gl_lists.c). */
            if (!program || sc_program_key(r->programs, programs[i])->ert == SCG_ERT_LISTS)
                continue;
            gl->ProgramUniformMatrix4fv(program, SCG_LOC_VIEW_PROJECTION, 1, GL_FALSE, vp);
            gl->ProgramUniform3fv(program, SCG_LOC_EYE, 1, eye);
            gl->ProgramUniform3fv(program, SCG_LOC_EYE_LOW, 1, eye_low);
            gl->ProgramUniform3fv(program, SCG_LOC_RASTER_EYE, 1, raster_eye);
            gl->ProgramUniform1f(program, SCG_LOC_FOOTPRINT, footprint);
        }
    }

    r->draw_calls = r->program_switches = r->culled = r->readbacks = 0;
    r->timed = r->time_hulls;
    double t0 = 0;
    if (r->timed) {
        if (!r->time_query)
            gl->GenQueries(1, &r->time_query);
        gl->Finish();
        t0 = sc_now();
        gl->BeginQuery(GL_TIME_ELAPSED, r->time_query);
    }
    GLuint current = 0;
    if (peel) {
        int status = sc_peel_draw(r, n, vp, raster_eye, &current, err);
        if (r->timed) {
            gl->EndQuery(GL_TIME_ELAPSED);
            gl->Finish();
            r->intersect_ms = 1e3 * (sc_now() - t0);
        }
        return status;
    }
    int nruns = 0, nidx = 0;
    for (int g = 0; g < r->ngroups; g++)
        for (int i = 0; i < ninside; i++)
            if (r->hull_group[r->inside[i]] == g)
                append_hull(r, &nruns, &nidx, r->inside[i], 1);
    submit_runs(r, nruns, 0, nidx, &current);
    if (r->take[0].nlisted && sc_lists_draw(r, vp, eye, eye_low, footprint, &current, err) != SC_OK)
        return SC_FAIL;
    if (manual && (ninside || r->list_entries) && n)
        refresh_nearest(r);
    /* Batches of batch_hulls drawn hulls (all of them but in the manual
     * modes); after each, sc_nearest_t takes its hits, so that a batch sees
     * every hit of the batches before it and none of its own, and whole
     * hulls behind those hits are culled. A read-back that culled nothing
     * doubles the next batch: it costs a copy, which only culling repays. */
    int batch = manual && !r->manhattan ? r->desc.batch_hulls : n + 1;
    for (int p = 0; p < n;) {
        int first = nidx, drawn = 0, culled = 0;
        double set = r->items[p].major;
        nruns = 0;
        for (; p < n && drawn < batch && !(r->manhattan && r->items[p].major != set); p++) {
            int k = r->items[p].hull;
            if (r->readbacks && hull_hidden(r, vp, fwd, k)) {
                culled++;
                continue;
            }
            append_hull(r, &nruns, &nidx, k, ert0_hulls ? 2 : 0);
            drawn++;
        }
        r->culled += culled;
        if (r->readbacks && !culled && batch < n)
            batch *= 2;
        if (!drawn)   /* all culled: a Manhattan set may end before the order does */
            continue;
        submit_runs(r, nruns, first, nidx, &current);
        if (manual && p < n)
            refresh_nearest(r);
    }
    if (manual)
        gl->BindTextureUnit(SCG_UNIT_NEAREST_T, 0);
    if (r->timed) {
        gl->EndQuery(GL_TIME_ELAPSED);
        gl->Finish();
        r->intersect_ms = 1e3 * (sc_now() - t0);
    }
    return SC_OK;
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
    /* A frame drawn without AOVs: drawn again with them, at its camera. */
    if (!r->frame_aovs) {
        sc_camera cam = r->camera;
        if (!(cam.fovy_deg > 0))
            return sc_fail(err, NULL, 0, "no frame of the renderer's own to draw again with "
                                         "its AOVs (sc_renderer_draw first)");
        if (sc_renderer_draw_aovs(r, &cam, err) != SC_OK)
            return SC_FAIL;
    }
    int n = t->width * t->height;
    sc_aov own;
    sc_aov *a = aov ? aov : &own;
    sc_aov_alloc(a, &r->camera, 1);
    /* The AOV attachments, by location; the surface ids straight into the
     * AOVs, the rest unpacked below. */
    void *read[SC_GL_TARGET_MAX_COLOURS] = {0};
    int status = SC_OK;
    for (int i = 0; i < SCG_FRAG_OUT_ENTRIES && status == SC_OK; i++) {
        const scg_frag_out_info *o = &scg_frag_outs[i];
        if (o->key_output != SCG_OUTPUT_AOV)
            continue;
        read[o->location] = o->location == SCG_FRAG_OUT_SURFACE
                                ? (void *)a->surface
                                : sc_alloc((size_t)n * 4, sizeof(float));
        status = sc_gl_target_read_attachment(gl, t, o->location, read[o->location], err);
    }
    const float *uvt = read[SCG_FRAG_OUT_UVT], *point = read[SCG_FRAG_OUT_POINT];
    const float *normal = read[SCG_FRAG_OUT_NORMAL];
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
    for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS; i++)
        if (read[i] != (void *)a->surface)
            free(read[i]);
    unsigned image = view_image_output(r->desc.view);
    if (status == SC_OK && img && image) {
        for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++)
            if (scg_frag_outs[i].key_output == image)
                status = sc_gl_target_read_image(gl, t, scg_frag_outs[i].location, img, err);
    } else if (status == SC_OK && img) {
        sc_image_alloc(img, t->width, t->height, 4);
        if (r->desc.view == SC_SHOW_NORMAL)
            grey_view(a, a->normal, 3, 1, img);
        else if (r->desc.view == SC_SHOW_REFLECT)
            sc_view_reflect(a, img);
        else
            grey_view(a, a->t, 1, 0, img);
    }
    /* One background for every view, and a legend. */
    if (status == SC_OK && img && img->pixels)
        sc_view_finish(r->desc.view, a, r->scene->nsurfaces ? r->keys[0].max_iters : 1, img);
    if (!aov || status != SC_OK)
        sc_aov_free(a);
    return status;
}

int sc_renderer_read_nearest(sc_renderer *r, float *t, sc_error *err)
{
    const sc_gl *gl = r->gl;
    if (!r->nearest_texture)
        return sc_fail(err, NULL, 0, "no nearest distances: nothing drawn with manual early ray "
                                     "termination yet");
    int w = r->target.width, h = r->target.height;
    int tw = (w + NEAREST_TILE - 1) / NEAREST_TILE, th = (h + NEAREST_TILE - 1) / NEAREST_TILE;
    float *tiles = sc_alloc((size_t)tw * (size_t)th, sizeof(float));
    gl->PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl->GetTextureImage(r->nearest_texture, 0, GL_RED, GL_FLOAT,
                        (GLsizei)((size_t)tw * (size_t)th * sizeof(float)), tiles);
    /* Tiles count rows from the bottom, as the window does. */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            t[(size_t)y * (size_t)w + (size_t)x] =
                tiles[(size_t)((h - 1 - y) / NEAREST_TILE) * (size_t)tw + (size_t)(x / NEAREST_TILE)];
    free(tiles);
    return sc_gl_check(gl, "reading the nearest distances", err);
}
