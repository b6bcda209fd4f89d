/* cmd_convert.c — `splinecast convert SCENE -o OUT.obj`: any scene the
 * readers take, written as Wavefront OBJ free-form surfaces with a .mtl of
 * its colours beside it. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast convert SCENE -o OUT.obj\n"
    "\n"
    "Reads SCENE (.bpt, .obj, .igs/.iges, .stp/.step, or `teapot`) and writes OUT.obj\n"
    "(rational B-spline surfaces, trim loops as curv2 + trim/hole, transforms\n"
    "baked in) and OUT.mtl (one material per colour). Prints:\n"
    "  surfaces N\n"
    "  wrote OUT.obj\n"
    "  wrote OUT.mtl\n";

int cmd_convert(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *scene_path = NULL, *out = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-o") && i + 1 < argc)
            out = argv[++i];
        else if (argv[i][0] != '-' && !scene_path)
            scene_path = argv[i];
        else
            return cli_usage_error("convert", "unexpected argument '%s'", argv[i]);
    }
    if (!scene_path || !out)
        return cli_usage_error("convert", "needs SCENE and -o OUT.obj");
    size_t len = strlen(out);
    if (len < 5 || strcmp(out + len - 4, ".obj"))
        return cli_usage_error("convert", "the output name must end in .obj, not '%s'", out);
    sc_scene_id scene;
    sc_scene_info info;
    sc_error err;
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err) != SC_OK)
        return cli_report(&err);
    int failed = sc_query_scene_info(scene, &info, &err) != SC_OK ||
                 sc_save_obj(scene, out, &err) != SC_OK;
    sc_destroy_scene(scene);
    if (failed)
        return cli_report(&err);
    printf("surfaces %d\nwrote %s\nwrote %.*s.mtl\n", info.surfaces, out, (int)(len - 4), out);
    return 0;
}
