/* interp.c — runs an IR program on the CPU in single precision, one
 * invocation at a time, so that every generated kernel can be checked
 * against the double-precision reference without a GL context. Jump targets
 * of the structured control flow are found once, then each run walks the
 * instruction array with a register per value. */
#include <stdlib.h>
#include <string.h>

#include "ir_eval.h"

/* A run that executes more instructions than this is taken to be stuck. */
#define MAX_STEPS 200000000LL

struct scg_interp {
    const scg_program *prog;
    int *jump;           /* IF → its ELSE or ENDIF, ELSE → ENDIF, LOOP → ENDLOOP,
                            ENDLOOP → LOOP, BREAK → ENDLOOP of its loop */
    int *var_offset;     /* first slot of each variable in `memory` */
    scg_type *arg_types; /* 4 per instruction */
    scg_reg *regs;
    int *loop_count;     /* per LOOP instruction: its count for this entry */
    scg_reg *memory;
    int memory_size;
};

int scg_interp_create(const scg_program *p, scg_interp **out, sc_error *err)
{
    if (scg_validate(p, err) != SC_OK)
        return SC_FAIL;
    scg_interp *it = sc_alloc(1, sizeof *it);
    size_t n = (size_t)p->count;
    it->prog = p;
    it->jump = sc_alloc(n, sizeof *it->jump);
    it->var_offset = sc_alloc(n, sizeof *it->var_offset);
    it->arg_types = sc_alloc(n * 4, sizeof *it->arg_types);
    it->regs = sc_alloc(n, sizeof *it->regs);
    it->loop_count = sc_alloc(n, sizeof *it->loop_count);
    int *stack = sc_alloc(n + 1, sizeof *stack);
    int *loops = sc_alloc(n + 1, sizeof *loops);
    int depth = 0, nloops = 0;
    for (int i = 1; i < p->count; i++) {
        const scg_inst *in = &p->insts[i];
        for (int k = 0; k < 4; k++)
            it->arg_types[4 * i + k] = in->arg[k] ? p->insts[in->arg[k]].type : SCG_VOID;
        switch (in->op) {
        case SCG_OP_IF:
            stack[++depth] = i;
            break;
        case SCG_OP_LOOP:
            stack[++depth] = i;
            loops[++nloops] = i;
            break;
        case SCG_OP_ELSE:
            it->jump[stack[depth]] = i;
            stack[depth] = i;
            break;
        case SCG_OP_ENDIF:
            it->jump[stack[depth--]] = i;
            break;
        case SCG_OP_ENDLOOP:
            it->jump[stack[depth]] = i;
            it->jump[i] = stack[depth--];
            nloops--;
            break;
        case SCG_OP_BREAK:
            it->jump[i] = loops[nloops];   /* resolved to the ENDLOOP below */
            break;
        case SCG_OP_VAR:
            it->var_offset[i] = it->memory_size;
            it->memory_size += in->slot > 0 ? in->slot : 1;
            break;
        default:
            break;
        }
    }
    for (int i = 1; i < p->count; i++)
        if (p->insts[i].op == SCG_OP_BREAK)
            it->jump[i] = it->jump[it->jump[i]];
    it->memory = sc_alloc((size_t)it->memory_size + 1, sizeof *it->memory);
    free(stack);
    free(loops);
    *out = it;
    return SC_OK;
}

void scg_interp_free(scg_interp *it)
{
    if (!it)
        return;
    free(it->jump);
    free(it->var_offset);
    free(it->arg_types);
    free(it->regs);
    free(it->loop_count);
    free(it->memory);
    free(it);
}

static int run_error(const scg_interp *it, int i, const char *what, sc_error *err)
{
    char key[SCG_KEY_MAX];
    scg_key_format(&it->prog->key, key, sizeof key);
    return sc_fail_key(err, key, "instruction v%d (%s): %s", i, scg_op_name(it->prog->insts[i].op),
                       what);
}

int scg_interp_run(scg_interp *it, const scg_interp_env *env, scg_interp_result *res,
                   sc_error *err)
{
    const scg_program *p = it->prog;
    scg_reg *r = it->regs;
    memset(res, 0, sizeof *res);
    long long steps = 0;
    int pc = 1;
    while (pc < p->count) {
        const scg_inst *in = &p->insts[pc];
        scg_reg *out = &r[pc];
        if (++steps > MAX_STEPS)
            return run_error(it, pc, "too many steps (a loop that does not end?)", err);
        switch (in->op) {
        case SCG_OP_CONST:
            memcpy(out, &in->imm, sizeof *out);
            break;
        case SCG_OP_INPUT:
            if (in->type == SCG_INT)
                out->i[0] = (int)env->inputs[in->slot][0];
            else
                memcpy(out->f, env->inputs[in->slot], sizeof out->f);
            break;
        case SCG_OP_UNIFORM:
            out->f[0] = env->uniforms[in->slot][0];
            break;
        case SCG_OP_FETCH: {
            int index = r[in->arg[0]].i[0];
            int w = in->slot == SCG_TEX_KNOTS ? 1 : 4;
            if (!env->texels[in->slot] || index < 0 || index >= env->texel_count[in->slot]) {
                char what[96];
                snprintf(what, sizeof what, "texel %d outside %s (%d texels)", index,
                         scg_texture_info(in->slot)->name, env->texel_count[in->slot]);
                return run_error(it, pc, what, err);
            }
            memcpy(out->f, env->texels[in->slot] + (size_t)index * w, (size_t)w * sizeof(float));
            break;
        }
        case SCG_OP_VAR: {
            scg_reg *v = &it->memory[it->var_offset[pc]];
            int len = in->slot > 0 ? in->slot : 1;
            if (in->arg[0])
                *v = r[in->arg[0]];
            else
                memset(v, 0, (size_t)len * sizeof *v);
            break;
        }
        case SCG_OP_LOAD:
        case SCG_OP_STORE: {
            const scg_inst *var = &p->insts[in->arg[0]];
            scg_value index_value = in->op == SCG_OP_LOAD ? in->arg[1] : in->arg[2];
            int index = index_value ? r[index_value].i[0] : 0;
            if (index < 0 || index >= (var->slot > 0 ? var->slot : 1))
                return run_error(it, pc, "array index out of range", err);
            scg_reg *slot = &it->memory[it->var_offset[in->arg[0]] + index];
            if (in->op == SCG_OP_LOAD)
                *out = *slot;
            else
                *slot = r[in->arg[1]];
            break;
        }
        case SCG_OP_IF:
            if (!r[in->arg[0]].i[0])
                pc = it->jump[pc];   /* to ELSE (then past it) or ENDIF */
            break;
        case SCG_OP_ELSE:
            pc = it->jump[pc];
            break;
        case SCG_OP_LOOP:
            it->loop_count[pc] = r[in->arg[0]].i[0];
            out->i[0] = 0;
            if (it->loop_count[pc] <= 0)
                pc = it->jump[pc];
            break;
        case SCG_OP_ENDLOOP: {
            int loop = it->jump[pc];
            if (++r[loop].i[0] < it->loop_count[loop])
                pc = loop;
            break;
        }
        case SCG_OP_BREAK:
            pc = it->jump[pc];
            break;
        case SCG_OP_ENDIF:
            break;
        case SCG_OP_OUTPUT: {
            const scg_reg *v = &r[in->arg[0]];
            scg_type t = p->insts[in->arg[0]].type;
            if (t == SCG_INT || t == SCG_BOOL)
                res->outputs[in->slot][0] = (float)v->i[0];
            else
                memcpy(res->outputs[in->slot], v->f, sizeof v->f);
            res->written[in->slot] = true;
            break;
        }
        default: {
            scg_reg ops[4];
            for (int k = 0; k < 4; k++)
                if (in->arg[k])
                    ops[k] = r[in->arg[k]];
            scg_eval_arith(in, ops, &it->arg_types[4 * pc], out);
            break;
        }
        }
        pc++;
    }
    res->steps = steps;
    return SC_OK;
}
