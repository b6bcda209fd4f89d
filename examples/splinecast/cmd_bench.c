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
 * more scenes. With --stability: the stability suite (bench_stability.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "chart.h"
#include "commands.h"
#include "options.h"

static const char usage[] =
    "usage: splinecast bench [SCENE...] [options]\n"
    "\n"
    "Times the GPU path on SCENE (default: the embedded teapot) and prints one\n"
    "line per program variant:\n"
    "  bench variant=specialized|generic frame_ms=T mpix_s=M covered=N iters_mean=I\n"
    "        gpu_bytes=B programs=P hulls=H triangles=T compile_ms=C compile_ms_per_program=C\n"
    "        draw_calls=N program_switches=N culled_hulls=N readbacks=N\n"
    "        intersections=N rays_per_covered_pixel=X peel_layers=N\n"
    "and the ratio of the two frame times. frame_ms is the median of the timed\n"
    "frames after a warm-up frame; mpix_s counts covered pixels only. Then what\n"
    "the scene cost before its first frame:\n"
    "  bench scene=PATH read_ms=R prepare_ms=P peak_rss_mb=M gpu_bytes=B hulls=H\n"
    "        triangles=T\n"
    "(prepare_ms: making the renderer, programs included; peak_rss_mb: the\n"
    "process's peak resident memory so far). Several SCENEs (without the sweep\n"
    "options below): every one prepared (its `bench scene=` line, the peak\n"
    "including the scenes before it), each timed frame drawing every scene in\n"
    "turn with the specialized programs alone; then one `variant=specialized`\n"
    "line per scene, in the order given, and per scene after the first\n"
    "  bench scene=PATH mpix_s_ratio_first_over_this=R\n"
    "(the cost per covered pixel against the first scene's).\n"
    "\n"
    "options:\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n"
    "  --size WxH             image size (default 1024x1024)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOVY   view (default: framing the scene)\n"
    "  --iters N              Newton iterations at most (default 6)\n"
    "  --hull uniform:N|adaptive:TOL   proxy hulls (default adaptive:0.003)\n"
    "  --init mid|cpmap|view  Newton start (default cpmap)\n"
    "  --method LIST          intersection method (hybrid); a comma list of\n"
    "                         newton, broyden, bclip, subdiv, hybrid compares\n"
    "                         them on SCENE, each timed frame drawn by every\n"
    "                         method in turn: one line `bench variant=method\n"
    "                         method=M ...` each, then the frame time of each\n"
    "                         over the first's\n"
    "  --eval LIST            evaluation form of the unrolled Bezier programs'\n"
    "                         iteration (default: pow up to degree 4, dc\n"
    "                         above; pow stops at degree 6); a comma list of\n"
    "                         dc, bern, pow compares\n"
    "                         them as --method does: one line `bench\n"
    "                         variant=eval eval=E ...` each, then the frame\n"
    "                         time of each over the first's\n"
    "  --accuracy PX[,DEG]    the defaults against the settings this accuracy\n"
    "                         target chooses (docs/accuracy.md); may be given up\n"
    "                         to 8 times. Each timed frame is drawn by every\n"
    "                         configuration in turn: one line `bench\n"
    "                         variant=accuracy accuracy_px=X normal_deg=A ...`\n"
    "                         each (0: the defaults), then each target's frame\n"
    "                         time over the defaults'\n"
    "  --frames N             timed frames (default 5)\n"
    "  --ert LIST             early ray termination: all or a comma list of none,\n"
    "                         conservative, manual, manual-both, peel, lists\n"
    "  --lists-below off|PX   in the manual modes, hulls at most PX pixels wide\n"
    "                         and high on screen go through candidate lists\n"
    "                         (default 8)\n"
    "  --threads N            CPU threads of each frame's pass over the hulls\n"
    "                         (default: one per processor; at most 8 used)\n"
    "  --order LIST           draw order: all or a comma list of front-to-back,\n"
    "                         by-program, hybrid\n"
    "  --batch LIST           comma list of hulls per batch (manual early ray\n"
    "                         termination, hybrid buckets; peel: the first of\n"
    "                         its doubling batches)\n"
    "                         Any of these three: every SCENE given (several may\n"
    "                         be) under every combination, one line each:\n"
    "                           bench variant=sweep scene=S ert=E order=O batch=B ...\n"
    "                         then per combination the frame time of the last\n"
    "                         scene over the first, and per scene each\n"
    "                         combination's frame time over the first one's\n"
    "  --degrees LO-HI        instead of a scene: one bumpy Bezier patch of each\n"
    "                         degree LO..HI filling the view, unrolled vs generic\n"
    "  --trim-table           instead of a scene: the cost of trimming, trimmed /\n"
    "                         untrimmed per method (bench --trim-table --help)\n"
    "  --stability            instead of a scene: the stability suite, every\n"
    "                         method and start against the CPU reference\n"
    "                         (bench --stability --help)\n"
    "  --chart DIR            every method, start, iteration cap and hull\n"
    "                         subdivision and the tessellation peers (GLU,\n"
    "                         tessellation shaders) in three views against the\n"
    "                         CPU reference: DIR/points.csv, chart.png, chart.svg\n"
    "                         (bench --chart DIR --help)\n"
    "  --colour-only          also time frames that write the AOVs every time\n"
    "                         (sc_renderer_desc.aovs = SC_AOVS_ALWAYS) against\n"
    "                         the default's shaded frames, which write colour\n"
    "                         and depth alone: a line `bench variant=aovs-always\n"
    "                         ...` after the specialized one, then\n"
    "                         bench frame_ratio_colour_only_over_aovs_always=R\n"
    "  --peak                 the machine's vec4 multiply-add rate in a fragment\n"
    "                         program against the rate the intersection programs\n"
    "                         achieve on SCENE (FLOPs counted from their IR for\n"
    "                         the iterations each pixel ran, over the GPU time\n"
    "                         of the hull draws): one line\n"
    "                           peak gflops=G achieved_gflops=A fraction=F ...\n"
    "  --update               every control point of every surface moved before\n"
    "                         each frame (the chart's deforming wave) through\n"
    "                         sc_update_surface: one line\n"
    "                           bench variant=update surfaces=S hulls=H update_ms=U\n"
    "                                 update_us_per_hull=X frame_ms=F still_frame_ms=S\n"
    "                                 image_ms=I uploaded_bytes_per_frame=B gpu_bytes=G\n"
    "                                 uploaded_fraction=R qhull_hulls_per_frame=Q\n"
    "                         (update_ms: the updates of one frame; frame_ms: the\n"
    "                         frame drawn after them; still_frame_ms: a frame of\n"
    "                         unchanged data; qhull_hulls_per_frame: hulls of\n"
    "                         flat pieces, which the small hull leaves to qhull;\n"
    "                         medians of the frames)\n";

/* A bumpy Bézier patch of degree d × d over [-1, 1]², heights from a fixed
 * pseudo-random sequence, so that Newton has work at every degree: a .bpt
 * file in memory, points u fastest, written with 17 digits so that they
 * are read back exactly. */
static int bumpy_patch(int d, sc_scene_id *scene, sc_error *err)
{
    size_t size = 64 + (size_t)(d + 1) * (size_t)(d + 1) * 80;
    char *text = malloc(size);
    if (!text) {
        snprintf(err->message, sizeof err->message, "out of memory");
        return SC_FAIL;
    }
    int len = snprintf(text, size, "1\n%d %d\n", d, d);
    unsigned state = 12345u + (unsigned)d;
    for (int j = 0; j <= d; j++)
        for (int i = 0; i <= d; i++) {
            state = state * 1103515245u + 12345u;
            len += snprintf(text + len, size - (size_t)len, "%.17g %.17g %.17g\n",
                            -1 + 2.0 * i / d, -1 + 2.0 * j / d,
                            0.3 * ((state >> 16) % 1000) / 1000.0);
        }
    sc_scene_desc desc = {.text = text, .size = (size_t)len, .name = "bumpy.bpt"};
    int status = sc_make_scene(&desc, scene, err);
    free(text);
    return status;
}

static int bench_degrees(sc_context_id ctx, sc_renderer_desc desc, int lo, int hi, int width,
                         int height, int frames)
{
    bench_result lowest = {0};
    for (int d = lo; d <= hi; d++) {
        sc_scene_id scene;
        sc_error err = {0};
        if (bumpy_patch(d, &scene, &err) != SC_OK)
            return cli_report(&err);
        sc_camera_desc cam = {.eye = {0, -0.001, 3.2}, .target = {0, 0, 0.15}, .fovy_deg = 36,
                              .width = width, .height = height};
        bench_result unrolled, generic;
        char extra[32];
        snprintf(extra, sizeof extra, " degree=%dx%d", d, d);
        desc.generic = 0;
        /* Above the unrolling limit the runtime itself picks the generic
         * program; the sweep wants the unrolled one at every degree. */
        desc.unroll_max_degree = SC_MAX_DEGREE;
        int status = bench_run(ctx, scene, &desc, &cam, frames, &unrolled, &err);
        if (status == SC_OK) {
            bench_print("unrolled", extra, &unrolled);
            desc.generic = 1;
            status = bench_run(ctx, scene, &desc, &cam, frames, &generic, &err);
        }
        sc_destroy_scene(scene);
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

/* Several scenes side by side, with the specialized programs alone (the
 * generic comparison is the one-scene mode's): each read and its renderer
 * made in turn (its `bench scene=` line: the peak memory is the process's
 * so far, which the earlier scenes' renderers are part of), then every
 * timed frame draws each scene in turn, so that the load of a shared
 * machine falls on all alike; then each one's `bench variant=specialized`
 * line and its covered-pixel rate against the first's, the cost per
 * covered pixel of a large scene set against a small one's. */
enum { BENCH_MAX_SCENES = 32 };

static int bench_scenes(sc_context_id ctx, const char *const *paths, int count,
                        sc_renderer_desc desc, const sc_camera_desc *cam, int frames)
{
    sc_error err = {0};
    sc_scene_id scenes[BENCH_MAX_SCENES] = {{0}};
    sc_renderer_id r[BENCH_MAX_SCENES] = {{0}};
    double warm_up[BENCH_MAX_SCENES] = {0}, mpix_s[BENCH_MAX_SCENES] = {0};
    double *times = calloc((size_t)(count * frames), sizeof *times);
    int status = SC_OK;
    /* Each renderer compiles its own programs, as a fresh process would. */
    desc.own_programs = 1;
    for (int i = 0; i < count && status == SC_OK; i++) {
        double t0 = sc_now();
        status = sc_make_scene(&(sc_scene_desc){.path = paths[i]}, &scenes[i], &err);
        double read_ms = 1e3 * (sc_now() - t0);
        bench_result made = {0};
        t0 = sc_now();
        if (status == SC_OK)
            status = sc_make_renderer(ctx, scenes[i], &desc, &r[i], &err);
        made.prepare_ms = 1e3 * (sc_now() - t0);
        if (status == SC_OK)
            status = sc_query_renderer_info(r[i], &made.stats, &err);
        if (status == SC_OK)
            bench_print_scene(paths[i], read_ms, &made);
        t0 = sc_now();
        if (status == SC_OK)
            status = sc_draw(r[i], cam, &err);
        warm_up[i] = 1e3 * (sc_now() - t0);
    }
    for (int f = 0; f < frames && status == SC_OK; f++)
        for (int i = 0; i < count && status == SC_OK; i++) {
            double t0 = sc_now();
            status = sc_draw(r[i], cam, &err);
            times[i * frames + f] = 1e3 * (sc_now() - t0);
        }
    for (int i = 0; i < count && status == SC_OK; i++) {
        bench_result res = {0};
        status = bench_finish(r[i], times + i * frames, frames, warm_up[i], &res, &err);
        if (status != SC_OK)
            break;
        bench_print("specialized", "", &res);
        mpix_s[i] = res.mpix_s;
    }
    for (int i = 1; i < count && status == SC_OK; i++)
        printf("bench scene=%s mpix_s_ratio_first_over_this=%.2f\n", paths[i],
               mpix_s[i] > 0 ? mpix_s[0] / mpix_s[i] : 0.0);
    for (int i = 0; i < count; i++) {
        sc_destroy_renderer(r[i]);
        sc_destroy_scene(scenes[i]);
    }
    free(times);
    return status == SC_OK ? 0 : cli_report(&err);
}

int cmd_bench(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--trim-table"))
            return bench_trim_table(argc, argv);
        if (!strcmp(argv[i], "--stability"))
            return bench_stability(argc, argv);
        if (!strcmp(argv[i], "--chart"))
            return bench_chart(argc, argv);
    }
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *scene_path = "teapot", *camera_arg = NULL;
    sc_context_desc ctx_desc = {0};
    sc_renderer_desc desc = {0};
    int width = 1024, height = 1024, frames = 5, deg_lo = 0, deg_hi = 0, status = 0;
    sc_error err = {0};
    bench_sweep sweep = {0};
    int methods[BENCH_MAX_SIDES], evals[BENCH_MAX_SIDES];
    int nmethods = 0, nevals = 0;
    double target_px[BENCH_MAX_TARGETS], target_deg[BENCH_MAX_TARGETS];
    int ntargets = 0, peak = 0, colour_only = 0, update = 0;
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
            if (end == argv[i] || *end || n < 1 || n > SC_MAX_ITERS)
                return cli_usage_error("bench", "--iters takes 1 to %d, not '%s'",
                                       SC_MAX_ITERS, argv[i]);
            desc.max_iters = (int)n;
        } else if (!strcmp(a, "--hull") && next) {
            if (cli_hulls_parse(argv[++i], &desc.hull_split, &desc.hull_divisions,
                                &desc.hull_tolerance, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--init") && next) {
            if (cli_start_parse(argv[++i], &desc.start, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--method") && next) {
            if ((status = bench_sides_parse(BENCH_SIDE_METHOD, argv[++i], methods,
                                            &nmethods)) != 0)
                return status;
            desc.method = (sc_method)methods[0];
        } else if (!strcmp(a, "--eval") && next) {
            if ((status = bench_sides_parse(BENCH_SIDE_EVAL, argv[++i], evals, &nevals)) != 0)
                return status;
            desc.eval = (sc_eval)evals[0];
        } else if (!strcmp(a, "--accuracy") && next) {
            if (ntargets == BENCH_MAX_TARGETS)
                return cli_usage_error("bench", "at most %d accuracy targets", BENCH_MAX_TARGETS);
            if (cli_accuracy_parse(argv[++i], &target_px[ntargets], &target_deg[ntargets],
                                   &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
            ntargets++;
        } else if (!strcmp(a, "--frames") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000)
                return cli_usage_error("bench", "--frames takes 1 to 1000, not '%s'", argv[i]);
            frames = (int)n;
        } else if (!strcmp(a, "--degrees") && next) {
            i++;
            if (sscanf(argv[i], "%d-%d", &deg_lo, &deg_hi) != 2 || deg_lo < 1 ||
                deg_hi < deg_lo || deg_hi > SC_MAX_DEGREE)
                return cli_usage_error("bench", "--degrees takes LO-HI within 1-%d, not '%s'",
                                       SC_MAX_DEGREE, argv[i]);
        } else if (!strcmp(a, "--colour-only")) {
            colour_only = 1;
        } else if (!strcmp(a, "--peak")) {
            peak = 1;
        } else if (!strcmp(a, "--update")) {
            update = 1;
        } else if (!strcmp(a, "--threads") && next) {
            if (cli_threads_parse(argv[++i], &desc.threads, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--lists-below") && next) {
            if (cli_list_below_parse(argv[++i], &desc.list_below_px, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
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
    if (nmethods > 1 && nevals > 1)
        return cli_usage_error("bench", "--method and --eval compare one at a time: give "
                                        "one of them a single name");
    if (sweep.nscenes > 1 && (peak || ntargets || nmethods > 1 || nevals > 1 || deg_lo))
        return cli_usage_error("bench", "several scenes go with --ert, --order, --batch or "
                                        "none of the other modes");
    sc_context_id ctx;
    sc_context_info ctx_info;
    if (sc_make_context(&ctx_desc, &ctx, &err) != SC_OK ||
        sc_query_context_info(ctx, &ctx_info, &err) != SC_OK) {
        sc_destroy_context(ctx);
        return cli_report(&err);
    }
    fprintf(stderr, "bench: %s\n", ctx_info.description);
    if (sweeping) {
        if (!sweep.nscenes)
            sweep.scenes[sweep.nscenes++] = scene_path;
        status = bench_sweep_run(ctx, &sweep, desc, camera_arg, width, height, frames);
        sc_destroy_context(ctx);
        return status;
    }
    if (deg_lo) {
        status = bench_degrees(ctx, desc, deg_lo, deg_hi, width, height, frames);
        sc_destroy_context(ctx);
        return status;
    }
    sc_camera_desc cam = {.width = width, .height = height, .text = camera_arg};
    if (camera_arg && sc_check_camera(&cam, &err) != SC_OK) {
        sc_destroy_context(ctx);
        return cli_usage_error("bench", "--camera: %s", err.message);
    }
    if (sweep.nscenes > 1) {
        status = bench_scenes(ctx, sweep.scenes, sweep.nscenes, desc, &cam, frames);
        sc_destroy_context(ctx);
        return status;
    }
    sc_scene_id scene;
    double t_read = sc_now();
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err) != SC_OK) {
        sc_destroy_context(ctx);
        return cli_report(&err);
    }
    double read_ms = 1e3 * (sc_now() - t_read);
    status = 0;
    if (peak) {
        status = bench_peak_run(ctx, scene, desc, &cam, frames);
    } else if (update) {
        status = bench_update_run(ctx, scene, desc, &cam, frames);
    } else if (ntargets) {
        status = bench_accuracy_run(ctx, scene, desc, &cam, frames, target_px, target_deg,
                                    ntargets);
    } else if (nmethods > 1) {
        status = bench_sides_run(ctx, scene, desc, &cam, frames, BENCH_SIDE_METHOD, methods,
                                 nmethods);
    } else if (nevals > 1) {
        status = bench_sides_run(ctx, scene, desc, &cam, frames, BENCH_SIDE_EVAL, evals, nevals);
    } else {
        bench_result specialized, generic;
        if (bench_run(ctx, scene, &desc, &cam, frames, &specialized, &err) != SC_OK) {
            status = cli_report(&err);
        } else {
            bench_print("specialized", "", &specialized);
            bench_print_scene(scene_path, read_ms, &specialized);
            bench_result always;
            sc_renderer_desc adesc = desc;
            adesc.aovs = SC_AOVS_ALWAYS;
            if (colour_only && bench_run(ctx, scene, &adesc, &cam, frames, &always, &err) != SC_OK)
                return cli_report(&err);
            if (colour_only) {
                bench_print("aovs-always", "", &always);
                printf("bench frame_ratio_colour_only_over_aovs_always=%.3f\n",
                       specialized.frame_ms / always.frame_ms);
            }
            desc.generic = 1;
            if (bench_run(ctx, scene, &desc, &cam, frames, &generic, &err) != SC_OK) {
                status = cli_report(&err);
            } else {
                bench_print("generic", "", &generic);
                printf("bench frame_ratio_generic_over_specialized=%.2f\n",
                       generic.frame_ms / specialized.frame_ms);
            }
        }
    }
    sc_destroy_scene(scene);
    sc_destroy_context(ctx);
    return status;
}
