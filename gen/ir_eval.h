/* ir_eval.h — the arithmetic of the IR's pure operations in single
 * precision, shared by the interpreter and constant folding so that a
 * folded constant is bit for bit what the program would have computed. */
#ifndef SCG_IR_EVAL_H
#define SCG_IR_EVAL_H

#include "ir.h"

/* One value: float components, or an int / bool in i[0]. */
typedef union scg_reg {
    float f[4];
    int i[4];
} scg_reg;

/* Evaluates instruction `in` of an op that reads only its operands
 * (SCG_OPF_EVAL in the op table: no texture, input, variable or control
 * flow), whose operands have values ops[0..3] and types types[0..3]. */
void scg_eval_arith(const scg_inst *in, const scg_reg *ops, const scg_type *types,
                    scg_reg *out);

#endif
