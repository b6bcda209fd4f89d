/* ir.h — the compiler's intermediate representation: one intersection
 * program (the fragment stage's "intersect" function) as a flat array of
 * typed instructions, the builder that the metaprograms use to write it, the
 * optimisation passes, the validator, the listing and the CPU interpreter.
 *
 * Shape of a program (in the spirit of Mesa NIR and QBE):
 *  - Every instruction defines at most one value; a value is named by the
 *    index of the instruction that defines it (scg_value). Index 0 is a
 *    reserved "no value", so operands that are absent are 0.
 *  - Values are immutable (SSA). Mutable state — what flows out of a guarded
 *    iteration or round a loop — lives in local variables (SCG_OP_VAR) that
 *    are read with LOAD and written with STORE; a variable may be an array.
 *  - Control flow is structured: IF … [ELSE …] ENDIF and LOOP … ENDLOOP nest
 *    like braces. A value defined inside a block is visible only until that
 *    block closes (GLSL scoping), so the GLSL emitter prints every value as a
 *    local `type name = expr;` where it is defined, and each block as braces.
 *  - Instructions appear in order: an operand is always defined earlier.
 *
 * Types follow GLSL: bool, int, float, vec2, vec3, vec4. Arithmetic on
 * vectors is componentwise; a float operand mixed with a vector is broadcast
 * (as GLSL's vec * float). */
#ifndef SCG_IR_H
#define SCG_IR_H

#include <stdbool.h>
#include <stdio.h>

#include "sc_base.h"
#include "key.h"
#include "gpu_layout.h"

typedef enum scg_type {
    SCG_VOID = 0,   /* instructions that define nothing (STORE, IF, OUTPUT…) */
    SCG_BOOL,
    SCG_INT,
    SCG_FLOAT,
    SCG_VEC2,
    SCG_VEC3,
    SCG_VEC4
} scg_type;

/* Component count of a float type (float 1, vecN N), 1 for bool and int,
 * 0 for void. */
int scg_type_width(scg_type t);
/* GLSL spelling: "bool", "int", "float", "vec2", …, "void". */
const char *scg_type_name(scg_type t);

/* The node kinds, one per row of the op table (ops.h), where each op's
 * operands, types, flags and GLSL form are given and commented. */
typedef enum scg_op {
#define X(name, mnemonic, min_args, max_args, args, result, flags, glsl, spelling) \
    SCG_OP_##name,
#include "ops.h"
#undef X
    SCG_OP_COUNT
} scg_op;

/* The type every operand of an op must have (ops.h, column args). */
typedef enum scg_arg_class {
    SCG_ARG_ANY,      /* no operands, or checked by hand in the validator */
    SCG_ARG_NUM,      /* int or a float type */
    SCG_ARG_FLOATS,   /* a float type: float, vec2, vec3, vec4 */
    SCG_ARG_SCALAR,   /* int or float */
    SCG_ARG_VECTOR,   /* vec2, vec3 or vec4 */
    SCG_ARG_BOOL,
    SCG_ARG_INT,
    SCG_ARG_FLOAT,
    SCG_ARG_VEC3
} scg_arg_class;

/* How the type of the value an op defines is found (ops.h, column result). */
typedef enum scg_result_rule {
    SCG_RESULT_VOID,      /* defines no value */
    SCG_RESULT_BOOL,
    SCG_RESULT_INT,
    SCG_RESULT_FLOAT,
    SCG_RESULT_VEC3,
    SCG_RESULT_AS_A,      /* the type of operand a */
    SCG_RESULT_AS_B,      /* the type of operand b */
    SCG_RESULT_BROADCAST, /* a's and b's type, a float broadcast to a vector */
    SCG_RESULT_DECLARED,  /* given by the builder (constants, variables, vecN) */
    SCG_RESULT_SLOT       /* set by the slot: the input's or texture's type */
} scg_result_rule;

/* Facts the passes key on (ops.h, column flags). */
typedef enum scg_op_flag {
    SCG_OPF_PURE = 1 << 0,   /* no effect; the value depends only on operands,
                                slot and imm: equal instructions are one value */
    SCG_OPF_EVAL = 1 << 1,   /* computed from its operands by scg_eval_arith,
                                so constant folding may evaluate it */
    SCG_OPF_COMM = 1 << 2,   /* commutative in a and b */
    SCG_OPF_EFFECT = 1 << 3, /* control flow or a result: always live */
    SCG_OPF_OPEN = 1 << 4,   /* opens a block (IF, ELSE, LOOP) */
    SCG_OPF_CLOSE = 1 << 5,  /* closes a block (ELSE, ENDIF, ENDLOOP) */
    SCG_OPF_VAR_A = 1 << 6   /* operand a is a variable (VAR), not a value */
} scg_op_flag;

/* How the GLSL emitter prints an op (ops.h, column glsl). */
typedef enum scg_glsl_form {
    SCG_GLSL_BY_HAND,   /* statements and odd expressions: the emitter's own code */
    SCG_GLSL_IN_PLACE,  /* printed where used, not held in a local */
    SCG_GLSL_INFIX,     /* a SPELLING b */
    SCG_GLSL_PREFIX,    /* SPELLING a */
    SCG_GLSL_CALL       /* SPELLING(a[, b]) */
} scg_glsl_form;

typedef struct scg_op_info {
    const char *name;         /* mnemonic of the listing ("add", "fetch", …) */
    int min_args, max_args;
    scg_arg_class args;
    scg_result_rule result;
    unsigned flags;           /* scg_op_flag */
    scg_glsl_form glsl;
    const char *spelling;     /* "+", "min", … for INFIX, PREFIX and CALL */
} scg_op_info;

/* The op table, by scg_op (defined in ir.c from ops.h). */
extern const scg_op_info scg_op_infos[SCG_OP_COUNT];

static inline bool scg_op_has(scg_op op, scg_op_flag flag)
{
    return (scg_op_infos[op].flags & flag) != 0;
}
/* Lower-case mnemonic used by the listing ("add", "fetch", …); "?" for a
 * number that is not an op. */
const char *scg_op_name(scg_op op);
/* The type op defines from operands of types ta and tb, by its result rule;
 * SCG_VOID also for DECLARED and SLOT, which the operands do not decide. */
scg_type scg_op_result_type(scg_op op, scg_type ta, scg_type tb);

typedef int scg_value;     /* index of the defining instruction; 0 = none */

typedef struct scg_inst {
    scg_op op;
    scg_type type;         /* type of the value defined (SCG_VOID if none) */
    scg_value arg[4];      /* operands a, b, c, d; 0 when absent */
    int slot;              /* input/uniform/output/texture number, component,
                              or array length (see scg_op) */
    union {
        float f[4];        /* CONST of float types */
        int i;             /* CONST of int and bool (0/1) */
    } imm;
    char name[16];         /* readable hint ("Su", "uv", "F") or ""; the
                              listing and the emitter append it to the value
                              number; passes keep it */
} scg_inst;

typedef struct scg_program {
    scg_key key;           /* the key the program was built for */
    int count;             /* instructions [1, count) are live; [0] is unused */
    int capacity;
    scg_inst *insts;
} scg_program;

scg_program *scg_program_create(const scg_key *key);
void scg_program_free(scg_program *prog);
/* Number of real instructions (excluding the reserved slot 0). */
int scg_program_size(const scg_program *prog);

/* ---- builder ----
 * Appends instructions at the end of a program; every helper returns the
 * new value (0 for void instructions). Type errors in the metaprograms are
 * programming errors: the builder does not check them, the validator does.
 * `name`, when not NULL, is copied into the hint of the values built after
 * it until it is changed (scg_name(b, NULL) clears it). */
typedef struct scg_builder {
    scg_program *prog;
    const char *name;
} scg_builder;

void scg_builder_init(scg_builder *b, scg_program *prog);
void scg_name(scg_builder *b, const char *name);
/* Sets the hint of one value after the fact. */
void scg_set_name(scg_builder *b, scg_value v, const char *name);
scg_value scg_emit(scg_builder *b, scg_op op, scg_type type, scg_value a,
                   scg_value bb, scg_value c, int slot);

scg_value scg_const_f(scg_builder *b, float x);
scg_value scg_const_vec(scg_builder *b, int width, const float *xs);
scg_value scg_const_i(scg_builder *b, int x);
scg_value scg_const_b(scg_builder *b, bool x);
scg_value scg_input(scg_builder *b, scg_input_slot slot);
scg_value scg_uniform(scg_builder *b, scg_uniform_slot slot);
scg_value scg_fetch(scg_builder *b, scg_texture tex, scg_value index);
void scg_output(scg_builder *b, scg_output_slot slot, scg_value v);

scg_value scg_add(scg_builder *b, scg_value x, scg_value y);
scg_value scg_sub(scg_builder *b, scg_value x, scg_value y);
scg_value scg_mul(scg_builder *b, scg_value x, scg_value y);
scg_value scg_div(scg_builder *b, scg_value x, scg_value y);
scg_value scg_neg(scg_builder *b, scg_value x);
scg_value scg_min(scg_builder *b, scg_value x, scg_value y);
scg_value scg_max(scg_builder *b, scg_value x, scg_value y);
scg_value scg_abs(scg_builder *b, scg_value x);
scg_value scg_sqrt(scg_builder *b, scg_value x);
scg_value scg_floor(scg_builder *b, scg_value x);
scg_value scg_dot(scg_builder *b, scg_value x, scg_value y);
scg_value scg_cross(scg_builder *b, scg_value x, scg_value y);
scg_value scg_length(scg_builder *b, scg_value x);
/* x + t (y - x), built from add/sub/mul (GLSL's mix, spelled out so that the
 * interpreter and the GPU round the same way). */
scg_value scg_lerp(scg_builder *b, scg_value x, scg_value y, scg_value t);
scg_value scg_vec2(scg_builder *b, scg_value x, scg_value y);
scg_value scg_vec3(scg_builder *b, scg_value x, scg_value y, scg_value z);
scg_value scg_vec4(scg_builder *b, scg_value x, scg_value y, scg_value z,
                   scg_value w);
scg_value scg_comp(scg_builder *b, scg_value v, int component);
/* The first three components of a vec3 or vec4, as a vec3. */
scg_value scg_xyz(scg_builder *b, scg_value v);
scg_value scg_lt(scg_builder *b, scg_value x, scg_value y);
scg_value scg_le(scg_builder *b, scg_value x, scg_value y);
scg_value scg_eq(scg_builder *b, scg_value x, scg_value y);
scg_value scg_ne(scg_builder *b, scg_value x, scg_value y);
scg_value scg_and(scg_builder *b, scg_value x, scg_value y);
scg_value scg_or(scg_builder *b, scg_value x, scg_value y);
scg_value scg_not(scg_builder *b, scg_value x);
scg_value scg_select(scg_builder *b, scg_value cond, scg_value x, scg_value y);
scg_value scg_i2f(scg_builder *b, scg_value x);
scg_value scg_f2i(scg_builder *b, scg_value x);

/* Variables: `init` may be 0; `array_length` 0 for a plain variable. */
scg_value scg_var(scg_builder *b, scg_type type, int array_length, scg_value init);
scg_value scg_load(scg_builder *b, scg_value var);
scg_value scg_load_at(scg_builder *b, scg_value var, scg_value index);
void scg_store(scg_builder *b, scg_value var, scg_value v);
void scg_store_at(scg_builder *b, scg_value var, scg_value index, scg_value v);

void scg_if(scg_builder *b, scg_value cond);
void scg_else(scg_builder *b);
void scg_endif(scg_builder *b);
/* Returns the loop counter (int, 0 … count-1). */
scg_value scg_loop(scg_builder *b, scg_value count);
void scg_break(scg_builder *b);
void scg_endloop(scg_builder *b);

/* ---- validation, listing ---- */
/* Checks operand order and scoping, types of every operand, block nesting,
 * slots and array lengths. On failure fills err with the instruction number
 * and what is wrong, and returns SC_FAIL. */
int scg_validate(const scg_program *prog, sc_error *err);
/* Readable listing, one instruction a line, blocks indented:
 *   v12 Su:vec3 = sub v9, v7 */
void scg_dump_ir(FILE *f, const scg_program *prog);

/* ---- passes: each returns true when it changed the program ---- */
bool scg_opt_fold(scg_program *prog);   /* constant folding, identities */
bool scg_opt_copy(scg_program *prog);   /* loads of variables whose value is known */
bool scg_opt_cse(scg_program *prog);    /* common subexpressions (scoped) */
bool scg_opt_dce(scg_program *prog);    /* dead code and unused variables */
/* Removes NOP instructions and renumbers values (used by the passes). */
void scg_compact(scg_program *prog);

/* ---- building a program for a key ---- */
/* Called after every stage: "build" first, then after each pass that made
 * progress ("fold", "copy", "cse", "dce"), with the program as it then is. */
typedef void (*scg_stage_fn)(const char *stage, const scg_program *prog,
                             void *user);

/* Runs the pass list to a fixed point, validating after every pass. */
int scg_optimize(scg_program *prog, scg_stage_fn on_stage, void *user,
                 sc_error *err);
/* Builds the key's program with its metaprogram (unoptimised) and validates
 * it. Fails with a clear message for keys naming what is not implemented
 * (err->key is set to the key's text). */
int scg_build_unoptimized(const scg_key *key, scg_program **out, sc_error *err);
/* Build, validate, optimise: the program the emitter prints. */
int scg_build_program(const scg_key *key, scg_program **out, sc_error *err);
/* Same, calling on_stage after the build and after each pass (for
 * `--dump-ir`). */
int scg_compile_stages(const scg_key *key, scg_stage_fn on_stage, void *user,
                       scg_program **out, sc_error *err);

/* The vertex stage's program of a `view` key (intersect.h,
 * scg_build_view_start), built, validated and optimised; it writes
 * SCG_OUT_START only. Keys whose vertex stages are one program share one
 * start key (scg_view_start_key). Fails for a key without the `view`
 * start. */
int scg_build_view_start_program(const scg_key *key, scg_program **out, sc_error *err);
/* The fields of a `view` key that its vertex stage depends on (kind,
 * degrees, rational, evaluation form, iterations, tolerance), the others
 * at one value: Newton, untrimmed, no early ray termination, shaded. */
scg_key scg_view_start_key(const scg_key *key);

/* ---- interpreter ----
 * Runs a program on the CPU in single precision, as a GPU would: float
 * arithmetic rounded after every operation (no fused multiply-add), the
 * same operation order as the generated GLSL. Textures are the arrays of
 * the GPU layout (gpu_layout.h). */
typedef struct scg_interp_env {
    float inputs[SCG_INPUT_COUNT][4];     /* by scg_input_slot; ints as float */
    float uniforms[SCG_UNIFORM_COUNT][4]; /* by scg_uniform_slot */
    const float *texels[SCG_TEXTURE_COUNT]; /* texel data, 4 or 1 floats each */
    int texel_count[SCG_TEXTURE_COUNT];
} scg_interp_env;

typedef struct scg_interp_result {
    float outputs[SCG_OUTPUT_COUNT][4];   /* by scg_output_slot; bool/int as
                                             float 0/1/n */
    bool written[SCG_OUTPUT_COUNT];
    long long steps;                      /* instructions executed */
} scg_interp_result;

typedef struct scg_interp scg_interp;
/* Prepares a program for repeated runs (jump targets, register file). The
 * program must stay alive and unchanged while the interpreter is used. */
int scg_interp_create(const scg_program *prog, scg_interp **out, sc_error *err);
void scg_interp_free(scg_interp *it);
/* One invocation (one pixel). Fails on a fetch outside a texture or a loop
 * that does not end, naming the instruction. */
int scg_interp_run(scg_interp *it, const scg_interp_env *env,
                   scg_interp_result *res, sc_error *err);

#endif
