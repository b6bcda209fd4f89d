/* cmd_info.c — `splinecast info SCENE`: what a scene holds, one line per
 * surface (degrees, rational, control net, trim loops and their curves),
 * what the reader skipped, loops dropped by validation, the world-space
 * bounding box of the control points and the variant keys of the surfaces
 * the GPU programs can draw. Any scene a reader accepts is described. */
#include <stdio.h>
#include <stdlib.h>

#include "commands.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast info SCENE\n"
    "\n"
    "Reads SCENE (.bpt, .obj, .igs/.iges, .stp/.step, or `teapot`) and prints:\n"
    "  surfaces N\n"
    "  surface I deg P Q rational 0|1 ctrl NU NV loops L segments S   (one per surface;\n"
    "                             S counts the trim curves over all L loops)\n"
    "  skipped TYPE N REASON      (what the reader did not turn into surfaces)\n"
    "  dropped_loops N            (when trim loops were dropped by validation)\n"
    "  projected_loops N max_dev D   (when trim loops given only in model space\n"
    "                             were projected into parameter space; D is the\n"
    "                             largest distance measured between such a loop\n"
    "                             on its surface and its 3D curves)\n"
    "  offset_surfaces N max_dev D   (when offset surfaces were fitted: D is the\n"
    "                             largest distance measured from the true offset)\n"
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
    sc_scene_id scene;
    sc_scene_info info;
    sc_error err;
    if (sc_make_scene(&(sc_scene_desc){.path = argv[1]}, &scene, &err) != SC_OK)
        return cli_report(&err);
    int status = sc_query_scene_info(scene, &info, &err);
    if (status == SC_OK)
        printf("surfaces %d\n", info.surfaces);
    for (int i = 0; i < info.surfaces && status == SC_OK; i++) {
        sc_surface_info s;
        status = sc_query_surface_info(scene, i, &s, &err);
        if (status == SC_OK)
            printf("surface %d deg %d %d rational %d ctrl %d %d loops %d segments %d\n", i,
                   s.deg_u, s.deg_v, s.rational, s.nu, s.nv, s.trim_loops, s.trim_curves);
    }
    for (int i = 0; i < info.skipped_kinds && status == SC_OK; i++) {
        sc_skipped_info k;
        status = sc_query_scene_skipped(scene, i, &k, &err);
        if (status == SC_OK)
            printf("skipped %s %d %s\n", k.type, k.count, k.reason);
    }
    if (status == SC_OK && info.dropped_loops)
        printf("dropped_loops %d\n", info.dropped_loops);
    if (status == SC_OK && info.projected_loops)
        printf("projected_loops %d max_dev %.6g\n", info.projected_loops, info.projection_dev);
    if (status == SC_OK && info.offset_surfaces)
        printf("offset_surfaces %d max_dev %.6g\n", info.offset_surfaces, info.offset_dev);
    if (status == SC_OK)
        printf("bbox %.17g %.17g %.17g %.17g %.17g %.17g\n", info.lo[0], info.lo[1], info.lo[2],
               info.hi[0], info.hi[1], info.hi[2]);
    sc_keys_desc keys_desc = {.skip_undrawable = 1};
    /* One call, so that the warning on an undrawable surface comes once:
     * a scene needs at most one key per surface. */
    int nkeys = 0, capacity = info.surfaces > 0 ? info.surfaces : 1;
    sc_key *keys = calloc((size_t)capacity, sizeof *keys);
    if (status == SC_OK)
        status = sc_query_scene_keys(scene, &keys_desc, keys, capacity, &nkeys, &err);
    for (int k = 0; k < nkeys && status == SC_OK; k++)
        printf("key %s\n", keys[k].text);
    free(keys);
    sc_destroy_scene(scene);
    return status != SC_OK ? cli_report(&err) : 0;
}
