/* bench_methods.c — `splinecast bench --method A,B,…`: the intersection
 * methods side by side on one scene and view. One renderer per method,
 * all made first; then every timed frame draws each renderer in turn, so
 * that the machine's load falls on all methods alike and the ratios of
 * their medians are fair on a shared machine (BRIEF: a speed claim is a
 * ratio of two things measured in the same run). Prints one `bench
 * variant=method method=M …` line per method and the frame time of each
 * over the first one's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "commands.h"
#include "io.h"
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

static int compare_ms(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Median frame time, iterations per covered pixel and the renderer's
 * figures of one method, from its times and its last frame. */
static int finish(sc_renderer *r, double *times, int frames, bench_result *out, sc_error *err)
{
    sc_aov aov;
    if (sc_renderer_read(r, NULL, &aov, err) != SC_OK)
        return SC_FAIL;
    qsort(times, (size_t)frames, sizeof *times, compare_ms);
    out->frame_ms = times[frames / 2];
    bench_figures(r, &aov, out);
    out->compile_ms = out->stats.compile_ms;
    sc_aov_free(&aov);
    return SC_OK;
}

int bench_methods_run(const sc_gl *gl, const char *scene_path, sc_render_desc desc,
                      const char *camera_arg, int width, int height, int frames,
                      const sc_method *methods, int count)
{
    sc_error err = {0};
    sc_scene scene;
    if (sc_read_scene(scene_path, &scene, &err) != SC_OK)
        return cli_report(&err);
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    if (camera_arg && sc_camera_parse(camera_arg, &cam, &err) != SC_OK) {
        sc_scene_free(&scene);
        return cli_usage_error("bench", "--camera: %s", err.message);
    }
    cam.width = width;
    cam.height = height;
    sc_renderer *r[BENCH_MAX_METHODS] = {0};
    double *times = calloc((size_t)(count * frames), sizeof *times);
    int status = SC_OK;
    for (int m = 0; m < count && status == SC_OK; m++) {
        desc.method = methods[m];
        status = sc_renderer_create(gl, &scene, &desc, &r[m], &err);
        if (status == SC_OK)
            status = sc_renderer_draw(r[m], &cam, &err); /* warm-up */
    }
    for (int f = 0; f < frames && status == SC_OK; f++)
        for (int m = 0; m < count && status == SC_OK; m++) {
            double t0 = sc_now();
            status = sc_renderer_draw(r[m], &cam, &err);
            times[m * frames + f] = 1e3 * (sc_now() - t0);
        }
    double first_ms = 0;
    for (int m = 0; m < count && status == SC_OK; m++) {
        bench_result res = {0};
        status = finish(r[m], times + m * frames, frames, &res, &err);
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
        if (r[m])
            sc_renderer_destroy(r[m]);
    free(times);
    sc_scene_free(&scene);
    return status == SC_OK ? 0 : cli_report(&err);
}
