/* cmd_render.c — `splinecast render SCENE -o out.png`: ray casts the scene
 * on the GPU (EGL or OSMesa) with the generated programs, writes the image
 * and its AOV file, prints one `stats` line and, with --ref, the accuracy
 * against the CPU reference for the same view. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast render SCENE -o OUT.png [options]\n"
    "\n"
    "Ray casts SCENE on the GPU and writes OUT.png and its AOVs (OUT.aov: surface\n"
    "id, (u, v), distance, point, normal and Newton iterations per pixel).\n"
    "\n"
    "options:\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n"
    "  --size WxH             image size (default 512x512)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOVY   eye, target, vertical field of view in\n"
    "                         degrees (default: framing the scene)\n"
    "  --iters N              Newton iterations at most (default 6)\n"
    "  --tol PX               Newton tolerance in pixel footprints (default 0.05)\n"
    "  --hull uniform:N|adaptive:TOL   proxy hulls: N x N per Bezier patch, or\n"
    "                         split until flat within TOL x the scene's size\n"
    "                         (default adaptive:0.003)\n"
    "  --init mid|cpmap|view  Newton start: the sub-patch's middle, the\n"
    "                         control-point parameters interpolated over the hull\n"
    "                         (default cpmap), or a Newton solve of the ray\n"
    "                         through each hull vertex, interpolated (view)\n"
    "  --method newton|broyden|bclip|subdiv|hybrid   intersection method\n"
    "                         (default hybrid; with subdiv, --iters is the\n"
    "                         stack depth, default 24; with bclip, the\n"
    "                         clipping steps, default 32)\n"
    "  --view shade|uv|iters|normal|depth|hull\n"
    "                         what the PNG shows (default shade); hull: each\n"
    "                         proxy hull in its own colour, dim where its ray\n"
    "                         misses the surface\n"
    "  --trim clip|left|fast[:ITERS]   trim method of trimmed surfaces and its cap\n"
    "                         on clipping iterations per crossing (default fast:16)\n"
    "  --ert none|conservative|manual|manual-both   early ray termination\n"
    "                         (default manual)\n"
    "  --order front-to-back|by-program|hybrid   draw order (default hybrid)\n"
    "  --batch N              hulls per batch, each seeing the hits of those\n"
    "                         before it (manual early ray termination), and per\n"
    "                         hybrid bucket\n"
    "                         (default 32)\n"
    "  --frames N             frames timed after a warm-up frame (default 5)\n"
    "  --ref                  also render the CPU reference and print its accuracy\n"
    "\n"
    "stdout: stats programs=N hulls=N triangles=N gpu_bytes=N compile_ms=T frame_ms=T\n"
    "        draw_calls=N program_switches=N culled_hulls=N readbacks=N\n"
    "        (frame_ms: median of the timed frames; compile_ms: generating,\n"
    "        validating, compiling and linking the programs, plus the warm-up\n"
    "        frame's excess over the median, where llvmpipe finishes compiling)\n"
    "        and with --ref: accuracy coverage_pct=... fail_pct=... (see diff)\n"
    "        then program KEY for each program compiled, in order of first use\n";

static int parse_size(const char *text, int *w, int *h)
{
    char *end;
    long a = strtol(text, &end, 10);
    if (end == text || (*end != 'x' && *end != 'X'))
        return 0;
    const char *second = end + 1;
    long b = strtol(second, &end, 10);
    if (end == second || *end || a < 1 || b < 1 || a > 16384 || b > 16384)
        return 0;
    *w = (int)a;
    *h = (int)b;
    return 1;
}

int cmd_render(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *scene_path = NULL, *out_path = NULL, *camera_arg = NULL;
    sc_context_desc ctx_desc = {0};
    sc_renderer_desc desc = {0};
    int width = 512, height = 512, frames = 5, with_ref = 0;
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-o") && next) {
            out_path = argv[++i];
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &ctx_desc.backend, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--size") && next) {
            if (!parse_size(argv[++i], &width, &height))
                return cli_usage_error("render", "--size takes WxH (e.g. 256x256), not '%s'",
                                       argv[i]);
        } else if (!strcmp(a, "--camera") && next) {
            camera_arg = argv[++i];
        } else if (!strcmp(a, "--iters") && next) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > SC_MAX_ITERS)
                return cli_usage_error("render", "--iters takes 1 to %d, not '%s'",
                                       SC_MAX_ITERS, argv[i]);
            desc.max_iters = (int)n;
        } else if (!strcmp(a, "--tol") && next) {
            char *end;
            double tol = strtod(argv[++i], &end);
            if (end == argv[i] || *end || !(tol >= 0.001) || !(tol <= 100))
                return cli_usage_error("render", "--tol takes 0.001 to 100 pixels, not '%s'",
                                       argv[i]);
            desc.tolerance_px = tol;
        } else if (!strcmp(a, "--hull") && next) {
            if (cli_hulls_parse(argv[++i], &desc.hull_split, &desc.hull_divisions,
                                &desc.hull_tolerance, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--init") && next) {
            if (cli_start_parse(argv[++i], &desc.start, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--method") && next) {
            if (cli_method_parse(argv[++i], &desc.method, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--trim") && next) {
            if (cli_trim_parse(argv[++i], &desc.trim, &desc.trim_iters, &err) !=
                SC_OK)
                return cli_usage_error("render", "--trim: %s", err.message);
        } else if (!strcmp(a, "--ert") && next) {
            if (cli_termination_parse(argv[++i], &desc.termination, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--order") && next) {
            if (cli_order_parse(argv[++i], &desc.order, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--batch") && next) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000000)
                return cli_usage_error("render", "--batch takes 1 to 1000000 hulls, not '%s'",
                                       argv[i]);
            desc.batch_hulls = (int)n;
        } else if (!strcmp(a, "--view") && next) {
            if (cli_show_parse(argv[++i], &desc.show, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--frames") && next) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000)
                return cli_usage_error("render", "--frames takes 1 to 1000, not '%s'", argv[i]);
            frames = (int)n;
        } else if (!strcmp(a, "--ref")) {
            with_ref = 1;
        } else if (a[0] != '-' && !scene_path) {
            scene_path = a;
        } else {
            return cli_usage_error("render", "unexpected argument '%s'", a);
        }
    }
    if (!scene_path || !out_path)
        return cli_usage_error("render", "needs SCENE and -o OUT.png");

    sc_camera_desc view = {.width = width, .height = height, .text = camera_arg};
    sc_scene_id scene;
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err) != SC_OK)
        return cli_report(&err);
    if (camera_arg && sc_check_camera(&view, &err) != SC_OK) {
        sc_destroy_scene(scene);
        return cli_usage_error("render", "--camera: %s", err.message);
    }

    int status = 1;
    sc_context_id ctx = {0};
    sc_renderer_id renderer;
    sc_context_info ctx_info;
    sc_renderer_info stats;
    sc_frame_id frame = {0}, ref = {0};
    sc_frame_info ref_info;
    sc_comparison acc;
    double *times = calloc((size_t)frames, sizeof(double));
    char aov_path[1024];
    cli_aov_path(out_path, aov_path, sizeof aov_path);
    if (sc_make_context(&ctx_desc, &ctx, &err) != SC_OK ||
        sc_query_context_info(ctx, &ctx_info, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    fprintf(stderr, "render: %s\n", ctx_info.description);
    if (sc_make_renderer(ctx, scene, &desc, &renderer, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    double t0 = sc_now();
    if (sc_draw(renderer, &view, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    double warm_up = 1e3 * (sc_now() - t0);
    for (int f = 0; f < frames; f++) {
        t0 = sc_now();
        if (sc_draw(renderer, &view, &err) != SC_OK) {
            cli_report(&err);
            goto done;
        }
        times[f] = 1e3 * (sc_now() - t0);
    }
    double frame_ms = cli_median(times, frames);
    if (sc_read_frame(renderer, &frame, &err) != SC_OK ||
        sc_save_aov(frame, aov_path, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    if (sc_save_png(frame, out_path, &err) != SC_OK) {
        remove(aov_path);
        cli_report(&err);
        goto done;
    }
    if (sc_query_renderer_info(renderer, &stats, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    double compile_ms = stats.compile_ms + (warm_up > frame_ms ? warm_up - frame_ms : 0);
    printf("stats programs=%d hulls=%d triangles=%d gpu_bytes=%zu compile_ms=%.1f "
           "frame_ms=%.2f draw_calls=%d program_switches=%d culled_hulls=%d readbacks=%d\n",
           stats.programs, stats.hulls, stats.triangles, stats.gpu_bytes, compile_ms, frame_ms,
           stats.draw_calls, stats.program_switches, stats.culled_hulls, stats.readbacks);
    fflush(stdout);
    if (with_ref) {
        if (sc_render_reference(scene, &view, NULL, &ref, &err) != SC_OK ||
            sc_query_frame_info(ref, &ref_info, &err) != SC_OK) {
            cli_report(&err);
            goto done;
        }
        fprintf(stderr, "render: reference in %.2f s\n", ref_info.reference.seconds);
        if (sc_compare_frames(ref, frame, &acc, &err) != SC_OK) {
            cli_report(&err);
            goto done;
        }
        printf("%s\n", acc.line);
    }
    /* The programs last, so that the lines above keep their places. The
     * context is fresh, so every key the renderer draws with was compiled
     * for it. */
    {
        int nkeys = 0;
        if (sc_query_renderer_keys(renderer, NULL, 0, &nkeys, &err) != SC_OK) {
            cli_report(&err);
            goto done;
        }
        sc_key *keys = calloc((size_t)(nkeys ? nkeys : 1), sizeof *keys);
        if (!keys || sc_query_renderer_keys(renderer, keys, nkeys, &nkeys, &err) != SC_OK) {
            free(keys);
            cli_report(&err);
            goto done;
        }
        for (int k = 0; k < nkeys; k++)
            printf("program %s\n", keys[k].text);
        free(keys);
    }
    status = 0;
done:
    free(times);
    sc_destroy_frame(frame);
    sc_destroy_frame(ref);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    return status;
}
