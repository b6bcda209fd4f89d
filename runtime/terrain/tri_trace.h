/* tri_trace.h — exact ray casting of triangular Bézier height meshes in
 * double precision: the CPU reference the `tri` programs (gen/tri_newton.c)
 * are measured against. It shares the programs' geometry (the ray clipped
 * to each patch's prism, the polynomial along the projected ray) but not
 * their numerics: the first root is isolated by Bézier subdivision of that
 * polynomial (convex hull property) to double precision, so the answer
 * depends on no starting value. */
#ifndef SC_TRI_TRACE_H
#define SC_TRI_TRACE_H

#include "tri_bezier.h"

typedef struct sc_tri_hit {
    int patch;            /* -1 for a miss */
    double t;             /* ray parameter (units of dir) */
    double point[3];      /* on the patch: (x, y, height) */
    double normal[3];     /* unit, upward (z > 0): (-hx, -hy, 1) normalised */
} sc_tri_hit;

/* The first hit with t > t_min of origin + t dir on one patch of degree n
 * (heights coef over the domain triangle tri); SC_OK on a hit. */
int sc_tri_patch_trace(int n, const double *coef, const double tri[6], const double origin[3],
                       const double dir[3], double t_min, sc_tri_hit *hit);

/* A mesh prepared for tracing: the height range of each square's two
 * patches, so that squares the ray passes above or below are skipped. */
typedef struct sc_tri_tracer {
    const sc_tri_mesh *mesh;
    double zmin, zmax;
    double *square_range;   /* 2 per square: lowest, highest coefficient */
} sc_tri_tracer;

void sc_tri_tracer_init(sc_tri_tracer *tr, const sc_tri_mesh *mesh);
void sc_tri_tracer_free(sc_tri_tracer *tr);
/* The nearest hit with t > t_min, walking the squares the projected ray
 * crosses in order. Thread-safe. */
int sc_tri_tracer_trace(const sc_tri_tracer *tr, const double origin[3], const double dir[3],
                        double t_min, sc_tri_hit *hit);

#endif
