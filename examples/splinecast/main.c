/* main.c — `splinecast COMMAND ...`: finds the subcommand in one table and
 * runs it. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"

static const command commands[] = {
    {"info", cmd_info, "what a scene holds and which variant keys it needs"},
    {"eval", cmd_eval, "evaluate a surface point, partials and normal"},
    {"convert", cmd_convert, "read a scene and write it as Wavefront OBJ"},
    {"ref", cmd_ref, "CPU reference image (PNG + AOV) in double precision"},
    {"diff", cmd_diff, "accuracy of one AOV image against a reference"},
    {"gen", cmd_gen, "generate and validate the GLSL of variant keys or a scene"},
    {"audit", cmd_audit, "size, SPIR-V, register and fetch counts per shader; compare"},
    {"render", cmd_render, "ray cast a scene on the GPU: PNG + AOV, stats, accuracy"},
    {"bench", cmd_bench, "speed of the GPU path: frame time, fill rate, iterations"},
    {"terrain", cmd_terrain, "ray cast the quartic spline of a height grid on the GPU"},
    {"splines", cmd_splines, "the quartic spline of a height grid; Table I error"},
    {"pick", cmd_pick, "the surface, (u, v), point and normal under an image point"},
    {"pack", cmd_pack, "write a scene's GPU data (records, trims, hulls, keys) to one file"},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: splinecast COMMAND [options]   (splinecast COMMAND --help)\n\n"
               "Ray casts trimmed NURBS and spline surfaces on the GPU.\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(f, "  %-9s %s\n", commands[i].name, commands[i].summary);
    fprintf(f, "\n  --version  print the version\n");
    fprintf(f, "\nA SCENE is a .bpt, .obj, .igs/.iges or .stp/.step file, or `teapot` for the "
               "embedded 32-patch teapot.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version")) {
        printf("splinecast %s\n", SPLINECAST_VERSION);
        return 0;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name))
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "splinecast: unknown command '%s'\n\n", argv[1]);
    usage(stderr);
    return 2;
}
