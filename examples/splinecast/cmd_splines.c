/* cmd_splines.c — `splinecast splines (FILE|--franke N) --scheme S
 * [--error]`: the quartic spline of a grid of heights, its patch count
 * and, for Franke's function, the paper's Table I error (relative RMS and
 * maximum at 10^6 uniformly distributed sites). Uses the public API alone. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast splines (HEIGHTS.pgm|HEIGHTS.csv|--franke N) [--scheme S] [--error]\n"
    "                          [--sites M]\n"
    "\n"
    "Builds the quartic spline of scheme S (c0, c1, c2 or linear; default c2) from\n"
    "a grid of heights or from Franke's function at N data points (144, 576, 2304,\n"
    "...), and prints what it is. --error measures it against Franke's function at\n"
    "M uniformly distributed sites (default 1000000), relative to the largest\n"
    "|f| among the data (the paper's Table I); a height file has no function to\n"
    "compare with, so --error needs --franke.\n"
    "\n"
    "stdout: splines scheme=S [points=N] patches=P [rel_rms=X rel_max=Y]\n";

int cmd_splines(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    sc_scene_desc sdesc = {0};
    sc_spline_error_desc edesc = {0};
    int with_error = 0;
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        char *end = NULL;
        if (!strcmp(a, "--franke") && next) {
            sdesc.franke = (int)strtol(argv[++i], &end, 10);
            if (*end || sdesc.franke < 1)
                return cli_usage_error("splines", "--franke takes N data points (144, 576, "
                                       "...), not '%s'", argv[i]);
        } else if (!strcmp(a, "--scheme") && next) {
            if (sc_parse_terrain_scheme(argv[++i], &sdesc.scheme, &err) != SC_OK)
                return cli_usage_error("splines", "%s", err.message);
        } else if (!strcmp(a, "--sites") && next) {
            edesc.sites = (int)strtol(argv[++i], &end, 10);
            if (*end || edesc.sites < 1 || edesc.sites > 100000000)
                return cli_usage_error("splines", "--sites takes 1 to 100000000, not '%s'",
                                       argv[i]);
        } else if (!strcmp(a, "--error")) {
            with_error = 1;
        } else if (a[0] != '-' && !sdesc.heights) {
            sdesc.heights = a;
        } else {
            return cli_usage_error("splines", "unexpected argument '%s'", a);
        }
    }
    if (!(sdesc.heights || sdesc.franke) || (sdesc.heights && sdesc.franke))
        return cli_usage_error("splines", "needs HEIGHTS or --franke N (one of them)");
    if (with_error && !sdesc.franke)
        return cli_usage_error("splines", "--error needs --franke N: a height file has no "
                               "function to measure against");
    if (with_error) {
        edesc.scheme = sdesc.scheme;
        edesc.points = sdesc.franke;
        sc_spline_error_info info;
        if (sc_measure_spline_error(&edesc, &info, &err) != SC_OK)
            return cli_report(&err);
        printf("%s\n", info.line);
        return 0;
    }
    sc_scene_id scene;
    sc_scene_info info;
    if (sc_make_scene(&sdesc, &scene, &err) != SC_OK ||
        sc_query_scene_info(scene, &info, &err) != SC_OK)
        return cli_report(&err);
    printf("splines scheme=%s", sc_terrain_scheme_name(sdesc.scheme));
    if (sdesc.franke)   /* as Table I counts them; a file's grid says its own size */
        printf(" points=%d", sdesc.franke);
    printf(" patches=%d\n", info.terrain_patches);
    sc_destroy_scene(scene);
    return 0;
}
