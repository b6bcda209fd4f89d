/* deform.h — the deformation `bench --chart`'s deforming view and `bench
 * --update` apply: every control point of every surface moved by a
 * travelling sine wave along z through sc_update_surface (deform.c). */
#ifndef SC_DEFORM_H
#define SC_DEFORM_H

#include "splinecast.h"

/* Every surface's control points as read, and the wave that moves them. */
typedef struct deformation {
    int nsurfaces;
    int *counts;
    double **points;         /* 3 per point, the surfaces' own coordinates */
    double amplitude, wavelength;
} deformation;

/* Reads the scene's control points; the wave: 1 % of the scene's size
 * high, three per scene. */
int deformation_init(sc_scene_id scene, deformation *d, sc_error *err);
void deformation_free(deformation *d);
/* Moves every control point: z += A sin(2π (x + y) / λ + phase); phase
 * NAN puts the points back as read. */
int deform(sc_scene_id scene, const deformation *d, double phase, sc_error *err);

#endif
