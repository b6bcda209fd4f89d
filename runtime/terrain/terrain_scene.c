/* terrain_scene.c — a terrain as a scene (terrain_scene.h). */
#include "terrain_scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void free_mesh(struct sc_tri_mesh *m)
{
    sc_tri_mesh_free(m);
    free(m);
}

void sc_tri_mesh_height_range(const sc_tri_mesh *m, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t k = 0; k < (size_t)m->count * (size_t)m->ncoef; k++) {
        *lo = fmin(*lo, m->coef[k]);
        *hi = fmax(*hi, m->coef[k]);
    }
}

void sc_terrain_scene(sc_tri_mesh *mesh, const char *name, sc_scene *out)
{
    sc_scene_init(out);
    snprintf(out->source, sizeof out->source, "%s", name);
    out->terrain = sc_alloc(1, sizeof *out->terrain);
    *out->terrain = *mesh;
    memset(mesh, 0, sizeof *mesh);
    out->terrain_free = free_mesh;
    const sc_tri_mesh *m = out->terrain;
    /* The stand-in: a bilinear patch from the lowest corner of the box to
     * the highest, whose control points span the terrain's box. */
    double zlo, zhi;
    sc_tri_mesh_height_range(m, &zlo, &zhi);
    sc_surface *s = sc_scene_add_surface(out);
    snprintf(s->name, sizeof s->name, "terrain");
    sc_surface_alloc(s, 1, 1, 2, 2);
    static const double knots[4] = {0, 0, 1, 1};
    memcpy(s->knots_u, knots, sizeof knots);
    memcpy(s->knots_v, knots, sizeof knots);
    double x1 = m->x0 + m->nx * m->hx, y1 = m->y0 + m->ny * m->hy;
    const double cp[16] = {m->x0, m->y0, zlo, 1, x1, m->y0, zlo, 1,
                           m->x0, y1,    zhi, 1, x1, y1,    zhi, 1};
    memcpy(s->cp, cp, sizeof cp);
    s->color[0] = 0.55f;
    s->color[1] = 0.7f;
    s->color[2] = 0.45f;
}
