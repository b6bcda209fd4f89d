/* cmd_info.c — `splinecast info SCENE`: what a scene holds, one line per
 * surface (degrees, rational, control net, trim loops and their curves),
 * what the reader skipped, loops dropped by validation, the world-space
 * bounding box of the control points and the variant keys of the surfaces
 * the GPU programs can draw. Any scene a reader accepts is described. */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "io.h"
#include "scene_keys.h"

static const char usage[] =
    "usage: splinecast info SCENE\n"
    "\n"
    "Reads SCENE (.bpt, .obj, .igs/.iges, or `teapot`) and prints:\n"
    "  surfaces N\n"
    "  surface I deg P Q rational 0|1 ctrl NU NV loops L segments S   (one per surface;\n"
    "                             S counts the trim curves over all L loops)\n"
    "  skipped TYPE N REASON      (what the reader did not turn into surfaces)\n"
    "  dropped_loops N            (when trim loops were dropped by validation)\n"
    "  bbox X0 Y0 Z0 X1 Y1 Z1     (world space, of the control points)\n"
    "  key K                      (each distinct variant key the scene needs, sorted)\n"
    "A surface the GPU programs cannot draw (a degree above 16) gets no key: a\n"
    "warning on stderr names it and says why, and info still succeeds (`render`\n"
    "refuses such a scene; `ref` and `eval` take it).\n";

int cmd_info(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    if (argc != 2 || argv[1][0] == '-')
        return cli_usage_error("info", "expected one SCENE argument");
    sc_scene scene;
    sc_error err;
    if (sc_read_scene(argv[1], &scene, &err))
        return cli_report(&err);
    printf("surfaces %d\n", scene.nsurfaces);
    for (int i = 0; i < scene.nsurfaces; i++) {
        const sc_surface *s = &scene.surfaces[i];
        int segments = 0;
        for (int l = 0; l < s->nloops; l++)
            segments += s->loops[l].ncurves;
        printf("surface %d deg %d %d rational %d ctrl %d %d loops %d segments %d\n", i, s->deg_u,
               s->deg_v, s->rational, s->nu, s->nv, s->nloops, segments);
    }
    for (int i = 0; i < scene.nskipped; i++)
        printf("skipped %s %d %s\n", scene.skipped[i].type, scene.skipped[i].count,
               scene.skipped[i].reason);
    if (scene.dropped_loops)
        printf("dropped_loops %d\n", scene.dropped_loops);
    double lo[3], hi[3];
    sc_scene_bounds(&scene, lo, hi);
    printf("bbox %.17g %.17g %.17g %.17g %.17g %.17g\n", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
    char(*keys)[SCG_KEY_MAX] = NULL;
    int nkeys = 0;
    sc_key_options opts = {.skip_undrawable = 1};
    int status = sc_scene_keys(&scene, &opts, &keys, &nkeys, &err);
    for (int k = 0; k < nkeys; k++)
        printf("key %s\n", keys[k]);
    free(keys);
    sc_scene_free(&scene);
    return status ? cli_report(&err) : 0;
}
