/* flops.c — the FLOP cost of each IR op, and the counts built on it
 * (flops.h). What counts: float arithmetic, one FLOP per lane per
 * operation, so that a multiply and an add cost 2 like the fused
 * multiply-add the peak measurement counts. A division and a square root
 * count 1 per lane, as hardware counters count them, though they take
 * several cycles; dot, cross and length count their multiplies and adds.
 * Comparisons, selects, conversions, integer arithmetic, fetches, loads
 * and control flow count 0: they are not floating-point work. */
#include "flops.h"

#include "hybrid.h"


/* FLOPs per lane of a float operation (n: the operands' width). */
static int op_flops(scg_op op, int n)
{
    switch (op) {
    case SCG_OP_ADD: case SCG_OP_SUB: case SCG_OP_MUL: case SCG_OP_DIV:
    case SCG_OP_NEG: case SCG_OP_MIN: case SCG_OP_MAX: case SCG_OP_ABS:
    case SCG_OP_SQRT: case SCG_OP_FLOOR:
        return n;
    case SCG_OP_DOT:    /* n multiplies, n - 1 adds */
        return 2 * n - 1;
    case SCG_OP_LENGTH: /* a dot and a square root */
        return 2 * n;
    case SCG_OP_CROSS:  /* 6 multiplies, 3 subtractions */
        return 9;
    default:
        return 0;
    }
}

static bool is_float(scg_type t)
{
    return t >= SCG_FLOAT && t <= SCG_VEC4;
}

int scg_inst_flops(const scg_program *prog, const scg_inst *inst)
{
    /* The widest float operand gives the lanes (a float broadcast to a
     * vector works on every lane); int arithmetic counts nothing. */
    int n = 0;
    for (int i = 0; i < 4 && inst->arg[i]; i++) {
        scg_type t = prog->insts[inst->arg[i]].type;
        if (is_float(t) && scg_type_width(t) > n)
            n = scg_type_width(t);
    }
    return n ? op_flops(inst->op, n) : 0;
}

long scg_program_flops(const scg_program *prog, long *in_loops)
{
    long sum = 0, inside = 0;
    int depth = 0;
    for (int i = 1; i < prog->count; i++) {
        const scg_inst *inst = &prog->insts[i];
        long f = scg_inst_flops(prog, inst);
        sum += f;
        if (depth)
            inside += f;
        depth += inst->op == SCG_OP_LOOP;
        depth -= inst->op == SCG_OP_ENDLOOP;
    }
    if (in_loops)
        *in_loops = inside;
    return sum;
}

static int key_total(const scg_key *key, long *out, long *in_loops, sc_error *err)
{
    scg_program *prog = NULL;
    if (scg_build_program(key, &prog, err) != SC_OK)
        return SC_FAIL;
    *out = scg_program_flops(prog, in_loops);
    scg_program_free(prog);
    return SC_OK;
}

int scg_key_flops(const scg_key *key, scg_flops *out, sc_error *err)
{
    long a, a_loops, b;
    if (key_total(key, &a, &a_loops, err) != SC_OK)
        return SC_FAIL;
    out->total = (double)a;
    if (key->method == SC_METHOD_HYBRID) {
        out->per_iter = (double)a_loops / scg_hybrid_pass_steps(key);
        out->fixed = (double)(a - a_loops);
        return SC_OK;
    }
    scg_key other = *key;
    other.max_iters = key->max_iters > 1 ? key->max_iters - 1 : 2;
    if (key_total(&other, &b, NULL, err) != SC_OK)
        return SC_FAIL;
    long d = key->max_iters > 1 ? a - b : b - a;
    out->per_iter = d > 0 ? (double)d : 0;
    out->fixed = (double)a - key->max_iters * out->per_iter;
    return SC_OK;
}
