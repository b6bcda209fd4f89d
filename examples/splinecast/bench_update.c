/* bench_update.c — `splinecast bench --update`: what following a moving
 * scene costs. Every frame moves every control point of every surface
 * (deform.h: the chart's deforming view) through sc_update_surface, then
 * draws; printed: the updates' time per frame and per hull, the bytes they
 * sent to the GPU per frame against the renderer's GPU data, the frame
 * drawn after them and the frame of unchanged data, medians over the
 * frames. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "commands.h"
#include "deform.h"

int bench_update_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                     const sc_camera_desc *cam, int frames)
{
    sc_error err = {0};
    deformation def = {0};
    sc_renderer_id r = {0};
    desc.own_programs = 1;
    int status = deformation_init(scene, &def, &err);
    if (status == SC_OK)
        status = sc_make_renderer(ctx, scene, &desc, &r, &err);
    double *update = calloc((size_t)frames, sizeof(double));
    double *drawn = calloc((size_t)frames, sizeof(double));
    double *still = calloc((size_t)frames, sizeof(double));
    double *bytes = calloc((size_t)frames, sizeof(double));
    double *rebuilt = calloc((size_t)frames, sizeof(double));
    sc_renderer_info info = {0};
    if (status == SC_OK)
        status = sc_draw(r, cam, &err);   /* warm-up */
    for (int f = 0; f < frames && status == SC_OK; f++) {
        sc_renderer_info before;
        status = sc_query_renderer_info(r, &before, &err);
        double t0 = sc_now();
        if (status == SC_OK)
            status = deform(scene, &def, 2 * M_PI * (f + 1) / 16.0, &err);
        double t1 = sc_now();
        if (status == SC_OK)
            status = sc_draw(r, cam, &err);
        double t2 = sc_now();
        if (status == SC_OK)
            status = sc_query_renderer_info(r, &info, &err);
        update[f] = 1e3 * (t1 - t0);
        drawn[f] = 1e3 * (t2 - t1);
        bytes[f] = (double)(info.uploaded_total_bytes - before.uploaded_total_bytes);
        rebuilt[f] = (double)(info.qhull_hulls - before.qhull_hulls);
    }
    for (int f = 0; f < frames && status == SC_OK; f++) {
        double t0 = sc_now();
        status = sc_draw(r, cam, &err);
        still[f] = 1e3 * (sc_now() - t0);
    }
    if (status == SC_OK) {
        double u = cli_median(update, frames), b = cli_median(bytes, frames);
        double d = cli_median(drawn, frames), s = cli_median(still, frames);
        printf("bench variant=update surfaces=%d hulls=%d update_ms=%.2f "
               "update_us_per_hull=%.2f frame_ms=%.1f still_frame_ms=%.1f image_ms=%.1f "
               "uploaded_bytes_per_frame=%.0f gpu_bytes=%zu uploaded_fraction=%.4f "
               "qhull_hulls_per_frame=%.0f\n",
               def.nsurfaces, info.hulls, u, info.hulls ? 1e3 * u / info.hulls : 0, d, s,
               u + d, b, info.gpu_bytes, info.gpu_bytes ? b / (double)info.gpu_bytes : 0,
               cli_median(rebuilt, frames));
    }
    if (deform(scene, &def, NAN, status == SC_OK ? &err : &(sc_error){0}) != SC_OK)
        status = SC_FAIL;
    free(update);
    free(drawn);
    free(still);
    free(bytes);
    free(rebuilt);
    sc_destroy_renderer(r);
    deformation_free(&def);
    return status == SC_OK ? 0 : cli_report(&err);
}
