/* opt_copy.c — copy propagation through variables: a load of a variable
 * whose value is known at that point (the last store to it, or its initial
 * value, with no store on any path in between) is replaced by that value.
 * The first Newton iteration then reads the start value and the zero count
 * directly, and each guarded iteration the values the one before stored,
 * instead of copying every variable into a local first; variables left
 * with no load are removed by dead code elimination.
 *
 * Knowledge flows forward through structured blocks, conservatively: a
 * variable stored anywhere in a block is unknown after it, and in its
 * else branch or loop body when stored in the then branch or the loop.
 * A value is known only while the store that recorded it is in scope, so
 * the replacement is always visible where the load was. Arrays are left
 * alone. */
#include <stdlib.h>
#include <string.h>

#include "ir.h"

/* Forgets every variable stored in instructions [from, to). */
static void forget_stored(const scg_program *p, int from, int to, scg_value *known)
{
    for (int i = from; i < to; i++)
        if (p->insts[i].op == SCG_OP_STORE)
            known[p->insts[i].arg[0]] = 0;
}

/* The instruction that closes the block opened at `open` (IF: its ELSE or
 * ENDIF; LOOP: its ENDLOOP). */
static int block_end(const scg_program *p, int open)
{
    int depth = 0;
    for (int i = open + 1; i < p->count; i++) {
        scg_op op = p->insts[i].op;
        bool opens = scg_op_has(op, SCG_OPF_OPEN), closes = scg_op_has(op, SCG_OPF_CLOSE);
        if (closes && depth == 0)
            return i;
        if (opens && !closes)
            depth++;
        else if (closes && !opens)
            depth--;
    }
    return p->count;
}

bool scg_opt_copy(scg_program *p)
{
    bool progress = false;
    scg_value *known = sc_alloc((size_t)p->count, sizeof *known);   /* by variable */
    scg_value *repl = sc_alloc((size_t)p->count, sizeof *repl);     /* by load */
    int *opened = sc_alloc((size_t)p->count, sizeof *opened);       /* block stack */
    int depth = 0;
    for (int i = 1; i < p->count; i++) {
        scg_inst *in = &p->insts[i];
        for (int k = 0; k < 4; k++)
            if (in->arg[k] && repl[in->arg[k]])
                in->arg[k] = repl[in->arg[k]];
        switch (in->op) {
        case SCG_OP_VAR:
            known[i] = in->slot > 0 ? 0 : in->arg[0];
            break;
        case SCG_OP_STORE:
            known[in->arg[0]] = p->insts[in->arg[0]].slot > 0 ? 0 : in->arg[1];
            break;
        case SCG_OP_LOAD:
            if (known[in->arg[0]]) {
                repl[i] = known[in->arg[0]];
                in->op = SCG_OP_NOP;
                progress = true;
            }
            break;
        default:
            /* Closing a branch or a loop forgets what it stored (ELSE:
             * the then branch, from its IF, which stays the opening the
             * endif is matched with). */
            if (scg_op_has(in->op, SCG_OPF_CLOSE)) {
                forget_stored(p, opened[depth - 1] + 1, i, known);
                if (!scg_op_has(in->op, SCG_OPF_OPEN))
                    depth--;
            } else if (scg_op_has(in->op, SCG_OPF_OPEN)) {
                /* The back edge brings the stores of the body to its start. */
                if (in->op == SCG_OP_LOOP)
                    forget_stored(p, i + 1, block_end(p, i), known);
                opened[depth++] = i;
            }
            break;
        }
    }
    free(opened);
    free(repl);
    free(known);
    if (progress)
        scg_compact(p);
    return progress;
}
