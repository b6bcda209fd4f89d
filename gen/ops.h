/* ops.h — the IR's op table: every per-op fact in one row, so that adding
 * an op is one row here plus, for an op the passes do not already know by
 * its facts, its evaluation (ir_eval.c for arithmetic). No include guard:
 * like QBE's ops.h the file is included once per use, with X defined to
 * pick the columns that use needs:
 *
 *   #define X(name, mnemonic, min_args, max_args, args, result, flags, glsl, spelling) \
 *       SCG_OP_##name,
 *   #include "ops.h"
 *   #undef X
 *
 * Columns (the types are in ir.h):
 *  - name      SCG_OP_<name>
 *  - mnemonic  the listing's name ("add"); unique
 *  - min_args, max_args: operands a, b, c, d present: a..(min-1) always,
 *              none from max on (VEC: exactly as many as its vecN has)
 *  - args      scg_arg_class: the type every operand must have; with two or
 *              more operands they also share one type (BROADCAST lets a
 *              float meet a vector). ANY: the validator checks by hand.
 *  - result    scg_result_rule: the type of the value defined (VOID: none)
 *  - flags     scg_op_flag names without SCG_OPF_ (PURE | EVAL …), or 0;
 *              the includer that reads this column defines those names
 *  - glsl, spelling: scg_glsl_form and the operator or function name of
 *              INFIX, PREFIX and CALL ops (NULL otherwise)
 *
 * Operands are a, b, c, d (scg_inst.arg[0..3]); "slot" and "imm" are the
 * instruction's immediate fields. Types follow GLSL. */

/* name     mnemonic   args  arg class result     flags                  GLSL form spelling */
X(NOP,      "nop",     0, 0, ANY,      VOID,      0,                     BY_HAND, NULL)
    /* removed by a pass; never present after compaction */

/* leaves */
X(CONST,    "const",   0, 0, ANY,      DECLARED,  PURE,                  IN_PLACE, NULL)
    /* imm.f[0..w-1] for float types, imm.i for int/bool */
X(INPUT,    "input",   0, 0, ANY,      SLOT,      PURE,                  IN_PLACE, NULL)
    /* fragment-stage input number `slot` (scg_input_slot) */
X(UNIFORM,  "uniform", 0, 0, ANY,      FLOAT,     PURE,                  IN_PLACE, NULL)
    /* uniform number `slot` (scg_uniform_slot) */
X(FETCH,    "fetch",   1, 1, INT,      SLOT,      PURE,                  BY_HAND, NULL)
    /* texelFetch(texture `slot` (scg_texture), int a): vec4 for RGBA
       textures, float for R32F */

/* arithmetic: float types, and int for ADD/SUB/MUL/DIV/NEG/MIN/MAX/ABS */
X(ADD,      "add",     2, 2, NUM,      BROADCAST, PURE | EVAL | COMM,    INFIX,   "+")
    /* a + b */
X(SUB,      "sub",     2, 2, NUM,      BROADCAST, PURE | EVAL,           INFIX,   "-")
    /* a - b */
X(MUL,      "mul",     2, 2, NUM,      BROADCAST, PURE | EVAL | COMM,    INFIX,   "*")
    /* a * b (componentwise) */
X(DIV,      "div",     2, 2, NUM,      BROADCAST, PURE | EVAL,           INFIX,   "/")
    /* a / b (int: truncating; the IR never divides ints by zero on
       purpose) */
X(NEG,      "neg",     1, 1, NUM,      AS_A,      PURE | EVAL,           PREFIX,  "-")
    /* -a */
X(MIN,      "min",     2, 2, NUM,      BROADCAST, PURE | EVAL | COMM,    CALL,    "min")
    /* min(a, b) */
X(MAX,      "max",     2, 2, NUM,      BROADCAST, PURE | EVAL | COMM,    CALL,    "max")
    /* max(a, b) */
X(ABS,      "abs",     1, 1, NUM,      AS_A,      PURE | EVAL,           CALL,    "abs")
    /* abs(a) */
X(SQRT,     "sqrt",    1, 1, FLOATS,   AS_A,      PURE | EVAL,           CALL,    "sqrt")
    /* sqrt(a) */
X(FLOOR,    "floor",   1, 1, FLOATS,   AS_A,      PURE | EVAL,           CALL,    "floor")
    /* floor(a) */
X(DOT,      "dot",     2, 2, FLOATS,   FLOAT,     PURE | EVAL | COMM,    CALL,    "dot")
    /* dot(a, b) */
X(CROSS,    "cross",   2, 2, VEC3,     VEC3,      PURE | EVAL,           CALL,    "cross")
    /* cross(a, b) */
X(LENGTH,   "length",  1, 1, FLOATS,   FLOAT,     PURE | EVAL,           CALL,    "length")
    /* length(a) */

/* vectors */
X(VEC,      "vec",     2, 4, FLOAT,    DECLARED,  PURE | EVAL,           BY_HAND, NULL)
    /* vecN(a, b[, c[, d]]) from N floats (type = vecN) */
X(COMP,     "comp",    1, 1, VECTOR,   FLOAT,     PURE | EVAL,           IN_PLACE, NULL)
    /* component `slot` (0 = x … 3 = w) of vector a */

/* comparisons of two floats or two ints */
X(LT,       "lt",      2, 2, SCALAR,   BOOL,      PURE | EVAL,           INFIX,   "<")
    /* a < b */
X(LE,       "le",      2, 2, SCALAR,   BOOL,      PURE | EVAL,           INFIX,   "<=")
    /* a <= b */
X(EQ,       "eq",      2, 2, SCALAR,   BOOL,      PURE | EVAL | COMM,    INFIX,   "==")
    /* a == b */
X(NE,       "ne",      2, 2, SCALAR,   BOOL,      PURE | EVAL | COMM,    INFIX,   "!=")
    /* a != b */

/* bool logic */
X(AND,      "and",     2, 2, BOOL,     BOOL,      PURE | EVAL | COMM,    INFIX,   "&&")
    /* a && b */
X(OR,       "or",      2, 2, BOOL,     BOOL,      PURE | EVAL | COMM,    INFIX,   "||")
    /* a || b */
X(NOT,      "not",     1, 1, BOOL,     BOOL,      PURE | EVAL,           PREFIX,  "!")
    /* !a */
X(SELECT,   "select",  3, 3, ANY,      AS_B,      PURE | EVAL,           BY_HAND, NULL)
    /* bool a ? b : c (b, c of one type) */

/* conversions */
X(I2F,      "i2f",     1, 1, INT,      FLOAT,     PURE | EVAL,           CALL,    "float")
    /* float(int a) */
X(F2I,      "f2i",     1, 1, FLOAT,    INT,       PURE | EVAL,           CALL,    "int")
    /* int(float a), truncation toward zero */

/* local variables (mutable state) */
X(VAR,      "var",     0, 1, ANY,      DECLARED,  0,                     BY_HAND, NULL)
    /* declares a variable of `type`; slot = array length (0: not an
       array); a = initial value or 0 (then the content is zero, and the
       emitter initialises it) */
X(LOAD,     "load",    1, 2, ANY,      AS_A,      VAR_A,                 BY_HAND, NULL)
    /* value of variable a (element b when an array) */
X(STORE,    "store",   2, 3, ANY,      VOID,      VAR_A,                 BY_HAND, NULL)
    /* variable a (element c when an array) = b */

/* structured control flow */
X(IF,       "if",      1, 1, BOOL,     VOID,      EFFECT | OPEN,         BY_HAND, NULL)
    /* if (bool a) { */
X(ELSE,     "else",    0, 0, ANY,      VOID,      EFFECT | CLOSE | OPEN, BY_HAND, NULL)
    /* } else { */
X(ENDIF,    "endif",   0, 0, ANY,      VOID,      EFFECT | CLOSE,        BY_HAND, NULL)
    /* } */
X(LOOP,     "loop",    1, 1, INT,      INT,       EFFECT | OPEN,         BY_HAND, NULL)
    /* for (int i = 0; i < int a; i++) { — defines the int counter i,
       visible inside the loop */
X(BREAK,    "break",   0, 0, ANY,      VOID,      EFFECT,                BY_HAND, NULL)
    /* break; out of the innermost LOOP */
X(ENDLOOP,  "endloop", 0, 0, ANY,      VOID,      EFFECT | CLOSE,        BY_HAND, NULL)
    /* } */

/* results */
X(OUTPUT,   "output",  1, 1, ANY,      VOID,      EFFECT,                BY_HAND, NULL)
    /* output number `slot` (scg_output_slot) = a */
