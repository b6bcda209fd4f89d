/* bench_run.c — one renderer timed the way every mode of `splinecast
 * bench` times it (a warm-up frame, then the median of the timed ones),
 * and the `bench variant=…` line that prints its figures. A file of its
 * own so that cmd_bench.c and bench_order.c both call it and not each
 * other. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "bench.h"
#include "commands.h"

int bench_run(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
              const sc_camera_desc *cam, int frames, bench_result *out, sc_error *err)
{
    sc_renderer_id r;
    memset(out, 0, sizeof *out);
    /* Each renderer compiles its programs, as a fresh process would: the
     * compile figures are not cache hits of an earlier run. */
    sc_renderer_desc own = *desc;
    own.own_programs = 1;
    double t_prepare = sc_now();
    if (sc_make_renderer(ctx, scene, &own, &r, err) != SC_OK)
        return SC_FAIL;
    double prepare_ms = 1e3 * (sc_now() - t_prepare);
    double *times = calloc((size_t)frames, sizeof(double));
    double t0 = sc_now();
    int status = sc_draw(r, cam, err);
    double warm_up = 1e3 * (sc_now() - t0);
    for (int f = 0; f < frames && status == SC_OK; f++) {
        t0 = sc_now();
        status = sc_draw(r, cam, err);
        times[f] = 1e3 * (sc_now() - t0);
    }
    if (status == SC_OK)
        status = bench_finish(r, times, frames, warm_up, out, err);
    out->prepare_ms = prepare_ms;
    free(times);
    sc_destroy_renderer(r);
    return status;
}

int bench_finish(sc_renderer_id r, double *times, int frames, double warm_up_ms,
                 bench_result *out, sc_error *err)
{
    sc_frame_id frame = {0};
    sc_frame_info info;
    /* The counts of the last timed frame, before the read draws it again
     * with the AOVs where it had none (and compiles their programs); the
     * intersections, which only frames with the AOVs count, of that
     * drawing then (the same camera and hulls). */
    int status = sc_query_renderer_info(r, &out->stats, err);
    if (status == SC_OK)
        status = sc_read_frame(r, &frame, err);
    sc_renderer_info counted;
    if (status == SC_OK && out->stats.intersections < 0 &&
        (status = sc_query_renderer_info(r, &counted, err)) == SC_OK)
        out->stats.intersections = counted.intersections;
    if (status == SC_OK)
        status = sc_query_frame_info(frame, &info, err);
    if (status == SC_OK) {
        out->frame_ms = cli_median(times, frames);
        double iters = 0;
        for (int p = 0; p < info.width * info.height; p++)
            if (info.surface[p] >= 0) {
                out->covered++;
                iters += info.iters[p];
            }
        out->iters_mean = out->covered ? iters / (double)out->covered : 0;
        out->mpix_s = out->frame_ms > 0 ? (double)out->covered / (out->frame_ms * 1e3) : 0;
        out->compile_ms = out->stats.compile_ms + fmax(warm_up_ms - out->frame_ms, 0);
    }
    sc_destroy_frame(frame);
    return status;
}

void bench_print(const char *variant, const char *extra, const bench_result *r)
{
    printf("bench variant=%s%s frame_ms=%.2f mpix_s=%.2f covered=%ld iters_mean=%.3f "
           "gpu_bytes=%zu programs=%d hulls=%d triangles=%d compile_ms=%.1f "
           "compile_ms_per_program=%.1f draw_calls=%d program_switches=%d culled_hulls=%d "
           "readbacks=%d intersections=%lld rays_per_covered_pixel=%.3f peel_layers=%d\n",
           variant, extra, r->frame_ms, r->mpix_s, r->covered, r->iters_mean,
           r->stats.gpu_bytes, r->stats.programs, r->stats.hulls, r->stats.triangles,
           r->compile_ms, r->stats.programs ? r->compile_ms / r->stats.programs : 0,
           r->stats.draw_calls, r->stats.program_switches, r->stats.culled_hulls,
           r->stats.readbacks, r->stats.intersections,
           r->covered ? (double)r->stats.intersections / (double)r->covered : 0.0,
           r->stats.peel_layers);
    fflush(stdout);
}

void bench_print_scene(const char *path, double read_ms, const bench_result *r)
{
    struct rusage usage;
    double peak_mb = getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss / 1024.0 : 0;
    printf("bench scene=%s read_ms=%.1f prepare_ms=%.1f peak_rss_mb=%.1f gpu_bytes=%zu hulls=%d "
           "triangles=%d\n",
           path, read_ms, r->prepare_ms, peak_mb, r->stats.gpu_bytes, r->stats.hulls,
           r->stats.triangles);
    fflush(stdout);
}
