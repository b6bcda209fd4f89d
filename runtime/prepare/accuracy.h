/* accuracy.h — settings from an accuracy target ("model no more than a
 * scene needs"): for each surface, the fewest Newton iterations and the
 * largest convergence tolerance that still meet a bound on the position
 * error in pixel footprints (and optionally on the normal error in
 * degrees) for a view, with the default hulls made finer only where the
 * bound needs it. The choice drives the knobs the
 * renderer has anyway — the hulls' adaptive tolerance (hulls.h), the key's
 * itN and tolT (key.h) — per surface. docs/accuracy.md derives the bounds
 * and gives the measurements behind the constants. */
#ifndef SC_ACCURACY_H
#define SC_ACCURACY_H

#include "camera.h"
#include "nurbs.h"
#include "splinecast_options.h"

/* Limits of a target: outside them a target is refused. */
#define SC_ACCURACY_MIN_PX 0.001   /* the finest key tolerance (tol0.001) */
#define SC_ACCURACY_MAX_PX 100.0   /* as `render --tol` */
#define SC_ACCURACY_MAX_DEG 90.0

typedef struct sc_accuracy_target {
    double px;          /* position error bound, pixel footprints (> 0) */
    double normal_deg;  /* normal error bound in degrees; 0: none */
    sc_camera view;     /* the view (and image size) it is met for */
} sc_accuracy_target;

/* What the target chose for one surface. */
typedef struct sc_accuracy_choice {
    double hull_tolerance;  /* adaptive flatness, as a fraction of the scene's
                               bounding-box diagonal (sc_hull_desc.tolerance) */
    int max_iters;          /* the key's itN; 0 for methods whose iterations
                               are not Newton steps (subdiv, bclip: their
                               defaults) */
    int tol_milli;          /* the key's tolerance, 1/1000 pixel footprint */
    double footprint;       /* world size of a pixel at the surface's nearest
                               distance to the eye */
    double radius;          /* smallest radius of curvature found (world;
                               HUGE_VAL for a flat surface) */
} sc_accuracy_choice;

/* A message for a target outside the limits above, or NULL when it is
 * usable; what names the field in the message's place. */
const char *sc_accuracy_check(double px, double normal_deg);

/* Chooses out[s] for every surface s of the scene from its world-space
 * Bézier patches (patches[s], sc_surface_world_patches). A looser target
 * never chooses a smaller hull tolerance, more iterations or a smaller
 * tolerance for any surface. */
void sc_accuracy_choose(const sc_scene *scene, const sc_patch_list *patches,
                        const sc_accuracy_target *target, sc_method method,
                        sc_accuracy_choice *out);

#endif
