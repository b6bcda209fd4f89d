/* terrain_scene.h — a terrain as a scene: the mesh of triangular patches
 * the renderer and the reference draw (sc_scene.terrain), and one stand-in
 * surface that gives the scene its bounding box, colour and name, so that
 * cameras, `info` and colours work as for any scene. */
#ifndef SC_TERRAIN_SCENE_H
#define SC_TERRAIN_SCENE_H

#include "scene.h"
#include "tri_bezier.h"

/* Moves *mesh into a new scene (mesh is left empty). */
void sc_terrain_scene(sc_tri_mesh *mesh, const char *name, sc_scene *out);

/* The lowest and highest BB-coefficient of the mesh (its heights lie
 * between them: convex hull property). */
void sc_tri_mesh_height_range(const sc_tri_mesh *m, double *lo, double *hi);

#endif
