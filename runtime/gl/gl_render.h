/* gl_render.h — the render path: a scene and a camera in, an image and its
 * AOVs out, by ray casting every pixel of every proxy hull with the
 * generated program of the surface's variant key (Pabst et al. 2006,
 * sections 3–4). Creating a renderer prepares everything that does not
 * depend on the view — hulls, GPU data, one program per distinct key — so
 * that a frame is sorting the hulls and drawing them. */
#ifndef SC_GL_RENDER_H
#define SC_GL_RENDER_H

#include "accuracy.h"
#include "aov.h"
#include "gl_loader.h"
#include "hulls.h"
#include "image.h"
#include "key.h"
#include "programs.h"
#include "splinecast_options.h"

/* Zero means default in every field. */
typedef struct sc_render_desc {
    sc_hull_desc hulls;     /* proxy hulls (hulls.h defaults) */
    sc_start start;         /* Newton start (default cpmap) */
    int max_iters;          /* Newton iterations (SCG_DEFAULT_ITERS, key.h) */
    int tol_milli;          /* tolerance in 1/1000 pixel footprints
                               (SCG_DEFAULT_TOL_MILLI) */
    sc_show view;
    int generic;            /* the generic program (runtime loops) for every
                               surface, whatever its degree */
    int unroll_max_degree;  /* highest degree drawn with unrolled programs
                               (SC_UNROLL_MAX_DEGREE, scene_keys.h) */
    sc_trim_method trim_method; /* trim method of trimmed surfaces (default
                               fast) */
    int trim_iters;         /* cap on clipping iterations per trim crossing
                               (SCG_DEFAULT_TRIM_ITERS) */
    sc_ray_termination ert; /* early ray termination (SC_DEFAULT_TERMINATION,
                               splinecast_options.h) */
    sc_hull_order order;    /* draw order policy */
    int batch_hulls;        /* hulls per batch in the manual modes (a batch
                               reads the hits of the batches before it;
                               doubling after a batch that culled no hull),
                               the first of depth peeling's batches (which
                               double),
                               and per bucket of the hybrid order
                               (SC_RENDER_DEFAULT_BATCH_HULLS) */
    int list_below_px;      /* manual modes: hulls at most this many pixels
                               wide and high on screen go through candidate
                               lists; 0: SC_RENDER_DEFAULT_LIST_BELOW_PX,
                               SC_LISTS_OFF: none */
    sc_program_cache *programs; /* the cache to take programs from, shared
                               with whoever else uses it and outliving the
                               renderer; NULL: a cache of the renderer's own */
    size_t gpu_memory_budget; /* most bytes of GPU data (patch data, hulls,
                               colours) the renderer may upload; a scene that
                               needs more is refused before anything is sent,
                               with the message a real GL_OUT_OF_MEMORY gives
                               (sc_gl_fail_memory). 0: no budget. Render
                               targets are not counted */
    sc_method method;       /* intersection method (default hybrid); with
                               subdiv, max_iters is the stack depth
                               (SCG_DEFAULT_SUBDIV_DEPTH) */
    sc_eval eval;           /* the unrolled Bézier keys' evaluation form */
    sc_accuracy_target accuracy; /* px > 0: each surface's hull tolerance,
                               iterations and tolerance chosen from this
                               target (accuracy.h) in place of hulls.tolerance,
                               max_iters and tol_milli; px 0: off */
    int deferred;           /* terrains: the intersection programs write the
                               AOVs only, and a full-screen pass shades from
                               them (gl_deferred.c) */
    int aovs_on_demand;     /* shaded frames (not deferred) of
                               sc_renderer_draw and sc_renderer_draw_app
                               write colour and depth alone, with programs
                               compiled without the AOVs (colour_frames);
                               sc_renderer_draw_aovs, and sc_renderer_read
                               after such a frame, draw with the AOVs.
                               0: every frame writes them */
    int time_intersection;  /* the frames' hull draws between two glFinish,
                               timed (sc_render_stats.intersect_ms) */
    int threads;            /* CPU threads of a frame's pass over the hulls
                               (the view test, candidate lists' outlines);
                               0: one per online processor; at most 8, and
                               one per 1,024 hulls */
} sc_render_desc;


typedef struct sc_render_stats {
    int programs;           /* distinct programs drawn with: one per key,
                               and the ert0 siblings for hulls holding the
                               eye */
    int hulls;
    int triangles;
    size_t gpu_bytes;       /* patch data, hull vertices and indices, colours */
    size_t bytes_uploaded;  /* by creation, or for the surface updates up to
                               the last send (sc_renderer_send_updates, or
                               a frame) since the one before: patch data,
                               hull vertices (and colours at creation; the
                               index buffer is written every frame) */
    double compile_ms;      /* generating, validating, compiling and linking */
    /* Of the last frame: */
    int draw_calls;
    int program_switches;   /* glUseProgram calls */
    int culled_hulls;       /* hulls not drawn: behind the hits so far at
                               every pixel they cover (manual modes) */
    int readbacks;          /* reads of the nearest distances so far (manual
                               modes), each also refreshing the texture the
                               programs read them from */
    long long intersections; /* fragment programs that ran the intersection
                               (past the early-termination test), counted on
                               the GPU by an atomic add in frames that write
                               the AOVs; -1 after a frame without them */
    double intersect_ms;    /* with desc.time_intersection, the last frame's
                               hull draws, from a glFinish before them to
                               one after; -1 otherwise */
    double intersect_query_ms; /* the same draws by a GL_TIME_ELAPSED query
                               (-1 as above; on llvmpipe it covers the
                               binning of the draws, not their raster) */
    size_t bytes_uploaded_total; /* since creation, creation included */
    long long qhull_hulls;  /* hulls qhull made (sc_hulls.qhull_pieces) */
    int peel_layers;        /* depth peeling: the layers that found hull
                               entries in front of a pixel's best hit (0
                               when the frame did not peel) */
    int threads;            /* CPU threads of the last frame's pass over
                               the hulls */
} sc_render_stats;

typedef struct sc_renderer sc_renderer;

/* Needs a current context (gl_context.h); the scene must outlive the
 * renderer. */
int sc_renderer_create(const sc_gl *gl, const sc_scene *scene, const sc_render_desc *desc,
                       sc_renderer **out, sc_error *err);
void sc_renderer_destroy(sc_renderer *r);

/* Draws one frame for cam (its size is the image size) and waits for it. */
int sc_renderer_draw(sc_renderer *r, const sc_camera *cam, sc_error *err);
/* The same, writing the AOVs whatever desc.aovs_on_demand says (the
 * programs that write them compiled on first use). */
int sc_renderer_draw_aovs(sc_renderer *r, const sc_camera *cam, sc_error *err);
/* Draws into the framebuffer bound in the current context (an
 * application's) with its viewport, depth buffer and matrices (column-major
 * float[16]: world to eye; a perspective projection), writing the hits'
 * depth; the GL state it changes is restored (gl_state.h). Nothing is
 * waited for or read back. */
int sc_renderer_draw_app(sc_renderer *r, const float view[16], const float proj[16],
                         sc_error *err);
/* The last frame: the image of the view (RGBA, allocated here) and, when
 * aov is not NULL, its AOVs (allocated here, with iteration counts). A
 * last frame that wrote no AOVs (desc.aovs_on_demand) is first drawn
 * again at its camera with them (sc_renderer_draw_aovs), once: that frame
 * is then the last. */
int sc_renderer_read(sc_renderer *r, sc_image *img, sc_aov *aov, sc_error *err);

/* The nearest distances so far as the programs of the last frame's last
 * batch read them (sc_nearest_t, manual modes): per pixel, rows top-down,
 * the largest over the pixel's tile (SCG_NEAREST_TILE², gpu_layout.h) of
 * the distances along the unit ray of the nearest hits of the batches
 * before that batch, 3e38 where a pixel of the tile had none. w × h
 * floats. */
int sc_renderer_read_nearest(sc_renderer *r, float *t, sc_error *err);

/* After surface s of the scene changed shape (same degrees, counts and
 * key): rebuilds its hulls alone, with the hull tolerance the renderer was
 * made with, and rewrites its patch data in its ranges of the GPU buffers
 * (all of it when its size changed). Its hull vertices are sent with the
 * next frame, or by sc_renderer_send_updates: each surface updated since
 * the last send in its range, and, where a surface's hull counts changed,
 * every surface after it (the whole buffer when it outgrew it). A surface
 * whose key changed is refused, changing nothing; after any other failure
 * the renderer may draw the surface half changed and should be
 * destroyed. */
int sc_renderer_update_surface(sc_renderer *r, int surface, sc_error *err);
/* Sends the hull vertices the updates since the last send left (every
 * frame does it first); stats.bytes_uploaded then counts what those
 * updates sent in all. */
int sc_renderer_send_updates(sc_renderer *r, sc_error *err);

void sc_renderer_stats(const sc_renderer *r, sc_render_stats *stats);
/* The scene the renderer draws: a packed renderer's stand-in (gl_pack.h),
 * whose surfaces have their colours and the scene's box alone. */
const sc_scene *sc_renderer_scene(const sc_renderer *r);
/* sc_scene_view_bounds of that scene, found once and again after a surface
 * changed (sc_renderer_update_surface); 0 for an empty scene. */
int sc_renderer_view_bounds(sc_renderer *r, double lo[3], double hi[3]);
/* The key surface s is drawn with. */
const scg_key *sc_renderer_surface_key(const sc_renderer *r, int surface);
/* What the accuracy target chose for surface s; NULL without a target. */
const sc_accuracy_choice *sc_renderer_surface_choice(const sc_renderer *r, int surface);
/* The number of hulls surface s is drawn with and the adaptive tolerance
 * they were built with (a fraction of the scene's size; 0 for uniform
 * hulls and terrains). */
void sc_renderer_surface_hulls(const sc_renderer *r, int surface, int *count,
                               double *tolerance);

#endif
