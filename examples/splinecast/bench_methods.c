/* bench_methods.c — `splinecast bench --method A,B,…`: the intersection
 * methods side by side on one scene and view. One renderer per method,
 * all made first; then every timed frame draws each renderer in turn, so
 * that the machine's load falls on all methods alike and the ratios of
 * their medians are fair on a shared machine (BRIEF: a speed claim is a
 * ratio of two things measured in the same run). Prints one `bench
 * variant=method method=M …` line per method and the frame time of each
 * over the first one's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "commands.h"
#include "options.h"

int bench_methods_parse(const char *text, sc_method *methods, int *count)
{
    char name[32];
    *count = 0;
    for (const char *p = text; *p;) {
        size_t len = strcspn(p, ",");
        if (len >= sizeof name || *count == BENCH_MAX_METHODS)
            return cli_usage_error("bench", "--method takes at most %d names", BENCH_MAX_METHODS);
        memcpy(name, p, len);
        name[len] = '\0';
        sc_error err;
        if (cli_method_parse(name, &methods[*count], &err) != SC_OK)
            return cli_usage_error("bench", "%s", err.message);
        (*count)++;
        p += len + (p[len] == ',');
    }
    return *count ? 0 : cli_usage_error("bench", "--method needs a name");
}

int bench_methods_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                      const sc_camera_desc *cam, int frames, const sc_method *methods,
                      int count)
{
    sc_error err = {0};
    sc_renderer_id r[BENCH_MAX_METHODS] = {{0}};
    double warm_up[BENCH_MAX_METHODS] = {0};
    double *times = calloc((size_t)(count * frames), sizeof *times);
    int status = SC_OK;
    /* Each renderer compiles its own programs: no method's compile figures
     * are cache hits of another's. */
    desc.own_programs = 1;
    for (int m = 0; m < count && status == SC_OK; m++) {
        desc.method = methods[m];
        status = sc_make_renderer(ctx, scene, &desc, &r[m], &err);
        double t0 = sc_now();
        if (status == SC_OK)
            status = sc_draw(r[m], cam, &err);
        warm_up[m] = 1e3 * (sc_now() - t0);
    }
    for (int f = 0; f < frames && status == SC_OK; f++)
        for (int m = 0; m < count && status == SC_OK; m++) {
            double t0 = sc_now();
            status = sc_draw(r[m], cam, &err);
            times[m * frames + f] = 1e3 * (sc_now() - t0);
        }
    double first_ms = 0;
    for (int m = 0; m < count && status == SC_OK; m++) {
        bench_result res = {0};
        status = bench_finish(r[m], times + m * frames, frames, warm_up[m], &res, &err);
        if (status != SC_OK)
            break;
        char extra[64];
        snprintf(extra, sizeof extra, " method=%s", cli_method_name(methods[m]));
        bench_print("method", extra, &res);
        if (m == 0)
            first_ms = res.frame_ms;
        else
            printf("bench frame_ratio_%s_over_%s=%.2f\n", cli_method_name(methods[m]),
                   cli_method_name(methods[0]), res.frame_ms / first_ms);
    }
    for (int m = 0; m < count; m++)
        sc_destroy_renderer(r[m]);
    free(times);
    return status == SC_OK ? 0 : cli_report(&err);
}
