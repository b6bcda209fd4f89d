/* emit_glsl.c — prints optimised IR as GLSL 4.50 core: the intersection
 * function (emit_glsl.h); assemble_glsl.c puts it into whole programs.
 *
 * The printer is deliberately plain: every IR value that is computed
 * becomes one local `type name = expression;` at the place the IR defines
 * it, named after the metaprogram's hint and its value number (`Su_41`,
 * listed as `v41_Su`), so a reader can follow a line of GLSL back to the IR
 * listing (`splinecast gen --dump-ir`). Constants, inputs, uniforms and components
 * are printed in place, where they cost the reader nothing. The optimiser
 * has already removed dead code and the metaprograms unrolled every loop,
 * so the printer never decides anything about the algorithm. */
#include "emit_glsl.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_layout.h"

/* ---- names and literals ---- */

/* Value names: the metaprogram's hint made a safe GLSL identifier, then the
 * value number, which keeps names unique and clear of keywords and of the
 * reserved gl_ prefix and double underscores. */
static void value_name(const scg_program *prog, scg_value v, char *buf, size_t size)
{
    char hint[24];
    size_t n = 0;
    for (const char *s = prog->insts[v].name; *s && n + 1 < sizeof hint; s++) {
        char c = isalnum((unsigned char)*s) ? *s : '_';
        if (c == '_' && (n == 0 || hint[n - 1] == '_'))
            continue;
        hint[n++] = c;
    }
    while (n && hint[n - 1] == '_')
        n--;
    hint[n] = 0;
    if (!n || isdigit((unsigned char)hint[0]) || !strncmp(hint, "gl_", 3))
        snprintf(buf, size, "v%d", v);
    else
        snprintf(buf, size, "%s_%d", hint, v);
}

/* Shortest decimal that reads back as the same float, always with a point
 * or exponent so GLSL types it as float. */
static void float_literal(float f, char *buf, size_t size)
{
    if (isnan(f)) {
        snprintf(buf, size, "uintBitsToFloat(0x7FC00000u)");
        return;
    }
    if (isinf(f)) {
        snprintf(buf, size, "uintBitsToFloat(%su)", f > 0 ? "0x7F800000" : "0xFF800000");
        return;
    }
    char digits[40];
    for (int precision = 1; precision <= 9; precision++) {
        snprintf(digits, sizeof digits, "%.*g", precision, (double)f);
        if (strtof(digits, NULL) == f)
            break;
    }
    char *e = strchr(digits, 'e');
    if (strchr(digits, '.'))
        snprintf(buf, size, "%s", digits);
    else if (e)
        snprintf(buf, size, "%.*s.0%s", (int)(e - digits), digits, e);
    else
        snprintf(buf, size, "%s.0", digits);
}

static void constant_text(const scg_inst *in, char *buf, size_t size)
{
    if (in->type == SCG_BOOL) {
        snprintf(buf, size, "%s", in->imm.i ? "true" : "false");
        return;
    }
    if (in->type == SCG_INT) {
        snprintf(buf, size, in->imm.i < 0 ? "(%d)" : "%d", in->imm.i);
        return;
    }
    int width = scg_type_width(in->type);
    char lit[4][48];
    int same = 1;
    for (int k = 0; k < width; k++) {
        float_literal(in->imm.f[k], lit[k], sizeof lit[k]);
        same &= !strcmp(lit[k], lit[0]);
    }
    if (width == 1) {
        snprintf(buf, size, lit[0][0] == '-' ? "(%s)" : "%s", lit[0]);
        return;
    }
    if (same) {
        snprintf(buf, size, "%s(%s)", scg_type_name(in->type), lit[0]);
        return;
    }
    int n = snprintf(buf, size, "%s(", scg_type_name(in->type));
    for (int k = 0; k < width && n > 0 && (size_t)n < size; k++)
        n += snprintf(buf + n, size - (size_t)n, "%s%s", k ? ", " : "", lit[k]);
    if (n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, ")");
}

/* Values printed where they are used rather than held in a local: leaves,
 * components (SCG_GLSL_IN_PLACE), and the loads that `load_in_place` marks. */
static int printed_in_place(const scg_program *prog, const unsigned char *loads, scg_value v)
{
    return scg_op_infos[prog->insts[v].op].glsl == SCG_GLSL_IN_PLACE || loads[v];
}

/* Marks the loads that can be read as their variable at every use: not an
 * array element, no store to the variable from the load to its last use,
 * and no loop opening in between (its back edge would bring a later store
 * before the use). `int v = iters; iters = v + n;` then reads
 * `iters = iters + n;`. */
static unsigned char *load_in_place(const scg_program *prog)
{
    unsigned char *loads = sc_alloc((size_t)prog->count, 1);
    /* A component is printed where it is used, so its uses are its
     * operand's too. */
    int *last_use = sc_alloc((size_t)prog->count, sizeof *last_use);
    for (int i = prog->count - 1; i > 0; i--) {
        const scg_inst *in = &prog->insts[i];
        int use = scg_op_infos[in->op].glsl == SCG_GLSL_IN_PLACE ? last_use[i] : i;
        for (int k = 0; k < 4; k++)
            if (in->arg[k] && last_use[in->arg[k]] < use)
                last_use[in->arg[k]] = use;
    }
    for (int i = 1; i < prog->count; i++) {
        const scg_inst *in = &prog->insts[i];
        if (in->op != SCG_OP_LOAD || in->arg[1] || !last_use[i])
            continue;
        bool safe = true;
        for (int j = i + 1; j < last_use[i] && safe; j++) {
            const scg_inst *between = &prog->insts[j];
            safe = between->op != SCG_OP_LOOP &&
                   !(between->op == SCG_OP_STORE && between->arg[0] == in->arg[0]);
        }
        loads[i] = safe;
    }
    free(last_use);
    return loads;
}

/* "x", "xz", "xyz" when every operand of the vector `in` is a component of
 * one value (then *source is that value), else NULL. */
static const char *swizzle(const scg_program *prog, const scg_inst *in, scg_value *source,
                           char *buf)
{
    int n = scg_type_width(in->type);
    *source = 0;
    for (int k = 0; k < n; k++) {
        const scg_inst *c = &prog->insts[in->arg[k]];
        if (c->op != SCG_OP_COMP || (k > 0 && c->arg[0] != *source))
            return NULL;
        *source = c->arg[0];
        buf[k] = "xyzw"[c->slot & 3];
    }
    buf[n] = 0;
    return buf;
}

/* How operand v reads in an expression. */
static void operand(const scg_program *prog, const unsigned char *loads, scg_value v, char *buf,
                    size_t size)
{
    const scg_inst *in = &prog->insts[v];
    if (loads[v]) {
        value_name(prog, in->arg[0], buf, size);
        return;
    }
    switch (in->op) {
    case SCG_OP_CONST:
        constant_text(in, buf, size);
        return;
    case SCG_OP_INPUT:
        snprintf(buf, size, "%s", scg_input_info((scg_input_slot)in->slot)->name);
        return;
    case SCG_OP_UNIFORM:
        snprintf(buf, size, "%s", scg_uniform_info((scg_uniform_slot)in->slot)->name);
        return;
    case SCG_OP_COMP: {
        char vec[128];
        operand(prog, loads, in->arg[0], vec, sizeof vec);
        snprintf(buf, size, "%s.%c", vec, "xyzw"[in->slot & 3]);
        return;
    }
    default:
        value_name(prog, v, buf, size);
    }
}

/* ---- the intersection function ---- */

typedef scg_program_use program_use;

static void scan_use(const scg_program *prog, program_use *use)
{
    memset(use, 0, sizeof *use);
    for (int i = 1; i < prog->count; i++) {
        const scg_inst *in = &prog->insts[i];
        if (in->op == SCG_OP_INPUT && in->slot >= 0 && in->slot < SCG_INPUT_COUNT)
            use->inputs[in->slot] = 1;
        else if (in->op == SCG_OP_UNIFORM && in->slot >= 0 && in->slot < SCG_UNIFORM_COUNT)
            use->uniforms[in->slot] = 1;
        else if (in->op == SCG_OP_FETCH && in->slot >= 0 && in->slot < SCG_TEXTURE_COUNT)
            use->textures[in->slot] = 1;
        else if (in->op == SCG_OP_OUTPUT && in->slot >= 0 && in->slot < SCG_OUTPUT_COUNT)
            use->outputs[in->slot] = 1;
    }
}

static void indent(scg_text *out, int depth)
{
    for (int d = 0; d < depth; d++)
        scg_text_append(out, "    ");
}

/* "0.0", "vec3(0.0)", "0", "false": what an uninitialised variable holds. */
static const char *zero_of(scg_type type)
{
    switch (type) {
    case SCG_BOOL: return "false";
    case SCG_INT: return "0";
    case SCG_FLOAT: return "0.0";
    case SCG_VEC2: return "vec2(0.0)";
    case SCG_VEC3: return "vec3(0.0)";
    case SCG_VEC4: return "vec4(0.0)";
    default: return "";
    }
}

/* The right-hand side of value i. */
static int expression(const scg_program *prog, const unsigned char *loads, int i, scg_text *out,
                      sc_error *err)
{
    const scg_inst *in = &prog->insts[i];
    char a[160] = "", b[160] = "", c[160] = "";
    if (in->arg[0])
        operand(prog, loads, in->arg[0], a, sizeof a);
    if (in->arg[1])
        operand(prog, loads, in->arg[1], b, sizeof b);
    if (in->arg[2])
        operand(prog, loads, in->arg[2], c, sizeof c);
    const scg_op_info *info = &scg_op_infos[in->op];
    switch (in->op) {
    case SCG_OP_FETCH: {
        const scg_slot_info *tex = scg_texture_info((scg_texture)in->slot);
        scg_text_printf(out, "texelFetch(%s, %s)%s", tex->name, a, tex->components == 1 ? ".r" : "");
        return SC_OK;
    }
    case SCG_OP_VEC: {
        char swz[5], source[160];
        scg_value from;
        if (swizzle(prog, in, &from, swz)) {
            operand(prog, loads, from, source, sizeof source);
            scg_text_printf(out, "%s.%s", source, swz);
            return SC_OK;
        }
        scg_text_printf(out, "%s(%s, %s", scg_type_name(in->type), a, b);
        if (in->arg[2])
            scg_text_printf(out, ", %s", c);
        if (in->arg[3]) {
            char d[160];
            operand(prog, loads, in->arg[3], d, sizeof d);
            scg_text_printf(out, ", %s", d);
        }
        scg_text_append(out, ")");
        return SC_OK;
    }
    case SCG_OP_SELECT:
        scg_text_printf(out, "%s ? %s : %s", a, b, c);
        return SC_OK;
    case SCG_OP_LOAD:
        if (in->arg[1])
            scg_text_printf(out, "%s[%s]", a, b);
        else
            scg_text_append(out, a);
        return SC_OK;
    default:
        break;
    }
    switch (info->glsl) {
    case SCG_GLSL_INFIX:
        scg_text_printf(out, "%s %s %s", a, info->spelling, b);
        return SC_OK;
    case SCG_GLSL_PREFIX:
        scg_text_printf(out, "%s%s", info->spelling, a);
        return SC_OK;
    case SCG_GLSL_CALL:
        /* GLSL has min(vecN, float) but not min(float, vecN): a broadcast
         * float goes second where the operands commute. */
        if (in->arg[1] && (info->flags & SCG_OPF_COMM) &&
            scg_type_width(prog->insts[in->arg[0]].type) < scg_type_width(in->type))
            scg_text_printf(out, "%s(%s, %s)", info->spelling, b, a);
        else
            scg_text_printf(out, in->arg[1] ? "%s(%s, %s)" : "%s(%s)", info->spelling, a, b);
        return SC_OK;
    default:
        break;
    }
    return sc_fail(err, NULL, 0, "emitter: instruction %d (%s) has no GLSL form", i,
                   scg_op_name(in->op));
}

static void variable_declaration(const scg_program *prog, const unsigned char *loads, int i,
                                 scg_text *out)
{
    const scg_inst *in = &prog->insts[i];
    char name[64], init[160];
    value_name(prog, i, name, sizeof name);
    const char *type = scg_type_name(in->type);
    if (in->arg[0])
        operand(prog, loads, in->arg[0], init, sizeof init);
    else
        snprintf(init, sizeof init, "%s", zero_of(in->type));
    if (in->slot <= 0) {
        scg_text_printf(out, "%s %s = %s;\n", type, name, init);
        return;
    }
    scg_text_printf(out, "%s %s[%d] = %s[%d](", type, name, in->slot, type, in->slot);
    for (int k = 0; k < in->slot; k++)
        scg_text_printf(out, "%s%s", k ? ", " : "", init);
    scg_text_append(out, ");\n");
}

static int function_body(const scg_program *prog, const unsigned char *loads, scg_text *out,
                         sc_error *err)
{
    int depth = 1, block_start = 1;
    char a[160], b[160], c[160], name[64];
    for (int i = 1; i < prog->count; i++) {
        const scg_inst *in = &prog->insts[i];
        a[0] = b[0] = c[0] = 0;
        if (in->arg[0])
            operand(prog, loads, in->arg[0], a, sizeof a);
        if (in->arg[1])
            operand(prog, loads, in->arg[1], b, sizeof b);
        if (in->arg[2])
            operand(prog, loads, in->arg[2], c, sizeof c);
        switch (in->op) {
        case SCG_OP_NOP:
            continue;
        case SCG_OP_IF:
        case SCG_OP_LOOP:
            /* A blank line before each block sets the unrolled steps apart. */
            if (!block_start)
                scg_text_append(out, "\n");
            indent(out, depth++);
            if (in->op == SCG_OP_IF) {
                scg_text_printf(out, "if (%s) {\n", a);
            } else {
                value_name(prog, i, name, sizeof name);
                scg_text_printf(out, "for (int %s = 0; %s < %s; %s++) {\n", name, name, a, name);
            }
            block_start = 1;
            continue;
        case SCG_OP_ELSE:
            indent(out, depth - 1);
            scg_text_append(out, "} else {\n");
            block_start = 1;
            continue;
        case SCG_OP_ENDIF:
        case SCG_OP_ENDLOOP:
            indent(out, --depth);
            scg_text_append(out, "}\n");
            block_start = 0;
            continue;
        default:
            break;
        }
        if (printed_in_place(prog, loads, i))
            continue;
        block_start = 0;
        indent(out, depth);
        switch (in->op) {
        case SCG_OP_VAR:
            variable_declaration(prog, loads, i, out);
            break;
        case SCG_OP_STORE:
            if (in->arg[2])
                scg_text_printf(out, "%s[%s] = %s;\n", a, c, b);
            else
                scg_text_printf(out, "%s = %s;\n", a, b);
            break;
        case SCG_OP_BREAK:
            scg_text_append(out, "break;\n");
            break;
        case SCG_OP_OUTPUT:
            scg_text_printf(out, "%s = %s;\n", scg_output_info((scg_output_slot)in->slot)->name, a);
            break;
        default:
            value_name(prog, i, name, sizeof name);
            scg_text_printf(out, "%s %s = ", scg_type_name(in->type), name);
            if (expression(prog, loads, i, out, err) != SC_OK)
                return SC_FAIL;
            scg_text_append(out, ";\n");
        }
    }
    return SC_OK;
}

/* The function `name`, its results as out parameters; `what` opens its
 * comment. Without a name, a block of statements that assigns the results
 * to locals declared before it. */
static int emit_function(const scg_program *prog, const char *what, const char *name,
                         scg_text *out, sc_error *err)
{
    program_use use;
    scan_use(prog, &use);
    scg_text_printf(out, "// %s, printed from the optimised IR (%d instructions):\n"
                         "// one statement per computed value, named hint_N after IR value N.\n",
                    what, scg_program_size(prog));
    if (name) {
        scg_text_printf(out, "void %s(", name);
        const char *sep = "";
        for (int s = 0; s < SCG_OUTPUT_COUNT; s++)
            if (use.outputs[s]) {
                const scg_slot_info *info = scg_output_info((scg_output_slot)s);
                scg_text_printf(out, "%sout %s %s", sep, info->glsl_type, info->name);
                sep = ", ";
            }
        scg_text_append(out, ")\n");
    }
    scg_text_append(out, "{\n");
    unsigned char *loads = load_in_place(prog);
    int status = function_body(prog, loads, out, err);
    free(loads);
    if (status != SC_OK)
        return SC_FAIL;
    scg_text_append(out, "}\n");
    return SC_OK;
}

int scg_emit_intersect_function(const scg_program *prog, scg_text *out, sc_error *err)
{
    return emit_function(prog, "The intersection", "sc_intersect", out, err);
}

int scg_emit_view_start_block(const scg_program *prog, scg_text *out, sc_error *err)
{
    return emit_function(prog, "The start at this hull vertex", NULL, out, err);
}

/* ---- for program assembly (assemble_glsl.c) ---- */

void scg_program_scan_use(const scg_program *prog, scg_program_use *use)
{
    scan_use(prog, use);
}

void scg_glsl_float_literal(float f, char *buf, size_t size)
{
    float_literal(f, buf, size);
}
