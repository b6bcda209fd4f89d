/* cmd_eval.c — `splinecast eval SCENE --surface I --uv U,V`: the point,
 * first partials and unit normal of one surface at one parameter pair, in
 * world space, printed with 17 significant digits so that scripts and
 * tests can compare them with values computed elsewhere. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "io.h"
#include "nurbs.h"

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

    sc_scene scene;
    sc_error err;
    if (sc_read_scene(scene_path, &scene, &err))
        return cli_report(&err);
    int status = 1;
    if (index >= scene.nsurfaces) {
        fprintf(stderr, "splinecast eval: %s has %d surfaces; there is no surface %ld\n",
                scene_path, scene.nsurfaces, index);
        goto done;
    }
    const sc_surface *s = &scene.surfaces[index];
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    if (!(u >= u0 && u <= u1 && v >= v0 && v <= v1)) {
        fprintf(stderr, "splinecast eval: (%.17g, %.17g) is outside the range of surface %ld: "
                "u in [%.17g, %.17g], v in [%.17g, %.17g]\n", u, v, index, u0, u1, v0, v1);
        goto done;
    }
    double p[3], su[3], sv[3], n[3];
    sc_surface_eval_world(s, u, v, p, su, sv);
    if (sc_surface_normal(s, u, v, n) != 0) {
        fprintf(stderr, "splinecast eval: surface %ld is degenerate: it has no normal at "
                "(%.17g, %.17g)\n", index, u, v);
        goto done;
    }
    sc_xform_normal(s->xform, n, n);
    printf("point %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    printf("du %.17g %.17g %.17g\n", su[0], su[1], su[2]);
    printf("dv %.17g %.17g %.17g\n", sv[0], sv[1], sv[2]);
    printf("normal %.17g %.17g %.17g\n", n[0], n[1], n[2]);
    status = 0;
done:
    sc_scene_free(&scene);
    return status;
}
