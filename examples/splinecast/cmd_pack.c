/* cmd_pack.c — `splinecast pack`: a scene's GPU data (patch records, trim
 * blocks, hull vertices and indices, each surface's key) written at build
 * time into one file (docs/pack-format.md), for a program that draws it
 * with sc_renderer_desc.pack and the programs of `splinecast gen`. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"
#include "options.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast pack SCENE -o FILE [options]\n"
    "\n"
    "Prepares SCENE as a renderer would (keys, Bezier patches, hulls, trim\n"
    "blocks) and writes the GPU data into FILE, a pack (docs/pack-format.md):\n"
    "a magic, a version, a checksum, then the records, trim blocks, hull\n"
    "vertices and indices and each surface's key. Needs no GL. FILE is\n"
    "written whole or not at all. stdout: `pack FILE bytes=N`.\n"
    "The programs a pack needs are the keys `splinecast gen --scene SCENE`\n"
    "writes with the same options (the defaults of both agree).\n"
    "  --iters N          Newton iterations (6)\n"
    "  --tol T            Newton tolerance in pixel footprints (0.05)\n"
    "  --hull MODE        uniform:N or adaptive:TOL (adaptive:0.003)\n"
    "  --init START       mid, cpmap (cpmap)\n"
    "  --method M         newton, bclip, subdiv, hybrid (hybrid)\n"
    "  --eval E           dc, bern, pow (pow up to degree 4, dc above)\n"
    "  --trim T[:N]       fast, clip, left; N clipping iterations (fast:16)\n"
    "  --ert MODE         none, conservative, manual, manual-both, peel (manual)\n"
    "  --view V           shade, uv, iters, normal, depth, hull (shade)\n"
    "\n";

int cmd_pack(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *scene_path = NULL, *out_path = NULL;
    sc_renderer_desc desc = {0};
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        int bad = 0;
        if (!strcmp(a, "-o") && next) {
            out_path = argv[++i];
        } else if (!strcmp(a, "--iters") && next) {
            char *end;
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > SC_MAX_ITERS)
                return cli_usage_error("pack", "--iters takes 1 to %d, not '%s'", SC_MAX_ITERS,
                                       argv[i]);
            desc.max_iters = (int)n;
        } else if (!strcmp(a, "--tol") && next) {
            char *end;
            double tol = strtod(argv[++i], &end);
            if (end == argv[i] || *end || !(tol >= 0.001) || !(tol <= 100))
                return cli_usage_error("pack", "--tol takes 0.001 to 100 pixels, not '%s'",
                                       argv[i]);
            desc.tolerance_px = tol;
        } else if (!strcmp(a, "--hull") && next) {
            bad = cli_hulls_parse(argv[++i], &desc.hull_split, &desc.hull_divisions,
                                  &desc.hull_tolerance, &err) != SC_OK;
        } else if (!strcmp(a, "--init") && next) {
            bad = cli_start_parse(argv[++i], &desc.start, &err) != SC_OK;
        } else if (!strcmp(a, "--method") && next) {
            bad = cli_method_parse(argv[++i], &desc.method, &err) != SC_OK;
        } else if (!strcmp(a, "--eval") && next) {
            bad = cli_eval_parse(argv[++i], &desc.eval, &err) != SC_OK;
        } else if (!strcmp(a, "--trim") && next) {
            bad = cli_trim_parse(argv[++i], &desc.trim, &desc.trim_iters, &err) != SC_OK;
        } else if (!strcmp(a, "--ert") && next) {
            bad = cli_termination_parse(argv[++i], &desc.termination, &err) != SC_OK;
        } else if (!strcmp(a, "--view") && next) {
            bad = cli_show_parse(argv[++i], &desc.show, &err) != SC_OK;
        } else if (a[0] != '-' && !scene_path) {
            scene_path = a;
        } else {
            return cli_usage_error("pack", "unexpected argument '%s'", a);
        }
        if (bad)
            return cli_usage_error("pack", "%s: %s", a, err.message);
    }
    if (!scene_path || !out_path)
        return cli_usage_error("pack", "needs SCENE and -o FILE");
    sc_scene_id scene;
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err) != SC_OK)
        return cli_report(&err);
    int status = sc_save_pack(scene, &desc, out_path, &err) != SC_OK ? cli_report(&err) : 0;
    sc_destroy_scene(scene);
    if (status == 0) {
        struct stat st;
        printf("pack %s bytes=%lld\n", out_path, stat(out_path, &st) == 0 ? (long long)st.st_size : -1LL);
    }
    return status;
}
