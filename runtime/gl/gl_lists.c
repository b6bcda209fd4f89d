/* gl_lists.c — candidate lists per pixel (ert5 programs).
 *
 * A hull a few pixels wide costs more as triangles than as a list entry:
 * llvmpipe transforms and bins every triangle on the thread that issues the
 * draw, and shades each one's pixels in 4 × 4 blocks, so that the ten front
 * faces of a tiny hull run its program ten times over the same block, with
 * most lanes masked (docs/speed.md, "Candidate lists"). Here such hulls are
 * not drawn: each frame, the screen rectangle of every listed hull (its
 * vertices projected) adds the hull to the list of each pixel whose centre
 * it holds, in the order of the distance from the eye to the hull's box.
 * Then one rectangle per program covers its pixels, and its fragment
 * program (listcast.frag) runs each pixel's list until the next box lies
 * behind the nearest hit: every lane of a block works on its own pixel's
 * candidates, and no triangle is binned.
 *
 * Built on the CPU from data it holds (the hull vertices and the camera),
 * so no read-back is involved. Hulls holding the eye or crossing the near
 * plane stay hulls: their rectangle is not a bound of their pixels. */
#include <stdlib.h>
#include <string.h>

#include "gl_render_private.h"

/* Pixel centres within this much of a rectangle's edge count as inside:
 * the rasteriser, which decides for the hull path, rounds too. */
#define EDGE_SLACK_PX 1e-3

/* The window rectangle [x0, x1) × [y0, y1) of pixels whose centres the
 * projection of hull k's vertices covers; 0 when a vertex lies outside the
 * near or far plane or behind the eye. */
static int hull_pixels(const sc_renderer *r, int k, const float vp[16], const double eye[3],
                       int width, int height, float *size, int rect[4])
{
    const sc_subpatch *s = &r->hulls.subpatches[k];
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int v = s->first_vertex; v < s->first_vertex + s->vertex_count; v++) {
        const double *p = r->hulls.vertices[v].pos;
        double q[3] = {p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]};
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = vp[row] * q[0] + vp[4 + row] * q[1] + vp[8 + row] * q[2] + vp[12 + row];
        if (!(clip[3] > 0) || clip[2] < -clip[3] || clip[2] > clip[3])
            return 0;
        for (int c = 0; c < 2; c++) {
            double window = (0.5 * clip[c] / clip[3] + 0.5) * (c ? height : width);
            lo[c] = fmin(lo[c], window);
            hi[c] = fmax(hi[c], window);
        }
    }
    *size = (float)fmax(hi[0] - lo[0], hi[1] - lo[1]);
    /* Pixel i's centre is i + 0.5. */
    int limit[2] = {width, height};
    for (int c = 0; c < 2; c++) {
        double first = ceil(lo[c] - 0.5 - EDGE_SLACK_PX), last = floor(hi[c] - 0.5 + EDGE_SLACK_PX);
        rect[c] = (int)fmax(first, 0);
        rect[2 + c] = (int)fmin(last + 1, limit[c]);
    }
    return 1;
}

int sc_lists_take(sc_renderer *r, int k, double distance, const float vp[16],
                  const double eye[3], int every_size)
{
    int width = r->target.width, height = r->target.height;
    float size;
    int rect[4];
    /* A box holding the eye: its distance orders nothing. */
    if (!(distance > 0) || !hull_pixels(r, k, vp, eye, width, height, &size, rect))
        return 0;
    if (!every_size && size > (float)r->desc.list_below_px)
        return 0;
    if (r->nlisted == r->listed_cap) {
        r->listed_cap = r->listed_cap ? 2 * r->listed_cap : 1024;
        r->listed = sc_realloc(r->listed, (size_t)r->listed_cap, sizeof *r->listed);
    }
    list_hull *l = &r->listed[r->nlisted++];
    *l = (list_hull){.hull = k, .group = r->hull_group[k], .distance = distance};
    memcpy(l->rect, rect, sizeof rect);
    return 1;
}

static int by_group_then_distance(const void *a, const void *b)
{
    const list_hull *x = a, *y = b;
    if (x->group != y->group)
        return x->group < y->group ? -1 : 1;
    if (x->distance != y->distance)
        return x->distance < y->distance ? -1 : 1;
    return (x->hull > y->hull) - (x->hull < y->hull);
}

static void *grow(void *p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return p;
    size_t n = *cap ? *cap : 4096;
    while (n < need)
        n *= 2;
    *cap = n;
    return sc_realloc(p, n, elem);
}

/* The program of group g for its listed hulls: its key as ert5 (which
 * starts from the sub-patch's middle), with the AOVs when the frame writes
 * them. Compiled when a frame first lists one of its hulls. */
static int list_program(sc_renderer *r, int g, sc_program *out, sc_error *err)
{
    group *gr = &r->groups[g];
    int aov = colour_frames(&r->desc) && r->frame_aovs;
    sc_program *lists = aov ? &gr->aov_lists : &gr->lists;
    if (!lists->id) {
        scg_key key = *sc_program_key(r->programs, aov ? gr->aov : gr->program);
        key.ert = SCG_ERT_LISTS;
        key.start = SC_START_MID;
        double t0 = sc_now();
        if (sc_program_for_key(r->programs, &key, lists, err) != SC_OK)
            return SC_FAIL;
        r->compile_ms += 1e3 * (sc_now() - t0);
    }
    *out = *lists;
    return SC_OK;
}

/* sc_pixel_to_ray: window (x, y, 1) to a world direction of the pixel's
 * ray, from the camera frame sc_camera_gl_matrices builds the projection
 * from: forward + (2x/w − 1)·tan·aspect·right + (2y/h − 1)·tan·up. Lists
 * are drawn only in the renderer's own frames (draw_frame), whose camera
 * r->camera is. */
static void pixel_to_ray(const sc_camera *cam, float m[9])
{
    double fwd[3], right[3], up[3];
    sc_camera_frame(cam, fwd, right, up);
    double ty = tan(0.5 * cam->fovy_deg * M_PI / 180.0);
    double tx = ty * cam->width / cam->height;
    for (int c = 0; c < 3; c++) {
        m[c] = (float)(2 * tx / cam->width * right[c]);
        m[3 + c] = (float)(2 * ty / cam->height * up[c]);
        m[6 + c] = (float)(fwd[c] - tx * right[c] - ty * up[c]);
    }
}

/* Sends n elements of one list array, re-attached to its texture. */
static void send(const sc_gl *gl, GLuint buffer, GLuint texture, GLenum format, size_t bytes,
                 const void *data)
{
    gl->NamedBufferData(buffer, (GLsizeiptr)(bytes ? bytes : 4), bytes ? data : NULL,
                        GL_STREAM_DRAW);
    gl->TextureBuffer(texture, format, buffer);
}

int sc_lists_draw(sc_renderer *r, const float vp[16], const float eye[3], const float eye_low[3],
                  float footprint, GLuint *current, sc_error *err)
{
    const sc_gl *gl = r->gl;
    int n = r->nlisted;
    r->list_entries = 0;
    if (!n)
        return SC_OK;
    int width = r->target.width, height = r->target.height;
    qsort(r->listed, (size_t)n, sizeof *r->listed, by_group_then_distance);

    /* Per slot (a listed hull, in this order) its domain, then its record
     * and box distance: what the program reads of a candidate. */
    r->list_slots = grow(r->list_slots, &r->list_slots_cap, (size_t)8 * n, sizeof(float));
    for (int i = 0; i < n; i++) {
        const sc_subpatch *s = &r->hulls.subpatches[r->listed[i].hull];
        /* As the hull vertices carry it (sc_prepare_fill_vertices). */
        const double *rect = r->kinds[s->surface] == SCG_PATCH_NURBS ? s->domain : s->local;
        float *slot = r->list_slots + 8 * (size_t)i;
        for (int c = 0; c < 4; c++)
            slot[c] = (float)rect[c];
        slot[4] = (float)sc_gpu_data_record(&r->data, s->surface, s->patch);
        /* Rounded down, so that it stays a bound of the box's points. */
        float d = (float)r->listed[i].distance;
        slot[5] = (double)d > r->listed[i].distance ? nextafterf(d, 0) : d;
        slot[6] = slot[7] = 0;
    }

    /* Per group, over the union of its rectangles: the pixels' lists as a
     * counting sort, each list in slot order (nearest box first). */
    size_t nheads = 0, nitems = 0;
    int ndraws = 0;
    for (int first = 0; first < n;) {
        int g = r->listed[first].group, end = first;
        int x0 = width, y0 = height, x1 = 0, y1 = 0;
        for (; end < n && r->listed[end].group == g; end++) {
            const int *rc = r->listed[end].rect;
            x0 = rc[0] < x0 ? rc[0] : x0;
            y0 = rc[1] < y0 ? rc[1] : y0;
            x1 = rc[2] > x1 ? rc[2] : x1;
            y1 = rc[3] > y1 ? rc[3] : y1;
        }
        if (x1 <= x0 || y1 <= y0) {   /* no pixel centre in any */
            first = end;
            continue;
        }
        int rw = x1 - x0;
        size_t cells = (size_t)rw * (size_t)(y1 - y0);
        r->list_heads = grow(r->list_heads, &r->list_heads_cap, nheads + cells + 1, sizeof(uint32_t));
        uint32_t *heads = r->list_heads + nheads;
        memset(heads, 0, (cells + 1) * sizeof *heads);
        for (int i = first; i < end; i++) {
            const int *rc = r->listed[i].rect;
            for (int y = rc[1]; y < rc[3]; y++)
                for (int x = rc[0]; x < rc[2]; x++)
                    heads[(size_t)(y - y0) * rw + (x - x0) + 1]++;
        }
        for (size_t c = 0; c < cells; c++)
            heads[c + 1] += heads[c];
        size_t count = heads[cells];
        r->list_items = grow(r->list_items, &r->list_items_cap, nitems + count, sizeof(uint32_t));
        /* heads[c] is where cell c's next entry goes, then its end; the
         * shift afterwards makes it the start again. */
        for (size_t c = 0; c < cells + 1; c++)
            heads[c] += (uint32_t)nitems;
        for (int i = first; i < end; i++) {
            const int *rc = r->listed[i].rect;
            for (int y = rc[1]; y < rc[3]; y++)
                for (int x = rc[0]; x < rc[2]; x++)
                    r->list_items[heads[(size_t)(y - y0) * rw + (x - x0)]++] = (uint32_t)i;
        }
        memmove(heads + 1, heads, cells * sizeof *heads);
        heads[0] = (uint32_t)nitems;
        r->list_draws = grow(r->list_draws, &r->list_draws_cap, (size_t)ndraws + 1,
                             sizeof *r->list_draws);
        r->list_draws[ndraws++] = (list_draw){.group = g, .rect = {x0, y0, x1, y1},
                                              .first_head = (int)nheads};
        nheads += cells + 1;
        nitems += count;
        first = end;
    }
    r->list_entries = (long long)nitems;
    if (!ndraws)
        return SC_OK;

    if (!r->list_vertex_array) {
        gl->CreateVertexArrays(1, &r->list_vertex_array);
        gl->CreateBuffers(3, r->list_buffers);
        gl->CreateTextures(GL_TEXTURE_BUFFER, 3, r->list_textures);
    }
    send(gl, r->list_buffers[0], r->list_textures[0], GL_R32UI, nheads * 4, r->list_heads);
    send(gl, r->list_buffers[1], r->list_textures[1], GL_R32UI, nitems * 4, r->list_items);
    send(gl, r->list_buffers[2], r->list_textures[2], GL_RGBA32F, (size_t)n * 32, r->list_slots);
    if (sc_gl_check_upload(gl, "sending the candidate lists", nheads * 4 + nitems * 4 + n * 32,
                           err) != SC_OK)
        return SC_FAIL;
    gl->BindTextureUnit(SCG_UNIT_LIST_HEADS, r->list_textures[0]);
    gl->BindTextureUnit(SCG_UNIT_LIST_ITEMS, r->list_textures[1]);
    gl->BindTextureUnit(SCG_UNIT_LIST_HULLS, r->list_textures[2]);

    float to_ray[9];
    pixel_to_ray(&r->camera, to_ray);
    gl->BindVertexArray(r->list_vertex_array);
    gl->Disable(GL_CULL_FACE);
    for (int d = 0; d < ndraws; d++) {
        const list_draw *ld = &r->list_draws[d];
        sc_program program;
        if (list_program(r, ld->group, &program, err) != SC_OK)
            return SC_FAIL;
        GLuint name = sc_program_gl_name(r->programs, program);
        gl->ProgramUniformMatrix4fv(name, SCG_LOC_VIEW_PROJECTION, 1, GL_FALSE, vp);
        gl->ProgramUniform3fv(name, SCG_LOC_EYE, 1, eye);
        gl->ProgramUniform3fv(name, SCG_LOC_EYE_LOW, 1, eye_low);
        gl->ProgramUniform1f(name, SCG_LOC_FOOTPRINT, footprint);
        gl->ProgramUniformMatrix3fv(name, SCG_LOC_PIXEL_TO_RAY, 1, GL_FALSE, to_ray);
        gl->ProgramUniform4i(name, SCG_LOC_LIST_CELLS, ld->rect[0], ld->rect[1],
                             ld->rect[2] - ld->rect[0], ld->first_head);
        gl->ProgramUniform4f(name, SCG_LOC_LIST_QUAD, 2.0f * ld->rect[0] / width - 1,
                             2.0f * ld->rect[1] / height - 1, 2.0f * ld->rect[2] / width - 1,
                             2.0f * ld->rect[3] / height - 1);
        if (name != *current) {
            gl->UseProgram(name);
            *current = name;
            r->program_switches++;
        }
        gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        r->draw_calls++;
    }
    gl->Enable(GL_CULL_FACE);
    gl->BindVertexArray(r->vertex_array);
    return SC_OK;
}

void sc_lists_destroy(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    if (r->list_vertex_array) {
        gl->DeleteVertexArrays(1, &r->list_vertex_array);
        gl->DeleteBuffers(3, r->list_buffers);
        gl->DeleteTextures(3, r->list_textures);
    }
    free(r->listed);
    free(r->list_slots);
    free(r->list_heads);
    free(r->list_items);
    free(r->list_draws);
}
