/* opt_dce.c — dead code elimination. Roots are outputs and control flow
 * (SCG_OPF_EFFECT in the op table) and stores to variables that some live
 * instruction loads; everything they do not reach is removed, then blocks
 * left empty (an if with nothing inside, an empty else, a loop with an
 * empty body) are removed too. */
#include <stdlib.h>

#include "ir.h"

/* Removes `if c {}`, `else {}` and loops whose body is empty; true when
 * something went. */
static bool remove_empty_blocks(scg_program *p)
{
    bool progress = false;
    int prev = 0;   /* last instruction still present before i */
    for (int i = 1; i < p->count; i++) {
        scg_inst *in = &p->insts[i];
        if (in->op == SCG_OP_NOP)
            continue;
        if (prev) {
            scg_op po = p->insts[prev].op;
            /* A block opened and at once closed for good (not by an ELSE,
             * whose branch may hold work: `if c {} else {…}` stays). */
            if (scg_op_has(po, SCG_OPF_OPEN) && scg_op_has(in->op, SCG_OPF_CLOSE) &&
                !scg_op_has(in->op, SCG_OPF_OPEN)) {
                p->insts[prev].op = SCG_OP_NOP;
                /* `else {}` ends the if: keep its endif. */
                if (!scg_op_has(po, SCG_OPF_CLOSE))
                    in->op = SCG_OP_NOP;
                progress = true;
                prev = 0;
                for (int j = i - 1; j > 0; j--)
                    if (p->insts[j].op != SCG_OP_NOP) {
                        prev = j;
                        break;
                    }
                if (in->op == SCG_OP_NOP)
                    continue;
            }
        }
        prev = i;
    }
    return progress;
}

bool scg_opt_dce(scg_program *p)
{
    size_t n = (size_t)p->count;
    bool *live = sc_alloc(n, sizeof *live);
    bool *var_read = sc_alloc(n, sizeof *var_read);
    int *work = sc_alloc(n, sizeof *work);
    /* Stores of each variable, chained: a store becomes live when the
     * first live load of its variable is found. */
    int *first_store = sc_alloc(n, sizeof *first_store);
    int *next_store = sc_alloc(n, sizeof *next_store);
    int nwork = 0;
    for (int i = p->count - 1; i > 0; i--) {
        const scg_inst *in = &p->insts[i];
        if (in->op == SCG_OP_STORE) {
            next_store[i] = first_store[in->arg[0]];
            first_store[in->arg[0]] = i;
        }
        if (scg_op_has(in->op, SCG_OPF_EFFECT)) {
            live[i] = true;
            work[nwork++] = i;
        }
    }
    while (nwork > 0) {
        const scg_inst *in = &p->insts[work[--nwork]];
        for (int k = 0; k < 4; k++) {
            scg_value v = in->arg[k];
            if (v && !live[v]) {
                live[v] = true;
                work[nwork++] = v;
            }
        }
        if (in->op == SCG_OP_LOAD && !var_read[in->arg[0]]) {
            var_read[in->arg[0]] = true;
            for (int st = first_store[in->arg[0]]; st; st = next_store[st])
                if (!live[st]) {
                    live[st] = true;
                    work[nwork++] = st;
                }
        }
    }
    free(work);
    free(first_store);
    free(next_store);
    bool progress = false;
    for (int i = 1; i < p->count; i++)
        if (!live[i]) {
            p->insts[i].op = SCG_OP_NOP;
            progress = true;
        }
    progress |= remove_empty_blocks(p);
    free(live);
    free(var_read);
    if (progress)
        scg_compact(p);
    return progress;
}
