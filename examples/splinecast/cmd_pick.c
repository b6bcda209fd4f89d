/* cmd_pick.c — `splinecast pick SCENE --at X,Y`: what lies under one image
 * point of the view `render` would draw (sc_pick: the GPU frame's surface
 * id and (u, v), refined in double precision on the CPU). One line on
 * stdout for scripts. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "splinecast.h"
#include "view_options.h"

static const char usage[] =
    "usage: splinecast pick SCENE --at X,Y [view options] [--backend egl|osmesa]\n"
    "                       [--method newton|broyden|bclip|subdiv|hybrid]\n"
    "                       [--eval dc|bern|pow]\n"
    "\n"
    "Draws SCENE on the GPU as `render` does and prints what lies under image\n"
    "point (X, Y): X a column and Y a row from the top left, in pixels, pixel\n"
    "centres at +0.5 (so --at 256.5,256.5 is the centre pixel of 512x512). The\n"
    "GPU's surface id and (u, v) are refined by Newton's method in double\n"
    "precision against the surface itself.\n"
    "\n"
    "%s"
    "\n"
    "stdout, one line:\n"
    "  pick surface=I u=U v=V point=X,Y,Z normal=X,Y,Z t=T\n"
    "    surface: the 0-based index `info` and `eval` use; (u, v) in the surface's\n"
    "    own knot range, as `eval --uv` takes them (eval gives the same point);\n"
    "    normal: unit, facing the viewer; t: distance from the eye; 12 digits\n"
    "  pick miss\n"
    "    when nothing is under the point\n";

static int parse_at(const char *text, double *x, double *y)
{
    char *end;
    *x = strtod(text, &end);
    if (end == text || *end != ',')
        return 0;
    const char *second = end + 1;
    *y = strtod(second, &end);
    return end != second && !*end;
}

int cmd_pick(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        printf(usage, cli_view_usage);
        return 0;
    }
    const char *scene_path = NULL;
    cli_view view_opts;
    cli_view_init(&view_opts);
    sc_context_desc ctx_desc = {0};
    sc_renderer_desc desc = {0};
    sc_error err = {0};
    double x = 0, y = 0;
    int have_at = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        int taken = cli_view_option("pick", argc, argv, &i, &view_opts);
        if (taken == 2)
            return 2;
        if (taken)
            continue;
        if (!strcmp(a, "--at") && next) {
            if (!parse_at(argv[++i], &x, &y))
                return cli_usage_error("pick", "--at takes X,Y in pixels (e.g. 256.5,256.5), "
                                       "not '%s'", argv[i]);
            have_at = 1;
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &ctx_desc.backend, &err) != SC_OK)
                return cli_usage_error("pick", "%s", err.message);
        } else if (!strcmp(a, "--method") && next) {
            if (cli_method_parse(argv[++i], &desc.method, &err) != SC_OK)
                return cli_usage_error("pick", "%s", err.message);
        } else if (!strcmp(a, "--eval") && next) {
            if (cli_eval_parse(argv[++i], &desc.eval, &err) != SC_OK)
                return cli_usage_error("pick", "%s", err.message);
        } else if (a[0] != '-' && !scene_path) {
            scene_path = a;
        } else {
            return cli_usage_error("pick", "unexpected argument '%s'", a);
        }
    }
    if (!scene_path || !have_at)
        return cli_usage_error("pick", "needs SCENE and --at X,Y");
    sc_camera_desc view;
    int bad = cli_view_camera("pick", &view_opts, &view);
    if (bad)
        return bad;
    if (!(x >= 0 && x < view.width && y >= 0 && y < view.height))
        return cli_usage_error("pick", "--at %g,%g is outside the %dx%d image", x, y, view.width,
                               view.height);
    sc_scene_id scene;
    if (cli_open_drawable_scene("pick", scene_path, &scene))
        return 1;
    int status = 1;
    sc_context_id ctx = {0};
    sc_renderer_id renderer;
    sc_pick_result hit;
    if (sc_make_context(&ctx_desc, &ctx, &err) != SC_OK ||
        sc_make_renderer(ctx, scene, &desc, &renderer, &err) != SC_OK ||
        sc_draw(renderer, &view, &err) != SC_OK || sc_pick(renderer, x, y, &hit, &err) != SC_OK) {
        cli_report(&err);
        goto done;
    }
    if (!hit.hit)
        printf("pick miss\n");
    else
        printf("pick surface=%d u=%.12g v=%.12g point=%.12g,%.12g,%.12g normal=%.12g,%.12g,%.12g "
               "t=%.12g\n", hit.surface, hit.u, hit.v, hit.point[0], hit.point[1], hit.point[2],
               hit.normal[0], hit.normal[1], hit.normal[2], hit.t);
    status = 0;
done:
    sc_destroy_context(ctx);
    sc_destroy_scene(scene);
    return status;
}
