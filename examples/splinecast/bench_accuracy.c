/* bench_accuracy.c — `splinecast bench --accuracy PX[,DEG]`: the renderer's
 * defaults against the settings accuracy targets choose (docs/accuracy.md),
 * each timed frame drawn by every configuration in turn, so that their
 * ratio is measured on one machine state. */
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "commands.h"
#include "options.h"

int bench_accuracy_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                       const sc_camera_desc *cam, int frames, const double *px,
                       const double *deg, int count)
{
    sc_error err = {0};
    int n = count + 1; /* the defaults first */
    sc_renderer_id r[BENCH_MAX_TARGETS + 1] = {{0}};
    double warm_up[BENCH_MAX_TARGETS + 1] = {0};
    double *times = calloc((size_t)(n * frames), sizeof *times);
    int status = SC_OK;
    /* Each renderer compiles its own programs, as a fresh process would. */
    desc.own_programs = 1;
    desc.accuracy_view = cam;
    for (int k = 0; k < n && status == SC_OK; k++) {
        desc.accuracy_px = k ? px[k - 1] : 0;
        desc.accuracy_normal_deg = k ? deg[k - 1] : 0;
        status = sc_make_renderer(ctx, scene, &desc, &r[k], &err);
        double t0 = sc_now();
        if (status == SC_OK)
            status = sc_draw(r[k], cam, &err);
        warm_up[k] = 1e3 * (sc_now() - t0);
    }
    for (int f = 0; f < frames && status == SC_OK; f++)
        for (int k = 0; k < n && status == SC_OK; k++) {
            double t0 = sc_now();
            status = sc_draw(r[k], cam, &err);
            times[k * frames + f] = 1e3 * (sc_now() - t0);
        }
    double default_ms = 0;
    for (int k = 0; k < n && status == SC_OK; k++) {
        bench_result res = {0};
        status = bench_finish(r[k], times + k * frames, frames, warm_up[k], &res, &err);
        if (status != SC_OK)
            break;
        char extra[96];
        snprintf(extra, sizeof extra, " accuracy_px=%g normal_deg=%g", k ? px[k - 1] : 0,
                 k ? deg[k - 1] : 0);
        bench_print("accuracy", extra, &res);
        if (k == 0)
            default_ms = res.frame_ms;
        else
            printf("bench frame_ratio_accuracy_%g_over_default=%.2f\n", px[k - 1],
                   res.frame_ms / default_ms);
    }
    for (int k = 0; k < n; k++)
        sc_destroy_renderer(r[k]);
    free(times);
    return status == SC_OK ? 0 : cli_report(&err);
}
