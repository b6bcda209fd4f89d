/* cmd_terrain.c — `splinecast terrain (HEIGHTS|--franke N) -o OUT.png`: a
 * grid of heights becomes quartic triangular patches (seed 004), ray cast
 * on the GPU inside their prisms, drawn in Manhattan sets; writes the image
 * and its AOVs, one `stats` line and, with --ref, the accuracy against the
 * exact CPU reference. Uses the public API alone. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "splinecast.h"
#include "view_options.h"

static const char usage[] =
    "usage: splinecast terrain (HEIGHTS.pgm|HEIGHTS.csv|--franke N) -o OUT.png [options]\n"
    "\n"
    "Builds the quartic spline of a grid of heights (a PGM, 8 or 16 bits, or a CSV\n"
    "of rows; or Franke's function at N data points on [0,1]^2: 144, 576, 2304, ...)\n"
    "and ray casts its triangular patches on the GPU: OUT.png and OUT.aov.\n"
    "\n"
    "options:\n"
    "  --scheme c0|c1|c2|linear   the spline (default c2; docs/splines.md)\n"
    "  --spacing D            distance between samples of a height file (default:\n"
    "                         the grid spans 1 along its longer side)\n"
    "  --zscale Z             factor on a file's heights (default 1; a PGM's gray\n"
    "                         levels are divided by maxval first)\n"
    "  --size WxH             image size (default 512x512)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOVY   the view (default: framing the terrain)\n"
    "  --iters N              Newton iterations at most (default 6)\n"
    "  --tol PX               tolerance in pixel footprints (default 0.05)\n"
    "  --view shade|uv|iters|normal|depth|hull|reflect   what the PNG shows (default shade)\n"
    "  --ert none|conservative|manual|manual-both|peel   early ray termination\n"
    "                         (default manual)\n"
    "  --order front-to-back|by-program|hybrid   draw order instead of the\n"
    "                         Manhattan sets (default: the sets)\n"
    "  --frames N             frames timed after a warm-up frame (default 5)\n"
    "  --backend egl|osmesa   GL context\n"
    "  --ref                  also render the CPU reference and print its accuracy\n"
    "  --deferred             shade in a full-screen pass from the AOVs (the\n"
    "                         intersection programs write no colour)\n"
    "\n"
    "stdout: stats scheme=S patches=N programs=N hulls=N gpu_bytes=N compile_ms=T\n"
    "        frame_ms=T covered_px=N mpix_s=X draw_calls=N readbacks=N culled_hulls=N\n"
    "        (frame_ms: median draw time; mpix_s: covered pixels per second of it)\n"
    "        and with --ref: accuracy coverage_pct=... fail_pct=... (see diff)\n";

/* Draws a warm-up frame and `frames` timed ones (the draw alone, waited
 * for), then reads the last back into *last; gives the median draw time. */
static int timed_frames(sc_renderer_id r, const sc_camera_desc *cam, int frames,
                        sc_frame_id *last, double *median_ms, double *warm_ms, sc_error *err)
{
    double *times = calloc((size_t)frames, sizeof *times);
    int status = SC_OK;
    for (int f = -1; f < frames && status == SC_OK; f++) {
        double t0 = sc_now();
        status = sc_draw(r, cam, err);
        double ms = 1e3 * (sc_now() - t0);
        if (f < 0)
            *warm_ms = ms;
        else
            times[f] = ms;
    }
    if (status == SC_OK) {
        *median_ms = cli_median(times, frames);
        status = sc_read_frame(r, last, err);
    }
    free(times);
    return status;
}

int cmd_terrain(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    sc_scene_desc sdesc = {0};
    sc_renderer_desc rdesc = {0};
    sc_context_desc cdesc = {0};
    sc_camera_desc cam = {.width = 512, .height = 512};
    const char *out_path = NULL;
    int frames = 5, with_ref = 0;
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        char *end = NULL;
        if (!strcmp(a, "-o") && next) {
            out_path = argv[++i];
        } else if (!strcmp(a, "--franke") && next) {
            sdesc.franke = (int)strtol(argv[++i], &end, 10);
            if (*end || sdesc.franke < 1)
                return cli_usage_error("terrain", "--franke takes N data points (144, 576, "
                                       "...), not '%s'", argv[i]);
        } else if (!strcmp(a, "--scheme") && next) {
            if (sc_parse_terrain_scheme(argv[++i], &sdesc.scheme, &err) != SC_OK)
                return cli_usage_error("terrain", "%s", err.message);
        } else if (!strcmp(a, "--spacing") && next) {
            sdesc.spacing = strtod(argv[++i], &end);
            if (*end || !(sdesc.spacing > 0))
                return cli_usage_error("terrain", "--spacing takes a positive distance, not "
                                       "'%s'", argv[i]);
        } else if (!strcmp(a, "--zscale") && next) {
            sdesc.height_scale = strtod(argv[++i], &end);
            if (*end || sdesc.height_scale == 0)
                return cli_usage_error("terrain", "--zscale takes a nonzero factor, not '%s'",
                                       argv[i]);
        } else if (!strcmp(a, "--size") && next) {
            char x;
            if (sscanf(argv[++i], "%d%c%d", &cam.width, &x, &cam.height) != 3 || x != 'x' ||
                cam.width < 1 || cam.height < 1 || cam.width > 16384 || cam.height > 16384)
                return cli_usage_error("terrain", "--size takes WxH (e.g. 512x512), not '%s'",
                                       argv[i]);
        } else if (!strcmp(a, "--camera") && next) {
            cam.text = argv[++i];
        } else if (!strcmp(a, "--iters") && next) {
            rdesc.max_iters = (int)strtol(argv[++i], &end, 10);
            if (*end || rdesc.max_iters < 1 || rdesc.max_iters > 64)
                return cli_usage_error("terrain", "--iters takes 1 to 64, not '%s'", argv[i]);
        } else if (!strcmp(a, "--tol") && next) {
            rdesc.tolerance_px = strtod(argv[++i], &end);
            if (*end || !(rdesc.tolerance_px >= 0.001) || !(rdesc.tolerance_px <= 100))
                return cli_usage_error("terrain", "--tol takes 0.001 to 100 pixels, not '%s'",
                                       argv[i]);
        } else if (!strcmp(a, "--view") && next) {
            if (cli_show_parse(argv[++i], &rdesc.show, &err) != SC_OK)
                return cli_usage_error("terrain", "%s", err.message);
        } else if (!strcmp(a, "--ert") && next) {
            if (cli_termination_parse(argv[++i], &rdesc.termination, &err) != SC_OK)
                return cli_usage_error("terrain", "%s", err.message);
        } else if (!strcmp(a, "--order") && next) {
            if (cli_order_parse(argv[++i], &rdesc.order, &err) != SC_OK)
                return cli_usage_error("terrain", "%s", err.message);
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &cdesc.backend, &err) != SC_OK)
                return cli_usage_error("terrain", "%s", err.message);
        } else if (!strcmp(a, "--frames") && next) {
            frames = (int)strtol(argv[++i], &end, 10);
            if (*end || frames < 1 || frames > 1000)
                return cli_usage_error("terrain", "--frames takes 1 to 1000, not '%s'", argv[i]);
        } else if (!strcmp(a, "--ref")) {
            with_ref = 1;
        } else if (!strcmp(a, "--deferred")) {
            rdesc.deferred = 1;
        } else if (a[0] != '-' && !sdesc.heights) {
            sdesc.heights = a;
        } else {
            return cli_usage_error("terrain", "unexpected argument '%s'", a);
        }
    }
    if (!(sdesc.heights || sdesc.franke) || (sdesc.heights && sdesc.franke) || !out_path)
        return cli_usage_error("terrain", "needs HEIGHTS or --franke N (one of them) and "
                               "-o OUT.png");
    if (cli_check_png_name("terrain", out_path))
        return 2;

    int status = 1;
    sc_scene_id scene = {0};
    sc_context_id ctx = {0};
    sc_renderer_id renderer = {0};
    sc_frame_id frame = {0}, ref = {0};
    if (sc_make_scene(&sdesc, &scene, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    sc_context_info cinfo;
    if (sc_make_context(&cdesc, &ctx, &err) != SC_OK ||
        sc_query_context_info(ctx, &cinfo, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    fprintf(stderr, "terrain: %s\n", cinfo.description);
    double frame_ms = 0, warm_ms = 0;
    sc_renderer_info rinfo;
    sc_scene_info sinfo;
    sc_frame_info finfo;
    if (sc_make_renderer(ctx, scene, &rdesc, &renderer, &err) != SC_OK ||
        timed_frames(renderer, &cam, frames, &frame, &frame_ms, &warm_ms, &err) != SC_OK ||
        sc_query_renderer_info(renderer, &rinfo, &err) != SC_OK ||
        sc_query_scene_info(scene, &sinfo, &err) != SC_OK ||
        sc_query_frame_info(frame, &finfo, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    char aov_path[1024];
    cli_aov_path(out_path, aov_path, sizeof aov_path);
    if (sc_save_aov(frame, aov_path, &err) != SC_OK || sc_save_png(frame, out_path, &err) != SC_OK) {
        remove(aov_path);
        cli_report(&err);
        goto done;
    }
    long covered = 0;
    for (long p = 0; p < (long)finfo.width * finfo.height; p++)
        covered += finfo.surface[p] >= 0;
    double compile_ms = rinfo.compile_ms + (warm_ms > frame_ms ? warm_ms - frame_ms : 0);
    printf("stats scheme=%s patches=%d programs=%d hulls=%d gpu_bytes=%zu compile_ms=%.1f "
           "frame_ms=%.2f covered_px=%ld mpix_s=%.2f draw_calls=%d readbacks=%d culled_hulls=%d\n",
           sc_terrain_scheme_name(sdesc.scheme), sinfo.terrain_patches, rinfo.programs,
           rinfo.hulls, rinfo.gpu_bytes, compile_ms, frame_ms, covered,
           frame_ms > 0 ? covered / (frame_ms * 1e3) : 0.0, rinfo.draw_calls, rinfo.readbacks,
           rinfo.culled_hulls);
    fflush(stdout);
    if (with_ref) {
        sc_comparison cmp;
        if (sc_render_reference(scene, &cam, NULL, &ref, &err) != SC_OK ||
            sc_compare_frames(ref, frame, &cmp, &err) != SC_OK) {
            cli_report(&err);
            goto done;
        }
        printf("%s\n", cmp.line);
    }
    status = 0;
done:
    sc_destroy_frame(ref);
    sc_destroy_frame(frame);
    sc_destroy_renderer(renderer);
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    return status;
}
