/* deform.c — the travelling wave of deform.h, applied surface by surface
 * through the public API. */
#include "deform.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int deformation_init(sc_scene_id scene, deformation *d, sc_error *err)
{
    sc_scene_info info;
    if (sc_query_scene_info(scene, &info, err) != SC_OK)
        return SC_FAIL;
    double diag = 0;
    for (int c = 0; c < 3; c++)
        diag += (info.hi[c] - info.lo[c]) * (info.hi[c] - info.lo[c]);
    diag = sqrt(diag);
    /* A wave of 1 % of the scene's size, three per scene: non-rigid, small
     * enough that the view still frames the scene. */
    d->amplitude = 0.01 * diag;
    d->wavelength = diag / 3;
    d->nsurfaces = info.surfaces;
    d->counts = calloc((size_t)info.surfaces, sizeof(int));
    d->points = calloc((size_t)info.surfaces, sizeof(double *));
    for (int s = 0; s < info.surfaces; s++) {
        sc_surface_info si;
        if (sc_query_surface_info(scene, s, &si, err) != SC_OK)
            return SC_FAIL;
        d->counts[s] = si.nu * si.nv;
        d->points[s] = malloc((size_t)d->counts[s] * 3 * sizeof(double));
        if (sc_query_surface_points(scene, s, d->points[s], NULL, d->counts[s], err) != SC_OK)
            return SC_FAIL;
    }
    return SC_OK;
}

void deformation_free(deformation *d)
{
    for (int s = 0; s < d->nsurfaces; s++)
        free(d->points[s]);
    free(d->points);
    free(d->counts);
}

int deform(sc_scene_id scene, const deformation *d, double phase, sc_error *err)
{
    for (int s = 0; s < d->nsurfaces; s++) {
        int n = d->counts[s];
        double *p = malloc((size_t)n * 3 * sizeof(double));
        memcpy(p, d->points[s], (size_t)n * 3 * sizeof(double));
        if (!isnan(phase))
            for (int i = 0; i < n; i++)
                p[3 * i + 2] += d->amplitude *
                                sin(2 * M_PI * (p[3 * i] + p[3 * i + 1]) / d->wavelength + phase);
        sc_surface_desc sd = {.surface = s, .count = n, .points = p};
        int status = sc_update_surface(scene, &sd, err);
        free(p);
        if (status != SC_OK)
            return SC_FAIL;
    }
    return SC_OK;
}
