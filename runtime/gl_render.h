/* gl_render.h — the render path: a scene and a camera in, an image and its
 * AOVs out, by ray casting every pixel of every proxy hull with the
 * generated program of the surface's variant key (Pabst et al. 2006,
 * sections 3–4). Creating a renderer prepares everything that does not
 * depend on the view — hulls, GPU data, one program per distinct key — so
 * that a frame is sorting the hulls and drawing them. */
#ifndef SC_GL_RENDER_H
#define SC_GL_RENDER_H

#include "aov.h"
#include "gl_loader.h"
#include "hulls.h"
#include "image.h"
#include "key.h"

/* What the image shows. shade, uv and iters come from the programs; normal
 * and depth are drawn from the AOVs. */
typedef enum sc_view {
    SC_VIEW_SHADE = 0,
    SC_VIEW_UV,
    SC_VIEW_ITERS,
    SC_VIEW_NORMAL,
    SC_VIEW_DEPTH,
} sc_view;

int sc_view_parse(const char *text, sc_view *view, sc_error *err);

/* Zero means default in every field. */
typedef struct sc_render_desc {
    sc_hull_desc hulls;     /* proxy hulls (hulls.h defaults) */
    scg_start start;        /* SCG_START_MID or SCG_START_CP (default) */
    int start_set;          /* 1 when `start` was chosen (0 picks the default) */
    int max_iters;          /* Newton iterations (SC_RENDER_DEFAULT_ITERS) */
    int tol_milli;          /* tolerance in 1/1000 pixel footprints
                               (SC_RENDER_DEFAULT_TOL_MILLI) */
    sc_view view;
    int generic;            /* the generic program (runtime loops) for every
                               surface, whatever its degree */
    int unroll_max_degree;  /* highest degree drawn with unrolled programs
                               (SC_UNROLL_MAX_DEGREE, programs.h) */
} sc_render_desc;

#define SC_RENDER_DEFAULT_ITERS 6
#define SC_RENDER_DEFAULT_TOL_MILLI 50

typedef struct sc_render_stats {
    int programs;           /* distinct keys compiled */
    int hulls;
    int triangles;
    size_t gpu_bytes;       /* patch data, hull vertices and indices, colours */
    double compile_ms;      /* generating, validating, compiling and linking */
} sc_render_stats;

typedef struct sc_renderer sc_renderer;

/* Needs a current context (gl_context.h); the scene must outlive the
 * renderer. */
int sc_renderer_create(const sc_gl *gl, const sc_scene *scene, const sc_render_desc *desc,
                       sc_renderer **out, sc_error *err);
void sc_renderer_destroy(sc_renderer *r);

/* Draws one frame for cam (its size is the image size) and waits for it. */
int sc_renderer_draw(sc_renderer *r, const sc_camera *cam, sc_error *err);
/* The last frame: the image of the view (RGBA, allocated here) and, when
 * aov is not NULL, its AOVs (allocated here, with iteration counts). */
int sc_renderer_read(sc_renderer *r, sc_image *img, sc_aov *aov, sc_error *err);

/* After surface s of the scene changed shape (same degrees and counts):
 * rebuilds its hulls and rewrites its GPU data alone. */
int sc_renderer_update_surface(sc_renderer *r, int surface, sc_error *err);

void sc_renderer_stats(const sc_renderer *r, sc_render_stats *stats);
/* The key surface s is drawn with. */
const scg_key *sc_renderer_surface_key(const sc_renderer *r, int surface);

#endif
