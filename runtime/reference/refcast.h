/* refcast.h — the CPU reference ray caster: the ground truth every GPU
 * image is measured against (BRIEF "Accuracy"). Double precision, no
 * starting values: Dammertz–Keller object-space subdivision of the
 * scene's Bézier patches (rational ones in homogeneous coordinates) until
 * the bounding box of a sub-patch no longer shrinks in floating point,
 * under a bounding-volume hierarchy over the patches, with exact trimming
 * (trim.h). How it works and what it costs: docs/reference.md. */
#ifndef SC_REFCAST_H
#define SC_REFCAST_H

#include "aov.h"
#include "scene.h"
#include "trim.h"

/* A scene prepared for ray casting: world-space Bézier patches, their BVH
 * and the trim data of every surface. It points into the scene, which must
 * outlive it. */
typedef struct sc_refcast sc_refcast;

int sc_refcast_prepare(const sc_scene *scene, sc_refcast **out, sc_error *err);
void sc_refcast_free(sc_refcast *rc);
int sc_refcast_patch_count(const sc_refcast *rc);

/* The nearest hit of one ray. */
typedef struct sc_ref_hit {
    int surface;          /* index in the scene, -1 for a miss */
    double u, v;          /* in the surface's own domain */
    double t;             /* distance along the unit ray */
    double point[3];      /* world space, the surface evaluated at (u, v) */
    double normal[3];     /* unit, world space, facing the ray origin */
    long subdivisions;    /* sub-patch splits this ray needed */
    int over_budget;      /* the search was cut short (see refcast.c) */
} sc_ref_hit;

/* Traces one ray (dir need not be unit length; t is measured along the
 * normalised direction). Thread-safe; allocates its own work space. */
void sc_refcast_trace(const sc_refcast *rc, const double origin[3], const double dir[3],
                      sc_ref_hit *hit);

typedef struct sc_refcast_options {
    int threads;          /* 0: one per online core */
    /* Called with the fraction of rows done (about every 10 %), from one
     * thread at a time; NULL for silence. */
    void (*progress)(double fraction, void *user);
    void *progress_user;
} sc_refcast_options;

typedef struct sc_refcast_stats {
    double seconds;       /* wall time of the render (not of preparation) */
    long rays, hits;
    long subdivisions;    /* sub-patch splits over all rays */
    long over_budget;     /* rays whose search was cut short: normally 0 */
    int threads;
} sc_refcast_stats;

/* Renders cam->width × cam->height pixels into a freshly allocated aov
 * (without iterations). The result does not depend on the thread count.
 * opt and stats may be NULL. */
int sc_refcast_render(const sc_refcast *rc, const sc_camera *cam, const sc_refcast_options *opt,
                      sc_aov *aov, sc_refcast_stats *stats, sc_error *err);

/* Reads a scene (sc_read_scene), renders its reference and keeps the AOV
 * in cache_dir under a name derived from the scene file's bytes, the camera,
 * the size and the reference's version, so that tests pay for a reference
 * only once. A cached file is read instead of rendering. */
int sc_refcast_cached(const char *scene_path, const sc_camera *cam, const char *cache_dir,
                      sc_aov *aov, sc_error *err);

#endif
