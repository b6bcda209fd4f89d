/* bench.h — what the modes of `splinecast bench` share (cmd_bench.c): one
 * renderer timed over several frames, its figures, and the line that prints
 * them. Each mode lives in its own bench_NAME.c. */
#ifndef SC_BENCH_H
#define SC_BENCH_H

#include "gl_render.h"

typedef struct bench_result {
    double frame_ms;        /* median of the timed frames */
    double mpix_s;          /* covered pixels per second, in millions */
    double iters_mean;      /* Newton iterations per covered pixel */
    double compile_ms;      /* programs, plus the warm-up frame's excess */
    long covered;
    sc_render_stats stats;
} bench_result;

/* Builds a renderer, draws a warm-up frame and `frames` timed ones. */
int bench_run(const sc_gl *gl, const sc_scene *scene, const sc_render_desc *desc,
              const sc_camera *cam, int frames, bench_result *out, sc_error *err);
/* Covered pixels, iterations per covered pixel, MPixel/s (from
 * out->frame_ms) and the renderer's figures, from its last frame's AOVs. */
void bench_figures(const sc_renderer *r, const sc_aov *aov, bench_result *out);
/* One `bench variant=…` line on stdout; `extra` goes after the variant. */
void bench_print(const char *variant, const char *extra, const bench_result *r);

/* The early-termination / draw-order / batch sweep (bench_order.c). */
typedef struct bench_sweep {
    const char *scenes[32];
    int nscenes;
    sc_ray_termination erts[4];
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
int bench_sweep_run(const sc_gl *gl, const bench_sweep *sweep, sc_render_desc desc,
                    const char *camera_arg, int width, int height, int frames);

/* The methods side by side (bench_methods.c): `--method A,B,…` parsed
 * into `methods` (0 or the exit status of a usage error), then one run
 * with every timed frame drawn by each method in turn. */
#define BENCH_MAX_METHODS 8
int bench_methods_parse(const char *text, sc_method *methods, int *count);
int bench_methods_run(const sc_gl *gl, const char *scene_path, sc_render_desc desc,
                      const char *camera_arg, int width, int height, int frames,
                      const sc_method *methods, int count);

#endif
