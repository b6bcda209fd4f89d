/* bench_compiler.c — figures for docs/compiler.md: IR instruction counts
 * before and after the passes, and the time to build, optimise and
 * interpret one key (median of several runs), for a list of keys.
 *
 *   make BUILD=build bench-compiler && build/bench_compiler [KEY…] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ir.h"

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* A flat bicubic-ish patch grid under a ray straight down. */
static void bench_env(const scg_key *key, scg_interp_env *env, float *points, float *knots,
                      float *records)
{
    int p = key->deg_u ? key->deg_u : 3, q = key->deg_v ? key->deg_v : 3;
    memset(env, 0, sizeof *env);
    for (int j = 0; j <= q; j++)
        for (int i = 0; i <= p; i++) {
            float *c = &points[4 * (j * (p + 1) + i)];
            c[0] = 2.0f * i / p - 1;
            c[1] = 2.0f * j / q - 1;
            c[2] = 0.1f * (float)((i * 7 + j * 3) % 5) / 5;
            c[3] = 1;
        }
    for (int k = 0; k < 2 * (p + 1); k++)
        knots[k] = k % (p + 1) == k % (2 * (p + 1)) && k <= p ? 0.0f : 1.0f;
    for (int k = 0; k < 2 * (q + 1); k++)
        knots[2 * (p + 1) + k] = k <= q ? 0.0f : 1.0f;
    float rec[16] = {0, (float)(p + 1), (float)(q + 1), 0, 0, (float)(2 * (p + 1)), (float)p,
                     (float)q, 0, 1, 0, 1, 0, 0, 0, 0};
    memcpy(records, rec, sizeof rec);
    env->texels[SCG_TEX_POINTS] = points;
    env->texel_count[SCG_TEX_POINTS] = (p + 1) * (q + 1);
    env->texels[SCG_TEX_KNOTS] = knots;
    env->texel_count[SCG_TEX_KNOTS] = 2 * (p + 1) + 2 * (q + 1);
    env->texels[SCG_TEX_RECORDS] = records;
    env->texel_count[SCG_TEX_RECORDS] = SCG_RECORD_TEXELS;
    env->uniforms[SCG_UNI_FOOTPRINT][0] = 0.002f;
    float o[3] = {0.13f, -0.21f, 3}, d[3] = {0.01f, 0.02f, -2.5f}, dom[4] = {0.5f, 0.75f, 0.25f, 0.5f};
    memcpy(env->inputs[SCG_IN_RAY_ORIGIN], o, sizeof o);
    memcpy(env->inputs[SCG_IN_RAY_DIR], d, sizeof d);
    memcpy(env->inputs[SCG_IN_DOMAIN], dom, sizeof dom);
    env->inputs[SCG_IN_T_LIMIT][0] = 3.0e38f;
}

int main(int argc, char **argv)
{
    static const char *const defaults[] = {
        "bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "bez3x3-poly-dc-trim0-newton-mid-it16-tol0.25-ert0-out.shade",
        "bez7x7-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "bez7x7-poly-dc-trim0-newton-mid-it16-tol0.25-ert0-out.shade",
        "bez3x3-rat-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "bez3x3-poly-bern-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "nurbs3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "bezdyn-poly-loop-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
    };
    int nkeys = argc > 1 ? argc - 1 : (int)(sizeof defaults / sizeof defaults[0]);
    enum { RUNS = 15 };
    printf("%-62s %7s %7s %9s %9s %9s %9s\n", "key", "built", "opt", "build_ms", "opt_ms",
           "interp_ms", "total_ms");
    for (int k = 0; k < nkeys; k++) {
        const char *text = argc > 1 ? argv[k + 1] : defaults[k];
        scg_key key;
        sc_error err;
        if (scg_key_parse(text, &key, &err) != SC_OK) {
            fprintf(stderr, "bench_compiler: %s\n", err.message);
            return 1;
        }
        double build_ms[RUNS], opt_ms[RUNS], run_ms[RUNS], total_ms[RUNS];
        int before = 0, after = 0;
        static float points[4 * 17 * 17], knots[4 * 17], records[16];
        for (int r = 0; r < RUNS; r++) {
            scg_program *prog;
            scg_interp *it;
            scg_interp_env env;
            scg_interp_result res;
            double t0 = sc_now();
            if (scg_build_unoptimized(&key, &prog, &err) != SC_OK) {
                fprintf(stderr, "bench_compiler: %s\n", err.message);
                return 1;
            }
            double t1 = sc_now();
            before = scg_program_size(prog);
            if (scg_optimize(prog, NULL, NULL, &err) != SC_OK) {
                fprintf(stderr, "bench_compiler: %s\n", err.message);
                return 1;
            }
            double t2 = sc_now();
            after = scg_program_size(prog);
            bench_env(&key, &env, points, knots, records);
            if (scg_interp_create(prog, &it, &err) != SC_OK ||
                scg_interp_run(it, &env, &res, &err) != SC_OK) {
                fprintf(stderr, "bench_compiler: %s\n", err.message);
                return 1;
            }
            double t3 = sc_now();
            scg_interp_free(it);
            scg_program_free(prog);
            build_ms[r] = 1e3 * (t1 - t0);
            opt_ms[r] = 1e3 * (t2 - t1);
            run_ms[r] = 1e3 * (t3 - t2);
            total_ms[r] = 1e3 * (t3 - t0);
        }
        qsort(build_ms, RUNS, sizeof(double), compare_doubles);
        qsort(opt_ms, RUNS, sizeof(double), compare_doubles);
        qsort(run_ms, RUNS, sizeof(double), compare_doubles);
        qsort(total_ms, RUNS, sizeof(double), compare_doubles);
        printf("%-62s %7d %7d %9.3f %9.3f %9.3f %9.3f\n", text, before, after, build_ms[RUNS / 2],
               opt_ms[RUNS / 2], run_ms[RUNS / 2], total_ms[RUNS / 2]);
    }
    return 0;
}
