/* gl_render_private.h — the renderer's state, shared by the files of the
 * render path: gl_prepare.c (keys, programs, hulls and patch data, surface
 * updates) and gl_render.c (one frame: order, batches, draw, read back). */
#ifndef SC_GL_RENDER_PRIVATE_H
#define SC_GL_RENDER_PRIVATE_H

#include <math.h>
#include <stddef.h>

#include "frame_threads.h"
#include "gl_render.h"
#include "gl_data.h"
#include "gl_target.h"

/* Locations, units and fragment outputs are gen/shader_contract.h's. */

/* A hull vertex as the vertex program reads it (the contract's
 * SCG_ATTRIBS; gpu_vertex_fields says which field is which attribute), the
 * vertex twice: relative to its record's centre, where the programs
 * compute the ray, and relative to one origin for the whole scene, where
 * it is rasterised, so that hulls of different records meeting at a point
 * meet there bit for bit and no crack opens between them. */
typedef struct gpu_vertex {
    float pos[3];
    float raster_pos[3];
    float uv[2];
    float domain[4];
    int32_t record;
} gpu_vertex;

/* Where each vertex attribute lies in gpu_vertex, by location
 * (tests/test_contract.c checks them against the contract). */
typedef struct gpu_vertex_field {
    size_t offset, size;
} gpu_vertex_field;
#define GPU_VERTEX_FIELD(field) {offsetof(gpu_vertex, field), sizeof(((gpu_vertex *)0)->field)}
static const gpu_vertex_field gpu_vertex_fields[] = {
    [SCG_ATTRIB_HULL_POSITION] = GPU_VERTEX_FIELD(pos),
    [SCG_ATTRIB_HULL_UV] = GPU_VERTEX_FIELD(uv),
    [SCG_ATTRIB_HULL_DOMAIN] = GPU_VERTEX_FIELD(domain),
    [SCG_ATTRIB_HULL_RECORD] = GPU_VERTEX_FIELD(record),
    [SCG_ATTRIB_HULL_RASTER_POSITION] = GPU_VERTEX_FIELD(raster_pos),
};
#undef GPU_VERTEX_FIELD

/* The key output (SCG_OUTPUT_*) whose attachment is the view's image; 0
 * for the views drawn from the AOVs. */
static inline unsigned view_image_output(sc_show view)
{
    switch (view) {
    case SC_SHOW_SHADE: return SCG_OUTPUT_SHADE;
    case SC_SHOW_ITERS: return SCG_OUTPUT_ITERS;
    case SC_SHOW_UV: return SCG_OUTPUT_UVVIEW;
    case SC_SHOW_HULL: return SCG_OUTPUT_HULLVIEW;
    default: return 0;
    }
}

/* Depth peeling's most layers a batch: a pixel whose ray enters more hulls
 * of a batch in front of its hit keeps the best hit of these
 * (docs/runtime.md). */
#define SC_PEEL_MAX_LAYERS 16
/* Batches of hulls peeled one after the other, front to back, doubling
 * from batch_hulls; the last takes what is left. */
#define SC_PEEL_MAX_BATCHES 12
#define SC_PEEL_QUERIES (SC_PEEL_MAX_BATCHES * (SC_PEEL_MAX_LAYERS + 1))

static inline int manual_ert(sc_ray_termination mode)
{
    return mode == SC_TERMINATION_MANUAL || mode == SC_TERMINATION_MANUAL_BOTH;
}

/* The outputs a render's programs write when the frame writes the AOVs:
 * the shaded colour, the AOVs (the read-back needs them) and the view's
 * image. */
static inline unsigned view_outputs(const sc_render_desc *d)
{
    return SCG_OUTPUT_SHADE | SCG_OUTPUT_AOV | view_image_output(d->view);
}

/* With desc.aovs_on_demand, the shaded view's frames (not deferred, which
 * shades from the AOVs) write the colour and depth alone unless asked for
 * the AOVs (sc_renderer_draw_aovs, or a read-back after such a frame):
 * their programs are the drawing keys less SCG_OUTPUT_AOV (and depth,
 * which every program writes; manual early termination then takes its
 * nearest distances from the depth buffer). */
static inline int colour_frames(const sc_render_desc *d)
{
    return d->aovs_on_demand && d->view == SC_SHOW_SHADE && !d->deferred;
}

/* The hulls drawn with one program. */
typedef struct group {
    sc_program program;
    /* The same key without early termination, for hulls holding the eye:
     * drawn by their back faces, their hits lie in front of the fragment,
     * which both the manual test (t < 1 on the hull) and depth_greater
     * assume is not so. Compiled when a frame first needs it. */
    sc_program inside;
    /* colour_frames: program and inside with the AOVs as well, for the
     * frames that write them; compiled when a frame first needs them. */
    sc_program aov, aov_inside;
    /* The same keys as ert5 (start mid), for hulls drawn through candidate
     * lists (gl_lists.c); compiled when a frame first lists one. */
    sc_program lists, aov_lists;
    int listable;   /* this frame: its list program can be had (a gen
                       folder may lack it; then its hulls stay hulls) */
} group;

/* A hull of the frame drawn through candidate lists (gl_lists.c): its
 * group, the distance from the eye to its box, and the pixels whose lists
 * hold it, as spans of the rows of a rectangle. */
typedef struct list_hull {
    int hull, group;
    float distance;   /* from the eye to its box, rounded down */
    int rect[4];      /* pixels [x0, x1) × [y0, y1) around it */
    size_t spans_first; /* per row of rect, [from, to) of its pixels, in
                           its list_take's spans */
} list_hull;

/* The listed hulls one thread of a frame's pass over the hulls took
 * (gl_render.c), their pixel spans, and room for one hull's projected
 * vertices. The frame's lists are those of take[0], to which the other
 * threads' are appended in hull order. */
typedef struct list_take {
    list_hull *listed;
    int nlisted;
    size_t listed_cap;
    int *spans;
    size_t spans_len, spans_cap;
    double *projected;
    size_t projected_cap;
} list_take;

/* One draw of a group's list program: the lists of the pixels of rect
 * (whole tiles) start at entry first_head of the heads, its tiles at
 * first_tile. */
typedef struct list_draw {
    int group;
    int rect[4];
    int first_head;
    int first_tile;   /* its first tile in renderer.list_tiles */
} list_draw;

/* One draw call of a frame. */
typedef struct draw_run {
    int group;
    int inside;              /* 1: hulls holding the eye: back faces, `inside`
                                program; 2: front faces, `inside` program
                                (depth peeling's frames that fall back) */
    int first, count;        /* range of the frame's index buffer */
} draw_run;

/* A hull's place in the frame's order: by major, then minor, then group,
 * then distance (the hull index makes the order total). */
typedef struct sort_item {
    double major, minor;
    int group;
    double distance;
    int hull;
} sort_item;

struct sc_renderer {
    const sc_gl *gl;
    const sc_scene *scene;
    /* The scene's view bounds (sc_renderer_view_bounds), kept until a
     * surface changes: framing a scene of 100,000 patches by default took
     * about 20 ms a frame to find them again. */
    int view_known, view_any;
    double view_lo[3], view_hi[3];
    sc_render_desc desc;
    scg_key *keys;           /* per surface */
    scg_patch_kind *kinds;   /* per surface */
    sc_accuracy_choice *choices; /* per surface, from desc.accuracy; NULL
                                without a target */
    sc_program *surface_program;
    sc_program_cache *programs;
    int own_programs;        /* the cache is the renderer's (not desc.programs) */
    sc_patch_list *patches;  /* per surface: its world-space Bézier patches,
                                which hulls and records are both built from */
    sc_gpu_data data;
    sc_hulls hulls;
    int ngroups;
    group *groups;
    int *surface_group;      /* per surface: its group */
    int *hull_group;         /* per hull: its group */
    GLuint vertex_array, vertex_buffer, index_buffer, colour_buffer, colour_texture;
    size_t hull_bytes, colour_bytes;
    size_t hull_bytes_uploaded;  /* vertices, by the last upload_hulls or
                                    upload_surface_hulls */
    size_t bytes_uploaded;   /* by creation, or for the surface updates
                                since the frame before the last: patch
                                data at once, hull vertices with the frame */
    size_t bytes_uploaded_total; /* since creation */
    /* Surface updates send their hull vertices with the next frame
     * (sc_renderer_send_updates), so that updating every surface sends each
     * vertex once, however many surfaces' hulls changed number. */
    unsigned char *stale;    /* per surface: its GPU vertices are old */
    int pending;             /* a surface was updated since the last frame */
    int recount;             /* and hull counts changed: groups, scratch */
    int counting_afresh;     /* the next update starts bytes_uploaded at 0 */
    int vertex_capacity, index_capacity; /* of the hull buffers */
    sc_gl_target target;
    /* sc_nearest_t: the distance channel of the uvt attachment as the
     * batches before the current one left it (R32F, the target's size). */
    GLuint nearest_texture;
    sc_camera camera;        /* of the last frame */
    int frame_aovs;          /* the frame being drawn (then the last one)
                                writes the AOVs; always 1 unless
                                colour_frames */
    int draw_calls, program_switches, culled, readbacks;  /* of the last frame */
    int outside;             /* of the last frame: hulls outside the view */
    /* The programs' count of intersections run (SCG_BUFFER_COUNTERS), zeroed
     * at the start of each frame that writes the AOVs (only their programs
     * count) and read only when asked for. */
    GLuint counter_buffer;
    /* desc.time_intersection: the hull draws of sc_renderer_draw's frames
     * (not an application's, which may time its own) between two glFinish
     * and in a GL_TIME_ELAPSED query; timed: the last frame was; its wall
     * time in intersect_ms. */
    GLuint time_query;
    int time_hulls, timed;
    double znear, zfar;      /* the last frame's depth range */
    double intersect_ms;
    double compile_ms;
    int manhattan;           /* a terrain drawn in Manhattan sets: its order
                                was left to the default */
    /* per frame scratch */
    uint32_t *frame_indices;
    double *distance;
    sort_item *items;
    int *inside;             /* hulls holding the eye */
    draw_run *runs;
    double *group_seen;      /* per group, for the hybrid buckets */
    float *uvt;              /* read back: the uvt attachment */
    float *nearest;          /* its largest distance per tile: sc_nearest_t */
    float *tile_far;         /* its largest value per tile */
    double raster_origin[3]; /* what hull vertices are rasterised relative to */
    float *cosine;           /* per tile the smallest, then the largest
                                cosine of its pixels' rays to the view
                                direction */
    double cosine_fovy;      /* the field of view they are for (0: none yet) */
    /* sc_nearest_t for draws into an application's framebuffer (gl_embed.c):
     * far everywhere, app_nearest_w × app_nearest_h tiles. */
    GLuint app_nearest;
    int app_nearest_w, app_nearest_h;
    sc_scene *own_scene;     /* a packed renderer's stand-in scene (gl_pack.c):
                                its surfaces' colours alone */
    GLuint deferred_program; /* gl_deferred.c's, made on first use */
    /* Depth peeling (gl_peel.c): the layers' entry depths (R32F, taking
     * turns) with their framebuffers (and the target's depth), the best hit
     * so far (R32F image), one query per layer and one past the last, the
     * pre-pass and resolve programs; made on first use. */
    GLuint peel_entry[2], peel_fb[2], peel_best, peel_depth;
    GLuint peel_queries[SC_PEEL_QUERIES];
    GLuint peel_program, resolve_program, composite_program, peel_vao;
    /* Its culling: the compute programs, the tiles with work (r32ui) and
     * the farthest best hit per tile (r32f), the buffers (slots; two
     * compact index lists; their commands) and their CPU sides (gl_peel.c's
     * peel_slot and peel_command). */
    GLuint cull_program, tile_far_program, peel_pending_tiles, peel_tile_far, peel_buffers[5];
    void *peel_slots, *peel_commands;
    size_t peel_capacity;
    int peel_w, peel_h;
    int peel_batches;        /* of the last frame: batches peeled (0: not peeled) */
    int peel_issued[SC_PEEL_MAX_BATCHES]; /* its layers issued per batch (one
                                more: the count past the last layer) */
    int peel_layers;         /* of the last frame: layers that found work,
                                summed over the batches */
    long long peel_pending;  /* of the last frame: hull fragments still in
                                front of their pixel's best hit after the
                                last layer (0 unless the layers ran out) */
    int peel_fallback;       /* the last frame fell back (gl_render.c) */
    /* Candidate lists (gl_lists.c): the listed hulls each thread took
     * (take[0]: the frame's), per slot their domain, record and box
     * distance, the heads and entries of the pixels' lists, the draws and
     * their tiles; their buffers and textures (heads, entries, slots,
     * tiles) and an empty vertex array for the tiles' points; the sort's
     * spare array and counts. */
    list_take take[SC_FRAME_MAX_THREADS];
    int frame_threads;       /* of the last frame: threads of its pass over
                                the hulls */
    list_hull *listed_spare;
    size_t *list_counts;
    size_t listed_spare_cap, list_counts_cap;
    float *list_slots;
    uint32_t *list_heads, *list_items;
    list_draw *list_draws;
    uint32_t *list_tiles;
    size_t list_slots_cap, list_heads_cap, list_items_cap, list_draws_cap, list_tiles_cap;
    GLuint list_buffers[4], list_textures[4], list_vertex_array;
    long long list_entries;  /* of the last frame: entries of all lists */
};

/* ---- preparation steps gl_prepare.c and gl_pack.c share ---- */

/* The key of surface s under the renderer's desc (generic where asked). */
/* choice: an accuracy target's choice for the surface, or NULL. */
void sc_prepare_surface_key(const sc_surface *s, const sc_render_desc *desc,
                            const sc_accuracy_choice *choice, scg_key *key);
/* The origin hulls are rasterised relative to: the middle of their box. */
void sc_prepare_raster_origin(sc_renderer *r);
/* The GPU vertices of hulls [first, first + count) (r->hulls, r->data's
 * records and centres, r->kinds, r->raster_origin). */
void sc_prepare_fill_vertices(const sc_renderer *r, int first, int count, gpu_vertex *verts);
/* New vertex (verts, r->hulls.nvertices of them) and index buffers, and
 * the frame's scratch sized for r->hulls. */
int sc_prepare_upload_hull_buffers(sc_renderer *r, const gpu_vertex *verts, sc_error *err);

void sc_prepare_vertex_array(sc_renderer *r);
int sc_prepare_upload_colours(sc_renderer *r, sc_error *err);
/* One group per distinct program of r->surface_program; each hull's. */
void sc_prepare_groups(sc_renderer *r);
void sc_prepare_group_hulls(sc_renderer *r);
/* The GPU bytes the renderer needs: patch data, hulls, colours. */
size_t sc_prepare_gpu_bytes(const sc_renderer *r);
/* r->desc's defaults filled in (termination, order, batch size). */
void sc_prepare_defaults(sc_renderer *r);

/* The camera's view-projection moved to the origin (what the programs'
 * sc_view_projection is): proj × view with view's translation dropped. */
void sc_render_eye_projection(const float view[16], const float proj[16], float vp[16]);

/* Draws every hull into the bound framebuffer with the depth test, the
 * programs' uniforms set from the eye (world space, double), vp
 * (sc_render_eye_projection) and footprint (2·tan(fovy/2) / image height);
 * fwd is the view direction. own_target: the renderer's own target is
 * bound, so the manual modes read back the nearest distances between
 * batches and depth peeling peels (gl_render.c's frames; not gl_embed.c's
 * draws into an application's framebuffer). */
int sc_render_hulls(sc_renderer *r, const double eye[3], const double fwd[3], const float vp[16],
                    float footprint, int own_target, sc_error *err);

/* The program group g's hulls are drawn with in the frame being drawn
 * (r->frame_aovs picks the set): its `inside` sibling for inside hulls
 * when that was compiled, else its own. */
static inline sc_program sc_render_group_program(const sc_renderer *r, int g, int inside)
{
    const group *gr = &r->groups[g];
    int aov = colour_frames(&r->desc) && r->frame_aovs;
    sc_program own = aov ? gr->aov : gr->program, in = aov ? gr->aov_inside : gr->inside;
    return inside && in.id ? in : own;
}

/* The renderer's own target at width × height (made again when the size
 * or r->frame_aovs's attachments changed), bound and cleared, GL_FRAMEBUFFER_SRGB enabled. */
int sc_render_begin_target(sc_renderer *r, int width, int height, sc_error *err);

/* The largest value of each tile of SCG_NEAREST_TILE² pixels of `pixels`
 * (w × h, rows overwritten) into `out` (tw tiles a row): the manual early
 * termination's read-backs (gl_render.c). */
void sc_tile_maxima(float *pixels, int w, int h, int tw, float *out);

/* Depth peeling (gl_peel.c): draws r->items[0, n) (no hull holding the
 * eye) into the renderer's own target, bound, with the frame's uniforms
 * set; vp and raster_eye for the pre-pass. */
int sc_peel_draw(sc_renderer *r, int n, const float vp[16], const float raster_eye[3],
                 GLuint *current, sc_error *err);
/* After the frame was waited for: its layers and what was left pending. */
void sc_peel_finish(sc_renderer *r);
void sc_peel_destroy(sc_renderer *r);

/* Candidate lists (gl_lists.c). Starts a frame's lists: none yet, and
 * which groups' list programs the program cache offers. */
void sc_lists_begin(sc_renderer *r);
/* Adds hull k (not holding the eye; box at `distance` from the eye) to
 * take's listed hulls when its group is listable, its vertices
 * project inside the near and far planes and, unless every_size, into a
 * rectangle at most desc.list_below_px wide and high on the renderer's
 * target; 1 when it did. */
int sc_lists_take(const sc_renderer *r, list_take *take, int k, double distance,
                  const float vp[16], const double eye[3], int every_size);
/* Appends the listed hulls of take[1 … threads) to take[0], in order. */
void sc_lists_merge(sc_renderer *r, int threads);
/* Builds the listed hulls' per-pixel lists, sends them and draws the
 * tiles that hold them with each group's ert5 program, into the
 * renderer's own target, bound, under the depth test. */
int sc_lists_draw(sc_renderer *r, const float vp[16], const float eye[3], const float eye_low[3],
                  float footprint, GLuint *current, sc_error *err);
void sc_lists_destroy(sc_renderer *r);
/* Into the bound framebuffer (an application's) at viewport (x, y, w, h):
 * the colour and depth of the renderer's target (its last frame, w × h)
 * wherever it holds a hit, under the depth test the caller set. */
int sc_peel_composite(sc_renderer *r, const int viewport[4], sc_error *err);

/* sRGB 0.2, the reference images' background (shade.c), in linear light:
 * the colour attachment is sRGB, so the GL encodes it on the way in. */
static inline float background_linear(void) { return (float)pow((0.2 + 0.055) / 1.055, 2.4); }

#endif
