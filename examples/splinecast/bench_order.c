/* bench_order.c — `splinecast bench --ert/--order/--batch`: the figures
 * behind the early-ray-termination mode, the draw-order policy and the
 * batch size the renderer defaults to (splinecast_options.h). Every scene given is
 * timed under every combination of the lists, each in a renderer of its
 * own; then, measured in the same run, each combination's frame time over
 * the first combination's (per scene) and the last scene's over the first
 * scene's (per combination) — with stack_2 … stack_128 that last ratio is
 * seed 000's Table 3. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "commands.h"
#include "options.h"

/* Splits a comma list into at most `max` words of `buf`; -1 when longer. */
static int split_list(const char *text, char *buf, size_t size, char **words, int max)
{
    snprintf(buf, size, "%s", text);
    int n = 0;
    for (char *w = strtok(buf, ","); w; w = strtok(NULL, ",")) {
        if (n == max)
            return -1;
        words[n++] = w;
    }
    return n;
}

int bench_sweep_parse_erts(const char *text, bench_sweep *sweep)
{
    enum { MAX = sizeof sweep->erts / sizeof sweep->erts[0] };
    sweep->nerts = 0;
    if (!strcmp(text, "all")) {
        for (int m = SC_TERMINATION_NONE; m <= SC_TERMINATION_LISTS; m++)
            sweep->erts[sweep->nerts++] = (sc_ray_termination)m;
        return 0;
    }
    char buf[256], *words[MAX];
    int n = split_list(text, buf, sizeof buf, words, MAX);
    if (n <= 0)
        return cli_usage_error("bench", "--ert takes all or a list of at most %d modes", MAX);
    for (int i = 0; i < n; i++) {
        sc_error err = {0};
        if (cli_termination_parse(words[i], &sweep->erts[i], &err) != SC_OK)
            return cli_usage_error("bench", "--ert: %s", err.message);
    }
    sweep->nerts = n;
    return 0;
}

int bench_sweep_parse_orders(const char *text, bench_sweep *sweep)
{
    enum { MAX = sizeof sweep->orders / sizeof sweep->orders[0] };
    sweep->norders = 0;
    if (!strcmp(text, "all")) {
        for (int o = SC_HULL_ORDER_FRONT_TO_BACK; o <= SC_HULL_ORDER_HYBRID; o++)
            sweep->orders[sweep->norders++] = (sc_hull_order)o;
        return 0;
    }
    char buf[256], *words[MAX];
    int n = split_list(text, buf, sizeof buf, words, MAX);
    if (n <= 0)
        return cli_usage_error("bench", "--order takes all or a list of at most %d policies",
                               MAX);
    for (int i = 0; i < n; i++) {
        sc_error err = {0};
        if (cli_order_parse(words[i], &sweep->orders[i], &err) != SC_OK)
            return cli_usage_error("bench", "--order: %s", err.message);
    }
    sweep->norders = n;
    return 0;
}

int bench_sweep_parse_batches(const char *text, bench_sweep *sweep)
{
    enum { MAX = sizeof sweep->batches / sizeof sweep->batches[0] };
    char buf[256], *words[MAX];
    int n = split_list(text, buf, sizeof buf, words, MAX);
    if (n <= 0)
        return cli_usage_error("bench", "--batch takes a list of at most %d sizes", MAX);
    for (int i = 0; i < n; i++) {
        char *end;
        long b = strtol(words[i], &end, 10);
        if (end == words[i] || *end || b < 1 || b > 1000000)
            return cli_usage_error("bench", "--batch takes sizes of 1 to 1000000 hulls, not '%s'",
                                   words[i]);
        sweep->batches[i] = (int)b;
    }
    sweep->nbatches = n;
    return 0;
}

/* The words of one combination, the defaults resolved. */
static void describe(const sc_renderer_desc *desc, char *buf, size_t size)
{
    snprintf(buf, size, "ert=%s order=%s batch=%d",
             cli_termination_name(desc->termination ? desc->termination
                                                    : SC_DEFAULT_TERMINATION),
             cli_order_name(desc->order ? desc->order : SC_RENDER_DEFAULT_ORDER),
             desc->batch_hulls ? desc->batch_hulls : SC_RENDER_DEFAULT_BATCH_HULLS);
}

/* Combination c of the sweep's lists, ert slowest, batch fastest. */
static void combination(const bench_sweep *sweep, int c, sc_renderer_desc *desc)
{
    int nb = sweep->nbatches ? sweep->nbatches : 1, no = sweep->norders ? sweep->norders : 1;
    desc->batch_hulls = sweep->nbatches ? sweep->batches[c % nb] : 0;
    desc->order = sweep->norders ? sweep->orders[c / nb % no] : SC_HULL_ORDER_DEFAULT;
    desc->termination = sweep->nerts ? sweep->erts[c / nb / no] : SC_TERMINATION_DEFAULT;
}

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

int bench_sweep_run(sc_context_id ctx, const bench_sweep *sweep, sc_renderer_desc desc,
                    const char *camera_arg, int width, int height, int frames)
{
    int combos = (sweep->nerts ? sweep->nerts : 1) * (sweep->norders ? sweep->norders : 1) *
                 (sweep->nbatches ? sweep->nbatches : 1);
    double *frame_ms = calloc((size_t)(sweep->nscenes * combos), sizeof(double));
    char words[128], extra[512];
    int status = 0;
    for (int si = 0; si < sweep->nscenes && !status; si++) {
        sc_error err = {0};
        sc_scene_id scene;
        if (sc_make_scene(&(sc_scene_desc){.path = sweep->scenes[si]}, &scene, &err) != SC_OK) {
            status = cli_report(&err);
            break;
        }
        sc_camera_desc cam = {.width = width, .height = height, .text = camera_arg};
        if (camera_arg && sc_check_camera(&cam, &err) != SC_OK) {
            sc_destroy_scene(scene);
            status = cli_usage_error("bench", "--camera: %s", err.message);
            break;
        }
        const char *name = base_name(sweep->scenes[si]);
        for (int c = 0; c < combos && !status; c++) {
            combination(sweep, c, &desc);
            describe(&desc, words, sizeof words);
            bench_result result;
            if (bench_run(ctx, scene, &desc, &cam, frames, &result, &err) != SC_OK) {
                status = cli_report(&err);
                break;
            }
            snprintf(extra, sizeof extra, " scene=%s %s", name, words);
            bench_print("sweep", extra, &result);
            frame_ms[si * combos + c] = result.frame_ms;
        }
        sc_destroy_scene(scene);
        for (int c = 1; c < combos && !status; c++) {
            combination(sweep, c, &desc);
            describe(&desc, words, sizeof words);
            printf("bench scene=%s %s frame_ratio_over_first_combination=%.3f\n", name, words,
                   frame_ms[si * combos + c] / frame_ms[si * combos]);
        }
    }
    int last = sweep->nscenes - 1;
    for (int c = 0; c < combos && !status && last > 0; c++) {
        combination(sweep, c, &desc);
        describe(&desc, words, sizeof words);
        printf("bench %s frame_ratio_%s_over_%s=%.3f\n", words, base_name(sweep->scenes[last]),
               base_name(sweep->scenes[0]), frame_ms[last * combos + c] / frame_ms[c]);
    }
    fflush(stdout);
    free(frame_ms);
    return status;
}
