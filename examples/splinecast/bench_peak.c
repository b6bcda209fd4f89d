/* bench_peak.c — `splinecast bench --peak`: the machine's vec4 multiply-add
 * rate in a fragment program (sc_measure_peak) against the rate the
 * intersection programs achieve on a scene. The achieved FLOPs are counted
 * from the IR (sc_count_key_flops) for the work the pixels did: each
 * covered pixel's iterations (its iteration count from the frame's AOVs)
 * times its key's cost per iteration, plus, per intersection program run
 * (the GPU's count), the fixed part of the key. They are divided by the
 * time of the intersection pass alone (the hull draws between two
 * glFinish, sc_renderer_desc.time_intersection; the GL_TIME_ELAPSED query
 * around them is printed beside it, but llvmpipe's covers only the
 * binning): medians over the frames. The peak is timed the same way. */
#include <stdio.h>
#include <stdlib.h>

#include "bench.h"
#include "commands.h"

int bench_peak_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                   const sc_camera_desc *cam, int frames)
{
    sc_error err = {0};
    sc_peak_info peak;
    if (sc_measure_peak(ctx, &(sc_peak_desc){.width = cam->width, .height = cam->height,
                                             .frames = frames},
                        &peak, &err) != SC_OK)
        return cli_report(&err);
    sc_scene_info scene_info;
    if (sc_query_scene_info(scene, &scene_info, &err) != SC_OK)
        return cli_report(&err);
    desc.own_programs = 1;
    desc.time_intersection = 1;
    /* The timed frames are those whose iterations are read back. */
    desc.aovs = SC_AOVS_ALWAYS;
    sc_renderer_id r;
    if (sc_make_renderer(ctx, scene, &desc, &r, &err) != SC_OK)
        return cli_report(&err);
    int n = scene_info.surfaces;
    sc_key_flops *cost = calloc((size_t)(n > 0 ? n : 1), sizeof *cost);
    double *pass_ms = calloc((size_t)frames, sizeof(double));
    double *frame_ms = calloc((size_t)frames, sizeof(double));
    double *query_ms = calloc((size_t)frames, sizeof(double));
    sc_frame_id frame = {0};
    sc_frame_info info;
    sc_renderer_info stats;
    int status = SC_OK;
    for (int s = 0; s < n && status == SC_OK; s++) {
        sc_renderer_surface_info si;
        status = sc_query_renderer_surface(r, s, &si, &err);
        if (status == SC_OK)
            status = sc_count_key_flops(si.key.text, &cost[s], &err);
    }
    if (status == SC_OK)
        status = sc_draw(r, cam, &err);   /* warm-up */
    for (int f = 0; f < frames && status == SC_OK; f++) {
        double t0 = sc_now();
        status = sc_draw(r, cam, &err);
        frame_ms[f] = 1e3 * (sc_now() - t0);
        if (status == SC_OK)
            status = sc_query_renderer_info(r, &stats, &err);
        pass_ms[f] = stats.intersect_ms;
        query_ms[f] = stats.intersect_query_ms;
    }
    if (status == SC_OK)
        status = sc_read_frame(r, &frame, &err);
    if (status == SC_OK)
        status = sc_query_frame_info(frame, &info, &err);
    if (status == SC_OK && !info.iters) {
        snprintf(err.message, sizeof err.message, "bench --peak: the frame has no iteration counts");
        status = SC_FAIL;
    }
    if (status == SC_OK) {
        double iter_flops = 0, fixed = 0;
        long covered = 0;
        for (long p = 0; p < (long)info.width * info.height; p++) {
            int s = info.surface[p];
            if (s < 0 || s >= n)
                continue;
            covered++;
            iter_flops += cost[s].per_iter * info.iters[p];
            fixed += cost[s].fixed;
        }
        /* Runs that left no hit (missed, trimmed away, or overdrawn by a
         * nearer hit) are counted with the covered pixels' mean fixed
         * part and none of their iterations: a lower bound. */
        double fixed_mean = covered ? fixed / (double)covered : 0;
        double flops = iter_flops + fixed_mean * (double)stats.intersections;
        double ms = cli_median(pass_ms, frames);
        double achieved = ms > 0 ? flops / (ms * 1e6) : 0;
        printf("peak gflops=%.1f achieved_gflops=%.1f fraction=%.3f peak_ms=%.2f "
               "peak_wall_ms=%.2f intersect_ms=%.2f intersect_query_ms=%.2f frame_ms=%.2f "
               "flops=%.0f covered=%ld intersections=%lld flops_per_covered_pixel=%.0f\n",
               peak.gflops, achieved, peak.gflops > 0 ? achieved / peak.gflops : 0,
               peak.gpu_ms, peak.wall_ms, ms, cli_median(query_ms, frames),
               cli_median(frame_ms, frames), flops, covered,
               stats.intersections, covered ? flops / (double)covered : 0);
    }
    sc_destroy_frame(frame);
    free(cost);
    free(pass_ms);
    free(frame_ms);
    free(query_ms);
    sc_destroy_renderer(r);
    return status == SC_OK ? 0 : cli_report(&err);
}
