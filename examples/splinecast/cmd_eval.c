/* cmd_eval.c — `splinecast eval SCENE --surface I --uv U,V`: the point,
 * first partials and unit normal of one surface at one parameter pair, in
 * world space, printed with 17 significant digits so that scripts and
 * tests can compare them with values computed elsewhere. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast eval SCENE --surface I --uv U,V\n"
    "\n"
    "Evaluates surface I (0-based) of SCENE at (U, V), which must lie in the\n"
    "surface's own knot range, with the surface's transform applied. Prints:\n"
    "  point X Y Z\n"
    "  du X Y Z        (partial derivative in u)\n"
    "  dv X Y Z        (partial derivative in v)\n"
    "  normal X Y Z    (unit; the limit normal at collapsed edges)\n";

static int parse_uv(const char *text, double *u, double *v)
{
    char *end;
    *u = strtod(text, &end);
    if (end == text || *end != ',')
        return 0;
    const char *second = end + 1;
    *v = strtod(second, &end);
    return end != second && !*end && isfinite(*u) && isfinite(*v);
}

int cmd_eval(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *scene_path = NULL, *surface_arg = NULL, *uv_arg = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--surface") && i + 1 < argc)
            surface_arg = argv[++i];
        else if (!strcmp(argv[i], "--uv") && i + 1 < argc)
            uv_arg = argv[++i];
        else if (argv[i][0] != '-' && !scene_path)
            scene_path = argv[i];
        else
            return cli_usage_error("eval", "unexpected argument '%s'", argv[i]);
    }
    if (!scene_path || !surface_arg || !uv_arg)
        return cli_usage_error("eval", "needs SCENE, --surface I and --uv U,V");
    char *end;
    long index = strtol(surface_arg, &end, 10);
    if (end == surface_arg || *end || index < 0)
        return cli_usage_error("eval", "--surface takes a surface number (0, 1, ...), not '%s'",
                               surface_arg);
    double u, v;
    if (!parse_uv(uv_arg, &u, &v))
        return cli_usage_error("eval", "--uv takes two finite numbers U,V, not '%s'", uv_arg);

    sc_scene_id scene;
    sc_error err;
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err) != SC_OK)
        return cli_report(&err);
    int status = 1;
    sc_scene_info info;
    sc_surface_info s;
    sc_surface_point at;
    if (sc_query_scene_info(scene, &info, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    if (index >= info.surfaces) {
        fprintf(stderr, "splinecast eval: %s has %d surfaces; there is no surface %ld\n",
                scene_path, info.surfaces, index);
        goto done;
    }
    if (sc_query_surface_info(scene, (int)index, &s, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    if (!(u >= s.u_min && u <= s.u_max && v >= s.v_min && v <= s.v_max)) {
        fprintf(stderr, "splinecast eval: (%.17g, %.17g) is outside the range of surface %ld: "
                "u in [%.17g, %.17g], v in [%.17g, %.17g]\n", u, v, index, s.u_min, s.u_max,
                s.v_min, s.v_max);
        goto done;
    }
    if (sc_eval_surface(scene, (int)index, u, v, &at, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    if (!at.has_normal) {
        fprintf(stderr, "splinecast eval: surface %ld is degenerate: it has no normal at "
                "(%.17g, %.17g)\n", index, u, v);
        goto done;
    }
    printf("point %.17g %.17g %.17g\n", at.point[0], at.point[1], at.point[2]);
    printf("du %.17g %.17g %.17g\n", at.du[0], at.du[1], at.du[2]);
    printf("dv %.17g %.17g %.17g\n", at.dv[0], at.dv[1], at.dv[2]);
    printf("normal %.17g %.17g %.17g\n", at.normal[0], at.normal[1], at.normal[2]);
    status = 0;
done:
    sc_destroy_scene(scene);
    return status;
}
