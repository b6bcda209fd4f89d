/* test_ops.c — the op table (gen/ops.h): every row complete, and each
 * arithmetic op's row agreeing with what the validator accepts and with
 * what CSE, folding, the interpreter and the GLSL emitter do with it, so
 * that a row added or changed wrongly fails here rather than in a kernel. */
#include <stdlib.h>

#include "emit_glsl.h"
#include "ir.h"
#include "test.h"

/* Rows of the table, counted by the preprocessor. */
enum {
    OP_ROWS = 0
#define X(...) +1
#include "ops.h"
#undef X
};

TEST(ops_table_names)
{
    CHECK_INT(OP_ROWS, SCG_OP_COUNT);
    for (int op = 0; op < SCG_OP_COUNT; op++) {
        const char *name = scg_op_infos[op].name;
        CHECK(name && name[0]);
        CHECK_STR(scg_op_name((scg_op)op), name);
        for (const char *c = name; *c; c++)
            CHECK((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9'));
        for (int other = 0; other < op; other++)
            CHECK(strcmp(scg_op_infos[other].name, name) != 0);
    }
    CHECK_STR(scg_op_name(SCG_OP_COUNT), "?");
    /* The listing's names are part of --dump-ir's text. */
    CHECK_STR(scg_op_name(SCG_OP_NOP), "nop");
    CHECK_STR(scg_op_name(SCG_OP_ADD), "add");
    CHECK_STR(scg_op_name(SCG_OP_OUTPUT), "output");
}

/* Facts that must go together in a row. */
TEST(ops_table_rows_consistent)
{
    for (int op = 0; op < SCG_OP_COUNT; op++) {
        const scg_op_info *in = &scg_op_infos[op];
        unsigned f = in->flags;
        CHECK(0 <= in->min_args && in->min_args <= in->max_args && in->max_args <= 4);
        /* Folding evaluates what CSE may merge; nothing with an effect. */
        if (f & SCG_OPF_EVAL)
            CHECK(f & SCG_OPF_PURE);
        if (f & SCG_OPF_PURE)
            CHECK(!(f & (SCG_OPF_EFFECT | SCG_OPF_VAR_A)) && in->result != SCG_RESULT_VOID);
        if (f & SCG_OPF_COMM)
            CHECK((f & SCG_OPF_EVAL) && in->min_args == 2 && in->max_args == 2);
        if (f & (SCG_OPF_OPEN | SCG_OPF_CLOSE))
            CHECK(f & SCG_OPF_EFFECT);
        if (f & SCG_OPF_VAR_A)
            CHECK(in->min_args >= 1);
        if (in->args != SCG_ARG_ANY)
            CHECK(in->min_args >= 1);
        /* Printed wherever used, so it must be free to repeat. */
        if (in->glsl == SCG_GLSL_IN_PLACE)
            CHECK((f & SCG_OPF_PURE) && in->max_args <= 1);
        switch (in->glsl) {
        case SCG_GLSL_INFIX:
            CHECK(in->spelling && in->min_args == 2 && in->max_args == 2);
            break;
        case SCG_GLSL_PREFIX:
            CHECK(in->spelling && in->min_args == 1 && in->max_args == 1);
            break;
        case SCG_GLSL_CALL:
            CHECK(in->spelling && in->min_args >= 1 && in->max_args <= 2);
            break;
        default:
            CHECK(in->spelling == NULL);
        }
    }
}

/* Types an operand of class c may have (a few), ending with SCG_VOID. */
static const scg_type *class_types(scg_arg_class c)
{
    static const scg_type num[] = {SCG_INT, SCG_FLOAT, SCG_VEC3, SCG_VOID};
    static const scg_type floats[] = {SCG_FLOAT, SCG_VEC2, SCG_VEC4, SCG_VOID};
    static const scg_type scalar[] = {SCG_INT, SCG_FLOAT, SCG_VOID};
    static const scg_type vector[] = {SCG_VEC2, SCG_VEC4, SCG_VOID};
    static const scg_type one[][2] = {
        {SCG_BOOL, SCG_VOID}, {SCG_INT, SCG_VOID}, {SCG_FLOAT, SCG_VOID}, {SCG_VEC3, SCG_VOID}};
    switch (c) {
    case SCG_ARG_NUM: return num;
    case SCG_ARG_FLOATS: return floats;
    case SCG_ARG_SCALAR: return scalar;
    case SCG_ARG_VECTOR: return vector;
    case SCG_ARG_BOOL: return one[0];
    case SCG_ARG_INT: return one[1];
    case SCG_ARG_FLOAT: return one[2];
    case SCG_ARG_VEC3: return one[3];
    default: return NULL;
    }
}

/* A constant of type t, its components k, k+1, …. */
static scg_value constant(scg_builder *b, scg_type t, int k)
{
    float xs[4] = {(float)k, (float)k + 1, (float)k + 2, (float)k + 3};
    if (t == SCG_BOOL)
        return scg_const_b(b, k & 1);
    if (t == SCG_INT)
        return scg_const_i(b, k);
    return scg_const_vec(b, scg_type_width(t), xs);
}

/* Instruction `op` on n constants, the first of type ta and value k, the
 * others of type tb and values k+1, …, its value stored in a variable so
 * that it is used; returns it. */
static scg_value instance(scg_builder *b, scg_op op, scg_type ta, scg_type tb, int n, int k)
{
    const scg_op_info *info = &scg_op_infos[op];
    scg_value args[4] = {0, 0, 0, 0};
    for (int j = 0; j < n; j++)
        args[j] = constant(b, j ? tb : ta, k + j);
    /* A declared type here is VEC's: vecN of its n floats. */
    scg_type result = info->result == SCG_RESULT_DECLARED ? (scg_type)(SCG_FLOAT + n - 1)
                                                          : scg_op_result_type(op, ta, tb);
    scg_value v = scg_emit(b, op, result, args[0], args[1], args[2], 0);
    b->prog->insts[v].arg[3] = args[3];
    scg_store(b, scg_var(b, result, 0, 0), v);
    return v;
}

static scg_program *one_instance(scg_op op, scg_type ta, scg_type tb, int n, scg_value *v)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 3, 3);
    scg_program *p = scg_program_create(&key);
    scg_builder b;
    scg_builder_init(&b, p);
    *v = instance(&b, op, ta, tb, n, 2);
    return p;
}

/* glslang accepts the emitter's GLSL of p: the table's GLSL forms, operand
 * classes and result rules are GLSL's. */
static int emits_valid_glsl(const scg_program *p, const char *spelling, sc_error *err)
{
    scg_text text = {0};
    scg_text_append(&text, "#version 450 core\n");
    int status = scg_emit_intersect_function(p, &text, err);
    scg_text_append(&text, "void main() { sc_intersect(); }\n");
    if (status == SC_OK && spelling && !strstr(scg_text_str(&text), spelling))
        status = sc_fail(err, NULL, 0, "'%s' not in the GLSL", spelling);
    if (status == SC_OK)
        status = scg_glslang_check(SCG_STAGE_FRAGMENT, scg_text_str(&text), NULL, NULL, err);
    scg_text_free(&text);
    return status;
}

/* The folded value stored by the `which`th store of p. */
static const scg_inst *stored(const scg_program *p, int which)
{
    for (int i = 1; i < p->count; i++)
        if (p->insts[i].op == SCG_OP_STORE && which-- == 0)
            return &p->insts[p->insts[i].arg[1]];
    return NULL;
}

static int count_op(const scg_program *p, scg_op op)
{
    int n = 0;
    for (int i = 1; i < p->count; i++)
        n += p->insts[i].op == op;
    return n;
}

/* One instance of op on operands of types ta, tb: valid; invalid with an
 * operand missing or extra or a wrong result type; run by the interpreter;
 * printed as GLSL that glslang accepts; folded away. */
static int check_instance(scg_op op, scg_type ta, scg_type tb, sc_error *err)
{
    const scg_op_info *info = &scg_op_infos[op];
    int n = info->min_args;
    scg_value v;
    scg_program *p = one_instance(op, ta, tb, n, &v);
    int status = SC_FAIL;
    scg_inst saved = p->insts[v];
    const char *why = NULL;
    if (scg_validate(p, err) != SC_OK)
        goto done;
    why = "a wrong result type passes";
    p->insts[v].type = saved.type == SCG_BOOL ? SCG_INT : SCG_BOOL;
    if (info->result != SCG_RESULT_DECLARED && scg_validate(p, err) == SC_OK)
        goto done;
    p->insts[v] = saved;
    why = "a missing operand passes";
    p->insts[v].arg[n - 1] = 0;
    if (scg_validate(p, err) == SC_OK)
        goto done;
    p->insts[v] = saved;
    why = "an extra operand passes";
    if (n < 4)
        p->insts[v].arg[n] = saved.arg[0];
    if (n < 4 && scg_validate(p, err) == SC_OK)
        goto done;
    p->insts[v] = saved;
    why = NULL;
    scg_interp *it;
    scg_interp_env env;
    scg_interp_result res;
    memset(&env, 0, sizeof env);
    if (scg_interp_create(p, &it, err) != SC_OK)
        goto done;
    int run = scg_interp_run(it, &env, &res, err);
    scg_interp_free(it);
    if (run != SC_OK || emits_valid_glsl(p, info->spelling, err) != SC_OK)
        goto done;
    why = "constant operands are not folded";
    if (!scg_opt_fold(p) || count_op(p, op) != 0)
        goto done;
    why = NULL;
    status = scg_validate(p, err);
done:
    if (status != SC_OK) {
        if (why)
            sc_fail(err, NULL, 0, "%s", why);
        fprintf(stderr, "  %s on %s, %s: %s\n", info->name, scg_type_name(ta), scg_type_name(tb),
                err->message);
    }
    scg_program_free(p);
    return status;
}

/* Every arithmetic op (SCG_OPF_EVAL) whose operand class the table gives,
 * at each kind of operand type its class and result rule allow. */
TEST(ops_arith_rows_match_the_passes)
{
    sc_error err;
    for (int o = 0; o < SCG_OP_COUNT; o++) {
        scg_op op = (scg_op)o;
        const scg_op_info *info = &scg_op_infos[op];
        if (!(info->flags & SCG_OPF_EVAL) || info->args == SCG_ARG_ANY)
            continue;
        for (const scg_type *t = class_types(info->args); *t != SCG_VOID; t++)
            CHECK_INT(check_instance(op, *t, *t, &err), SC_OK);
        if (info->result == SCG_RESULT_BROADCAST) {
            CHECK_INT(check_instance(op, SCG_FLOAT, SCG_VEC3, &err), SC_OK);
            CHECK_INT(check_instance(op, SCG_VEC2, SCG_FLOAT, &err), SC_OK);
        }
        /* Operands outside the class. */
        scg_type wrong = info->args == SCG_ARG_BOOL ? SCG_INT : SCG_BOOL;
        scg_value v;
        scg_program *p = one_instance(op, wrong, wrong, info->min_args, &v);
        CHECK_INT(scg_validate(p, &err), SC_FAIL);
        scg_program_free(p);
    }
}

/* op(a, b), op(a, b) again and, for two operands, op(b, a), each stored. */
static scg_program *three_instances(scg_op op, scg_type t, int n)
{
    scg_value v;
    scg_program *p = one_instance(op, t, t, n, &v);
    scg_inst first = p->insts[v];
    scg_builder b;
    scg_builder_init(&b, p);
    scg_value same = scg_emit(&b, op, first.type, first.arg[0], first.arg[1], first.arg[2], 0);
    p->insts[same].arg[3] = first.arg[3];
    scg_store(&b, scg_var(&b, first.type, 0, 0), same);
    if (n == 2) {
        scg_value swapped = scg_emit(&b, op, first.type, first.arg[1], first.arg[0], 0, 0);
        scg_store(&b, scg_var(&b, first.type, 0, 0), swapped);
    }
    return p;
}

/* CSE merges op(a, b) with op(a, b), and with op(b, a) exactly when the
 * table says the op commutes, which evaluation confirms. */
TEST(ops_cse_and_commutativity)
{
    sc_error err;
    for (int o = 0; o < SCG_OP_COUNT; o++) {
        scg_op op = (scg_op)o;
        const scg_op_info *info = &scg_op_infos[op];
        if (!(info->flags & SCG_OPF_EVAL) || info->args == SCG_ARG_ANY)
            continue;
        int n = info->min_args;
        bool comm = (info->flags & SCG_OPF_COMM) != 0;
        scg_type t = class_types(info->args)[0];
        scg_program *p = three_instances(op, t, n);
        CHECK_INT(scg_validate(p, &err), SC_OK);
        scg_opt_cse(p);
        int left = count_op(p, op);
        scg_program_free(p);
        if (left != (n == 2 && !comm ? 2 : 1))
            fprintf(stderr, "  %s: %d instances after CSE\n", info->name, left);
        CHECK_INT(left, n == 2 && !comm ? 2 : 1);
        if (n != 2)
            continue;
        p = three_instances(op, t, n);
        scg_opt_fold(p);
        const scg_inst *ab = stored(p, 0), *ba = stored(p, 2);
        bool equal = ab->op == SCG_OP_CONST && ba->op == SCG_OP_CONST &&
                     memcmp(&ab->imm, &ba->imm, sizeof ab->imm) == 0;
        scg_program_free(p);
        if (equal != comm)
            fprintf(stderr, "  %s: op(a, b) %s op(b, a)\n", info->name, equal ? "==" : "!=");
        CHECK(equal == comm);
    }
}
