/* opt_fold.c — constant folding and algebraic identities. Operations whose
 * operands are all constants become constants (evaluated with the
 * interpreter's own arithmetic, so folding never changes a result), and
 * x+0, x-0, x·1, x/1, --x, comp(vec(…)), select on a constant and logic on
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

/* The operand an identity reduces `in` to, or 0. Only same-typed
 * replacements: x·1 with a vector 1 and a float x would change the type. */
static scg_value identity(const scg_program *p, const scg_inst *in)
{
    scg_value a = in->arg[0], b = in->arg[1];
    scg_type t = in->type;
    const scg_inst *ia = a ? &p->insts[a] : NULL;
    switch (in->op) {
    case SCG_OP_ADD:
        if (is_const_value(p, b, 0.0f) && ia->type == t) return a;
        if (is_const_value(p, a, 0.0f) && p->insts[b].type == t) return b;
        break;
    case SCG_OP_SUB:
        if (is_const_value(p, b, 0.0f) && ia->type == t) return a;
        break;
    case SCG_OP_MUL:
        if (is_const_value(p, b, 1.0f) && ia->type == t) return a;
        if (is_const_value(p, a, 1.0f) && p->insts[b].type == t) return b;
        break;
    case SCG_OP_DIV:
        if (is_const_value(p, b, 1.0f) && ia->type == t) return a;
        break;
    case SCG_OP_NEG:
        if (ia->op == SCG_OP_NEG) return ia->arg[0];
        break;
    case SCG_OP_COMP:
        if (ia->op == SCG_OP_VEC) return ia->arg[in->slot];
        break;
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
        if (!scg_op_is_arith(in->op))
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
