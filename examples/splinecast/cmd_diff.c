/* cmd_diff.c — `splinecast diff REF TEST`: the accuracy of one AOV image
 * against a reference, as one `accuracy` line (sc_compare_frames). */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast diff REF TEST\n"
    "\n"
    "Compares the AOV file TEST against the AOV file REF (an image name such as\n"
    "out.png stands for the AOV beside it, out.aov) and prints one line:\n"
    "  accuracy coverage_pct=P fail_pct=P pos_median_px=X pos_max_px=X\n"
    "           normal_mean_deg=A normal_max_deg=A [iters_mean=N iters_max=N]\n"
    "Percentages are of the pixels REF hits: coverage = holes + false hits,\n"
    "fail = those plus pixels where both hit but the points are more than one\n"
    "pixel footprint apart (so they can pass 100). When REF hits nothing, both\n"
    "are 0 if TEST hits nothing too and inf if TEST hits anything.\n"
    "Position errors are in pixel footprints at REF's distance and\n"
    "normal errors in degrees, both over the pixels both hit; iterations (when TEST\n"
    "has them) over TEST's hit pixels. Exits 1 when the two files differ in size or\n"
    "camera.\n";

static const char *aov_name(const char *path, char *buf, size_t size)
{
    size_t n = strlen(path);
    if (n >= 4 && !strcmp(path + n - 4, ".png")) {
        /* A name that is only the extension (".png", "dir/.png") keeps it. */
        int bare = n == 4 || path[n - 5] == '/';
        snprintf(buf, size, "%.*s.aov", (int)(bare ? n : n - 4), path);
        return buf;
    }
    return path;
}

int cmd_diff(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    if (argc != 3 || argv[1][0] == '-' || argv[2][0] == '-')
        return cli_usage_error("diff", "expected two arguments: REF TEST");
    char ref_buf[1024], test_buf[1024];
    const char *ref_path = aov_name(argv[1], ref_buf, sizeof ref_buf);
    const char *test_path = aov_name(argv[2], test_buf, sizeof test_buf);
    sc_error err = {0};
    sc_frame_id ref, test;
    if (sc_load_frame(ref_path, &ref, &err) != SC_OK)
        return cli_report(&err);
    if (sc_load_frame(test_path, &test, &err) != SC_OK) {
        sc_destroy_frame(ref);
        return cli_report(&err);
    }
    sc_comparison cmp;
    int status = sc_compare_frames(ref, test, &cmp, &err);
    sc_destroy_frame(ref);
    sc_destroy_frame(test);
    if (status != SC_OK) {
        fprintf(stderr, "splinecast diff: %s and %s: %s\n", ref_path, test_path, err.message);
        return 1;
    }
    puts(cmp.line);
    return 0;
}
