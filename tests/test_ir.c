/* test_ir.c — the IR: builder and validator, each pass on small programs
 * whose result is known, the interpreter's control flow, and the passes
 * preserving the results of a whole generated program bit for bit. */
#include <stdlib.h>

#include "ir.h"
#include "test.h"

static scg_program *new_program(scg_builder *b)
{
    scg_key k;
    scg_key_default(&k, SCG_PATCH_BEZIER, 3, 3);
    scg_program *p = scg_program_create(&k);
    scg_builder_init(b, p);
    return p;
}

/* Runs p with zero inputs and input T_LIMIT = x; returns output T. */
static float run_t(const scg_program *p, float x)
{
    scg_interp *it;
    scg_interp_env env;
    scg_interp_result res;
    sc_error err;
    memset(&env, 0, sizeof env);
    env.inputs[SCG_IN_T_LIMIT][0] = x;
    if (scg_interp_create(p, &it, &err) != SC_OK)
        return NAN;
    int status = scg_interp_run(it, &env, &res, &err);
    scg_interp_free(it);
    return status == SC_OK ? res.outputs[SCG_OUT_T][0] : NAN;
}

TEST(ir_fold_constants)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_value five = scg_add(&b, scg_const_f(&b, 2.0f), scg_const_f(&b, 3.0f));
    scg_value y = scg_mul(&b, scg_add(&b, x, scg_const_f(&b, 0.0f)), scg_const_f(&b, 1.0f));
    scg_output(&b, SCG_OUT_T, scg_mul(&b, y, five));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    CHECK_NEAR(run_t(p, 1.5f), 7.5, 0);
    CHECK(scg_opt_fold(p));
    CHECK_INT(scg_validate(p, &err), SC_OK);
    scg_opt_dce(p);
    /* input, const 5, mul, output */
    CHECK_INT(scg_program_size(p), 4);
    CHECK_NEAR(run_t(p, 1.5f), 7.5, 0);
    scg_program_free(p);
}

/* A value computed inside an if block must not replace the same
 * expression after the block closes; two at top level merge. */
TEST(ir_cse_respects_scopes)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_value var = scg_var(&b, SCG_FLOAT, 0, scg_const_f(&b, 0.0f));
    scg_if(&b, scg_lt(&b, scg_const_f(&b, 1.0f), x));
    scg_store(&b, var, scg_mul(&b, x, x));
    scg_endif(&b);
    scg_value sq = scg_mul(&b, x, x);
    scg_value sq2 = scg_mul(&b, x, x);
    scg_output(&b, SCG_OUT_T, scg_add(&b, scg_load(&b, var), scg_add(&b, sq, sq2)));
    int before = scg_program_size(p);
    CHECK(scg_opt_cse(p));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    CHECK_INT(scg_program_size(p), before - 1);
    CHECK_NEAR(run_t(p, 3.0f), 27.0, 0);
    CHECK_NEAR(run_t(p, 0.5f), 0.5, 0);
    scg_program_free(p);
}

TEST(ir_dce_removes_dead_code)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_value unused = scg_var(&b, SCG_FLOAT, 0, x);        /* stored, never loaded */
    scg_store(&b, unused, scg_sqrt(&b, x));
    scg_if(&b, scg_lt(&b, x, scg_const_f(&b, 0.0f)));        /* becomes empty */
    scg_store(&b, unused, x);
    scg_endif(&b);
    scg_mul(&b, x, x);                                      /* result unused */
    scg_output(&b, SCG_OUT_T, scg_neg(&b, x));
    CHECK(scg_opt_dce(p));
    while (scg_opt_dce(p))
        ;
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    CHECK_INT(scg_program_size(p), 3);   /* input, neg, output */
    CHECK_NEAR(run_t(p, 2.0f), -2.0, 0);
    scg_program_free(p);
}

TEST(ir_validator_rejects)
{
    sc_error err;
    scg_builder b;
    /* use before definition */
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_value y = scg_add(&b, x, x);
    p->insts[y].arg[1] = y + 1;
    scg_const_f(&b, 1.0f);
    CHECK_INT(scg_validate(p, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "not defined before");
    scg_program_free(p);
    /* a value used after its block closed */
    p = new_program(&b);
    x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_if(&b, scg_lt(&b, x, x));
    y = scg_add(&b, x, x);
    scg_endif(&b);
    scg_output(&b, SCG_OUT_T, y);
    CHECK_INT(scg_validate(p, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "already closed");
    scg_program_free(p);
    /* types */
    p = new_program(&b);
    x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_add(&b, x, scg_input(&b, SCG_IN_RECORD));
    CHECK_INT(scg_validate(p, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "types");
    scg_program_free(p);
    /* unclosed block, break outside a loop */
    p = new_program(&b);
    scg_if(&b, scg_const_b(&b, true));
    CHECK_INT(scg_validate(p, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "not closed");
    scg_program_free(p);
    p = new_program(&b);
    scg_break(&b);
    CHECK_INT(scg_validate(p, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "break outside");
    scg_program_free(p);
}

/* Σ i for i < 100, stopping at the first i with i·i > 50: 0+…+7 = 28. */
TEST(ir_interp_loop_and_break)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value sum = scg_var(&b, SCG_INT, 0, scg_const_i(&b, 0));
    scg_value arr = scg_var(&b, SCG_FLOAT, 4, 0);
    scg_value i = scg_loop(&b, scg_const_i(&b, 100));
    scg_if(&b, scg_lt(&b, scg_const_i(&b, 50), scg_mul(&b, i, i)));
    scg_break(&b);
    scg_else(&b);
    scg_store(&b, sum, scg_add(&b, scg_load(&b, sum), i));
    scg_endif(&b);
    scg_endloop(&b);
    scg_store_at(&b, arr, scg_const_i(&b, 3), scg_i2f(&b, scg_load(&b, sum)));
    scg_output(&b, SCG_OUT_T, scg_load_at(&b, arr, scg_const_i(&b, 3)));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    CHECK_NEAR(run_t(p, 0), 28.0, 0);
    scg_program_free(p);
}

/* The passes change how a program computes, never what: the bicubic and a
 * rational NURBS program give the same bits before and after, on rays
 * around a patch. */
static void same_results(const char *key_text)
{
    scg_key key;
    sc_error err;
    scg_program *raw, *opt;
    if (scg_key_parse(key_text, &key, &err) != SC_OK ||
        scg_build_unoptimized(&key, &raw, &err) != SC_OK) {
        TEST_FAIL_("%s", err.message);
        return;
    }
    CHECK_INT(scg_build_program(&key, &opt, &err), SC_OK);
    CHECK(scg_program_size(opt) < scg_program_size(raw));
    float points[4 * 16], knots[16], records[4 * SCG_RECORD_TEXELS] = {
        0, 4, 4, 3, 0, 8, 3, 3, 0, 1, 0, 1, 0, 0, 0, 0};
    unsigned long long rng = 5;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            float w = key.rational ? 0.5f + (float)test_rand(&rng) : 1.0f;
            points[4 * (4 * j + i) + 0] = (i - 1.5f) * w;
            points[4 * (4 * j + i) + 1] = (j - 1.5f) * w;
            points[4 * (4 * j + i) + 2] = ((float)test_rand(&rng) - 0.5f) * w;
            points[4 * (4 * j + i) + 3] = w;
        }
    for (int k = 0; k < 16; k++)
        knots[k] = (k % 8) < 4 ? 0.0f : 1.0f;
    scg_interp *a, *c;
    CHECK_INT(scg_interp_create(raw, &a, &err), SC_OK);
    CHECK_INT(scg_interp_create(opt, &c, &err), SC_OK);
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    env.texels[SCG_TEX_POINTS] = points;
    env.texel_count[SCG_TEX_POINTS] = 16;
    env.texels[SCG_TEX_KNOTS] = knots;
    env.texel_count[SCG_TEX_KNOTS] = 16;
    env.texels[SCG_TEX_RECORDS] = records;
    env.texel_count[SCG_TEX_RECORDS] = SCG_RECORD_TEXELS;
    env.uniforms[SCG_UNI_FOOTPRINT][0] = 0.002f;
    int hits = 0;
    for (int r = 0; r < 200; r++) {
        float o[3] = {(float)test_rand(&rng) * 2 - 1, (float)test_rand(&rng) * 2 - 1, 4};
        float d[3] = {(float)test_rand(&rng) - 0.5f, (float)test_rand(&rng) - 0.5f, -3.5f};
        memcpy(env.inputs[SCG_IN_RAY_ORIGIN], o, sizeof o);
        memcpy(env.inputs[SCG_IN_RAY_DIR], d, sizeof d);
        float dom[4] = {0, 0.5f, 0.5f, 1};
        memcpy(env.inputs[SCG_IN_DOMAIN], dom, sizeof dom);
        scg_interp_result ra, rc;
        CHECK_INT(scg_interp_run(a, &env, &ra, &err), SC_OK);
        CHECK_INT(scg_interp_run(c, &env, &rc, &err), SC_OK);
        CHECK(rc.steps < ra.steps);
        CHECK(memcmp(ra.outputs, rc.outputs, sizeof ra.outputs) == 0);
        hits += ra.outputs[SCG_OUT_HIT][0] != 0;
    }
    CHECK(hits > 10);
    scg_interp_free(a);
    scg_interp_free(c);
    scg_program_free(raw);
    scg_program_free(opt);
}

TEST(ir_passes_preserve_results)
{
    same_results("bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade");
    same_results("nurbs3x3-rat-dc-trim0-newton-mid-it6-tol0.5-ert0-out.shade");
    same_results("bezdyn-rat-loop-trim0-newton-mid-it6-tol0.5-ert0-out.shade");
}

/* The bicubic Newton program is straight-line: no runtime loop, one guard
 * per iteration after the first, 16 point fetches and one record fetch
 * pair; the listing names its values. */
TEST(ir_dump_bicubic_straight_line)
{
    scg_key key;
    sc_error err;
    scg_program *p;
    CHECK_INT(scg_key_parse("bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade", &key, &err),
              SC_OK);
    CHECK_INT(scg_build_program(&key, &p, &err), SC_OK);
    int ifs = 0, loops = 0, fetches = 0;
    for (int i = 1; i < p->count; i++) {
        ifs += p->insts[i].op == SCG_OP_IF;
        loops += p->insts[i].op == SCG_OP_LOOP;
        fetches += p->insts[i].op == SCG_OP_FETCH && p->insts[i].slot == SCG_TEX_POINTS;
    }
    CHECK_INT(ifs, 3);
    CHECK_INT(loops, 0);
    CHECK_INT(fetches, 16);
    char *text = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&text, &size);
    scg_dump_ir(f, p);
    fclose(f);
    CHECK_CONTAINS(text, "# program bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade");
    CHECK_CONTAINS(text, "= fetch sc_points, ");
    CHECK_CONTAINS(text, "_Su:vec3 = ");
    CHECK_CONTAINS(text, "output hit = ");
    free(text);
    scg_program_free(p);
}

/* Runs p once with env; returns the status and leaves the error in err. */
static int run_env(const scg_program *p, const scg_interp_env *env, sc_error *err)
{
    scg_interp *it;
    scg_interp_result res;
    if (scg_interp_create(p, &it, err) != SC_OK)
        return SC_FAIL;
    int status = scg_interp_run(it, env, &res, err);
    scg_interp_free(it);
    return status;
}

/* A fetch reads texel `record` of sc_points: inside the texture it gives
 * the texel, one past the end, before the start or from a texture the
 * environment does not have, the run fails and names the instruction. */
TEST(ir_interp_fetch_outside_texture)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value index = scg_input(&b, SCG_IN_RECORD);
    scg_value texel = scg_fetch(&b, SCG_TEX_POINTS, index);
    scg_output(&b, SCG_OUT_T, scg_comp(&b, texel, 2));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    const float points[4 * 2] = {0, 1, 2, 3, 4, 5, 6, 7};
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    env.texels[SCG_TEX_POINTS] = points;
    env.texel_count[SCG_TEX_POINTS] = 2;
    env.inputs[SCG_IN_RECORD][0] = 1;
    scg_interp *it;
    scg_interp_result res;
    CHECK_INT(scg_interp_create(p, &it, &err), SC_OK);
    CHECK_INT(scg_interp_run(it, &env, &res, &err), SC_OK);
    CHECK_NEAR(res.outputs[SCG_OUT_T][0], 6.0, 0);
    scg_interp_free(it);

    env.inputs[SCG_IN_RECORD][0] = 2;
    CHECK_INT(run_env(p, &env, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "instruction v2 (fetch): texel 2 outside sc_points (2 texels)");
    CHECK_STR(err.key, "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade");
    env.inputs[SCG_IN_RECORD][0] = -1;
    CHECK_INT(run_env(p, &env, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "texel -1 outside sc_points");
    env.inputs[SCG_IN_RECORD][0] = 0;
    env.texels[SCG_TEX_POINTS] = NULL;
    CHECK_INT(run_env(p, &env, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "texel 0 outside sc_points");
    scg_program_free(p);
}

/* Loop counts come from the program, so a loop always ends, but a count
 * read from bad data can make it run for hours: two nested loops of 2^30
 * iterations stop at the interpreter's step limit with an error. */
TEST(ir_interp_endless_loop)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value sum = scg_var(&b, SCG_INT, 0, scg_const_i(&b, 0));
    scg_loop(&b, scg_const_i(&b, 1 << 30));
    scg_loop(&b, scg_const_i(&b, 1 << 30));
    scg_store(&b, sum, scg_add(&b, scg_load(&b, sum), scg_const_i(&b, 1)));
    scg_endloop(&b);
    scg_endloop(&b);
    scg_output(&b, SCG_OUT_ITERS, scg_load(&b, sum));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    CHECK_INT(run_env(p, &env, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "too many steps");
    scg_program_free(p);
}

/* An array index outside the array's length fails rather than reading
 * past it. */
TEST(ir_interp_index_outside_array)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value arr = scg_var(&b, SCG_FLOAT, 4, 0);
    scg_value index = scg_input(&b, SCG_IN_RECORD);
    scg_output(&b, SCG_OUT_T, scg_load_at(&b, arr, index));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    env.inputs[SCG_IN_RECORD][0] = 3;
    CHECK_INT(run_env(p, &env, &err), SC_OK);
    env.inputs[SCG_IN_RECORD][0] = 4;
    CHECK_INT(run_env(p, &env, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "(load): array index out of range");
    scg_program_free(p);
}

/* Integer identities fold like the float ones (x+0, 0+x, x-0, x·1, 1·x,
 * x/1, and x·0 for ints only), and so do !!b and a vector gathered whole
 * from its own components. */
TEST(ir_fold_integer_identities)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value r = scg_input(&b, SCG_IN_RECORD);
    scg_value zero = scg_const_i(&b, 0), one = scg_const_i(&b, 1);
    scg_value x = scg_add(&b, scg_add(&b, r, zero), scg_mul(&b, r, zero));
    x = scg_mul(&b, one, scg_sub(&b, scg_add(&b, zero, x), zero));
    x = scg_div(&b, scg_mul(&b, x, one), one);
    scg_output(&b, SCG_OUT_ITERS, x);
    scg_value dir = scg_input(&b, SCG_IN_RAY_DIR);
    scg_value dx = scg_comp(&b, dir, 0), dy = scg_comp(&b, dir, 1), dz = scg_comp(&b, dir, 2);
    scg_output(&b, SCG_OUT_NORMAL, scg_vec3(&b, dx, dy, dz));
    scg_value positive = scg_lt(&b, scg_const_f(&b, 0.0f), dx);
    scg_output(&b, SCG_OUT_HIT, scg_not(&b, scg_not(&b, positive)));
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    CHECK(scg_opt_fold(p));
    CHECK_INT(scg_validate(p, &err), SC_OK);
    while (scg_opt_dce(p))
        ;
    /* r, x·0 folded to the constant 0 and r + 0 to r, so r + 0 is r; then
     * dir, its x, 0.0, the comparison, and three outputs. */
    for (int i = 1; i < p->count; i++) {
        const scg_inst *in = &p->insts[i];
        if (in->op == SCG_OP_OUTPUT && in->slot == SCG_OUT_ITERS)
            CHECK_INT(p->insts[in->arg[0]].op, SCG_OP_INPUT);
        if (in->op == SCG_OP_OUTPUT && in->slot == SCG_OUT_NORMAL)
            CHECK_INT(p->insts[in->arg[0]].op, SCG_OP_INPUT);
        if (in->op == SCG_OP_OUTPUT && in->slot == SCG_OUT_HIT)
            CHECK_INT(p->insts[in->arg[0]].op, SCG_OP_LT);
        CHECK(in->op != SCG_OP_ADD && in->op != SCG_OP_SUB && in->op != SCG_OP_MUL &&
              in->op != SCG_OP_DIV && in->op != SCG_OP_NOT && in->op != SCG_OP_VEC);
    }
    scg_program_free(p);
}

/* x·0 stays for floats: NaN·0 is NaN, not 0. */
TEST(ir_fold_keeps_float_times_zero)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_output(&b, SCG_OUT_T, scg_mul(&b, x, scg_const_f(&b, 0.0f)));
    CHECK(!scg_opt_fold(p));
    CHECK(isnan(run_t(p, NAN)));
    scg_program_free(p);
}

/* A load reads the value last stored when no path in between stores the
 * variable: after the initial value and after a store in the same block,
 * but not after an if or inside a loop that stores it. */
TEST(ir_copy_forwards_known_values)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_T_LIMIT);
    scg_value var = scg_var(&b, SCG_FLOAT, 0, x);
    scg_value first = scg_load(&b, var);                        /* x */
    scg_value doubled = scg_add(&b, first, first);
    scg_store(&b, var, doubled);
    scg_value second = scg_load(&b, var);                       /* 2x */
    scg_if(&b, scg_lt(&b, scg_const_f(&b, 1.0f), x));
    scg_value inside = scg_load(&b, var);                       /* 2x */
    scg_store(&b, var, scg_mul(&b, inside, x));
    scg_endif(&b);
    scg_value after_if = scg_load(&b, var);                     /* 2x or 2x² */
    scg_loop(&b, scg_const_i(&b, 2));
    scg_value in_loop = scg_load(&b, var);                      /* grows */
    scg_store(&b, var, scg_add(&b, in_loop, scg_const_f(&b, 1.0f)));
    scg_endloop(&b);
    scg_value after_loop = scg_load(&b, var);
    scg_value sum = scg_add(&b, scg_add(&b, second, after_if), after_loop);
    scg_output(&b, SCG_OUT_T, sum);
    sc_error err;
    CHECK_INT(scg_validate(p, &err), SC_OK);
    /* x = 3: 6 + 18 + 20 = 44; x = 0.5: 1 + 1 + 3 = 5. */
    CHECK_NEAR(run_t(p, 3.0f), 44.0, 0);
    CHECK_NEAR(run_t(p, 0.5f), 5.0, 0);
    CHECK(scg_opt_copy(p));
    CHECK_INT(scg_validate(p, &err), SC_OK);
    CHECK(!scg_opt_copy(p));
    int loads = 0;
    for (int i = 1; i < p->count; i++)
        loads += p->insts[i].op == SCG_OP_LOAD;
    CHECK_INT(loads, 3);   /* after the if, in the loop, after the loop */
    CHECK_NEAR(run_t(p, 3.0f), 44.0, 0);
    CHECK_NEAR(run_t(p, 0.5f), 5.0, 0);
    scg_program_free(p);
}
