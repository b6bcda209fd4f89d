/* cmd_bench.c — `splinecast bench`: speed of the GPU path, printed, not
 * asserted. For a scene (default: the embedded teapot at 1024×1024): frame
 * time, MPixel/s of covered pixels, mean Newton iterations, GPU bytes, hull
 * triangles and compile time per program, for the specialized (unrolled)
 * programs and, in the same run, for the generic program with runtime
 * loops, so that their ratio is measured on one machine state. With
 * --degrees: one full-screen Bézier patch per degree, unrolled against
 * generic, with compile times: the figures that set the unrolling limit
 * (programs.h) and the draw time by degree. With --ert, --order or --batch:
 * the early-termination and draw-order sweep of bench_order.c over one or
 * more scenes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "commands.h"
#include "options.h"
#include "gl_context.h"
#include "gl_render.h"
#include "io.h"

static const char usage[] =
    "usage: splinecast bench [SCENE] [options]\n"
    "\n"
    "Times the GPU path on SCENE (default: the embedded teapot) and prints one\n"
    "line per program variant:\n"
    "  bench variant=specialized|generic frame_ms=T mpix_s=M covered=N iters_mean=I\n"
    "        gpu_bytes=B programs=P hulls=H triangles=T compile_ms=C compile_ms_per_program=C\n"
    "        draw_calls=N program_switches=N culled_hulls=N readbacks=N\n"
    "and the ratio of the two frame times. frame_ms is the median of the timed\n"
    "frames after a warm-up frame; mpix_s counts covered pixels only.\n"
    "\n"
    "options:\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n"
    "  --size WxH             image size (default 1024x1024)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOVY   view (default: framing the scene)\n"
    "  --iters N              Newton iterations at most (default 6)\n"
    "  --hull uniform:N|adaptive:TOL   proxy hulls (default adaptive:0.003)\n"
    "  --init mid|cpmap|view  Newton start (default cpmap)\n"
    "  --method LIST          intersection method (newton); a comma list of\n"
    "                         newton, broyden, bclip, subdiv, hybrid compares\n"
    "                         them on SCENE, each timed frame drawn by every\n"
    "                         method in turn: one line `bench variant=method\n"
    "                         method=M ...` each, then the frame time of each\n"
    "                         over the first's\n"
    "  --frames N             timed frames (default 5)\n"
    "  --ert LIST             early ray termination: all or a comma list of none,\n"
    "                         conservative, manual, manual-both\n"
    "  --order LIST           draw order: all or a comma list of front-to-back,\n"
    "                         by-program, hybrid\n"
    "  --batch LIST           comma list of hulls per batch (manual early ray\n"
    "                         termination, hybrid buckets)\n"
    "                         Any of these three: every SCENE given (several may\n"
    "                         be) under every combination, one line each:\n"
    "                           bench variant=sweep scene=S ert=E order=O batch=B ...\n"
    "                         then per combination the frame time of the last\n"
    "                         scene over the first, and per scene each\n"
    "                         combination's frame time over the first one's\n"
    "  --degrees LO-HI        instead of a scene: one bumpy Bezier patch of each\n"
    "                         degree LO..HI filling the view, unrolled vs generic\n"
    "  --trim-table           instead of a scene: the cost of trimming, trimmed /\n"
    "                         untrimmed per method (bench --trim-table --help)\n";

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

void bench_figures(const sc_renderer *r, const sc_aov *aov, bench_result *out)
{
    double iters = 0;
    for (int p = 0; p < aov->width * aov->height; p++)
        if (aov->surface[p] >= 0) {
            out->covered++;
            iters += aov->iters[p];
        }
    out->iters_mean = out->covered ? iters / (double)out->covered : 0;
    out->mpix_s = out->frame_ms > 0 ? (double)out->covered / (out->frame_ms * 1e3) : 0;
    sc_renderer_stats(r, &out->stats);
}

int bench_run(const sc_gl *gl, const sc_scene *scene, const sc_render_desc *desc,
              const sc_camera *cam, int frames, bench_result *out, sc_error *err)
{
    sc_renderer *r;
    memset(out, 0, sizeof *out);
    if (sc_renderer_create(gl, scene, desc, &r, err) != SC_OK)
        return SC_FAIL;
    double *times = sc_alloc((size_t)frames, sizeof(double));
    double t0 = sc_now();
    int status = sc_renderer_draw(r, cam, err);
    double warm_up = 1e3 * (sc_now() - t0);
    for (int f = 0; f < frames && status == SC_OK; f++) {
        t0 = sc_now();
        status = sc_renderer_draw(r, cam, err);
        times[f] = 1e3 * (sc_now() - t0);
    }
    sc_aov aov;
    if (status == SC_OK)
        status = sc_renderer_read(r, NULL, &aov, err);
    if (status == SC_OK) {
        qsort(times, (size_t)frames, sizeof(double), compare_double);
        out->frame_ms = frames % 2 ? times[frames / 2]
                                   : 0.5 * (times[frames / 2 - 1] + times[frames / 2]);
        bench_figures(r, &aov, out);
        out->compile_ms = out->stats.compile_ms + fmax(warm_up - out->frame_ms, 0);
        sc_aov_free(&aov);
    }
    free(times);
    sc_renderer_destroy(r);
    return status;
}

void bench_print(const char *variant, const char *extra, const bench_result *r)
{
    printf("bench variant=%s%s frame_ms=%.2f mpix_s=%.2f covered=%ld iters_mean=%.3f "
           "gpu_bytes=%zu programs=%d hulls=%d triangles=%d compile_ms=%.1f "
           "compile_ms_per_program=%.1f draw_calls=%d program_switches=%d culled_hulls=%d "
           "readbacks=%d\n",
           variant, extra, r->frame_ms, r->mpix_s, r->covered, r->iters_mean,
           r->stats.gpu_bytes, r->stats.programs, r->stats.hulls, r->stats.triangles,
           r->compile_ms, r->stats.programs ? r->compile_ms / r->stats.programs : 0,
           r->stats.draw_calls, r->stats.program_switches, r->stats.culled_hulls,
           r->stats.readbacks);
    fflush(stdout);
}

/* A bumpy Bézier patch of degree d × d over [-1, 1]², heights from a fixed
 * pseudo-random sequence, so that Newton has work at every degree. */
static void bumpy_patch(sc_scene *scene, int d)
{
    sc_scene_init(scene);
    sc_surface *s = sc_scene_add_surface(scene);
    sc_surface_alloc(s, d, d, d + 1, d + 1);
    for (int k = 0; k <= 2 * d + 1; k++) {
        s->knots_u[k] = s->knots_v[k] = k <= d ? 0 : 1;
    }
    unsigned state = 12345u + (unsigned)d;
    for (int j = 0; j <= d; j++)
        for (int i = 0; i <= d; i++) {
            double *cp = s->cp + 4 * (j * (d + 1) + i);
            state = state * 1103515245u + 12345u;
            cp[0] = -1 + 2.0 * i / d;
            cp[1] = -1 + 2.0 * j / d;
            cp[2] = 0.3 * ((state >> 16) % 1000) / 1000.0;
            cp[3] = 1;
        }
    sc_surface_update_rational(s);
}

static int bench_degrees(const sc_gl *gl, sc_render_desc desc, int lo, int hi, int width,
                         int height, int frames)
{
    bench_result lowest = {0};
    for (int d = lo; d <= hi; d++) {
        sc_scene scene;
        bumpy_patch(&scene, d);
        sc_camera cam = {.eye = {0, -0.001, 3.2}, .target = {0, 0, 0.15}, .fovy_deg = 36,
                         .width = width, .height = height};
        bench_result unrolled, generic;
        sc_error err = {0};
        char extra[32];
        snprintf(extra, sizeof extra, " degree=%dx%d", d, d);
        desc.generic = 0;
        /* Above the unrolling limit the runtime itself picks the generic
         * program; the sweep wants the unrolled one at every degree. */
        desc.unroll_max_degree = SCG_MAX_DEGREE;
        int status = bench_run(gl, &scene, &desc, &cam, frames, &unrolled, &err);
        if (status == SC_OK) {
            bench_print("unrolled", extra, &unrolled);
            desc.generic = 1;
            status = bench_run(gl, &scene, &desc, &cam, frames, &generic, &err);
        }
        sc_scene_free(&scene);
        if (status != SC_OK)
            return cli_report(&err);
        bench_print("generic", extra, &generic);
        double saved = generic.frame_ms - unrolled.frame_ms;
        double extra_compile = unrolled.compile_ms - generic.compile_ms;
        if (d == lo)
            lowest = unrolled;
        printf("bench degree=%dx%d frame_ratio_generic_over_unrolled=%.2f "
               "break_even_frames=%s%.0f unrolled_frame_ratio_over_%dx%d=%.2f\n",
               d, d, generic.frame_ms / unrolled.frame_ms, saved > 0 ? "" : "never:",
               saved > 0 ? fmax(extra_compile, 0) / saved : 0, lo, lo,
               unrolled.frame_ms / lowest.frame_ms);
        fflush(stdout);
    }
    return 0;
}

int cmd_bench(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "--trim-table"))
            return bench_trim_table(argc, argv);
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *scene_path = "teapot", *camera_arg = NULL;
    sc_gl_context_desc ctx_desc = {0};
    sc_render_desc desc = {0};
    int width = 1024, height = 1024, frames = 5, deg_lo = 0, deg_hi = 0, status = 0;
    sc_error err = {0};
    bench_sweep sweep = {0};
    sc_method methods[BENCH_MAX_METHODS];
    int nmethods = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &ctx_desc.backend, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--size") && next) {
            i++;
            if (sscanf(argv[i], "%dx%d", &width, &height) != 2 || width < 1 || height < 1 ||
                width > 16384 || height > 16384)
                return cli_usage_error("bench", "--size takes WxH, not '%s'", argv[i]);
        } else if (!strcmp(a, "--camera") && next) {
            camera_arg = argv[++i];
        } else if (!strcmp(a, "--iters") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > SCG_MAX_ITERS)
                return cli_usage_error("bench", "--iters takes 1 to %d, not '%s'",
                                       SCG_MAX_ITERS, argv[i]);
            desc.max_iters = (int)n;
        } else if (!strcmp(a, "--hull") && next) {
            if (cli_hulls_parse(argv[++i], &desc.hulls.mode, &desc.hulls.divisions,
                                &desc.hulls.tolerance, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--init") && next) {
            if (cli_start_parse(argv[++i], &desc.start, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--method") && next) {
            if ((status = bench_methods_parse(argv[++i], methods, &nmethods)) != 0)
                return status;
            desc.method = methods[0];
        } else if (!strcmp(a, "--frames") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000)
                return cli_usage_error("bench", "--frames takes 1 to 1000, not '%s'", argv[i]);
            frames = (int)n;
        } else if (!strcmp(a, "--degrees") && next) {
            i++;
            if (sscanf(argv[i], "%d-%d", &deg_lo, &deg_hi) != 2 || deg_lo < 1 ||
                deg_hi < deg_lo || deg_hi > SCG_MAX_DEGREE)
                return cli_usage_error("bench", "--degrees takes LO-HI within 1-%d, not '%s'",
                                       SCG_MAX_DEGREE, argv[i]);
        } else if (!strcmp(a, "--ert") && next) {
            if ((status = bench_sweep_parse_erts(argv[++i], &sweep)) != 0)
                return status;
        } else if (!strcmp(a, "--order") && next) {
            if ((status = bench_sweep_parse_orders(argv[++i], &sweep)) != 0)
                return status;
        } else if (!strcmp(a, "--batch") && next) {
            if ((status = bench_sweep_parse_batches(argv[++i], &sweep)) != 0)
                return status;
        } else if (a[0] != '-') {
            if (sweep.nscenes == (int)(sizeof sweep.scenes / sizeof sweep.scenes[0]))
                return cli_usage_error("bench", "at most %d scenes",
                                       (int)(sizeof sweep.scenes / sizeof sweep.scenes[0]));
            scene_path = a;
            sweep.scenes[sweep.nscenes++] = a;
        } else {
            return cli_usage_error("bench", "unexpected argument '%s'", a);
        }
    }
    int sweeping = sweep.nerts || sweep.norders || sweep.nbatches;
    if (sweep.nscenes > 1 && !sweeping)
        return cli_usage_error("bench", "several scenes need --ert, --order or --batch");
    sc_gl_context *ctx;
    if (sc_gl_context_create(&ctx_desc, &ctx, &err) != SC_OK)
        return cli_report(&err);
    fprintf(stderr, "bench: %s\n", sc_gl_context_description(ctx));
    const sc_gl *gl = sc_gl_context_gl(ctx);
    if (sweeping) {
        if (!sweep.nscenes)
            sweep.scenes[sweep.nscenes++] = scene_path;
        status = bench_sweep_run(gl, &sweep, desc, camera_arg, width, height, frames);
        sc_gl_context_destroy(ctx);
        return status;
    }
    if (nmethods > 1) {
        status = bench_methods_run(gl, scene_path, desc, camera_arg, width, height, frames,
                                   methods, nmethods);
        sc_gl_context_destroy(ctx);
        return status;
    }
    if (deg_lo) {
        status = bench_degrees(gl, desc, deg_lo, deg_hi, width, height, frames);
        sc_gl_context_destroy(ctx);
        return status;
    }
    sc_scene scene;
    if (sc_read_scene(scene_path, &scene, &err) != SC_OK) {
        sc_gl_context_destroy(ctx);
        return cli_report(&err);
    }
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    status = 0;
    if (camera_arg && sc_camera_parse(camera_arg, &cam, &err) != SC_OK) {
        status = cli_usage_error("bench", "--camera: %s", err.message);
    } else {
        cam.width = width;
        cam.height = height;
        bench_result specialized, generic;
        if (bench_run(gl, &scene, &desc, &cam, frames, &specialized, &err) != SC_OK) {
            status = cli_report(&err);
        } else {
            bench_print("specialized", "", &specialized);
            desc.generic = 1;
            if (bench_run(gl, &scene, &desc, &cam, frames, &generic, &err) != SC_OK) {
                status = cli_report(&err);
            } else {
                bench_print("generic", "", &generic);
                printf("bench frame_ratio_generic_over_specialized=%.2f\n",
                       generic.frame_ms / specialized.frame_ms);
            }
        }
    }
    sc_scene_free(&scene);
    sc_gl_context_destroy(ctx);
    return status;
}
