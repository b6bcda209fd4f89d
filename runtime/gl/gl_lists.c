/* gl_lists.c — candidate lists per pixel (ert5 programs).
 *
 * A hull a few pixels wide costs more as triangles than as a list entry:
 * llvmpipe transforms and bins every triangle on the thread that issues the
 * draw, and shades each one's pixels in 4 × 4 blocks, so that the ten front
 * faces of a tiny hull run its program ten times over the same block, with
 * most lanes masked (docs/speed.md, "Candidate lists"). Here such hulls are
 * not drawn: each frame, the convex outline of every listed hull's
 * projected vertices (the pixels its triangles would cover) adds the hull
 * to the list of each pixel whose centre it holds, in the order of the
 * distance from the eye to the hull's box. Then one point per tile of
 * LIST_TILE_PX² pixels that hold a list covers them, and the fragment
 * program (listcast.frag) runs each pixel's list until the next box lies
 * behind the nearest hit: every lane of a block works on its own pixel's
 * candidates, and only a few primitives are binned. Points, not two
 * triangles a tile, because a block that a diagonal cuts runs the program
 * once per triangle; not one rectangle over all lists, because llvmpipe
 * runs the whole program on a block whose pixels hold none.
 *
 * Built on the CPU from data it holds (the hull vertices and the camera),
 * so no read-back is involved. Hulls holding the eye or crossing the near
 * plane stay hulls: their outline is not a bound of their pixels. */
#include <stdlib.h>
#include <string.h>

#include "gl_render_private.h"

/* Pixel centres within this much of an outline's edge count as inside:
 * the rasteriser, which decides for the hull path, rounds too. */
#define EDGE_SLACK_PX 1e-3
/* The side of the tiles drawn over the pixels that hold candidates (4,
 * 8 and 16 drew the grid of docs/speed.md alike). */
#define LIST_TILE_PX 8

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

/* Twice the signed area of (o, a, b), points as x, y pairs. */
static double turn(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/* The convex outline of n window points (x, y pairs; sorted in place by
 * x, then y), counter-clockwise, into out (room for n + 1 points);
 * returns its length. Andrew's monotone chain: the lower chain left to
 * right, then the upper one back. A hull has a dozen vertices or so, so
 * an insertion sort. */
static int convex_outline(double *pts, int n, double *out)
{
    for (int i = 1; i < n; i++) {
        double x = pts[2 * i], y = pts[2 * i + 1];
        int j = i;
        for (; j > 0 && (pts[2 * j - 2] > x || (pts[2 * j - 2] == x && pts[2 * j - 1] > y)); j--) {
            pts[2 * j] = pts[2 * j - 2];
            pts[2 * j + 1] = pts[2 * j - 1];
        }
        pts[2 * j] = x;
        pts[2 * j + 1] = y;
    }
    if (n < 3) {
        memcpy(out, pts, (size_t)n * 2 * sizeof *pts);
        return n;
    }
    int m = 0;
    for (int i = 0; i < n; i++) {
        while (m >= 2 && turn(out + 2 * (m - 2), out + 2 * (m - 1), pts + 2 * i) <= 0)
            m--;
        memcpy(out + 2 * m++, pts + 2 * i, 2 * sizeof *pts);
    }
    for (int i = n - 2, lower = m + 1; i >= 0; i--) {
        while (m >= lower && turn(out + 2 * (m - 2), out + 2 * (m - 1), pts + 2 * i) <= 0)
            m--;
        memcpy(out + 2 * m++, pts + 2 * i, 2 * sizeof *pts);
    }
    return m - 1;   /* the last point is the first again */
}

/* For each row of rect, the pixels [from, to) whose centres the outline
 * (n points) holds, into spans (2 ints a row). A row that the edge slack
 * admits above or below the outline takes the span at its edge. */
static void outline_spans(const double *outline, int n, const int rect[4], int *spans)
{
    double y_lo = INFINITY, y_hi = -INFINITY;
    for (int i = 0; i < n; i++) {
        double y = outline[2 * i + 1];
        y_lo = y < y_lo ? y : y_lo;
        y_hi = y > y_hi ? y : y_hi;
    }
    for (int y = rect[1]; y < rect[3]; y++) {
        double cy = y + 0.5 < y_lo ? y_lo : y + 0.5 > y_hi ? y_hi : y + 0.5;
        double lo = INFINITY, hi = -INFINITY;
        for (int i = 0; i < n; i++) {
            const double *a = outline + 2 * i, *b = outline + 2 * ((i + 1) % n);
            double below = a[1] < b[1] ? a[1] : b[1], above = a[1] < b[1] ? b[1] : a[1];
            if (cy < below || cy > above)
                continue;
            /* A level edge at the row's height holds both its ends. */
            double xa = a[0], xb = b[0];
            if (a[1] != b[1])
                xa = xb = a[0] + (cy - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            lo = xa < lo ? xa : lo;
            lo = xb < lo ? xb : lo;
            hi = xa > hi ? xa : hi;
            hi = xb > hi ? xb : hi;
        }
        int from = (int)ceil(lo - 0.5 - EDGE_SLACK_PX), to = (int)floor(hi - 0.5 + EDGE_SLACK_PX) + 1;
        int *span = spans + 2 * (y - rect[1]);
        span[0] = from > rect[0] ? from : rect[0];
        span[1] = to < rect[2] ? to : rect[2];
    }
}

/* Hull k's vertices projected to the window (the first 2n doubles of
 * t->projected, which has room for their outline after them), the
 * largest side of their bounding rectangle, and in l->rect the pixels
 * [x0, x1) × [y0, y1) whose centres that rectangle holds; 0 when a vertex
 * lies outside the near or far plane or behind the eye. */
static int project_hull(const sc_renderer *r, list_take *t, int k, const float vp[16],
                        const double eye[3], float *size, list_hull *l)
{
    const sc_subpatch *s = &r->hulls.subpatches[k];
    int width = r->target.width, height = r->target.height, n = s->vertex_count;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    t->projected = grow(t->projected, &t->projected_cap, (size_t)4 * (n + 1), sizeof(double));
    for (int v = 0; v < n; v++) {
        const double *p = r->hulls.vertices[s->first_vertex + v].pos;
        double q[3] = {p[0] - eye[0], p[1] - eye[1], p[2] - eye[2]};
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = vp[row] * q[0] + vp[4 + row] * q[1] + vp[8 + row] * q[2] + vp[12 + row];
        if (!(clip[3] > 0) || clip[2] < -clip[3] || clip[2] > clip[3])
            return 0;
        for (int c = 0; c < 2; c++) {
            double window = (0.5 * clip[c] / clip[3] + 0.5) * (c ? height : width);
            t->projected[2 * v + c] = window;
            lo[c] = window < lo[c] ? window : lo[c];
            hi[c] = window > hi[c] ? window : hi[c];
        }
    }
    *size = (float)(hi[0] - lo[0] > hi[1] - lo[1] ? hi[0] - lo[0] : hi[1] - lo[1]);
    /* Pixel i's centre is i + 0.5. */
    int limit[2] = {width, height};
    for (int c = 0; c < 2; c++) {
        double first = ceil(lo[c] - 0.5 - EDGE_SLACK_PX), last = floor(hi[c] - 0.5 + EDGE_SLACK_PX);
        l->rect[c] = first > 0 ? (int)first : 0;
        l->rect[2 + c] = last + 1 < limit[c] ? (int)(last + 1) : limit[c];
    }
    return 1;
}

int sc_lists_take(const sc_renderer *r, list_take *t, int k, double distance,
                  const float vp[16], const double eye[3], int every_size)
{
    float size;
    list_hull l = {.hull = k, .group = r->hull_group[k]};
    /* A box holding the eye: its distance orders nothing. */
    if (!r->groups[l.group].listable || !(distance > 0) ||
        !project_hull(r, t, k, vp, eye, &size, &l))
        return 0;
    if (!every_size && size > (float)r->desc.list_below_px)
        return 0;
    /* Rounded down, so that it stays a bound of the box's points. */
    l.distance = (float)distance;
    if ((double)l.distance > distance)
        l.distance = nextafterf(l.distance, 0);
    /* The pixels are those of the projection's convex outline: the
     * projection of the convex hull, the pixels the hull path would
     * rasterise (a third fewer than its rectangle's on the grid of
     * docs/speed.md). */
    int n = r->hulls.subpatches[k].vertex_count;
    double *outline = t->projected + 2 * (n + 1);
    int count = convex_outline(t->projected, n, outline);
    int rows = l.rect[3] > l.rect[1] ? l.rect[3] - l.rect[1] : 0;
    t->spans = grow(t->spans, &t->spans_cap, t->spans_len + 2 * (size_t)rows, sizeof(int));
    l.spans_first = t->spans_len;
    outline_spans(outline, count, l.rect, t->spans + l.spans_first);
    t->spans_len += 2 * (size_t)rows;
    t->listed = grow(t->listed, &t->listed_cap, (size_t)t->nlisted + 1, sizeof *t->listed);
    t->listed[t->nlisted++] = l;
    return 1;
}

void sc_lists_merge(sc_renderer *r, int threads)
{
    list_take *to = &r->take[0];
    for (int i = 1; i < threads; i++) {
        const list_take *from = &r->take[i];
        to->listed = grow(to->listed, &to->listed_cap, (size_t)to->nlisted + from->nlisted,
                          sizeof *to->listed);
        for (int j = 0; j < from->nlisted; j++) {
            list_hull l = from->listed[j];
            l.spans_first += to->spans_len;
            to->listed[to->nlisted++] = l;
        }
        to->spans = grow(to->spans, &to->spans_cap, to->spans_len + from->spans_len, sizeof(int));
        memcpy(to->spans + to->spans_len, from->spans, from->spans_len * sizeof(int));
        to->spans_len += from->spans_len;
    }
}

/* The listed hulls in slot order: by group, then box distance (its float
 * bits, which order positive floats as numbers), ties in the order they
 * were taken. A radix sort, 8 bits a pass, then a counting sort by group;
 * each pass stable. */
static void sort_listed(sc_renderer *r)
{
    list_take *frame = &r->take[0];
    int n = frame->nlisted;
    r->listed_spare = grow(r->listed_spare, &r->listed_spare_cap, (size_t)n, sizeof *frame->listed);
    list_hull *from = frame->listed, *to = r->listed_spare;
    for (int pass = 0; pass < 5; pass++) {
        int buckets = pass < 4 ? 256 : r->ngroups;
        r->list_counts = grow(r->list_counts, &r->list_counts_cap, (size_t)buckets + 1, sizeof(size_t));
        size_t *count = r->list_counts;
        memset(count, 0, ((size_t)buckets + 1) * sizeof *count);
        for (int i = 0; i < n; i++) {
            uint32_t bits;
            memcpy(&bits, &from[i].distance, sizeof bits);
            count[1 + (pass < 4 ? bits >> (8 * pass) & 255 : (uint32_t)from[i].group)]++;
        }
        for (int b = 0; b < buckets; b++)
            count[b + 1] += count[b];
        for (int i = 0; i < n; i++) {
            uint32_t bits;
            memcpy(&bits, &from[i].distance, sizeof bits);
            to[count[pass < 4 ? bits >> (8 * pass) & 255 : (uint32_t)from[i].group]++] = from[i];
        }
        list_hull *t = from;
        from = to;
        to = t;
    }
    /* An odd number of passes: the sorted hulls are in the spare. */
    r->listed_spare = frame->listed;
    frame->listed = from;
    size_t cap = r->listed_spare_cap;
    r->listed_spare_cap = frame->listed_cap;
    frame->listed_cap = cap;
}

/* The key of group g's list program: its key as candidate lists draw it
 * (scg_key_for_lists), with the AOVs when the frame writes them. */
static scg_key list_key(const sc_renderer *r, int g, int aov)
{
    const group *gr = &r->groups[g];
    scg_key key = *sc_program_key(r->programs, aov ? gr->aov : gr->program);
    scg_key_for_lists(&key);
    return key;
}

static int frame_aovs(const sc_renderer *r) { return colour_frames(&r->desc) && r->frame_aovs; }

void sc_lists_begin(sc_renderer *r)
{
    for (int i = 0; i < SC_FRAME_MAX_THREADS; i++) {
        r->take[i].nlisted = 0;
        r->take[i].spans_len = 0;
    }
    for (int g = 0; g < r->ngroups; g++) {
        scg_key key = list_key(r, g, frame_aovs(r));
        r->groups[g].listable = sc_program_cache_offers(r->programs, &key);
    }
}

/* Group g's list program, compiled when a frame first lists one of its
 * hulls. */
static int list_program(sc_renderer *r, int g, sc_program *out, sc_error *err)
{
    int aov = frame_aovs(r);
    sc_program *lists = aov ? &r->groups[g].aov_lists : &r->groups[g].lists;
    if (!lists->id) {
        scg_key key = list_key(r, g, aov);
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

/* The tiles of LIST_TILE_PX² pixels of the rectangle [x0, x1) × [y0, y1)
 * (whose sides are multiples of the tile) whose heads (its cells' first entries,
 * one more ending the last) show a candidate, appended to r->list_tiles
 * from entry `ntiles`; returns the new count. */
static size_t add_tiles(sc_renderer *r, const uint32_t *heads, int x0, int y0, int x1, int y1,
                        size_t ntiles)
{
    const int tile = LIST_TILE_PX;
    int rw = x1 - x0;
    for (int ty = y0; ty < y1; ty += tile)
        for (int tx = x0; tx < x1; tx += tile) {
            int any = 0;
            for (int y = ty; y < ty + tile && !any; y++) {
                const uint32_t *row = heads + (size_t)(y - y0) * rw + (tx - x0);
                any = row[tile] != row[0];
            }
            if (!any)
                continue;
            r->list_tiles = grow(r->list_tiles, &r->list_tiles_cap, ntiles + 1, sizeof(uint32_t));
            r->list_tiles[ntiles++] = (uint32_t)tx | (uint32_t)ty << 16;
        }
    return ntiles;
}

/* The rows [from_row, to_row) of one group's lists, built on a thread of
 * their own: the cells of a row band are disjoint from the other bands',
 * and so are their entries once the counts are summed. */
typedef struct list_band {
    const list_hull *listed;
    const int *spans;
    int first, end;       /* the group's listed hulls */
    uint32_t *heads, *items;
    int x0, y0, rw;       /* the group's cells: rw a row, from (x0, y0) */
    int from_row, to_row;
} list_band;

/* Bands for a group of at least this many listed hulls each (building the
 * 100,352-patch grid's lists took 16-22 ms of its frame on one thread). */
#define BAND_MIN_HULLS 1024

/* Over the band's pixels of every listed hull: without items, counts
 * each cell's entries at heads[cell + 1]; with them, puts each cell's
 * entries in slot order from heads[cell] on. */
static void *band_entries(void *arg)
{
    const list_band *b = arg;
    for (int i = b->first; i < b->end; i++) {
        const list_hull *l = &b->listed[i];
        int from = l->rect[1] > b->from_row ? l->rect[1] : b->from_row;
        int to = l->rect[3] < b->to_row ? l->rect[3] : b->to_row;
        for (int y = from; y < to; y++) {
            const int *span = b->spans + l->spans_first + 2 * (y - l->rect[1]);
            uint32_t *row = b->heads + (size_t)(y - b->y0) * b->rw;
            for (int x = span[0]; x < span[1]; x++) {
                if (b->items)
                    b->items[row[x - b->x0]++] = (uint32_t)i;
                else
                    row[x - b->x0 + 1]++;
            }
        }
    }
    return NULL;
}

int sc_lists_draw(sc_renderer *r, const float vp[16], const float eye[3], const float eye_low[3],
                  float footprint, GLuint *current, sc_error *err)
{
    const sc_gl *gl = r->gl;
    int n = r->take[0].nlisted;
    r->list_entries = 0;
    if (!n)
        return SC_OK;
    int width = r->target.width, height = r->target.height;
    sort_listed(r);
    const list_hull *listed = r->take[0].listed;

    /* Per slot (a listed hull, in this order) its domain, then its record
     * and box distance: what the program reads of a candidate. */
    r->list_slots = grow(r->list_slots, &r->list_slots_cap, (size_t)8 * n, sizeof(float));
    for (int i = 0; i < n; i++) {
        const sc_subpatch *s = &r->hulls.subpatches[listed[i].hull];
        /* As the hull vertices carry it (sc_prepare_fill_vertices). */
        const double *rect = r->kinds[s->surface] == SCG_PATCH_NURBS ? s->domain : s->local;
        float *slot = r->list_slots + 8 * (size_t)i;
        for (int c = 0; c < 4; c++)
            slot[c] = (float)rect[c];
        slot[4] = (float)sc_gpu_data_record(&r->data, s->surface, s->patch);
        slot[5] = listed[i].distance;
        slot[6] = slot[7] = 0;
    }

    /* Per group, over the union of its rectangles: the pixels' lists as a
     * counting sort, each list in slot order (nearest box first). */
    const int *spans = r->take[0].spans;
    const int tile = LIST_TILE_PX;
    size_t nheads = 0, nitems = 0, ntiles = 0;
    int ndraws = 0;
    for (int first = 0; first < n;) {
        int g = listed[first].group, end = first;
        int x0 = width, y0 = height, x1 = 0, y1 = 0;
        for (; end < n && listed[end].group == g; end++) {
            const int *rc = listed[end].rect;
            x0 = rc[0] < x0 ? rc[0] : x0;
            y0 = rc[1] < y0 ? rc[1] : y0;
            x1 = rc[2] > x1 ? rc[2] : x1;
            y1 = rc[3] > y1 ? rc[3] : y1;
        }
        if (x1 <= x0 || y1 <= y0) {   /* no pixel centre in any */
            first = end;
            continue;
        }
        /* Whole tiles, some beyond the target's edge. */
        x0 -= x0 % tile;
        y0 -= y0 % tile;
        x1 += (tile - x1 % tile) % tile;
        y1 += (tile - y1 % tile) % tile;
        int rw = x1 - x0;
        size_t cells = (size_t)rw * (size_t)(y1 - y0);
        r->list_heads = grow(r->list_heads, &r->list_heads_cap, nheads + cells + 1, sizeof(uint32_t));
        uint32_t *heads = r->list_heads + nheads;
        memset(heads, 0, (cells + 1) * sizeof *heads);
        int threads = sc_frame_shares(r->desc.threads, end - first, BAND_MIN_HULLS);
        list_band bands[SC_FRAME_MAX_THREADS];
        for (int t = 0; t < threads; t++)
            bands[t] = (list_band){.listed = listed, .spans = spans, .first = first, .end = end,
                                   .heads = heads, .x0 = x0, .y0 = y0, .rw = rw,
                                   .from_row = y0 + (int)((long long)(y1 - y0) * t / threads),
                                   .to_row = y0 + (int)((long long)(y1 - y0) * (t + 1) / threads)};
        sc_run_shares(band_entries, bands, sizeof bands[0], threads);
        for (size_t c = 0; c < cells; c++)
            heads[c + 1] += heads[c];
        size_t count = heads[cells];
        r->list_items = grow(r->list_items, &r->list_items_cap, nitems + count, sizeof(uint32_t));
        /* heads[c] is where cell c's next entry goes, then its end; the
         * shift afterwards makes it the start again. */
        for (size_t c = 0; c < cells + 1; c++)
            heads[c] += (uint32_t)nitems;
        for (int t = 0; t < threads; t++)
            bands[t].items = r->list_items;
        sc_run_shares(band_entries, bands, sizeof bands[0], threads);
        memmove(heads + 1, heads, cells * sizeof *heads);
        heads[0] = (uint32_t)nitems;
        r->list_draws = grow(r->list_draws, &r->list_draws_cap, (size_t)ndraws + 1,
                             sizeof *r->list_draws);
        r->list_draws[ndraws++] = (list_draw){.group = g, .rect = {x0, y0, x1, y1},
                                              .first_head = (int)nheads,
                                              .first_tile = (int)ntiles};
        ntiles = add_tiles(r, heads, x0, y0, x1, y1, ntiles);
        nheads += cells + 1;
        nitems += count;
        first = end;
    }
    r->list_entries = (long long)nitems;
    if (!ndraws)
        return SC_OK;

    if (!r->list_vertex_array) {
        gl->CreateVertexArrays(1, &r->list_vertex_array);
        gl->CreateBuffers(4, r->list_buffers);
        gl->CreateTextures(GL_TEXTURE_BUFFER, 4, r->list_textures);
    }
    send(gl, r->list_buffers[0], r->list_textures[0], GL_R32UI, nheads * 4, r->list_heads);
    send(gl, r->list_buffers[1], r->list_textures[1], GL_R32UI, nitems * 4, r->list_items);
    send(gl, r->list_buffers[2], r->list_textures[2], GL_RGBA32F, (size_t)n * 32, r->list_slots);
    send(gl, r->list_buffers[3], r->list_textures[3], GL_R32UI, ntiles * 4, r->list_tiles);
    if (sc_gl_check_upload(gl, "sending the candidate lists",
                           nheads * 4 + nitems * 4 + n * 32 + ntiles * 4, err) != SC_OK)
        return SC_FAIL;
    gl->BindTextureUnit(SCG_UNIT_LIST_HEADS, r->list_textures[0]);
    gl->BindTextureUnit(SCG_UNIT_LIST_ITEMS, r->list_textures[1]);
    gl->BindTextureUnit(SCG_UNIT_LIST_HULLS, r->list_textures[2]);
    gl->BindTextureUnit(SCG_UNIT_LIST_TILES, r->list_textures[3]);

    float to_ray[9];
    pixel_to_ray(&r->camera, to_ray);
    gl->BindVertexArray(r->list_vertex_array);
    gl->Disable(GL_CULL_FACE);
    gl->Enable(GL_PROGRAM_POINT_SIZE);
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
        gl->ProgramUniform4i(name, SCG_LOC_LIST_TILE, ld->first_tile, width, height, tile);
        if (name != *current) {
            gl->UseProgram(name);
            *current = name;
            r->program_switches++;
        }
        int tiles = (d + 1 < ndraws ? r->list_draws[d + 1].first_tile : (int)ntiles) - ld->first_tile;
        gl->DrawArrays(GL_POINTS, 0, tiles);
        r->draw_calls++;
    }
    gl->Disable(GL_PROGRAM_POINT_SIZE);
    gl->Enable(GL_CULL_FACE);
    gl->BindVertexArray(r->vertex_array);
    return SC_OK;
}

void sc_lists_destroy(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    if (r->list_vertex_array) {
        gl->DeleteVertexArrays(1, &r->list_vertex_array);
        gl->DeleteBuffers(4, r->list_buffers);
        gl->DeleteTextures(4, r->list_textures);
    }
    for (int i = 0; i < SC_FRAME_MAX_THREADS; i++) {
        free(r->take[i].listed);
        free(r->take[i].spans);
        free(r->take[i].projected);
    }
    free(r->listed_spare);
    free(r->list_counts);
    free(r->list_slots);
    free(r->list_heads);
    free(r->list_items);
    free(r->list_draws);
    free(r->list_tiles);
}
