/* assemble_glsl.c — the complete programs around the intersection function
 * (emit_glsl.h): the fragment program of a key and the vertex program that
 * draws its hulls, each a template (templates/) whose slots this file
 * fills. Everything the runtime binds is declared from the shader contract
 * (shader_contract.h), so no template and no line here holds a location or
 * a binding: this file only decides which declarations a program needs and
 * where they go. */
#include "emit_glsl.h"

#include <stdio.h>
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
    case SCG_EVAL_POWER: return "power basis by Horner's rule in the iteration, de Casteljau for the hit";
    }
    return "?";
}

static const char *method_words(sc_method method)
{
    switch (method) {
    case SC_METHOD_DEFAULT: break;
    case SC_METHOD_NEWTON: return "Newton iteration on the ray's two planes";
    case SC_METHOD_BROYDEN: return "Broyden iteration";
    case SC_METHOD_BCLIP: return "Bezier clipping";
    case SC_METHOD_SUBDIV: return "object-space subdivision";
    case SC_METHOD_HYBRID: return "Newton iteration, restarted across the sub-patch where it fails";
    }
    return "?";
}

static const char *start_words(sc_start start)
{
    switch (start) {
    case SC_START_MID: return "the centre of the hull's sub-patch domain";
    case SC_START_CPMAP: return "the control points' parameters, interpolated over the hull";
    case SC_START_VIEW: return "a view-dependent solve at the hull vertices";
    case SC_START_SECURE: return "0, the inflection points and 1 of the quartic along the ray";
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
    case SCG_ERT_PEEL: return "depth peeling: no depth written, the hit kept when nearer than "
                              "the best so far";
    case SCG_ERT_LISTS: return "candidate lists: each pixel's hulls, nearest box first, until "
                               "a hit lies in front of the next box";
    }
    return "?";
}

static void describe_key(scg_text *out, const scg_key *key)
{
    char degrees[32] = "of any degree";
    if (key->kind == SCG_PATCH_TRIANGLE)
        snprintf(degrees, sizeof degrees, "of degree %d", key->deg_u);
    else if (key->eval != SCG_EVAL_LOOP)
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
    int tri = key->kind == SCG_PATCH_TRIANGLE;
    scg_text_printf(out, "// evaluation: %s\n",
                    tri ? "blossoming to the polynomial along the projected ray, unrolled"
                        : eval_words(key->eval));
    scg_text_printf(out,
                    "// method: %s, at most %d iteration%s,\n"
                    "//   tolerance %g pixel footprints\n"
                    "// start: %s\n",
                    tri ? "Newton iteration on it from four starts at once"
                        : method_words(key->method),
                    key->max_iters, key->max_iters == 1 ? "" : "s",
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

/* ---- declarations, from the contract ---- */

/* One declaration line, without its newline. */
typedef char decl_line[160];

static const char *attrib_line(decl_line buf, int location)
{
    const scg_slot_info *a = scg_contract_find(scg_attribs, SCG_ATTRIB_ENTRIES, location);
    snprintf(buf, sizeof(decl_line), "layout(location = %d) in %s %s;", a->location,
             a->glsl_type, a->name);
    return buf;
}

/* `storage` is "in" (fragment stage) or "out" (vertex stage). */
static const char *varying_line(decl_line buf, const scg_slot_info *v, const char *storage)
{
    snprintf(buf, sizeof(decl_line), "layout(location = %d) %s%s %s %s;", v->location,
             v->flat ? "flat " : "", storage, v->glsl_type, v->name);
    return buf;
}

static const char *varying_at(decl_line buf, int location, const char *storage)
{
    return varying_line(buf, scg_contract_find(scg_varyings, SCG_VARYING_ENTRIES, location),
                        storage);
}

static const char *uniform_line(decl_line buf, const scg_slot_info *u)
{
    snprintf(buf, sizeof(decl_line), "layout(location = %d) uniform %s %s;", u->location,
             u->glsl_type, u->name);
    return buf;
}

static const char *uniform_at(decl_line buf, int location)
{
    return uniform_line(buf, scg_contract_find(scg_uniforms, SCG_UNIFORM_ENTRIES, location));
}

static const char *texture_line(decl_line buf, const scg_slot_info *t)
{
    snprintf(buf, sizeof(decl_line), "layout(binding = %d) uniform %s %s;", t->location,
             t->glsl_type, t->name);
    return buf;
}

static const char *texture_at(decl_line buf, int unit)
{
    return texture_line(buf, scg_contract_find(scg_textures, SCG_TEXTURE_ENTRIES, unit));
}

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

/* The parts of the fragment skeletons, in the order of slot_names: those of
 * raycast.frag (hulls) and of listcast.frag (ert5's candidate lists). */
enum { HEADER, INPUTS, CENTRE, BASE_COLOUR, VIEW_PROJECTION, UNIFORMS, TEXTURES, OUTPUTS, GLOBALS,
       FUNCTION, FUNCTIONS, PREPARE, RESULTS, CALL, ON_MISS, DEPTH, WRITE,
       /* listcast.frag's own */
       CANDIDATE_RESULTS, COUNT, KEEP, RECORD_TEXELS, FETCH_BASE_COLOUR, NPARTS };
static const char *const hull_slot_names[] = {
    [HEADER] = "HEADER", [INPUTS] = "INPUTS", [CENTRE] = "VARYING_CENTRE",
    [BASE_COLOUR] = "VARYING_BASE_COLOUR", [VIEW_PROJECTION] = "UNIFORM_VIEW_PROJECTION",
    [UNIFORMS] = "UNIFORMS", [TEXTURES] = "TEXTURES", [OUTPUTS] = "OUTPUTS",
    [GLOBALS] = "GLOBALS", [FUNCTION] = "INTERSECT_FUNCTION", [FUNCTIONS] = "FUNCTIONS",
    [PREPARE] = "PREPARE", [RESULTS] = "RESULTS", [CALL] = "CALL", [ON_MISS] = "ON_MISS",
    [DEPTH] = "DEPTH", [WRITE] = "WRITE_OUTPUTS"};
static const char *const list_slot_names[] = {
    [HEADER] = "HEADER", [INPUTS] = "INPUTS", [CENTRE] = "GLOBAL_CENTRE",
    [BASE_COLOUR] = "GLOBAL_BASE_COLOUR", [VIEW_PROJECTION] = "UNIFORM_VIEW_PROJECTION",
    [UNIFORMS] = "UNIFORMS", [TEXTURES] = "TEXTURES", [OUTPUTS] = "OUTPUTS",
    [GLOBALS] = "GLOBALS", [FUNCTION] = "INTERSECT_FUNCTION", [FUNCTIONS] = "FUNCTIONS",
    [PREPARE] = NULL, [RESULTS] = "RESULTS", [CALL] = "CALL", [ON_MISS] = "ON_MISS",
    [DEPTH] = "DEPTH", [WRITE] = "WRITE_OUTPUTS", [CANDIDATE_RESULTS] = "CANDIDATE_RESULTS",
    [COUNT] = "COUNT", [KEEP] = "KEEP", [RECORD_TEXELS] = "RECORD_TEXELS",
    [FETCH_BASE_COLOUR] = "BASE_COLOUR"};

/* A global of the list skeleton, "vec3 sc_centre = vec3(0.0);": set
 * before the intersection reads it, but drivers cannot tell. */
static const char *global_line(decl_line buf, const scg_slot_info *v)
{
    int scalar = !strcmp(v->glsl_type, "int") || !strcmp(v->glsl_type, "float");
    snprintf(buf, sizeof(decl_line), "%s %s = %s%s0%s;", v->glsl_type, v->name,
             scalar ? "" : v->glsl_type, scalar ? "" : "(", scalar ? "" : ".0)");
    return buf;
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
    for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++) {
        const scg_frag_out_info *o = &scg_frag_outs[i];
        if (outputs & o->key_output)
            scg_text_printf(out, "layout(location = %d) out %s %s;\n", o->location, o->glsl_type,
                            o->name);
    }
}

static int fragment_slots(const scg_program *prog, const scg_program_use *use, scg_text *parts,
                          sc_error *err)
{
    const scg_key *key = &prog->key;
    char key_text[SCG_KEY_MAX];
    scg_key_format(key, key_text, sizeof key_text);
    int lists = key->ert == SCG_ERT_LISTS;
    decl_line line;

    char stage[96];
    snprintf(stage, sizeof stage, "fragment program, drawn with vertex program %s.vert",
             scg_vertex_program_name(key));
    header(&parts[HEADER], stage, key_text);
    describe_key(&parts[HEADER], key);

    /* The skeleton reads the ray itself (depth, normals); the list
     * skeleton sets the record and its domain for each candidate. */
    for (int s = 0; s < SCG_INPUT_COUNT; s++) {
        /* The hull view colours by the hull's record and domain. */
        int hull_id = (key->outputs & SCG_OUTPUT_HULLVIEW) &&
                      (s == SCG_IN_DOMAIN || s == SCG_IN_RECORD);
        int list_sets = lists && (s == SCG_IN_DOMAIN || s == SCG_IN_RECORD);
        if (s == SCG_IN_T_LIMIT || (!use->inputs[s] && s != SCG_IN_RAY_DIR &&
                                    s != SCG_IN_RAY_ORIGIN && !hull_id && !list_sets))
            continue;
        const scg_slot_info *in = scg_input_info((scg_input_slot)s);
        scg_text_printf(&parts[INPUTS], "%s\n",
                        lists ? global_line(line, in) : varying_line(line, in, "in"));
    }
    const scg_slot_info *centre =
        scg_contract_find(scg_varyings, SCG_VARYING_ENTRIES, SCG_VARYING_CENTRE);
    const scg_slot_info *base_colour =
        scg_contract_find(scg_varyings, SCG_VARYING_ENTRIES, SCG_VARYING_BASE_COLOUR);
    int shade = (key->outputs & SCG_OUTPUT_SHADE) != 0;
    scg_text_append(&parts[CENTRE],
                    lists ? global_line(line, centre) : varying_line(line, centre, "in"));
    if (shade)
        scg_text_append(&parts[BASE_COLOUR], lists ? global_line(line, base_colour)
                                                   : varying_line(line, base_colour, "in"));
    scg_text_append(&parts[VIEW_PROJECTION], uniform_at(line, SCG_LOC_VIEW_PROJECTION));
    for (int s = 0; s < SCG_UNIFORM_COUNT; s++)
        if (use->uniforms[s])
            scg_text_printf(&parts[UNIFORMS], "%s\n",
                            uniform_line(line, scg_uniform_info((scg_uniform_slot)s)));
    if (lists) {
        static const int list_uniforms[] = {SCG_LOC_EYE, SCG_LOC_EYE_LOW, SCG_LOC_PIXEL_TO_RAY,
                                            SCG_LOC_LIST_CELLS};
        for (size_t i = 0; i < sizeof list_uniforms / sizeof list_uniforms[0]; i++)
            scg_text_printf(&parts[UNIFORMS], "%s\n", uniform_at(line, list_uniforms[i]));
    }
    int any_texture = use->inputs[SCG_IN_T_LIMIT] || lists;
    for (int s = 0; s < SCG_TEXTURE_COUNT; s++)
        any_texture |= use->textures[s];
    if (any_texture)
        scg_text_append(&parts[TEXTURES],
                        "// Patch data (gpu_layout.h), bound to the unit equal to the binding.\n");
    for (int s = 0; s < SCG_TEXTURE_COUNT; s++)
        if (use->textures[s] || (lists && s == SCG_TEX_RECORDS))
            scg_text_printf(&parts[TEXTURES], "%s\n",
                            texture_line(line, scg_texture_info((scg_texture)s)));
    if (lists) {
        if (shade)
            scg_text_printf(&parts[TEXTURES], "// Linear RGB of each surface, by surface id.\n%s\n",
                            texture_at(line, SCG_UNIT_COLOURS));
        static const int list_units[] = {SCG_UNIT_LIST_HEADS, SCG_UNIT_LIST_ITEMS,
                                         SCG_UNIT_LIST_HULLS};
        scg_text_append(&parts[TEXTURES], "// The candidate lists (shader_contract.h).\n");
        for (size_t i = 0; i < sizeof list_units / sizeof list_units[0]; i++)
            scg_text_printf(&parts[TEXTURES], "%s\n", texture_at(line, list_units[i]));
        scg_text_append(&parts[GLOBALS],
                        "// Early ray termination: the nearest hit of the candidates run so "
                        "far, in\n// units of sc_ray_dir.\nfloat sc_t_limit = 3.0e38;\n\n");
        char texels[16];
        snprintf(texels, sizeof texels, "%d", SCG_RECORD_TEXELS);
        scg_text_append(&parts[RECORD_TEXELS], texels);
        if (shade)
            scg_text_printf(&parts[FETCH_BASE_COLOUR],
                            "sc_base_colour = texelFetch(sc_colours, int(texelFetch(sc_records, "
                            "%d * sc_record).w)).rgb;",
                            SCG_RECORD_TEXELS);
    } else if (use->inputs[SCG_IN_T_LIMIT]) {
        scg_text_printf(&parts[TEXTURES],
                        "// Per tile of %d x %d pixels, the largest distance along the unit ray to "
                        "the\n// nearest surfaces drawn so far.\n%s\n",
                        SCG_NEAREST_TILE, SCG_NEAREST_TILE, texture_at(line, SCG_UNIT_NEAREST_T));
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
    /* Counted on the GPU, after the early-termination test: each fragment
     * that gets here runs the intersection once. The count is a figure of
     * the frames that measure (those writing the AOVs), as the AOVs are:
     * a shaded frame's programs leave out the atomic add, which cost 6.5 %
     * of the teapot's frame on llvmpipe (docs/speed.md). */
    if (key->outputs & SCG_OUTPUT_AOV) {
        scg_text_printf(&parts[OUTPUTS],
                        "// Intersections run, counted by the runtime per frame.\n"
                        "layout(std430, binding = %d) buffer %s {\n    uint %s;\n};\n",
                        SCG_BUFFER_COUNTERS, SCG_COUNTERS_BLOCK, SCG_COUNTER_INTERSECTIONS);
        scg_text_printf(&parts[lists ? COUNT : PREPARE], "atomicAdd(%s, 1u);\n",
                        SCG_COUNTER_INTERSECTIONS);
    }
    if (key->ert == SCG_ERT_CONSERVATIVE)
        scg_text_append(&parts[OUTPUTS],
                        "// The hit lies on the ray behind the hull's front face: its depth is "
                        "never less\n// than the fragment's, so early depth testing may stay "
                        "on.\nlayout(depth_greater) out float gl_FragDepth;\n");
    if (key->ert == SCG_ERT_PEEL) {
        /* Nothing here writes gl_FragDepth, so the depth test can run
         * before the program, and it must: the image store is a side
         * effect, which GL otherwise keeps for fragments that fail. */
        scg_text_printf(&parts[OUTPUTS],
                        "// Depth peeling: the depth test (equal to this layer's hull entry) "
                        "runs before\n// the program; the window depth of the nearest hit so "
                        "far, per pixel.\nlayout(early_fragment_tests) in;\n"
                        "layout(r32f, binding = %d) uniform coherent image2D %s;\n",
                        SCG_IMAGE_BEST_DEPTH, SCG_BEST_DEPTH_NAME);
        /* One fragment a pixel passes the test of a layer (hulls meeting at
         * exactly the same depth aside), so the load and store do not race. */
        scg_text_printf(&parts[DEPTH],
                        "float sc_depth = 0.5 * (clip.z / clip.w) + 0.5;\n"
                        "// A nearer hit of an earlier layer stays.\n"
                        "if (sc_depth >= imageLoad(%s, ivec2(gl_FragCoord.xy)).r)\n"
                        "    discard;\n"
                        "imageStore(%s, ivec2(gl_FragCoord.xy), vec4(sc_depth));",
                        SCG_BEST_DEPTH_NAME, SCG_BEST_DEPTH_NAME);
    } else {
        scg_text_append(&parts[DEPTH], "gl_FragDepth = 0.5 * (clip.z / clip.w) + 0.5;");
    }

    /* The list skeleton keeps the nearest hit by its t. */
    unsigned need = needed_results(key->outputs) | (lists ? 1u << SCG_OUT_T : 0);
    for (int s = 0; s < SCG_OUTPUT_COUNT; s++)
        if ((need & (1u << s)) && !use->outputs[s])
            return sc_fail_key(err, key_text,
                               "emitter: the program does not compute '%s', which the key's "
                               "outputs need", scg_output_info((scg_output_slot)s)->name);
    if (scg_emit_intersect_function(prog, &parts[FUNCTION], err) != SC_OK)
        return keyed(err, key_text);

    /* The list skeleton calls it for each candidate and keeps the nearest
     * hit's results in the names the writes read. */
    scg_text_append(&parts[CALL], "sc_intersect(");
    const char *sep = "", *prefix = lists ? "candidate_" : "";
    for (int s = 0; s < SCG_OUTPUT_COUNT; s++)
        if (use->outputs[s]) {
            const scg_slot_info *info = scg_output_info((scg_output_slot)s);
            scg_text_printf(&parts[RESULTS], "%s %s%s;\n", info->glsl_type, info->name,
                            lists && s == SCG_OUT_HIT ? " = false" : "");
            scg_text_printf(&parts[CALL], "%s%s%s", sep, prefix, info->name);
            if (lists) {
                scg_text_printf(&parts[CANDIDATE_RESULTS], "%s %s%s;\n", info->glsl_type, prefix,
                                info->name);
                scg_text_printf(&parts[KEEP], "%s = %s%s;\n", info->name, prefix, info->name);
            }
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
        scg_glsl_float_literal((float)(key->max_iters > 1 ? key->max_iters - 1 : 1), span,
                               sizeof span);
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
    for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++) {
        const scg_frag_out_info *o = &scg_frag_outs[i];
        if ((key->outputs & o->key_output) && o->miss)
            scg_text_printf(&clear, "%s = %s;\n", o->name, o->miss);
    }
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
    int lists = prog->key.ert == SCG_ERT_LISTS;
    const char *const *names = lists ? list_slot_names : hull_slot_names;
    int nnames = lists ? NPARTS : WRITE + 1;
    scg_program_use use;
    scg_program_scan_use(prog, &use);
    scg_text parts[NPARTS];
    memset(parts, 0, sizeof parts);
    int status = fragment_slots(prog, &use, parts, err);
    if (status == SC_OK) {
        scg_slot slots[NPARTS];
        int n = 0;
        for (int s = 0; s < nnames; s++)
            if (names[s])
                slots[n++] = (scg_slot){names[s], scg_text_str(&parts[s])};
        status = scg_template_expand(out, lists ? "listcast.frag" : "raycast.frag", slots, n, err);
    }
    for (int s = 0; s < NPARTS; s++)
        scg_text_free(&parts[s]);
    return status;
}

/* ---- the vertex program ---- */

static int vertex_needs_colour(const scg_key *key) { return (key->outputs & SCG_OUTPUT_SHADE) != 0; }

const char *scg_vertex_program_name(const scg_key *key)
{
    if (key->ert == SCG_ERT_LISTS)
        return "list-tiles";
    switch (key->start) {
    case SC_START_CPMAP: return vertex_needs_colour(key) ? "hull-cp-colour" : "hull-cp";
    case SC_START_VIEW: {
        /* Its solve is generated for the key: the fields it depends on
         * (scg_view_start_key) name it, "hull-view-bez3x3-poly-dc-it6-tol0.05". */
        static _Thread_local char name[64];
        char text[SCG_KEY_MAX];
        scg_key k = scg_view_start_key(key);
        scg_key_format(&k, text, sizeof text);
        /* kind-rational-eval, then itN-tolT: fields 0-2 and 6-7 of the text. */
        const char *fields[10] = {0};
        int n = 0;
        fields[n++] = text;
        for (char *c = text; *c && n < 10; c++)
            if (*c == '-') {
                *c = 0;
                fields[n++] = c + 1;
            }
        /* At most 10 + 10 + 5 + 5 + 5 + 12 + 7 = 54 characters. */
        snprintf(name, sizeof name, "hull-view-%.10s-%.4s-%.4s-%.4s-%.11s%s", fields[0], fields[1], fields[2],
                 fields[6], fields[7], vertex_needs_colour(key) ? "-colour" : "");
        return name;
    }
    default: return vertex_needs_colour(key) ? "hull-mid-colour" : "hull-mid";
    }
}

/* The vertex stage's solve of a `view` key: its declarations (the uniform
 * and patch textures it reads beyond the records) and the statements of
 * main() that set sc_uv0. */
static int view_start_parts(const scg_key *key, scg_text *decls, scg_text *start, sc_error *err)
{
    scg_program *prog;
    if (scg_build_view_start_program(key, &prog, err) != SC_OK)
        return SC_FAIL;
    scg_program_use use;
    scg_program_scan_use(prog, &use);
    decl_line line;
    scg_text_append(decls, "// What the start's Newton solve reads: the pixel footprint and the "
                           "patch data.\n");
    for (int s = 0; s < SCG_UNIFORM_COUNT; s++)
        if (use.uniforms[s])
            scg_text_printf(decls, "%s\n", uniform_line(line, scg_uniform_info((scg_uniform_slot)s)));
    for (int s = 0; s < SCG_TEXTURE_COUNT; s++)
        if (use.textures[s] && s != SCG_TEX_RECORDS)
            scg_text_printf(decls, "%s\n", texture_line(line, scg_texture_info((scg_texture)s)));
    scg_text_append(start, "// Seed 000 section 4.4: the ray from the eye through this hull vertex, "
                           "solved with\n// Newton's method from the vertex's control-point "
                           "parameters; the rasteriser\n// interpolates the result as the "
                           "fragment's start.\nsc_uv0 = sc_hull_uv;\nvec2 start_uv;\n");
    int status = scg_emit_view_start_block(prog, start, err);
    scg_text_append(start, "sc_uv0 = start_uv;");
    scg_program_free(prog);
    return status;
}

/* ert5: tiles of pixels, a point each; the fragment stage computes each
 * pixel's ray. */
static int emit_list_tiles(const scg_key *key, scg_text *out, sc_error *err)
{
    scg_text head = {0};
    scg_text_printf(&head, "// Generated by %s. Do not edit: regenerate with\n"
                           "//   splinecast gen --key KEY -o DIR (any key it serves)\n"
                           "// vertex program: %s\n"
                           "// stage: vertex program for the tiles of candidate lists; it "
                           "serves every ert5 key.\n",
                    SCG_GENERATOR_VERSION, scg_vertex_program_name(key));
    decl_line tile, tiles;
    scg_slot slots[] = {{"HEADER", scg_text_str(&head)},
                        {"UNIFORM_LIST_TILE", uniform_at(tile, SCG_LOC_LIST_TILE)},
                        {"TEXTURE_LIST_TILES", texture_at(tiles, SCG_UNIT_LIST_TILES)}};
    int status = scg_template_expand(out, "list_tiles.vert", slots, 3, err);
    scg_text_free(&head);
    return status;
}

int scg_emit_vertex(const scg_key *key, scg_text *out, sc_error *err)
{
    if (key->ert == SCG_ERT_LISTS)
        return emit_list_tiles(key, out, err);
    const char *name = scg_vertex_program_name(key);
    int view = key->start == SC_START_VIEW;
    int uv = key->start == SC_START_CPMAP || view, colour = vertex_needs_colour(key);
    scg_text head = {0}, view_decls = {0}, view_start = {0};
    if (view && view_start_parts(key, &view_decls, &view_start, err) != SC_OK) {
        scg_text_free(&view_decls);
        scg_text_free(&view_start);
        return SC_FAIL;
    }
    scg_text_printf(&head, "// Generated by %s. Do not edit: regenerate with\n"
                           "//   splinecast gen --key KEY -o DIR (any key it serves)\n"
                           "// vertex program: %s\n"
                           "// stage: vertex program for the hulls; it serves every key with "
                           "start '%s'%s.\n",
                    SCG_GENERATOR_VERSION, name, view ? "view" : uv ? "cp" : "mid",
                    colour ? " and the shaded colour" : " and no shaded colour");
    char record_texels[16];
    snprintf(record_texels, sizeof record_texels, "%d", SCG_RECORD_TEXELS);
    char colour_line[160];
    snprintf(colour_line, sizeof colour_line,
             "sc_base_colour = texelFetch(sc_colours, int(texelFetch(sc_records, %d * "
             "sc_hull_record).w)).rgb;",
             SCG_RECORD_TEXELS);
    decl_line colour_texture;
    char colour_texture_slot[sizeof colour_texture + 64];
    snprintf(colour_texture_slot, sizeof colour_texture_slot,
             "// Linear RGB of each surface, by surface id.\n%s",
             texture_at(colour_texture, SCG_UNIT_COLOURS));
    /* Every attribute and every varying has its line in the template; the
     * start values and the colour only where the key needs them. */
    scg_slot slots[32];
    decl_line lines[32];
    int n = 0;
#define SLOT(name, text) (slots[n] = (scg_slot){name, text}, n++)
#define ATTRIB(ID, needed) SLOT("ATTRIB_" #ID, (needed) ? attrib_line(lines[n], SCG_ATTRIB_##ID) : "")
#define VARYING(ID, needed) \
    SLOT("VARYING_" #ID, (needed) ? varying_at(lines[n], SCG_VARYING_##ID, "out") : "")
#define UNIFORM(ID) SLOT("UNIFORM_" #ID, uniform_at(lines[n], SCG_LOC_##ID))
    SLOT("HEADER", scg_text_str(&head));
    ATTRIB(HULL_POSITION, 1);
    ATTRIB(HULL_UV, uv);
    ATTRIB(HULL_DOMAIN, 1);
    ATTRIB(HULL_RECORD, 1);
    ATTRIB(HULL_RASTER_POSITION, 1);
    UNIFORM(VIEW_PROJECTION);
    UNIFORM(EYE);
    UNIFORM(EYE_LOW);
    UNIFORM(RASTER_EYE);
    SLOT("TEXTURE_RECORDS", texture_at(lines[n], SCG_UNIT_RECORDS));
    SLOT("COLOUR_TEXTURE", colour ? colour_texture_slot : "");
    VARYING(RAY_ORIGIN, 1);
    VARYING(RAY_DIR, 1);
    VARYING(UV0, uv);
    VARYING(DOMAIN, 1);
    VARYING(RECORD, 1);
    VARYING(CENTRE, 1);
    VARYING(BASE_COLOUR, colour);
    SLOT("RECORD_TEXELS", record_texels);
    SLOT("VIEW_START_DECLARATIONS", scg_text_str(&view_decls));
    SLOT("UV_START", view ? scg_text_str(&view_start) : uv ? "sc_uv0 = sc_hull_uv;" : "");
    SLOT("COLOUR", colour ? colour_line : "");
#undef SLOT
#undef ATTRIB
#undef VARYING
#undef UNIFORM
    int status = scg_template_expand(out, "hull.vert", slots, n, err);
    scg_text_free(&head);
    scg_text_free(&view_decls);
    scg_text_free(&view_start);
    return status;
}
