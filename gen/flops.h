/* flops.h — floating-point operations an intersection program executes,
 * counted from its IR: each op's cost per lane (flops.c, one row per op of
 * ops.h), summed over a program, and split into the part every run pays
 * and the part each iteration adds. `bench --peak` divides the work the
 * pixels of a frame actually did by the time of the intersection pass. */
#ifndef SCG_FLOPS_H
#define SCG_FLOPS_H

#include "ir.h"

/* FLOPs of one instruction: its op's cost (flops.c) times its lanes. */
int scg_inst_flops(const scg_program *prog, const scg_inst *inst);

/* Sum over the program's instructions, each counted once (a LOOP's body
 * once, whatever its trip count); *in_loops (may be NULL) gets the part
 * inside LOOP blocks. */
long scg_program_flops(const scg_program *prog, long *in_loops);

typedef struct scg_flops {
    double total;        /* the whole optimised program, each instruction once */
    double per_iter;     /* what one iteration costs (see scg_key_flops) */
    double fixed;        /* what a run costs besides its iterations */
} scg_flops;

/* The hybrid's iterations are a runtime loop of passes of several Newton
 * steps: per_iter is the loop body over its steps, fixed the rest of the
 * program. Unrolled methods: the key's program is built at max_iters and
 * at max_iters - 1 (+ 1 when max_iters is 1), per_iter is the difference
 * and fixed = total - max_iters * per_iter. A pixel that ran i iterations
 * did fixed + i * per_iter. Other runtime loops (generic programs) are not
 * separated: per_iter 0 when the two builds cost the same. */
int scg_key_flops(const scg_key *key, scg_flops *out, sc_error *err);

#endif
