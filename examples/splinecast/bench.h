/* bench.h — what the modes of `splinecast bench` share: one renderer timed
 * over several frames, its figures and the line that prints them
 * (bench_run.c), and the early-termination / draw-order sweep
 * (bench_order.c), which cmd_bench.c runs. */
#ifndef SC_BENCH_H
#define SC_BENCH_H

#include "splinecast.h"

typedef struct bench_result {
    double frame_ms;        /* median of the timed frames */
    double mpix_s;          /* covered pixels per second, in millions */
    double iters_mean;      /* Newton iterations per covered pixel */
    double compile_ms;      /* programs, plus the warm-up frame's excess */
    double prepare_ms;      /* sc_make_renderer: keys, programs, hulls, GPU data */
    long covered;
    sc_renderer_info stats;
} bench_result;

/* Makes a renderer, draws a warm-up frame and `frames` timed ones (with
 * the AOVs as desc->aovs says), then reads the last back (bench_finish;
 * drawn again with the AOVs when it had none). */
int bench_run(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
              const sc_camera_desc *cam, int frames, bench_result *out, sc_error *err);
/* The figures of a renderer already timed: the median of its `frames`
 * times (sorted in place), and covered pixels, iterations and the
 * renderer's counts from a frame read back now; warm_up_ms beyond a
 * frame's time counts as compiling. */
int bench_finish(sc_renderer_id r, double *times, int frames, double warm_up_ms,
                 bench_result *out, sc_error *err);
/* One `bench variant=…` line on stdout; `extra` goes after the variant. */
void bench_print(const char *variant, const char *extra, const bench_result *r);
/* The line of what a scene costs before its first frame (cmd_bench.c):
 * `bench scene=PATH read_ms=R prepare_ms=P peak_rss_mb=M gpu_bytes=B
 * hulls=H triangles=T`; peak_rss_mb is the process's peak so far
 * (getrusage's ru_maxrss). */
void bench_print_scene(const char *path, double read_ms, const bench_result *r);

/* The early-termination / draw-order / batch sweep (bench_order.c). */
typedef struct bench_sweep {
    const char *scenes[32];
    int nscenes;
    sc_ray_termination erts[5];
    int nerts;
    sc_hull_order orders[3];
    int norders;
    int batches[16];
    int nbatches;
} bench_sweep;

/* "all" or a comma list of names (cli_termination_parse, cli_order_parse),
 * and a comma list of batch sizes; 0 or the exit status of a usage error. */
int bench_sweep_parse_erts(const char *text, bench_sweep *sweep);
int bench_sweep_parse_orders(const char *text, bench_sweep *sweep);
int bench_sweep_parse_batches(const char *text, bench_sweep *sweep);
/* Times every scene under every combination; returns the exit status. */
int bench_sweep_run(sc_context_id ctx, const bench_sweep *sweep, sc_renderer_desc desc,
                    const char *camera_arg, int width, int height, int frames);

/* Renderers side by side (bench_sides.c): `--method A,B,…` or `--eval
 * A,B,…` parsed into `values` (0 or the exit status of a usage error),
 * then one run with every timed frame drawn by each in turn. */
#define BENCH_MAX_SIDES 8
typedef enum bench_side_field { BENCH_SIDE_METHOD, BENCH_SIDE_EVAL } bench_side_field;
int bench_sides_parse(bench_side_field field, const char *text, int *values, int *count);
int bench_sides_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                    const sc_camera_desc *cam, int frames, bench_side_field field,
                    const int *values, int count);

/* The defaults against accuracy targets (bench_accuracy.c): `--accuracy
 * PX[,DEG]`, given up to BENCH_MAX_TARGETS times. */
#define BENCH_MAX_TARGETS 8
int bench_accuracy_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                       const sc_camera_desc *cam, int frames, const double *px,
                       const double *deg, int count);

/* `--peak` (bench_peak.c): the peak vec4 multiply-add rate and the rate
 * the intersection achieves on scene; returns the exit status. */
int bench_peak_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                   const sc_camera_desc *cam, int frames);

/* `--update` (bench_update.c): every surface moved through
 * sc_update_surface before each frame; returns the exit status. */
int bench_update_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                     const sc_camera_desc *cam, int frames);

#endif
