/* hulls.h — proxy geometry for ray casting (Pabst et al. 2006, section 4.4):
 * every surface is cut into Bézier patches, every patch into sub-patches —
 * uniformly (n × n) or adaptively (split until the control mesh is flat
 * within a tolerance, or a maximum depth) — and each sub-patch is bounded by
 * the convex hull of its control points (libqhull; small_hull.h or the
 * triangles it had when a surface update rebuilds it). Rasterising a hull
 * starts one ray per covered pixel; the hull carries the start values of
 * the intersection: the centre of its parameter rectangle ("mid") and, per
 * vertex, the parameters of the control point the vertex is ("cp").
 *
 * Positions are in world space (each surface's transform applied); by the
 * convex hull property of Bézier patches with positive weights each hull
 * holds its piece of surface. */
#ifndef SC_HULLS_H
#define SC_HULLS_H

#include <stdint.h>

#include "nurbs.h"
#include "splinecast_options.h"

/* Zero means default in every field. */
typedef struct sc_hull_desc {
    sc_hull_split mode;  /* SC_SPLIT_DEFAULT: adaptive */
    int divisions;       /* uniform: n × n sub-patches per Bézier patch (2) */
    double tolerance;    /* adaptive: largest distance of a control point from
                            the bilinear patch through the sub-patch's corners,
                            as a fraction of the scene's bounding-box diagonal
                            (SC_HULL_DEFAULT_TOLERANCE) */
    int max_depth;       /* adaptive: most splits of one Bézier patch, along u
                            and v together (8) */
    const double *surface_tolerance; /* adaptive: one tolerance per surface of
                            the scene, as `tolerance`, in its place (an
                            accuracy target chooses them, accuracy.h); NULL:
                            `tolerance` for every surface. Copied */
} sc_hull_desc;

#define SC_HULL_DEFAULT_TOLERANCE 0.003

typedef struct sc_hull_vertex {
    double pos[3];       /* world space */
    double uv[2];        /* the control point's parameters, local to its
                            Bézier patch ([0, 1]²): the "cp" start */
    int source;          /* the hull builder's input point it is: control
                            point number × the sub-patch's copies + copy */
} sc_hull_vertex;

/* One sub-patch and its hull. */
typedef struct sc_subpatch {
    int surface;         /* index of the surface in the scene */
    int patch;           /* index of its Bézier patch within the surface's
                            sc_patch_list (u fastest, as sc_surface_to_bezier
                            numbers them) */
    double local[4];     /* (u0, u1, v0, v1) in the Bézier patch's [0, 1]² */
    double domain[4];    /* the same rectangle in the surface's parameters */
    int first_vertex, vertex_count;
    int first_index, index_count;  /* 3 per triangle */
    double lo[3], hi[3]; /* bounding box of the hull */
    int copies;          /* input points per control point: 1, or 6 for a
                            slab (flat pieces); 0 for hulls not built from
                            control points here (prisms, packs) */
} sc_subpatch;

/* Where one surface's hulls sit: its sub-patches, and the vertices and
 * indices they use, are contiguous, so that the surface can be rebuilt
 * alone. */
typedef struct sc_hull_range {
    int first_subpatch, subpatch_count;
    int first_vertex, vertex_count;
    int first_index, index_count;
    int patch_count;     /* Bézier patches */
} sc_hull_range;

typedef struct sc_hulls {
    int count;
    sc_subpatch *subpatches;
    int nvertices;
    sc_hull_vertex *vertices;
    int nindices;
    uint32_t *indices;   /* into vertices; triangles counter-clockwise seen
                            from outside the hull */
    int npatches;        /* Bézier patches the sub-patches came from */
    int nsurfaces;
    sc_hull_range *surfaces; /* per surface of the scene */
    sc_hull_desc desc;   /* what they were built with, defaults filled in */
    double tolerance;    /* adaptive: the flatness bound in world units,
                            fixed when the hulls were built */
    double *surface_tolerance; /* the same per surface, when the desc gave
                            them; NULL otherwise */
    long qhull_pieces;   /* sub-patches whose hull qhull made: every one of
                            the build, and those of the surface updates
                            since that neither kept their triangles nor got
                            a small hull (flat pieces) */
    long kept_pieces;    /* sub-patches of the updates that kept their
                            triangles */
} sc_hulls;

/* Builds the hulls of every surface of the scene. Collapsed sub-patches (all
 * control points in one point) get no hull; flat ones a thin slab. */
int sc_hulls_build(const sc_scene *scene, const sc_hull_desc *desc, sc_hulls *hulls,
                   sc_error *err);
/* The same from patches[s], the world-space Bézier patches of surface s
 * (sc_surface_world_patches), which a renderer also packs into its GPU
 * records: sub-patch .patch p of surface s then comes from the very patch
 * record p holds. */
int sc_hulls_build_from(const sc_scene *scene, const sc_patch_list *patches,
                        const sc_hull_desc *desc, sc_hulls *hulls, sc_error *err);
void sc_hulls_free(sc_hulls *hulls);

/* After surface s of the scene changed shape: rebuilds its hulls alone, as
 * sc_hulls_build would with the tolerance the hulls were built with (the
 * same sub-patches, unless the change moved the scene's bounding box,
 * which a full build would take its tolerance from). A sub-patch that was
 * there before (same Bézier patch, same rectangle) keeps its triangles
 * when they still bound its moved control points (sc_small_hull_bounds:
 * a moved but not reshaped patch keeps exactly its hulls); the others get
 * small_hull.h's hull, qhull's where that refuses — the same convex body
 * as a build's, its coplanar faces possibly triangulated otherwise. *moved is 0 when the
 * surface's sub-patch, vertex and index counts stayed, so that only its
 * ranges changed; 1 when the hulls of the surfaces after it moved. On
 * failure the hulls are left as they were. */
int sc_hulls_update_surface(sc_hulls *hulls, const sc_scene *scene, int surface, int *moved,
                            sc_error *err);
/* The same from that surface's world-space patches. */
int sc_hulls_update_surface_from(sc_hulls *hulls, const sc_scene *scene, int surface,
                                 const sc_patch_list *patches, int *moved, sc_error *err);

/* Whether the world-space point p lies inside hull `index` (or on it):
 * hulls that hold the eye are drawn by their back faces. */
int sc_hull_contains(const sc_hulls *hulls, int index, const double p[3]);

#endif
