/* tri_prisms.h — what a terrain (sc_scene.terrain) becomes before drawing
 * (seed 004, sections VI–VII): one GPU record per triangular patch, a
 * prism over each patch's domain triangle as its proxy (the triangle
 * times the range of its BB-coefficients, which holds the patch by the
 * convex hull property), and the Manhattan distance that sorts the prisms
 * into sets that do not overlap on screen. */
#ifndef SC_TRI_PRISMS_H
#define SC_TRI_PRISMS_H

#include "hulls.h"
#include "key.h"
#include "tri_bezier.h"

/* The patches as a patch list for the GPU records (gl_data.c): patch p
 * holds the mesh's patch p as deg_u = deg_v = the degree and its
 * sc_tri_ncoef points (x, y, height, 1), in sc_tri_index order, each at
 * its domain point; surface 0. */
void sc_tri_patch_list(const sc_tri_mesh *m, sc_patch_list *out);

/* One prism per patch (sub-patch p = patch p of surface 0): 6 vertices,
 * 8 outward triangles. */
void sc_tri_prisms(const sc_tri_mesh *m, sc_hulls *out);

/* The L1 distance, in squares, of patch p's square from the square under
 * the eye (clamped to the mesh): prisms of one distance do not overlap on
 * screen, and lower distances lie in front (section VII). */
int sc_tri_manhattan(const sc_tri_mesh *m, int patch, const double eye[3]);

/* The key of a terrain: `tri` with the mesh's degree, the secure starts,
 * and the iterations, tolerance, early ray termination and outputs of
 * `like` (a key of the render's options). */
void sc_tri_key(const sc_tri_mesh *m, const scg_key *like, scg_key *out);

#endif
