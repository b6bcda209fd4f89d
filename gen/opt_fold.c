/* opt_fold.c — constant folding and algebraic identities. Operations whose
 * operands are all constants become constants (evaluated with the
 * interpreter's own arithmetic, so folding never changes a result), and
 * x+0, x-0, x·1, x/1 (float and int), x·0 (int), --x, !!x, comp(vec(…)),
 * vecN(s.x, s.y, …) of a vecN s, select on a constant and logic on
 * constants collapse to one of their operands. */
#include <stdlib.h>
#include <string.h>

#include "ir_eval.h"

static bool is_const(const scg_program *p, scg_value v)
{
    return v > 0 && p->insts[v].op == SCG_OP_CONST;
}

/* True when v is a constant whose every component equals x. */
static bool is_const_value(const scg_program *p, scg_value v, float x)
{
    if (!is_const(p, v) || p->insts[v].type < SCG_FLOAT)
        return false;
    for (int k = 0; k < scg_type_width(p->insts[v].type); k++)
        if (p->insts[v].imm.f[k] != x)
            return false;
    return true;
}

/* True when v is the int constant x. */
static bool is_const_int(const scg_program *p, scg_value v, int x)
{
    return is_const(p, v) && p->insts[v].type == SCG_INT && p->insts[v].imm.i == x;
}

/* True when v is the number x: every component of a float constant, or an
 * int constant. */
static bool is_number(const scg_program *p, scg_value v, int x)
{
    return is_const_value(p, v, (float)x) || is_const_int(p, v, x);
}

/* The vector `in` gathers whole and in order — vecN(s.x, s.y, …) with s
 * itself a vecN — or 0. */
static scg_value whole_vector(const scg_program *p, const scg_inst *in)
{
    int n = scg_type_width(in->type);
    const scg_inst *first = &p->insts[in->arg[0]];
    if (first->op != SCG_OP_COMP || p->insts[first->arg[0]].type != in->type)
        return 0;
    for (int k = 0; k < n; k++) {
        const scg_inst *c = &p->insts[in->arg[k]];
        if (c->op != SCG_OP_COMP || c->arg[0] != first->arg[0] || c->slot != k)
            return 0;
    }
    return first->arg[0];
}

/* The operand an identity reduces `in` to, or 0. Only same-typed
 * replacements: x·1 with a vector 1 and a float x would change the type.
 * Every identity is exact in float as in int (x·0 is not: NaN, ∞ and -0,
 * so it is folded for ints only). */
static scg_value identity(const scg_program *p, const scg_inst *in)
{
    scg_value a = in->arg[0], b = in->arg[1];
    scg_type t = in->type;
    const scg_inst *ia = a ? &p->insts[a] : NULL;
    switch (in->op) {
    case SCG_OP_ADD:
        if (is_number(p, b, 0) && ia->type == t) return a;
        if (is_number(p, a, 0) && p->insts[b].type == t) return b;
        break;
    case SCG_OP_SUB:
        if (is_number(p, b, 0) && ia->type == t) return a;
        break;
    case SCG_OP_MUL:
        if (is_number(p, b, 1) && ia->type == t) return a;
        if (is_number(p, a, 1) && p->insts[b].type == t) return b;
        if (is_const_int(p, a, 0)) return a;
        if (is_const_int(p, b, 0)) return b;
        break;
    case SCG_OP_DIV:
        if (is_number(p, b, 1) && ia->type == t) return a;
        break;
    case SCG_OP_NEG:
        if (ia->op == SCG_OP_NEG) return ia->arg[0];
        break;
    case SCG_OP_NOT:
        if (ia->op == SCG_OP_NOT) return ia->arg[0];
        break;
    case SCG_OP_COMP:
        if (ia->op == SCG_OP_VEC) return ia->arg[in->slot];
        break;
    case SCG_OP_VEC:
        return whole_vector(p, in);
    case SCG_OP_SELECT:
        if (is_const(p, a)) return ia->imm.i ? b : in->arg[2];
        if (b == in->arg[2]) return b;
        break;
    case SCG_OP_AND:
        if (is_const(p, a)) return ia->imm.i ? b : a;
        if (is_const(p, b)) return p->insts[b].imm.i ? a : b;
        break;
    case SCG_OP_OR:
        if (is_const(p, a)) return ia->imm.i ? a : b;
        if (is_const(p, b)) return p->insts[b].imm.i ? b : a;
        break;
    default:
        break;
    }
    return 0;
}

bool scg_opt_fold(scg_program *p)
{
    bool progress = false;
    int *repl = sc_alloc((size_t)p->count, sizeof *repl);
    for (int i = 1; i < p->count; i++) {
        scg_inst *in = &p->insts[i];
        for (int k = 0; k < 4; k++)
            if (in->arg[k] && repl[in->arg[k]])
                in->arg[k] = repl[in->arg[k]];
        if (!scg_op_has(in->op, SCG_OPF_EVAL))
            continue;
        scg_value same = identity(p, in);
        if (same) {
            repl[i] = same;
            in->op = SCG_OP_NOP;
            progress = true;
            continue;
        }
        bool all_const = true;
        scg_reg ops[4];
        scg_type types[4] = {SCG_VOID, SCG_VOID, SCG_VOID, SCG_VOID};
        memset(ops, 0, sizeof ops);
        for (int k = 0; k < 4 && in->arg[k]; k++) {
            const scg_inst *o = &p->insts[in->arg[k]];
            if (o->op != SCG_OP_CONST) {
                all_const = false;
                break;
            }
            types[k] = o->type;
            if (o->type == SCG_INT || o->type == SCG_BOOL)
                ops[k].i[0] = o->imm.i;
            else
                memcpy(ops[k].f, o->imm.f, sizeof ops[k].f);
        }
        if (!all_const)
            continue;
        scg_reg r;
        memset(&r, 0, sizeof r);
        scg_eval_arith(in, ops, types, &r);
        in->op = SCG_OP_CONST;
        memset(in->arg, 0, sizeof in->arg);
        in->slot = 0;
        memset(&in->imm, 0, sizeof in->imm);
        if (in->type == SCG_INT || in->type == SCG_BOOL)
            in->imm.i = r.i[0];
        else
            memcpy(in->imm.f, r.f, sizeof in->imm.f);
        progress = true;
    }
    free(repl);
    if (progress)
        scg_compact(p);
    return progress;
}
