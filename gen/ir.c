/* ir.c — the IR's core: the op table (built from ops.h), programs, the
 * builder with its typing rules, the validator that runs after every stage,
 * the listing behind --dump-ir and the compaction that passes use to drop
 * what they removed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ir.h"

int scg_type_width(scg_type t)
{
    switch (t) {
    case SCG_VOID: return 0;
    case SCG_VEC2: return 2;
    case SCG_VEC3: return 3;
    case SCG_VEC4: return 4;
    default: return 1;
    }
}

const char *scg_type_name(scg_type t)
{
    static const char *const names[] = {"void", "bool", "int", "float", "vec2", "vec3", "vec4"};
    return (unsigned)t <= SCG_VEC4 ? names[t] : "?";
}

static bool is_float_type(scg_type t) { return t >= SCG_FLOAT && t <= SCG_VEC4; }

/* The flags column of ops.h names flags without their prefix. */
#define PURE SCG_OPF_PURE
#define EVAL SCG_OPF_EVAL
#define COMM SCG_OPF_COMM
#define EFFECT SCG_OPF_EFFECT
#define OPEN SCG_OPF_OPEN
#define CLOSE SCG_OPF_CLOSE
#define VAR_A SCG_OPF_VAR_A
const scg_op_info scg_op_infos[SCG_OP_COUNT] = {
#define X(name, mnemonic, min_args, max_args, args, result, flags, glsl, spelling)              \
    [SCG_OP_##name] = {mnemonic,           min_args, max_args,      SCG_ARG_##args,            \
                       SCG_RESULT_##result, flags,   SCG_GLSL_##glsl, spelling},
#include "ops.h"
#undef X
};
#undef PURE
#undef EVAL
#undef COMM
#undef EFFECT
#undef OPEN
#undef CLOSE
#undef VAR_A

const char *scg_op_name(scg_op op)
{
    return (unsigned)op < SCG_OP_COUNT ? scg_op_infos[op].name : "?";
}

scg_type scg_op_result_type(scg_op op, scg_type ta, scg_type tb)
{
    switch (scg_op_infos[op].result) {
    case SCG_RESULT_BOOL: return SCG_BOOL;
    case SCG_RESULT_INT: return SCG_INT;
    case SCG_RESULT_FLOAT: return SCG_FLOAT;
    case SCG_RESULT_VEC3: return SCG_VEC3;
    case SCG_RESULT_AS_A: return ta;
    case SCG_RESULT_AS_B: return tb;
    /* GLSL's rule for binary arithmetic: a float mixed with a vector broadcasts. */
    case SCG_RESULT_BROADCAST: return ta == SCG_FLOAT && tb > SCG_FLOAT ? tb : ta;
    default: return SCG_VOID;
    }
}

/* Types of the layout's slots, in IR terms. */
static const scg_type input_types[SCG_INPUT_COUNT] = {
    [SCG_IN_RAY_ORIGIN] = SCG_VEC3, [SCG_IN_RAY_DIR] = SCG_VEC3, [SCG_IN_UV0] = SCG_VEC2,
    [SCG_IN_DOMAIN] = SCG_VEC4,     [SCG_IN_RECORD] = SCG_INT,   [SCG_IN_T_LIMIT] = SCG_FLOAT,
};
static const scg_type output_types[SCG_OUTPUT_COUNT] = {
    [SCG_OUT_HIT] = SCG_BOOL,    [SCG_OUT_UV] = SCG_VEC2,     [SCG_OUT_T] = SCG_FLOAT,
    [SCG_OUT_POINT] = SCG_VEC3,  [SCG_OUT_NORMAL] = SCG_VEC3, [SCG_OUT_ITERS] = SCG_INT,
    [SCG_OUT_SURFACE] = SCG_INT, [SCG_OUT_START] = SCG_VEC2,
};

/* ---- programs ---- */

scg_program *scg_program_create(const scg_key *key)
{
    scg_program *p = sc_alloc(1, sizeof *p);
    if (key)
        p->key = *key;
    p->capacity = 256;
    p->insts = sc_alloc((size_t)p->capacity, sizeof *p->insts);
    p->count = 1;
    return p;
}

void scg_program_free(scg_program *prog)
{
    if (!prog)
        return;
    free(prog->insts);
    free(prog);
}

int scg_program_size(const scg_program *prog) { return prog->count - 1; }

/* ---- builder ---- */

void scg_builder_init(scg_builder *b, scg_program *prog)
{
    b->prog = prog;
    b->name = NULL;
}

void scg_name(scg_builder *b, const char *name) { b->name = name; }

void scg_set_name(scg_builder *b, scg_value v, const char *name)
{
    if (v > 0 && v < b->prog->count)
        snprintf(b->prog->insts[v].name, sizeof b->prog->insts[v].name, "%s", name ? name : "");
}

scg_value scg_emit(scg_builder *b, scg_op op, scg_type type, scg_value a, scg_value bb,
                   scg_value c, int slot)
{
    scg_program *p = b->prog;
    if (p->count == p->capacity) {
        p->capacity *= 2;
        p->insts = sc_realloc(p->insts, (size_t)p->capacity, sizeof *p->insts);
    }
    scg_inst *in = &p->insts[p->count];
    memset(in, 0, sizeof *in);
    in->op = op;
    in->type = type;
    in->arg[0] = a;
    in->arg[1] = bb;
    in->arg[2] = c;
    in->slot = slot;
    /* Constants are shared by CSE across unrelated uses: no hint. */
    if (b->name && type != SCG_VOID && op != SCG_OP_CONST)
        snprintf(in->name, sizeof in->name, "%s", b->name);
    return p->count++;
}

static scg_type type_of(scg_builder *b, scg_value v)
{
    return v > 0 && v < b->prog->count ? b->prog->insts[v].type : SCG_VOID;
}

/* An op whose type its operands decide (scg_op_result_type). */
static scg_value typed3(scg_builder *b, scg_op op, scg_value x, scg_value y, scg_value z)
{
    scg_type t = scg_op_result_type(op, type_of(b, x), type_of(b, y));
    return scg_emit(b, op, t, x, y, z, 0);
}

static scg_value typed(scg_builder *b, scg_op op, scg_value x, scg_value y)
{
    return typed3(b, op, x, y, 0);
}

scg_value scg_const_f(scg_builder *b, float x) { return scg_const_vec(b, 1, &x); }

scg_value scg_const_vec(scg_builder *b, int width, const float *xs)
{
    static const scg_type types[] = {SCG_VOID, SCG_FLOAT, SCG_VEC2, SCG_VEC3, SCG_VEC4};
    scg_value v = scg_emit(b, SCG_OP_CONST, types[width], 0, 0, 0, 0);
    for (int i = 0; i < width; i++)
        b->prog->insts[v].imm.f[i] = xs[i];
    return v;
}

scg_value scg_const_i(scg_builder *b, int x)
{
    scg_value v = scg_emit(b, SCG_OP_CONST, SCG_INT, 0, 0, 0, 0);
    b->prog->insts[v].imm.i = x;
    return v;
}

scg_value scg_const_b(scg_builder *b, bool x)
{
    scg_value v = scg_emit(b, SCG_OP_CONST, SCG_BOOL, 0, 0, 0, 0);
    b->prog->insts[v].imm.i = x;
    return v;
}

scg_value scg_input(scg_builder *b, scg_input_slot slot)
{
    return scg_emit(b, SCG_OP_INPUT, input_types[slot], 0, 0, 0, slot);
}

scg_value scg_uniform(scg_builder *b, scg_uniform_slot slot)
{
    return scg_emit(b, SCG_OP_UNIFORM, SCG_FLOAT, 0, 0, 0, slot);
}

scg_value scg_fetch(scg_builder *b, scg_texture tex, scg_value index)
{
    return scg_emit(b, SCG_OP_FETCH, tex == SCG_TEX_KNOTS ? SCG_FLOAT : SCG_VEC4, index, 0, 0,
                    tex);
}

void scg_output(scg_builder *b, scg_output_slot slot, scg_value v)
{
    scg_emit(b, SCG_OP_OUTPUT, SCG_VOID, v, 0, 0, slot);
}

scg_value scg_add(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_ADD, x, y); }
scg_value scg_sub(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_SUB, x, y); }
scg_value scg_mul(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_MUL, x, y); }
scg_value scg_div(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_DIV, x, y); }
scg_value scg_min(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_MIN, x, y); }
scg_value scg_max(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_MAX, x, y); }
scg_value scg_neg(scg_builder *b, scg_value x) { return typed(b, SCG_OP_NEG, x, 0); }
scg_value scg_abs(scg_builder *b, scg_value x) { return typed(b, SCG_OP_ABS, x, 0); }
scg_value scg_sqrt(scg_builder *b, scg_value x) { return typed(b, SCG_OP_SQRT, x, 0); }
scg_value scg_floor(scg_builder *b, scg_value x) { return typed(b, SCG_OP_FLOOR, x, 0); }
scg_value scg_dot(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_DOT, x, y); }
scg_value scg_cross(scg_builder *b, scg_value x, scg_value y)
{
    return typed(b, SCG_OP_CROSS, x, y);
}
scg_value scg_length(scg_builder *b, scg_value x) { return typed(b, SCG_OP_LENGTH, x, 0); }

scg_value scg_lerp(scg_builder *b, scg_value x, scg_value y, scg_value t)
{
    return scg_add(b, x, scg_mul(b, scg_sub(b, y, x), t));
}

scg_value scg_vec2(scg_builder *b, scg_value x, scg_value y)
{
    return scg_emit(b, SCG_OP_VEC, SCG_VEC2, x, y, 0, 0);
}
scg_value scg_vec3(scg_builder *b, scg_value x, scg_value y, scg_value z)
{
    return scg_emit(b, SCG_OP_VEC, SCG_VEC3, x, y, z, 0);
}
scg_value scg_vec4(scg_builder *b, scg_value x, scg_value y, scg_value z, scg_value w)
{
    scg_value v = scg_emit(b, SCG_OP_VEC, SCG_VEC4, x, y, z, 0);
    b->prog->insts[v].arg[3] = w;
    return v;
}

scg_value scg_comp(scg_builder *b, scg_value v, int component)
{
    return scg_emit(b, SCG_OP_COMP, SCG_FLOAT, v, 0, 0, component);
}

scg_value scg_xyz(scg_builder *b, scg_value v)
{
    /* One statement per component: C leaves the order of argument
     * evaluation open, and the listing should follow the source order. */
    scg_value x = scg_comp(b, v, 0);
    scg_value y = scg_comp(b, v, 1);
    scg_value z = scg_comp(b, v, 2);
    return scg_vec3(b, x, y, z);
}

scg_value scg_lt(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_LT, x, y); }
scg_value scg_le(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_LE, x, y); }
scg_value scg_eq(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_EQ, x, y); }
scg_value scg_ne(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_NE, x, y); }
scg_value scg_and(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_AND, x, y); }
scg_value scg_or(scg_builder *b, scg_value x, scg_value y) { return typed(b, SCG_OP_OR, x, y); }
scg_value scg_not(scg_builder *b, scg_value x) { return typed(b, SCG_OP_NOT, x, 0); }
scg_value scg_select(scg_builder *b, scg_value cond, scg_value x, scg_value y)
{
    return typed3(b, SCG_OP_SELECT, cond, x, y);
}
scg_value scg_i2f(scg_builder *b, scg_value x) { return typed(b, SCG_OP_I2F, x, 0); }
scg_value scg_f2i(scg_builder *b, scg_value x) { return typed(b, SCG_OP_F2I, x, 0); }

scg_value scg_var(scg_builder *b, scg_type type, int array_length, scg_value init)
{
    return scg_emit(b, SCG_OP_VAR, type, init, 0, 0, array_length);
}
scg_value scg_load(scg_builder *b, scg_value var) { return typed(b, SCG_OP_LOAD, var, 0); }
scg_value scg_load_at(scg_builder *b, scg_value var, scg_value index)
{
    return typed(b, SCG_OP_LOAD, var, index);
}
void scg_store(scg_builder *b, scg_value var, scg_value v) { typed(b, SCG_OP_STORE, var, v); }
void scg_store_at(scg_builder *b, scg_value var, scg_value index, scg_value v)
{
    typed3(b, SCG_OP_STORE, var, v, index);
}

void scg_if(scg_builder *b, scg_value cond) { typed(b, SCG_OP_IF, cond, 0); }
void scg_else(scg_builder *b) { typed(b, SCG_OP_ELSE, 0, 0); }
void scg_endif(scg_builder *b) { typed(b, SCG_OP_ENDIF, 0, 0); }
scg_value scg_loop(scg_builder *b, scg_value count) { return typed(b, SCG_OP_LOOP, count, 0); }
void scg_break(scg_builder *b) { typed(b, SCG_OP_BREAK, 0, 0); }
void scg_endloop(scg_builder *b) { typed(b, SCG_OP_ENDLOOP, 0, 0); }

/* ---- validation ---- */

static int invalid(sc_error *err, const scg_program *p, int i, const char *what)
{
    char key[SCG_KEY_MAX];
    scg_key_format(&p->key, key, sizeof key);
    return sc_fail_key(err, key, "invalid IR for %s: instruction v%d (%s): %s", key, i,
                       scg_op_name(i < p->count ? p->insts[i].op : SCG_OP_NOP), what);
}

/* Whether a value of type t may be an operand of an op of class c. */
static bool in_class(scg_type t, scg_arg_class c)
{
    switch (c) {
    case SCG_ARG_NUM: return t == SCG_INT || is_float_type(t);
    case SCG_ARG_FLOATS: return is_float_type(t);
    case SCG_ARG_SCALAR: return t == SCG_INT || t == SCG_FLOAT;
    case SCG_ARG_VECTOR: return t >= SCG_VEC2 && t <= SCG_VEC4;
    case SCG_ARG_BOOL: return t == SCG_BOOL;
    case SCG_ARG_INT: return t == SCG_INT;
    case SCG_ARG_FLOAT: return t == SCG_FLOAT;
    case SCG_ARG_VEC3: return t == SCG_VEC3;
    default: return true;
    }
}

/* What is wrong with the types, slot or operands of one instruction, or
 * NULL. Operands are known to be defined before it and present as its row
 * of the op table asks. The table's classes and result rules check most
 * ops; what they cannot say (slots, vecN, select, variables) is checked by
 * hand below. */
static const char *type_error(const scg_program *p, const scg_inst *in)
{
    const scg_op_info *info = &scg_op_infos[in->op];
    scg_type t = in->type, at[4];
    for (int k = 0; k < 4; k++)
        at[k] = in->arg[k] ? p->insts[in->arg[k]].type : SCG_VOID;
    scg_type ta = at[0], tb = at[1], tc = at[2];
    if ((unsigned)t > SCG_VEC4)
        return "bad result type";
    if (info->args != SCG_ARG_ANY)
        for (int k = 0; k < 4 && in->arg[k]; k++) {
            if (!in_class(at[k], info->args))
                return "operand of the wrong type";
            bool broadcast = info->result == SCG_RESULT_BROADCAST && k == 1 &&
                             ((ta == SCG_FLOAT && tb >= SCG_VEC2) ||
                              (tb == SCG_FLOAT && ta >= SCG_VEC2));
            if (at[k] != ta && !broadcast)
                return "operand types do not match";
        }
    if (info->result != SCG_RESULT_DECLARED && info->result != SCG_RESULT_SLOT &&
        t != scg_op_result_type(in->op, ta, tb))
        return "result type does not follow from the operands";
    switch (in->op) {
    case SCG_OP_CONST:
        if (t == SCG_VOID)
            return "constant without a type";
        break;
    case SCG_OP_INPUT:
        if ((unsigned)in->slot >= SCG_INPUT_COUNT || t != input_types[in->slot])
            return "bad input slot or type";
        break;
    case SCG_OP_UNIFORM:
        if ((unsigned)in->slot >= SCG_UNIFORM_COUNT)
            return "bad uniform slot";
        break;
    case SCG_OP_FETCH:
        if ((unsigned)in->slot >= SCG_TEXTURE_COUNT ||
            t != (in->slot == SCG_TEX_KNOTS ? SCG_FLOAT : SCG_VEC4))
            return "bad texture or result type";
        break;
    case SCG_OP_VEC:
        if (t < SCG_VEC2)
            return "vec must build vec2, vec3 or vec4";
        for (int k = 0; k < 4; k++)
            if ((k < scg_type_width(t)) != (in->arg[k] != 0))
                return "vecN takes N components";
        break;
    case SCG_OP_COMP:
        if (in->slot < 0 || in->slot >= scg_type_width(ta))
            return "component out of range";
        break;
    case SCG_OP_SELECT:
        if (ta != SCG_BOOL || tb != tc)
            return "select needs a bool and two values of one type";
        break;
    case SCG_OP_VAR:
        if (t == SCG_VOID || in->slot < 0 || (in->arg[0] && (in->slot > 0 || ta != t)))
            return "bad variable declaration";
        break;
    case SCG_OP_LOAD: {
        const scg_inst *var = &p->insts[in->arg[0]];
        if ((var->slot > 0) != (in->arg[1] != 0) || (in->arg[1] && tb != SCG_INT))
            return "bad load (index on a non-array, or not an int)";
        break;
    }
    case SCG_OP_STORE: {
        const scg_inst *var = &p->insts[in->arg[0]];
        if (tb != var->type || (var->slot > 0) != (in->arg[2] != 0) ||
            (in->arg[2] && tc != SCG_INT))
            return "bad store (type, or index on a non-array)";
        break;
    }
    case SCG_OP_OUTPUT:
        if ((unsigned)in->slot >= SCG_OUTPUT_COUNT || ta != output_types[in->slot])
            return "bad output slot or type";
        break;
    default:
        break;
    }
    return NULL;
}

int scg_validate(const scg_program *p, sc_error *err)
{
    int n = p->count;
    /* Block of each value's definition, and whether that block is open. */
    int *block_of = sc_alloc((size_t)n, sizeof *block_of);
    int *open = sc_alloc((size_t)n + 1, sizeof *open);
    int *stack = sc_alloc((size_t)n + 1, sizeof *stack);
    int *stack_op = sc_alloc((size_t)n + 1, sizeof *stack_op);
    int depth = 0, next_block = 1, status = SC_OK;
    stack[0] = 0;
    open[0] = 1;
    const char *why = NULL;
    int at = 0;

#define FAIL(i, msg) do { at = (i); why = (msg); goto done; } while (0)
    for (int i = 1; i < n; i++) {
        const scg_inst *in = &p->insts[i];
        if ((unsigned)in->op >= SCG_OP_COUNT || in->op == SCG_OP_NOP)
            FAIL(i, "unknown or removed instruction");
        const scg_op_info *info = &scg_op_infos[in->op];
        /* Operands defined before, visible here, and values (not variables
         * unless the op takes a variable). */
        for (int k = 0; k < 4; k++) {
            scg_value v = in->arg[k];
            if (v == 0)
                continue;
            if (v < 0 || v >= i)
                FAIL(i, "operand not defined before its use");
            if (!open[block_of[v]])
                FAIL(i, "operand defined in a block that is already closed");
            bool var_operand = k == 0 && (info->flags & SCG_OPF_VAR_A);
            if ((p->insts[v].op == SCG_OP_VAR) != var_operand)
                FAIL(i, var_operand ? "operand a is not a variable" : "a variable used as a value");
            if (p->insts[v].type == SCG_VOID)
                FAIL(i, "operand defines no value");
        }
        for (int k = 0; k < 4; k++) {
            if (k < info->min_args && !in->arg[k])
                FAIL(i, "missing operand");
            if (k >= info->max_args && in->arg[k])
                FAIL(i, "extra operand");
        }
        const char *type_problem = type_error(p, in);
        if (type_problem)
            FAIL(i, type_problem);
        /* Block structure. */
        switch (in->op) {
        case SCG_OP_IF:
        case SCG_OP_LOOP:
            depth++;
            stack[depth] = next_block;
            stack_op[depth] = in->op;
            open[next_block++] = 1;
            break;
        case SCG_OP_ELSE:
            if (depth == 0 || stack_op[depth] != SCG_OP_IF)
                FAIL(i, "else without if");
            open[stack[depth]] = 0;
            stack[depth] = next_block;
            stack_op[depth] = SCG_OP_ELSE;
            open[next_block++] = 1;
            break;
        case SCG_OP_ENDIF:
            if (depth == 0 || stack_op[depth] == SCG_OP_LOOP)
                FAIL(i, "endif without if");
            open[stack[depth--]] = 0;
            break;
        case SCG_OP_ENDLOOP:
            if (depth == 0 || stack_op[depth] != SCG_OP_LOOP)
                FAIL(i, "endloop without loop");
            open[stack[depth--]] = 0;
            break;
        case SCG_OP_BREAK: {
            bool in_loop = false;
            for (int d = depth; d > 0; d--)
                in_loop |= stack_op[d] == SCG_OP_LOOP;
            if (!in_loop)
                FAIL(i, "break outside a loop");
            break;
        }
        default:
            break;
        }
        block_of[i] = stack[depth];
    }
    if (depth != 0)
        FAIL(n - 1, "block not closed at the end of the program");
#undef FAIL
done:
    if (why)
        status = invalid(err, p, at, why);
    free(block_of);
    free(open);
    free(stack);
    free(stack_op);
    return status;
}

/* ---- listing ---- */

static void print_value(FILE *f, const scg_program *p, scg_value v)
{
    if (p->insts[v].name[0])
        fprintf(f, "v%d_%s", v, p->insts[v].name);
    else
        fprintf(f, "v%d", v);
}

void scg_dump_ir(FILE *f, const scg_program *p)
{
    char key[SCG_KEY_MAX];
    fprintf(f, "# program %s: %d instructions\n", scg_key_format(&p->key, key, sizeof key),
            scg_program_size(p));
    int indent = 1;
    for (int i = 1; i < p->count; i++) {
        const scg_inst *in = &p->insts[i];
        if (scg_op_has(in->op, SCG_OPF_CLOSE))
            indent--;
        fprintf(f, "%*s", 2 * indent, "");
        if (scg_op_has(in->op, SCG_OPF_OPEN))
            indent++;
        switch (in->op) {
        case SCG_OP_ELSE:
            fprintf(f, "} else {\n");
            continue;
        case SCG_OP_ENDIF:
        case SCG_OP_ENDLOOP:
            fprintf(f, "}\n");
            continue;
        case SCG_OP_IF:
            fprintf(f, "if ");
            print_value(f, p, in->arg[0]);
            fprintf(f, " {\n");
            continue;
        case SCG_OP_BREAK:
            fprintf(f, "break\n");
            continue;
        case SCG_OP_STORE:
            fprintf(f, "store ");
            print_value(f, p, in->arg[0]);
            if (in->arg[2]) {
                fprintf(f, "[");
                print_value(f, p, in->arg[2]);
                fprintf(f, "]");
            }
            fprintf(f, " = ");
            print_value(f, p, in->arg[1]);
            fprintf(f, "\n");
            continue;
        case SCG_OP_OUTPUT:
            fprintf(f, "output %s = ", scg_output_info(in->slot)->name);
            print_value(f, p, in->arg[0]);
            fprintf(f, "\n");
            continue;
        default:
            break;
        }
        print_value(f, p, i);
        fprintf(f, ":%s", scg_type_name(in->type));
        if (in->op == SCG_OP_VAR && in->slot > 0)
            fprintf(f, "[%d]", in->slot);
        fprintf(f, " = %s", scg_op_name(in->op));
        switch (in->op) {
        case SCG_OP_CONST:
            if (in->type == SCG_INT)
                fprintf(f, " %d", in->imm.i);
            else if (in->type == SCG_BOOL)
                fprintf(f, " %s", in->imm.i ? "true" : "false");
            else
                for (int k = 0; k < scg_type_width(in->type); k++)
                    fprintf(f, "%s%.9g", k ? ", " : " ", in->imm.f[k]);
            break;
        case SCG_OP_INPUT:
            fprintf(f, " %s", scg_input_info(in->slot)->name);
            break;
        case SCG_OP_UNIFORM:
            fprintf(f, " %s", scg_uniform_info(in->slot)->name);
            break;
        case SCG_OP_FETCH:
            fprintf(f, " %s, ", scg_texture_info(in->slot)->name);
            print_value(f, p, in->arg[0]);
            break;
        case SCG_OP_COMP:
            fprintf(f, " ");
            print_value(f, p, in->arg[0]);
            fprintf(f, ".%c", "xyzw"[in->slot]);
            break;
        default:
            for (int k = 0; k < 4 && in->arg[k]; k++) {
                fprintf(f, k ? ", " : " ");
                print_value(f, p, in->arg[k]);
            }
            break;
        }
        if (in->op == SCG_OP_LOOP)
            fprintf(f, " {");
        fprintf(f, "\n");
    }
}

/* ---- compaction ---- */

void scg_compact(scg_program *p)
{
    int *map = sc_alloc((size_t)p->count, sizeof *map);
    int out = 1;
    for (int i = 1; i < p->count; i++)
        if (p->insts[i].op != SCG_OP_NOP)
            map[i] = out++;
    out = 1;
    for (int i = 1; i < p->count; i++) {
        scg_inst in = p->insts[i];
        if (in.op == SCG_OP_NOP)
            continue;
        for (int k = 0; k < 4; k++)
            in.arg[k] = in.arg[k] ? map[in.arg[k]] : 0;
        p->insts[out++] = in;
    }
    p->count = out;
    free(map);
}
