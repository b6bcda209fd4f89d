/* bench_sides.c — `splinecast bench --method A,B,…` and `--eval A,B,…`:
 * intersection methods, or evaluation forms, side by side on one scene and
 * view. One renderer per value, all made first; then every timed frame
 * draws each renderer in turn, so that the machine's load falls on all of
 * them alike and the ratios of their medians are fair on a shared machine
 * (BRIEF: a speed claim is a ratio of two things measured in the same
 * run). Prints one `bench variant=method method=M …` (or `variant=eval
 * eval=E …`) line per value and the frame time of each over the first
 * one's. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "commands.h"
#include "options.h"

static const char *const field_names[] = {"method", "eval"};

static int parse_value(bench_side_field field, const char *name, int *value, sc_error *err)
{
    if (field == BENCH_SIDE_METHOD) {
        sc_method method;
        int status = cli_method_parse(name, &method, err);
        *value = (int)method;
        return status;
    }
    sc_eval eval;
    int status = cli_eval_parse(name, &eval, err);
    *value = (int)eval;
    return status;
}

static const char *value_name(bench_side_field field, int value)
{
    return field == BENCH_SIDE_METHOD ? cli_method_name((sc_method)value)
                                      : cli_eval_name((sc_eval)value);
}

int bench_sides_parse(bench_side_field field, const char *text, int *values, int *count)
{
    const char *option = field_names[field];
    char name[32];
    *count = 0;
    for (const char *p = text; *p;) {
        size_t len = strcspn(p, ",");
        if (len >= sizeof name || *count == BENCH_MAX_SIDES)
            return cli_usage_error("bench", "--%s takes at most %d names", option,
                                   BENCH_MAX_SIDES);
        memcpy(name, p, len);
        name[len] = '\0';
        sc_error err;
        if (parse_value(field, name, &values[*count], &err) != SC_OK)
            return cli_usage_error("bench", "%s", err.message);
        (*count)++;
        p += len + (p[len] == ',');
    }
    return *count ? 0 : cli_usage_error("bench", "--%s needs a name", option);
}

int bench_sides_run(sc_context_id ctx, sc_scene_id scene, sc_renderer_desc desc,
                    const sc_camera_desc *cam, int frames, bench_side_field field,
                    const int *values, int count)
{
    sc_error err = {0};
    sc_renderer_id r[BENCH_MAX_SIDES] = {{0}};
    double warm_up[BENCH_MAX_SIDES] = {0};
    double *times = calloc((size_t)(count * frames), sizeof *times);
    int status = SC_OK;
    /* Each renderer compiles its own programs: no value's compile figures
     * are cache hits of another's. */
    desc.own_programs = 1;
    for (int m = 0; m < count && status == SC_OK; m++) {
        if (field == BENCH_SIDE_METHOD)
            desc.method = (sc_method)values[m];
        else
            desc.eval = (sc_eval)values[m];
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
    const char *first = value_name(field, values[0]);
    for (int m = 0; m < count && status == SC_OK; m++) {
        bench_result res = {0};
        status = bench_finish(r[m], times + m * frames, frames, warm_up[m], &res, &err);
        if (status != SC_OK)
            break;
        const char *name = value_name(field, values[m]);
        char extra[64];
        snprintf(extra, sizeof extra, " %s=%s", field_names[field], name);
        bench_print(field_names[field], extra, &res);
        if (m == 0)
            first_ms = res.frame_ms;
        else
            printf("bench frame_ratio_%s_over_%s=%.2f\n", name, first, res.frame_ms / first_ms);
    }
    for (int m = 0; m < count; m++)
        sc_destroy_renderer(r[m]);
    free(times);
    return status == SC_OK ? 0 : cli_report(&err);
}
