/* test_peak.c — `bench --peak`: the FLOP cost table against hand counts
 * (a program built by hand, and the IR of a small key counted from its
 * listing), and the peak line's fields. */
#include <stdio.h>
#include <stdlib.h>

#include "flops.h"
#include "ir.h"
#include "splinecast.h"
#include "test.h"

/* Each op's row of the cost table: lanes from the widest float operand, a
 * float broadcast over a vector counts every lane, int arithmetic and
 * comparisons count nothing. */
TEST(flops_ops_hand_count)
{
    scg_key k;
    scg_key_default(&k, SCG_PATCH_BEZIER, 1, 1);
    scg_program *p = scg_program_create(&k);
    scg_builder b;
    scg_builder_init(&b, p);
    scg_value o = scg_input(&b, SCG_IN_RAY_ORIGIN);   /* vec3 */
    scg_value d = scg_input(&b, SCG_IN_RAY_DIR);      /* vec3 */
    scg_value s = scg_const_f(&b, 2);
    scg_value i = scg_const_i(&b, 3);
    long want = 0;
    scg_value dot = scg_dot(&b, o, d);                 /* 3 mul + 2 add */
    want += 5;
    scg_value cr = scg_cross(&b, o, d);                /* 6 mul + 3 sub */
    want += 9;
    scg_value sc = scg_mul(&b, cr, s);                 /* vec3 * float: 3 */
    want += 3;
    scg_value len = scg_length(&b, sc);                /* dot 5 + sqrt 1 */
    want += 6;
    scg_value q = scg_div(&b, dot, len);               /* 1 */
    want += 1;
    scg_value r = scg_sqrt(&b, scg_abs(&b, q));        /* 1 + 1 */
    want += 2;
    scg_value m = scg_min(&b, scg_sub(&b, o, d), scg_neg(&b, d));  /* 3 + 3 + 3 */
    want += 9;
    scg_add(&b, i, i);                                  /* int: 0 */
    scg_lt(&b, r, s);                                   /* comparison: 0 */
    scg_select(&b, scg_lt(&b, r, s), r, s);             /* 0 */
    scg_value v4 = scg_vec4(&b, r, r, r, r);            /* 0 */
    scg_floor(&b, scg_add(&b, v4, v4));                 /* 4 + 4 */
    want += 8;
    scg_comp(&b, m, 0);
    CHECK_INT(scg_program_flops(p, NULL), want);
    scg_program_free(p);
}

/* The smallest Newton key, counted by hand from its final IR listing
 * (`splinecast gen --key KEY --dump-ir`, the last stage, 219
 * instructions), op by op, with lanes per op:
 *   dot vec3 ×22 (5 each) 110, length vec3 ×6 (6) 36, cross ×2 (9) 18,
 *   add float ×10, vec2 ×2 (2), vec3 ×9 (3): 10 + 4 + 27 = 41,
 *   sub float ×6, vec2 ×3 (2), vec3 ×9 (3): 6 + 6 + 27 = 39,
 *   mul float ×16, vec2 ×2 (2), vec3·float ×10 (3): 16 + 4 + 30 = 50,
 *   div float ×3, vec2·float ×1 (2), vec3·float ×3 (3): 3 + 2 + 9 = 14,
 *   neg float ×4, vec3 ×1 (3): 7, abs float ×3: 3
 * = 318; int adds and muls, comparisons, selects, fetches and vecN count 0.
 * One iteration: the key with it2 is per_iter more. */
TEST(flops_small_key_hand_count)
{
    const char *key = "bez1x1-poly-dc-trim0-newton-mid-it1-tol0.05-ert0-out.shade";
    sc_key_flops f, f2;
    sc_error err = {0};
    CHECK_INT(sc_count_key_flops(key, &f, &err), SC_OK);
    CHECK_INT((long)f.total, 318);
    CHECK(f.per_iter > 0 && f.per_iter < f.total);
    CHECK_INT((long)(f.fixed + f.per_iter), 318);
    CHECK_INT(sc_count_key_flops("bez1x1-poly-dc-trim0-newton-mid-it2-tol0.05-ert0-out.shade",
                                 &f2, &err), SC_OK);
    CHECK_INT((long)f2.total, (long)(f.total + f.per_iter));
    CHECK_INT((long)f2.per_iter, (long)f.per_iter);
    CHECK_INT(sc_count_key_flops("bez1x1-nonsense", &f, &err), SC_FAIL);
}

/* The peak line: the peak, the achieved rate and their ratio, from a small
 * frame. */
TEST(peak_line)
{
    char cmd[1024], *out = NULL;
    snprintf(cmd, sizeof cmd, "LP_NUM_THREADS=2 %s bench --peak --size 96x96 --frames 1",
             test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK(out != NULL);
    const char *line = out ? strstr(out, "peak gflops=") : NULL;
    CHECK(line != NULL);
    double g = 0, a = 0, f = -1, per_pixel = 0;
    CHECK_INT(line ? sscanf(line, "peak gflops=%lf achieved_gflops=%lf fraction=%lf", &g, &a, &f)
                   : 0, 3);
    CHECK(g > 0 && a > 0);
    /* The three are printed to 0.1, 0.1 and 0.001: the fraction agrees with
     * their quotient within what that rounding can move it (a small peak
     * under load moves it most). */
    double rounding = g > 0 ? 0.0005 + 0.05 / g + (a + 0.05) * 0.05 / (g * (g - 0.05)) : 0;
    CHECK_NEAR(f, a / g, rounding + 1e-9);
    const char *pp = line ? strstr(line, "flops_per_covered_pixel=") : NULL;
    CHECK(pp && sscanf(pp, "flops_per_covered_pixel=%lf", &per_pixel) == 1 && per_pixel > 0);
    free(out);
}
