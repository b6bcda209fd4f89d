/* opt_cse.c — common subexpression elimination over the structured
 * program, by hashed value numbering in one pass over the instructions. A
 * pure instruction (SCG_OPF_PURE in the op table: constant, input, uniform,
 * texture fetch, arithmetic) equal to one already seen in an enclosing,
 * still open block is replaced by it. Scopes follow the blocks: what a
 * block computes is forgotten when it closes, so no value is used outside
 * its scope. Variable loads are
 * never merged: a store may lie between them.
 *
 * The table is open addressing with linear probing, holding value numbers
 * only (an entry is compared with the instruction that defines it). Blocks
 * close in the reverse order of their entries, so forgetting a block is
 * undoing its insertions newest first, which linear probing allows without
 * tombstones: no older entry's probe sequence runs through a newer slot. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ir.h"

/* Operands in canonical order: commutative operations compare equal with
 * their operands swapped. */
static void canonical_args(const scg_inst *in, scg_value args[4])
{
    memcpy(args, in->arg, 4 * sizeof *args);
    if (scg_op_has(in->op, SCG_OPF_COMM) && args[1] < args[0]) {
        scg_value t = args[0];
        args[0] = args[1];
        args[1] = t;
    }
}

static uint32_t mix(uint32_t h, uint32_t x)
{
    h ^= x * 0xcc9e2d51u;
    return (h << 13 | h >> 19) * 5 + 0xe6546b64u;
}

static uint32_t hash_inst(const scg_inst *in, const scg_value args[4])
{
    uint32_t h = mix(0x9e3779b9u, (uint32_t)in->op << 8 | (uint32_t)in->type);
    h = mix(h, (uint32_t)in->slot);
    for (int k = 0; k < 4; k++)
        h = mix(h, (uint32_t)args[k]);
    if (in->op == SCG_OP_CONST) {
        uint32_t bits[4];
        memcpy(bits, &in->imm, sizeof bits);  /* bit patterns: -0 and 0 differ */
        for (int k = 0; k < 4; k++)
            h = mix(h, bits[k]);
    }
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    return h;
}

static bool same_value(const scg_inst *a, const scg_value a_args[4], const scg_inst *b)
{
    if (a->op != b->op || a->type != b->type || a->slot != b->slot)
        return false;
    scg_value b_args[4];
    canonical_args(b, b_args);
    if (memcmp(a_args, b_args, sizeof b_args) != 0)
        return false;
    return a->op != SCG_OP_CONST || memcmp(&a->imm, &b->imm, sizeof a->imm) == 0;
}

bool scg_opt_cse(scg_program *p)
{
    uint32_t capacity = 16;
    while (capacity < (uint32_t)p->count * 2)
        capacity *= 2;
    scg_value *table = sc_alloc(capacity, sizeof *table);        /* 0: empty */
    uint32_t *inserted = sc_alloc((size_t)p->count, sizeof *inserted); /* slots, in order */
    int *marks = sc_alloc((size_t)p->count + 1, sizeof *marks);  /* insertions at block open */
    scg_value *repl = sc_alloc((size_t)p->count, sizeof *repl);
    int ninserted = 0, depth = 0;
    bool progress = false;

    for (int i = 1; i < p->count; i++) {
        scg_inst *in = &p->insts[i];
        for (int k = 0; k < 4; k++)
            if (in->arg[k] && repl[in->arg[k]])
                in->arg[k] = repl[in->arg[k]];
        /* ELSE closes the then branch and opens the else branch at the
         * same depth, with the same mark. */
        bool opens = scg_op_has(in->op, SCG_OPF_OPEN), closes = scg_op_has(in->op, SCG_OPF_CLOSE);
        if (closes) {
            while (ninserted > marks[depth])
                table[inserted[--ninserted]] = 0;
            if (!opens)
                depth--;
            continue;
        }
        if (opens) {
            marks[++depth] = ninserted;
            continue;
        }
        if (!scg_op_has(in->op, SCG_OPF_PURE))
            continue;
        scg_value args[4];
        canonical_args(in, args);
        uint32_t slot = hash_inst(in, args) & (capacity - 1);
        scg_value found = 0;
        for (; table[slot]; slot = (slot + 1) & (capacity - 1))
            if (same_value(in, args, &p->insts[table[slot]])) {
                found = table[slot];
                break;
            }
        if (found) {
            repl[i] = found;
            if (!p->insts[found].name[0])
                memcpy(p->insts[found].name, in->name, sizeof in->name);
            in->op = SCG_OP_NOP;
            progress = true;
            continue;
        }
        table[slot] = i;
        inserted[ninserted++] = slot;
    }
    free(table);
    free(inserted);
    free(marks);
    free(repl);
    if (progress)
        scg_compact(p);
    return progress;
}
