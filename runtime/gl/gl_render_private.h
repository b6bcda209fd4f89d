/* gl_render_private.h — the renderer's state, shared by the files of the
 * render path: gl_prepare.c (keys, programs, hulls and patch data, surface
 * updates) and gl_render.c (one frame: order, batches, draw, read back). */
#ifndef SC_GL_RENDER_PRIVATE_H
#define SC_GL_RENDER_PRIVATE_H

#include <math.h>

#include "gl_render.h"
#include "gl_data.h"
#include "gl_target.h"

/* Fragment-stage uniform and vertex-stage uniform locations (templates/hull.vert). */
enum { LOC_VIEW_PROJECTION = 16, LOC_EYE = 17, LOC_EYE_LOW = 18, LOC_RASTER_EYE = 19 };
/* Texture units of the per-surface colours (emit_glsl.c, hull.vert) and of
 * the nearest distance so far, `sc_nearest_t` (emit_glsl.c, ert1/ert2 keys). */
enum { COLOUR_UNIT = 3, NEAREST_T_UNIT = 4 };

/* One vertex of a hull as the vertex program reads it (templates/hull.vert:
 * locations 0 position, 1 start (u, v), 2 sub-patch domain, 3 record). */
/* A hull vertex twice: relative to its record's centre, where the programs
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

/* The hulls drawn with one program. */
typedef struct group {
    sc_program program;
    /* The same key without early termination, for hulls holding the eye:
     * drawn by their back faces, their hits lie in front of the fragment,
     * which both the manual test (t < 1 on the hull) and depth_greater
     * assume is not so. Compiled when a frame first needs it. */
    sc_program inside;
} group;

/* One draw call of a frame. */
typedef struct draw_run {
    int group;
    int inside;              /* hulls holding the eye: back faces, `inside` program */
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
    sc_render_desc desc;
    scg_key *keys;           /* per surface */
    scg_patch_kind *kinds;   /* per surface */
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
    size_t bytes_uploaded;   /* by creation or the last surface update */
    sc_gl_target target;
    /* sc_nearest_t: the distance channel of the uvt attachment as the
     * batches before the current one left it (R32F, the target's size). */
    GLuint nearest_texture;
    sc_camera camera;        /* of the last frame */
    int draw_calls, program_switches, culled, readbacks;  /* of the last frame */
    double compile_ms;
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
    float *cosine;           /* per pixel: cosine of its ray to the view direction */
    double cosine_fovy;      /* the field of view they are for (0: none yet) */
};

static inline int manual_ert(sc_ert_mode mode)
{
    return mode == SC_ERT_MANUAL || mode == SC_ERT_MANUAL_BOTH;
}

/* sRGB 0.2, the reference images' background (shade.c), in linear light:
 * the colour attachment is sRGB, so the GL encodes it on the way in. */
static inline float background_linear(void) { return (float)pow((0.2 + 0.055) / 1.055, 2.4); }

#endif
