/* cmd_ref.c — `splinecast ref SCENE -o out.png`: the CPU reference image
 * of a scene (sc_render_reference), written as a shaded PNG and as the AOV file
 * beside it that `diff` compares against. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"
#include "view_options.h"

static const char usage[] =
    "usage: splinecast ref SCENE -o OUT.png [view options] [--threads N] [--stats]\n"
    "\n"
    "Ray casts SCENE (.bpt, .obj, .igs/.iges, .stp/.step, or `teapot`) on the CPU in double\n"
    "precision (object-space subdivision to floating-point precision, exact trimming)\n"
    "and writes a shaded PNG to OUT.png and the AOV file (surface id, u v, distance,\n"
    "point, normal facing the viewer) beside it, which `diff` reads: the extension\n"
    "of OUT is replaced by .aov (out.png -> out.aov). Format: docs/aov-format.md.\n"
    "\n"
    "%s"
    "  --threads N            worker threads (default: one per online core)\n"
    "  --stats                also print rays per second\n"
    "\n"
    "stdout:\n"
    "  ref image=OUT.png aov=OUT.aov size=WxH camera=EX,...,FOVY hit_pixels=N\n"
    "  stats rays=N hits=N seconds=S rays_per_s=R subdivisions_per_ray=D over_budget=N threads=T\n"
    "        (--stats; over_budget counts rays whose search was cut short, normally 0)\n"
    "Progress goes to stderr for images above 256x256.\n";

static void print_progress(double fraction, void *user)
{
    double t0 = *(const double *)user;
    fprintf(stderr, "ref: %3.0f%% (%.1f s)\n", 100.0 * fraction, sc_now() - t0);
}

int cmd_ref(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        printf(usage, cli_view_usage);
        return 0;
    }
    const char *scene_path = NULL, *out_path = NULL;
    cli_view view_opts;
    cli_view_init(&view_opts);
    int threads = 0, want_stats = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int has_value = i + 1 < argc;
        int taken = cli_view_option("ref", argc, argv, &i, &view_opts);
        if (taken == 2)
            return 2;
        if (taken)
            continue;
        if (!strcmp(a, "-o") && has_value)
            out_path = argv[++i];
        else if (!strcmp(a, "--threads") && has_value) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (*end || n < 1 || n > 256)
                return cli_usage_error("ref", "--threads takes 1 to 256, not '%s'", argv[i]);
            threads = (int)n;
        } else if (!strcmp(a, "--stats"))
            want_stats = 1;
        else if (a[0] == '-' && a[1])
            return cli_usage_error("ref", "unexpected argument '%s'", a);
        else if (!scene_path)
            scene_path = a;
        else
            return cli_usage_error("ref", "unexpected argument '%s'", a);
    }
    if (!scene_path || !out_path)
        return cli_usage_error("ref", "needs SCENE and -o OUT.png");
    int bad = cli_check_png_name("ref", out_path);
    if (bad)
        return bad;
    char aov_path[1024];
    cli_aov_path(out_path, aov_path, sizeof aov_path);

    sc_error err = {0};
    sc_camera_desc view;
    if ((bad = cli_view_camera("ref", &view_opts, &view)) != 0)
        return bad;
    sc_scene_id scene;
    if (cli_open_drawable_scene("ref", scene_path, &scene))
        return 1;
    double t0 = sc_now();
    sc_reference_desc desc = {.threads = threads};
    if ((long)view.width * view.height > 256L * 256L) {
        desc.progress = print_progress;
        desc.progress_user = &t0;
    }
    sc_frame_id frame;
    sc_frame_info info;
    int status = sc_render_reference(scene, &view, &desc, &frame, &err);
    sc_destroy_scene(scene);
    if (status != SC_OK)
        return cli_report(&err);
    status = sc_save_aov(frame, aov_path, &err);
    if (status == SC_OK) {
        status = sc_save_png(frame, out_path, &err);
        if (status != SC_OK)
            remove(aov_path); /* the pair is written whole or not at all */
    }
    if (status == SC_OK)
        status = sc_query_frame_info(frame, &info, &err);
    sc_destroy_frame(frame);
    if (status != SC_OK)
        return cli_report(&err);
    const sc_reference_stats *stats = &info.reference;
    printf("ref image=%s aov=%s size=%dx%d camera=%s hit_pixels=%ld\n", out_path, aov_path,
           info.width, info.height, info.camera, stats->hits);
    if (want_stats)
        printf("stats rays=%ld hits=%ld seconds=%.3f rays_per_s=%.0f subdivisions_per_ray=%.1f "
               "over_budget=%ld threads=%d\n",
               stats->rays, stats->hits, stats->seconds,
               stats->seconds > 0 ? stats->rays / stats->seconds : 0.0,
               stats->rays ? (double)stats->subdivisions / stats->rays : 0.0, stats->over_budget,
               stats->threads);
    if (stats->over_budget)
        fprintf(stderr,
                "splinecast ref: warning: %ld rays spent their split budget; they keep the "
                "nearest hit found\n",
                stats->over_budget);
    return 0;
}
