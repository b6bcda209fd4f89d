/* scene.h — the scene model every reader fills and every consumer reads:
 * tensor-product NURBS surfaces of any degree, rational or not, with clamped
 * knot vectors, optional trim loops of 2D NURBS curves in parameter space, a
 * transform, a name and a colour.
 *
 * Control points are stored homogeneous (x·w, y·w, z·w, w), the form in which
 * knot insertion, subdivision and de Boor work unchanged for rational and
 * polynomial geometry alike. */
#ifndef SC_SCENE_H
#define SC_SCENE_H

#include "sc_base.h"

/* A NURBS curve of dimension 2 (trim curves, in a surface's (u, v) space) or
 * 3. `cp` holds ncp points of dim+1 doubles each: (x·w, y·w[, z·w], w).
 * `knots` has ncp + degree + 1 entries, clamped (degree+1 equal at each end). */
typedef struct sc_curve {
    int dim;
    int degree;
    int ncp;
    double *knots;
    double *cp;
} sc_curve;

/* A closed trim loop: curves in order, each ending where the next starts
 * (gaps are closed by sc_scene_validate_loops). */
typedef struct sc_loop {
    int is_hole;  /* 0: the outer boundary; 1: a hole */
    int ncurves;
    sc_curve *curves;
} sc_loop;

/* A tensor-product NURBS surface. Control point (i, j), i along u (0..nu-1),
 * j along v (0..nv-1), is cp[4 * (j * nu + i) + 0..3] = (x·w, y·w, z·w, w).
 * knots_u has nu + deg_u + 1 entries, knots_v has nv + deg_v + 1, both
 * clamped. The surface's domain is [knots_u[deg_u], knots_u[nu]] ×
 * [knots_v[deg_v], knots_v[nv]]. */
typedef struct sc_surface {
    char name[64];
    float color[3];       /* linear RGB in [0, 1] */
    double xform[12];     /* row-major 3×4 affine, object → world */
    int deg_u, deg_v;
    int nu, nv;
    double *knots_u, *knots_v;
    double *cp;
    int rational;         /* weights not all equal to 1e-12 relative (BRIEF) */
    int nloops;           /* 0: untrimmed */
    sc_loop *loops;
} sc_surface;

/* Something a reader did not turn into geometry: counted per kind, printed
 * by `info` as `skipped TYPE N REASON`. */
typedef struct sc_skipped {
    char type[32];        /* e.g. "polygon", "iges-406" */
    int count;
    char reason[96];      /* one word or a few joined by '-' */
} sc_skipped;

typedef struct sc_scene {
    int nsurfaces;
    sc_surface *surfaces;
    int nskipped;
    sc_skipped *skipped;
    int dropped_loops;    /* loops removed by validation */
    int repaired_gaps;    /* gaps closed with a straight segment */
    char source[256];     /* file name the scene came from (for messages) */
    int projected_loops;  /* trim loops given in model space, projected */
    double projection_dev; /* the largest distance measured between such a
                              loop on the surface and its 3D curves */
    int offset_surfaces;  /* offset surfaces fitted (not exact) */
    double offset_dev;    /* the largest distance measured between such a
                             fit and the true offset */
    /* A terrain (runtime/terrain/tri_bezier.h): triangular Bézier height
     * patches, drawn with a `tri` key and traced by the terrain reference
     * instead of the surfaces' geometry. Surface 0 then only stands for it
     * (its bounding box, colour and name). Owned: sc_scene_free calls
     * terrain_free on it. NULL for scenes of surfaces. */
    struct sc_tri_mesh *terrain;
    void (*terrain_free)(struct sc_tri_mesh *terrain);
} sc_scene;

/* ---- lifetime ---- */
void sc_scene_init(sc_scene *scene);
void sc_scene_free(sc_scene *scene);
/* Appends a zeroed surface with identity transform and a default colour and
 * returns it. The pointer stays valid until the next append. */
sc_surface *sc_scene_add_surface(sc_scene *scene);
/* Allocates knots and control points for the given degrees and counts. */
void sc_surface_alloc(sc_surface *s, int deg_u, int deg_v, int nu, int nv);
void sc_surface_free(sc_surface *s);
void sc_curve_alloc(sc_curve *c, int dim, int degree, int ncp);
void sc_curve_free(sc_curve *c);
void sc_curve_copy(sc_curve *dst, const sc_curve *src);
/* The same for sizes that come from a file: SC_FAIL (and nothing
 * allocated) when the memory is not there, where the forms above abort;
 * the reader reports it with its position (sc_fail_oom). */
sc_surface *sc_scene_try_add_surface(sc_scene *scene);
int sc_surface_try_alloc(sc_surface *s, int deg_u, int deg_v, int nu, int nv);
int sc_curve_try_alloc(sc_curve *c, int dim, int degree, int ncp);
int sc_curve_try_copy(sc_curve *dst, const sc_curve *src);
void sc_surface_copy(sc_surface *dst, const sc_surface *src);
/* Adds (or increments) a skipped-record. */
void sc_scene_skip(sc_scene *scene, const char *type, const char *reason, int count);

/* ---- derived facts ---- */
/* Sets s->rational from the weights (BRIEF: all equal to 1e-12 relative →
 * polynomial; the weights are then normalised to 1 so that every consumer
 * can treat the surface as polynomial). */
void sc_surface_update_rational(sc_surface *s);
/* Checks degrees, counts, knots (non-decreasing, clamped), weights (> 0,
 * finite) and coordinates (finite). On failure fills err (no file/line). */
int sc_surface_check(const sc_surface *s, sc_error *err);
int sc_curve_check(const sc_curve *c, sc_error *err);
/* World-space bounding box of the control points (the convex hull property
 * makes it a bound of the surface). Returns 0 for an empty scene. */
int sc_scene_bounds(const sc_scene *scene, double lo[3], double hi[3]);
void sc_surface_bounds(const sc_surface *s, double lo[3], double hi[3]);
/* Applies s->xform to an object-space point / direction. */
void sc_xform_point(const double xform[12], const double p[3], double out[3]);
void sc_xform_vector(const double xform[12], const double v[3], double out[3]);
/* Normal transform: inverse transpose of the linear part, then normalised. */
void sc_xform_normal(const double xform[12], const double n[3], double out[3]);
/* Multiplies every control point by s->xform and resets it to identity. */
void sc_surface_bake_xform(sc_surface *s);

/* ---- loop validation (every reader calls it once, at the end) ----
 * For each loop of each surface: a gap between consecutive curves (and
 * between the last and the first) up to 1e-9 of the domain size is closed
 * silently by moving the end points together; up to 1e-3 it is closed with a
 * straight segment and a warning naming surface and loop; a larger gap, a
 * self-crossing loop or a curve above SC_TRIM_MAX_DEGREE (trim.h) drops the
 * loop with a warning (the surface is kept) and is counted in
 * scene->dropped_loops. Warnings start with scene->source when it is set.
 * Curves outside the domain are not an error (real files have them slightly
 * outside). Fails only when memory runs out ("out of memory: N bytes for
 * validating trim loop L of surface S", the file being scene->source); the
 * scene can then still be freed. */
int sc_scene_validate_loops(sc_scene *scene, sc_error *err);

#endif
