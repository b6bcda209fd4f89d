/* emit_glsl.c — prints optimised IR as GLSL 4.50 core (emit_glsl.h).
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

/* Names the key in a failure a callee reported without one. */
static int keyed(sc_error *err, const char *key_text)
{
    if (err)
        snprintf(err->key, sizeof err->key, "%s", key_text);
    return SC_FAIL;
}

/* ---- describing a key in words, for headers ---- */

static const char *kind_words(scg_patch_kind kind)
{
    switch (kind) {
    case SCG_PATCH_BEZIER: return "tensor Bezier";
    case SCG_PATCH_NURBS: return "tensor NURBS (knots from the knot texture)";
    case SCG_PATCH_TRIANGLE: return "triangular Bezier";
    }
    return "?";
}

static const char *eval_words(scg_eval_form eval)
{
    switch (eval) {
    case SCG_EVAL_DC: return "de Casteljau (Bezier) / de Boor (NURBS), unrolled";
    case SCG_EVAL_BASIS: return "Bernstein basis sums, unrolled";
    case SCG_EVAL_LOOP: return "generic, with runtime loops over the record's degrees";
    }
    return "?";
}

static const char *method_words(scg_method method)
{
    switch (method) {
    case SCG_METHOD_NEWTON: return "Newton iteration on the ray's two planes";
    case SCG_METHOD_BROYDEN: return "Broyden iteration";
    case SCG_METHOD_BCLIP: return "Bezier clipping";
    case SCG_METHOD_SUBDIV: return "object-space subdivision";
    case SCG_METHOD_HYBRID: return "hybrid subdivision and Newton";
    }
    return "?";
}

static const char *start_words(sc_start start)
{
    switch (start) {
    case SC_START_MID: return "the centre of the hull's sub-patch domain";
    case SC_START_CPMAP: return "the control points' parameters, interpolated over the hull";
    case SC_START_VIEW: return "a view-dependent solve at the hull vertices";
    case SC_START_DEFAULT: break;   /* never in a key */
    }
    return "?";
}

static const char *ert_words(scg_ert ert)
{
    switch (ert) {
    case SCG_ERT_NONE: return "no early ray termination";
    case SCG_ERT_BEFORE: return "early ray termination before the intersection";
    case SCG_ERT_BOTH: return "early ray termination before and after the intersection";
    case SCG_ERT_CONSERVATIVE: return "conservative depth (depth_greater)";
    }
    return "?";
}

static void describe_key(scg_text *out, const scg_key *key)
{
    char degrees[32] = "of any degree";
    if (key->eval != SCG_EVAL_LOOP)
        snprintf(degrees, sizeof degrees, "%dx%d", key->deg_u, key->deg_v);
    char trim[64] = "untrimmed";
    if (key->trim == SC_TRIM_CLIP)
        snprintf(trim, sizeof trim, "trimmed by Bezier clipping (curves of degree <= %d)",
                 key->trim_degree);
    else if (key->trim == SC_TRIM_LEFT)
        snprintf(trim, sizeof trim, "trimmed by left-only Bezier clipping (curves of degree <= %d)",
                 key->trim_degree);
    else if (key->trim == SC_TRIM_FAST)
        snprintf(trim, sizeof trim, "trimmed, accelerated (curves of degree <= %d)",
                 key->trim_degree);
    scg_text_printf(out, "// patch: %s %s, %s, %s\n", kind_words(key->kind), degrees,
                    key->rational ? "rational" : "polynomial", trim);
    scg_text_printf(out, "// evaluation: %s\n", eval_words(key->eval));
    scg_text_printf(out,
                    "// method: %s, at most %d iteration%s,\n"
                    "//   tolerance %g pixel footprints\n"
                    "// start: %s\n",
                    method_words(key->method), key->max_iters, key->max_iters == 1 ? "" : "s",
                    (double)scg_key_tolerance(key), start_words(key->start));
    scg_text_printf(out, "// depth: %s\n// outputs:", ert_words(key->ert));
    static const char *const output_words[] = {"shaded colour", "AOVs", "iterations view",
                                               "uv view", "hull view"};
    const char *sep = " ";
    for (int bit = 0; bit < (int)(sizeof output_words / sizeof output_words[0]); bit++)
        if (key->outputs & (1u << bit)) {
            scg_text_printf(out, "%s%s", sep, output_words[bit]);
            sep = ", ";
        }
    scg_text_append(out, "\n");
}

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

typedef struct program_use {
    int inputs[SCG_INPUT_COUNT];
    int uniforms[SCG_UNIFORM_COUNT];
    int textures[SCG_TEXTURE_COUNT];
    int outputs[SCG_OUTPUT_COUNT];
} program_use;

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

int scg_emit_intersect_function(const scg_program *prog, scg_text *out, sc_error *err)
{
    program_use use;
    scan_use(prog, &use);
    scg_text_printf(out, "// The intersection, printed from the optimised IR (%d instructions):\n"
                         "// one statement per computed value, named hint_N after IR value N.\n",
                    scg_program_size(prog));
    scg_text_append(out, "void sc_intersect(");
    const char *sep = "";
    for (int s = 0; s < SCG_OUTPUT_COUNT; s++)
        if (use.outputs[s]) {
            const scg_slot_info *info = scg_output_info((scg_output_slot)s);
            scg_text_printf(out, "%sout %s %s", sep, info->glsl_type, info->name);
            sep = ", ";
        }
    scg_text_append(out, ")\n{\n");
    unsigned char *loads = load_in_place(prog);
    int status = function_body(prog, loads, out, err);
    free(loads);
    if (status != SC_OK)
        return SC_FAIL;
    scg_text_append(out, "}\n");
    return SC_OK;
}

/* ---- the fragment program ---- */

/* Results of sc_intersect that each output needs. */
static unsigned needed_results(unsigned outputs)
{
    unsigned need = 1u << SCG_OUT_HIT | 1u << SCG_OUT_POINT;
    if (outputs & SCG_OUTPUT_SHADE)
        need |= 1u << SCG_OUT_NORMAL;
    if (outputs & SCG_OUTPUT_AOV)
        need |= 1u << SCG_OUT_SURFACE | 1u << SCG_OUT_UV | 1u << SCG_OUT_T |
                1u << SCG_OUT_ITERS | 1u << SCG_OUT_NORMAL;
    if (outputs & SCG_OUTPUT_ITERS)
        need |= 1u << SCG_OUT_ITERS;
    if (outputs & SCG_OUTPUT_UVVIEW)
        need |= 1u << SCG_OUT_UV;
    if (outputs & SCG_OUTPUT_HULLVIEW)
        need |= 1u << SCG_OUT_NORMAL;
    return need;
}

static void header(scg_text *out, const char *what, const char *key_text)
{
    scg_text_printf(out, "// Generated by %s. Do not edit: regenerate with\n"
                         "//   splinecast gen --key %s -o DIR\n"
                         "// key: %s\n"
                         "// stage: %s\n",
                    SCG_GENERATOR_VERSION, key_text, key_text, what);
}

/* Declarations of the colour attachments the key's outputs write. */
static void output_declarations(scg_text *out, unsigned outputs)
{
    scg_text_append(out, "// Colour attachments, by location (docs/emitter.md).\n");
    if (outputs & SCG_OUTPUT_SHADE)
        scg_text_printf(out, "layout(location = %d) out vec4 sc_colour;\n", SCG_FRAG_OUT_COLOUR);
    if (outputs & SCG_OUTPUT_AOV)
        scg_text_printf(out,
                        "layout(location = %d) out int sc_aov_surface;\n"
                        "layout(location = %d) out vec4 sc_aov_uvt;\n"
                        "layout(location = %d) out vec4 sc_aov_point;\n"
                        "layout(location = %d) out vec4 sc_aov_normal;\n",
                        SCG_FRAG_OUT_SURFACE, SCG_FRAG_OUT_UVT, SCG_FRAG_OUT_POINT,
                        SCG_FRAG_OUT_NORMAL);
    if (outputs & SCG_OUTPUT_ITERS)
        scg_text_printf(out, "layout(location = %d) out vec4 sc_view_iters;\n", SCG_FRAG_OUT_ITERS);
    if (outputs & SCG_OUTPUT_UVVIEW)
        scg_text_printf(out, "layout(location = %d) out vec4 sc_view_uv;\n", SCG_FRAG_OUT_UV);
    if (outputs & SCG_OUTPUT_HULLVIEW)
        scg_text_printf(out, "layout(location = %d) out vec4 sc_view_hull;\n", SCG_FRAG_OUT_HULL);
}

/* The binding and texture that hold, per pixel, the distance along the
 * unit ray of the nearest surface drawn so far (early ray termination). */
enum { NEAREST_T_BINDING = 4 };

static int fragment_slots(const scg_program *prog, const program_use *use, scg_text *parts,
                          sc_error *err)
{
    const scg_key *key = &prog->key;
    char key_text[SCG_KEY_MAX];
    scg_key_format(key, key_text, sizeof key_text);
    enum { HEADER, INPUTS, COLOUR_INPUT, UNIFORMS, TEXTURES, OUTPUTS, GLOBALS, FUNCTION,
           FUNCTIONS, PREPARE, RESULTS, CALL, ON_MISS, WRITE };

    char stage[96];
    snprintf(stage, sizeof stage, "fragment program, drawn with vertex program %s.vert",
             scg_vertex_program_name(key));
    header(&parts[HEADER], stage, key_text);
    describe_key(&parts[HEADER], key);

    /* The skeleton reads the ray itself (depth, normals). */
    for (int s = 0; s < SCG_INPUT_COUNT; s++) {
        /* The hull view colours by the hull's record and domain. */
        int hull_id = (key->outputs & SCG_OUTPUT_HULLVIEW) &&
                      (s == SCG_IN_DOMAIN || s == SCG_IN_RECORD);
        if (s == SCG_IN_T_LIMIT ||
            (!use->inputs[s] && s != SCG_IN_RAY_DIR && s != SCG_IN_RAY_ORIGIN && !hull_id))
            continue;
        const scg_slot_info *info = scg_input_info((scg_input_slot)s);
        scg_text_printf(&parts[INPUTS], "layout(location = %d) %sin %s %s;\n", s,
                        info->flat ? "flat " : "", info->glsl_type, info->name);
    }
    if (key->outputs & SCG_OUTPUT_SHADE)
        scg_text_append(&parts[COLOUR_INPUT], "layout(location = 9) flat in vec3 sc_base_colour;\n");
    for (int s = 0; s < SCG_UNIFORM_COUNT; s++)
        if (use->uniforms[s]) {
            const scg_slot_info *info = scg_uniform_info((scg_uniform_slot)s);
            scg_text_printf(&parts[UNIFORMS], "layout(location = %d) uniform %s %s;\n", s,
                            info->glsl_type, info->name);
        }
    int any_texture = use->inputs[SCG_IN_T_LIMIT];
    for (int s = 0; s < SCG_TEXTURE_COUNT; s++)
        any_texture |= use->textures[s];
    if (any_texture)
        scg_text_append(&parts[TEXTURES],
                        "// Patch data (gpu_layout.h), bound to the unit equal to the binding.\n");
    for (int s = 0; s < SCG_TEXTURE_COUNT; s++)
        if (use->textures[s]) {
            const scg_slot_info *info = scg_texture_info((scg_texture)s);
            scg_text_printf(&parts[TEXTURES], "layout(binding = %d) uniform %s %s;\n", s,
                            info->glsl_type, info->name);
        }
    if (use->inputs[SCG_IN_T_LIMIT]) {
        scg_text_printf(&parts[TEXTURES],
                        "// Per tile of %d x %d pixels, the largest distance along the unit ray to "
                        "the\n// nearest surfaces drawn so far.\n"
                        "layout(binding = %d) uniform sampler2D sc_nearest_t;\n",
                        SCG_NEAREST_TILE, SCG_NEAREST_TILE, NEAREST_T_BINDING);
        scg_text_append(&parts[GLOBALS],
                        "// Early ray termination: the ray parameter of the nearest surface so "
                        "far, in\n// units of sc_ray_dir.\nfloat sc_t_limit = 0.0;\n\n");
        /* The intersection refuses such a hull too; leaving at once also
         * skips loading the patch and the final evaluation where the
         * hardware branches per group of pixels. */
        scg_text_printf(&parts[PREPARE],
                        "sc_t_limit = texelFetch(sc_nearest_t, ivec2(gl_FragCoord.xy) / %d, 0).r / "
                        "length(sc_ray_dir);\n"
                        "// The hull's front face (t = 1) lies behind the nearest surface so far.\n"
                        "if (sc_t_limit < 1.0)\n    discard;\n",
                        SCG_NEAREST_TILE);
    }
    output_declarations(&parts[OUTPUTS], key->outputs);
    if (key->ert == SCG_ERT_CONSERVATIVE)
        scg_text_append(&parts[OUTPUTS],
                        "// The hit lies on the ray behind the hull's front face: its depth is "
                        "never less\n// than the fragment's, so early depth testing may stay "
                        "on.\nlayout(depth_greater) out float gl_FragDepth;\n");

    unsigned need = needed_results(key->outputs);
    for (int s = 0; s < SCG_OUTPUT_COUNT; s++)
        if ((need & (1u << s)) && !use->outputs[s])
            return sc_fail_key(err, key_text,
                               "emitter: the program does not compute '%s', which the key's "
                               "outputs need", scg_output_info((scg_output_slot)s)->name);
    if (scg_emit_intersect_function(prog, &parts[FUNCTION], err) != SC_OK)
        return keyed(err, key_text);

    scg_text_append(&parts[CALL], "sc_intersect(");
    const char *sep = "";
    for (int s = 0; s < SCG_OUTPUT_COUNT; s++)
        if (use->outputs[s]) {
            const scg_slot_info *info = scg_output_info((scg_output_slot)s);
            scg_text_printf(&parts[RESULTS], "%s %s;\n", info->glsl_type, info->name);
            scg_text_printf(&parts[CALL], "%s%s", sep, info->name);
            sep = ", ";
        }
    scg_text_append(&parts[CALL], ");\n");

    if (key->outputs & (SCG_OUTPUT_SHADE | SCG_OUTPUT_AOV | SCG_OUTPUT_HULLVIEW)) {
        scg_text_append(&parts[WRITE], "\n");
        if (scg_template_expand(&parts[WRITE], "view_facing_normal.glsl", NULL, 0, err) != SC_OK)
            return SC_FAIL;
    }
    if (key->outputs & (SCG_OUTPUT_SHADE | SCG_OUTPUT_HULLVIEW)) {
        if (scg_template_expand(&parts[FUNCTIONS], "shade_headlight.glsl", NULL, 0, err) != SC_OK)
            return SC_FAIL;
        scg_text_append(&parts[FUNCTIONS], "\n");
    }
    if (key->outputs & SCG_OUTPUT_SHADE &&
        scg_template_expand(&parts[WRITE], "view_shade.glsl", NULL, 0, err) != SC_OK)
        return SC_FAIL;
    if (key->outputs & SCG_OUTPUT_AOV &&
        scg_template_expand(&parts[WRITE], "view_aov.glsl", NULL, 0, err) != SC_OK)
        return SC_FAIL;
    if (key->outputs & SCG_OUTPUT_ITERS) {
        char max_iters[16], span[32];
        snprintf(max_iters, sizeof max_iters, "%d", key->max_iters);
        float_literal((float)(key->max_iters > 1 ? key->max_iters - 1 : 1), span, sizeof span);
        scg_slot slots[] = {{"MAX_ITERS", max_iters}, {"MAX_ITERS_MINUS_ONE", span}};
        if (scg_template_expand(&parts[WRITE], "view_iters.glsl", slots, 2, err) != SC_OK)
            return SC_FAIL;
    }
    if (key->outputs & SCG_OUTPUT_UVVIEW &&
        scg_template_expand(&parts[WRITE], "view_uv.glsl", NULL, 0, err) != SC_OK)
        return SC_FAIL;
    if (!(key->outputs & SCG_OUTPUT_HULLVIEW)) {
        scg_text_append(&parts[ON_MISS], "if (!hit)\n    discard;\n");
        return SC_OK;
    }
    /* A miss still writes every declared output: the surface id marks it as
     * one, the rest is defined. */
    scg_text clear = {0};
    if (key->outputs & SCG_OUTPUT_SHADE)
        scg_text_append(&clear, "sc_colour = vec4(0.0);\n");
    if (key->outputs & SCG_OUTPUT_AOV)
        scg_text_append(&clear, "sc_aov_surface = -1;\nsc_aov_uvt = vec4(0.0);\n"
                                "sc_aov_point = vec4(0.0);\nsc_aov_normal = vec4(0.0);\n");
    if (key->outputs & SCG_OUTPUT_ITERS)
        scg_text_append(&clear, "sc_view_iters = vec4(0.0);\n");
    if (key->outputs & SCG_OUTPUT_UVVIEW)
        scg_text_append(&clear, "sc_view_uv = vec4(0.0);\n");
    scg_slot slot = {"CLEAR_OUTPUTS", scg_text_str(&clear)};
    int status = scg_template_expand(&parts[FUNCTIONS], "hull_colour.glsl", NULL, 0, err);
    if (status == SC_OK)
        status = scg_template_expand(&parts[ON_MISS], "view_hull_miss.glsl", &slot, 1, err);
    if (status == SC_OK)
        status = scg_template_expand(&parts[WRITE], "view_hull.glsl", NULL, 0, err);
    scg_text_free(&clear);
    return status;
}

int scg_emit_fragment(const scg_program *prog, scg_text *out, sc_error *err)
{
    static const char *const slot_names[] = {"HEADER", "INPUTS", "COLOUR_INPUT", "UNIFORMS",
                                             "TEXTURES", "OUTPUTS", "GLOBALS",
                                             "INTERSECT_FUNCTION", "FUNCTIONS", "PREPARE",
                                             "RESULTS", "CALL", "ON_MISS", "WRITE_OUTPUTS"};
    enum { NSLOTS = sizeof slot_names / sizeof slot_names[0] };
    program_use use;
    scan_use(prog, &use);
    scg_text parts[NSLOTS];
    memset(parts, 0, sizeof parts);
    int status = fragment_slots(prog, &use, parts, err);
    if (status == SC_OK) {
        scg_slot slots[NSLOTS];
        for (int s = 0; s < NSLOTS; s++)
            slots[s] = (scg_slot){slot_names[s], scg_text_str(&parts[s])};
        status = scg_template_expand(out, "raycast.frag", slots, NSLOTS, err);
    }
    for (int s = 0; s < NSLOTS; s++)
        scg_text_free(&parts[s]);
    return status;
}

/* ---- the vertex program ---- */

static int vertex_needs_colour(const scg_key *key) { return (key->outputs & SCG_OUTPUT_SHADE) != 0; }

const char *scg_vertex_program_name(const scg_key *key)
{
    switch (key->start) {
    case SC_START_CPMAP: return vertex_needs_colour(key) ? "hull-cp-colour" : "hull-cp";
    case SC_START_VIEW: return vertex_needs_colour(key) ? "hull-view-colour" : "hull-view";
    default: return vertex_needs_colour(key) ? "hull-mid-colour" : "hull-mid";
    }
}

int scg_emit_vertex(const scg_key *key, scg_text *out, sc_error *err)
{
    const char *name = scg_vertex_program_name(key);
    int uv = key->start == SC_START_CPMAP, colour = vertex_needs_colour(key);
    scg_text head = {0};
    scg_text_printf(&head, "// Generated by %s. Do not edit: regenerate with\n"
                           "//   splinecast gen --key KEY -o DIR (any key it serves)\n"
                           "// vertex program: %s\n"
                           "// stage: vertex program for the hulls; it serves every key with "
                           "start '%s'%s.\n",
                    SCG_GENERATOR_VERSION, name, uv ? "cp" : key->start == SC_START_VIEW ? "view" : "mid",
                    colour ? " and the shaded colour" : " and no shaded colour");
    char record_texels[16];
    snprintf(record_texels, sizeof record_texels, "%d", SCG_RECORD_TEXELS);
    char colour_line[160];
    snprintf(colour_line, sizeof colour_line,
             "sc_base_colour = texelFetch(sc_colours, int(texelFetch(sc_records, %d * "
             "sc_hull_record).w)).rgb;",
             SCG_RECORD_TEXELS);
    scg_slot slots[] = {
        {"HEADER", scg_text_str(&head)},
        {"UV_ATTRIBUTE", uv ? "layout(location = 1) in vec2 sc_hull_uv;" : ""},
        {"COLOUR_TEXTURE",
         colour ? "// Linear RGB of each surface, by surface id.\n"
                  "layout(binding = 3) uniform samplerBuffer sc_colours;"
                : ""},
        {"UV_OUTPUT", uv ? "layout(location = 2) out vec2 sc_uv0;" : ""},
        {"COLOUR_OUTPUT", colour ? "layout(location = 9) flat out vec3 sc_base_colour;" : ""},
        {"RECORD_TEXELS", record_texels},
        {"UV_START", uv ? "sc_uv0 = sc_hull_uv;" : ""},
        {"COLOUR", colour ? colour_line : ""},
    };
    int status = scg_template_expand(out, "hull.vert", slots, (int)(sizeof slots / sizeof slots[0]),
                                     err);
    scg_text_free(&head);
    return status;
}

/* ---- the pipeline for one key ---- */

static int generate(const scg_key *key, bool count_spirv, scg_generated *gen, sc_error *err)
{
    memset(gen, 0, sizeof *gen);
    scg_key_format(key, gen->key, sizeof gen->key);
    snprintf(gen->vertex_name, sizeof gen->vertex_name, "%s", scg_vertex_program_name(key));
    if (scg_build_program(key, &gen->program, err) != SC_OK) {
        keyed(err, gen->key);
        goto fail;
    }
    if (scg_emit_fragment(gen->program, &gen->fragment, err) != SC_OK ||
        scg_emit_vertex(key, &gen->vertex, err) != SC_OK) {
        keyed(err, gen->key);
        goto fail;
    }
    if (scg_glslang_check_program(scg_text_str(&gen->vertex), scg_text_str(&gen->fragment),
                                  gen->key, count_spirv ? &gen->vertex_check : NULL,
                                  count_spirv ? &gen->fragment_check : NULL, err) != SC_OK)
        goto fail;
    return SC_OK;
fail:
    scg_generated_free(gen);
    return SC_FAIL;
}

int scg_generate(const scg_key *key, scg_generated *gen, sc_error *err)
{
    return generate(key, false, gen, err);
}

int scg_generate_counted(const scg_key *key, scg_generated *gen, sc_error *err)
{
    return generate(key, true, gen, err);
}

void scg_generated_free(scg_generated *gen)
{
    if (gen->program)
        scg_program_free(gen->program);
    scg_text_free(&gen->fragment);
    scg_text_free(&gen->vertex);
    gen->program = NULL;
}
