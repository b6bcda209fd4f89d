/* cmd_render.c — `splinecast render SCENE -o out.png`: ray casts the scene
 * on the GPU (EGL or OSMesa) with the generated programs, writes the image
 * (and with --aov its AOV file), prints one `stats` line and, with --ref,
 * the accuracy against the CPU reference for the same view. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "splinecast.h"
#include "view_options.h"

static const char usage[] =
    "usage: splinecast render SCENE -o OUT.png [options]\n"
    "\n"
    "Ray casts SCENE on the GPU and writes OUT.png; with --aov FILE also its AOVs\n"
    "(surface id, (u, v), distance, point, normal and iterations per pixel).\n"
    "\n"
    "options:\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n"
    "%s"
    "  --aov FILE             also write the AOV file (docs/aov-format.md)\n"
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
    "  --eval dc|bern|pow     how the unrolled Bezier programs evaluate the\n"
    "                         patch in the iteration (default: pow up to\n"
    "                         degree 4, dc above; pow stops at degree 6)\n"
    "  --view shade|uv|iters|normal|depth|hull|reflect\n"
    "                         what the PNG shows (default shade); hull: each\n"
    "                         proxy hull in its own colour, dim where its ray\n"
    "                         misses the surface\n"
    "  --trim clip|left|fast[:ITERS]   trim method of trimmed surfaces and its cap\n"
    "                         on clipping iterations per crossing (default fast:16)\n"
    "  --ert none|conservative|manual|manual-both|peel|lists   early ray\n"
    "                         termination (default manual)\n"
    "  --lists-below off|PX   in the manual modes, hulls at most PX pixels wide\n"
    "                         and high on screen go through candidate lists\n"
    "                         per pixel instead of being drawn (default 8)\n"
    "  --order front-to-back|by-program|hybrid   draw order (default hybrid)\n"
    "  --threads N            CPU threads of each frame's pass over the hulls\n"
    "                         (default: one per processor; at most 8 used)\n"
    "  --batch N              hulls per batch, each seeing the hits of those\n"
    "                         before it (manual early ray termination), the\n"
    "                         first of peel's doubling batches, and per hybrid\n"
    "                         bucket\n"
    "                         (default 32)\n"
    "  --accuracy PX[,DEG]    choose each surface's hulls, iterations and\n"
    "                         tolerance from a bound on the position error in\n"
    "                         pixel footprints (0.001 to 100), and optionally on\n"
    "                         the normal error in degrees, for this view; they\n"
    "                         replace --hull, --iters and --tol (docs/accuracy.md)\n"
    "  --frames N             frames timed after a warm-up frame (default 5)\n"
    "  --ref                  also render the CPU reference and print its accuracy\n"
    "                         (progress on stderr)\n"
    "\n"
    "stdout: stats programs=N hulls=N triangles=N gpu_bytes=N compile_ms=T frame_ms=T\n"
    "        draw_calls=N program_switches=N culled_hulls=N readbacks=N\n"
    "        intersections=N rays_per_covered_pixel=X peel_layers=N\n"
    "        (intersections: fragment programs that ran the intersection in the\n"
    "        last frame, counted on the GPU, over the pixels that hit a surface;\n"
    "        frame_ms: median of the timed frames; compile_ms: generating,\n"
    "        validating, compiling and linking the programs, plus the warm-up\n"
    "        frame's excess over the median, where llvmpipe finishes compiling)\n"
    "        and with --ref: accuracy coverage_pct=... fail_pct=... (see diff)\n"
    "        with --accuracy: chosen accuracy_px=X normal_deg=A surfaces=N hulls=N\n"
    "        iters_min=N iters_max=N tol_px_min=X tol_px_max=X hull_tol_min=X\n"
    "        hull_tol_max=X (and one line per surface on stderr)\n"
    "        then program KEY for each program compiled, in order of first use\n";

static void print_progress(double fraction, void *user)
{
    double t0 = *(const double *)user;
    fprintf(stderr, "render: reference %3.0f%% (%.1f s)\n", 100.0 * fraction, sc_now() - t0);
}

/* What an accuracy target chose: a line per surface on stderr, a summary
 * on stdout. */
static int print_choice(sc_scene_id scene, sc_renderer_id renderer, const sc_renderer_desc *desc,
                        sc_error *err)
{
    sc_scene_info info;
    if (sc_query_scene_info(scene, &info, err) != SC_OK)
        return SC_FAIL;
    int hulls = 0, iters_min = 0, iters_max = 0;
    double tol_min = 0, tol_max = 0, hull_min = 0, hull_max = 0;
    for (int s = 0; s < info.surfaces; s++) {
        sc_renderer_surface_info si;
        if (sc_query_renderer_surface(renderer, s, &si, err) != SC_OK)
            return SC_FAIL;
        fprintf(stderr, "render: surface %d: hull_tol=%.4g hulls=%d iters=%d tol_px=%g "
                "footprint=%.4g radius=%.4g\n", s, si.hull_tolerance, si.hulls, si.max_iters,
                si.tolerance_px, si.footprint, si.radius);
        hulls += si.hulls;
        if (s == 0 || si.max_iters < iters_min)
            iters_min = si.max_iters;
        if (s == 0 || si.max_iters > iters_max)
            iters_max = si.max_iters;
        if (s == 0 || si.tolerance_px < tol_min)
            tol_min = si.tolerance_px;
        if (s == 0 || si.tolerance_px > tol_max)
            tol_max = si.tolerance_px;
        if (s == 0 || si.hull_tolerance < hull_min)
            hull_min = si.hull_tolerance;
        if (s == 0 || si.hull_tolerance > hull_max)
            hull_max = si.hull_tolerance;
    }
    printf("chosen accuracy_px=%g normal_deg=%g surfaces=%d hulls=%d iters_min=%d iters_max=%d "
           "tol_px_min=%g tol_px_max=%g hull_tol_min=%.4g hull_tol_max=%.4g\n",
           desc->accuracy_px, desc->accuracy_normal_deg, info.surfaces, hulls, iters_min,
           iters_max, tol_min, tol_max, hull_min, hull_max);
    return SC_OK;
}

int cmd_render(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        printf(usage, cli_view_usage);
        return 0;
    }
    const char *scene_path = NULL, *out_path = NULL, *aov_path = NULL;
    cli_view view_opts;
    cli_view_init(&view_opts);
    sc_context_desc ctx_desc = {0};
    sc_renderer_desc desc = {0};
    int frames = 5, with_ref = 0;
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        int taken = cli_view_option("render", argc, argv, &i, &view_opts);
        if (taken == 2)
            return 2;
        if (taken) {
        } else if (!strcmp(a, "-o") && next) {
            out_path = argv[++i];
        } else if (!strcmp(a, "--aov") && next) {
            aov_path = argv[++i];
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &ctx_desc.backend, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
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
        } else if (!strcmp(a, "--eval") && next) {
            if (cli_eval_parse(argv[++i], &desc.eval, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--trim") && next) {
            if (cli_trim_parse(argv[++i], &desc.trim, &desc.trim_iters, &err) !=
                SC_OK)
                return cli_usage_error("render", "--trim: %s", err.message);
        } else if (!strcmp(a, "--ert") && next) {
            if (cli_termination_parse(argv[++i], &desc.termination, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--lists-below") && next) {
            if (cli_list_below_parse(argv[++i], &desc.list_below_px, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--order") && next) {
            if (cli_order_parse(argv[++i], &desc.order, &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
        } else if (!strcmp(a, "--threads") && next) {
            if (cli_threads_parse(argv[++i], &desc.threads, &err) != SC_OK)
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
        } else if (!strcmp(a, "--accuracy") && next) {
            if (cli_accuracy_parse(argv[++i], &desc.accuracy_px, &desc.accuracy_normal_deg,
                                   &err) != SC_OK)
                return cli_usage_error("render", "%s", err.message);
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
    sc_camera_desc view;
    int bad = cli_check_png_name("render", out_path);
    if (!bad)
        bad = cli_view_camera("render", &view_opts, &view);
    if (!bad && aov_path && !strcmp(aov_path, out_path))
        bad = cli_usage_error("render", "--aov and -o name the same file '%s'", out_path);
    if (bad)
        return bad;
    sc_scene_id scene;
    if (cli_open_drawable_scene("render", scene_path, &scene))
        return 1;

    int status = 1;
    sc_context_id ctx = {0};
    sc_renderer_id renderer;
    sc_context_info ctx_info;
    sc_renderer_info stats;
    sc_frame_id frame = {0}, ref = {0};
    sc_frame_info ref_info;
    sc_comparison acc;
    double *times = calloc((size_t)frames, sizeof(double));
    if (sc_make_context(&ctx_desc, &ctx, &err) != SC_OK ||
        sc_query_context_info(ctx, &ctx_info, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    fprintf(stderr, "render: %s\n", ctx_info.description);
    desc.accuracy_view = &view;
    /* Its frames are read back (images, AOVs, the stats line's covered
     * pixels): each timed frame writes the AOVs, and the last is read. */
    desc.aovs = SC_AOVS_ALWAYS;
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
        (aov_path && sc_save_aov(frame, aov_path, &err) != SC_OK)) {
        cli_report(&err);
        goto done;
    }
    if (sc_save_png(frame, out_path, &err) != SC_OK) {
        if (aov_path)
            remove(aov_path); /* the pair is written whole or not at all */
        cli_report(&err);
        goto done;
    }
    if (sc_query_renderer_info(renderer, &stats, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    sc_frame_info frame_info;
    if (sc_query_frame_info(frame, &frame_info, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    long covered = 0;
    for (long p = 0; p < (long)frame_info.width * frame_info.height; p++)
        covered += frame_info.surface[p] >= 0;
    double compile_ms = stats.compile_ms + (warm_up > frame_ms ? warm_up - frame_ms : 0);
    printf("stats programs=%d hulls=%d triangles=%d gpu_bytes=%zu compile_ms=%.1f "
           "frame_ms=%.2f draw_calls=%d program_switches=%d culled_hulls=%d readbacks=%d "
           "intersections=%lld rays_per_covered_pixel=%.3f peel_layers=%d\n",
           stats.programs, stats.hulls, stats.triangles, stats.gpu_bytes, compile_ms, frame_ms,
           stats.draw_calls, stats.program_switches, stats.culled_hulls, stats.readbacks,
           stats.intersections, covered ? (double)stats.intersections / (double)covered : 0.0,
           stats.peel_layers);
    fflush(stdout);
    if (with_ref) {
        double ref_t0 = sc_now();
        sc_reference_desc ref_desc = {.progress = print_progress, .progress_user = &ref_t0};
        if (sc_render_reference(scene, &view, &ref_desc, &ref, &err) != SC_OK ||
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
    if (desc.accuracy_px > 0 && print_choice(scene, renderer, &desc, &err) != SC_OK) {
        cli_report(&err);
        goto done;
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
