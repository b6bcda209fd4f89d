/* test_contract.c — the shader contract (gen/shader_contract.h) holds on
 * both sides: its tables are consistent (no location shared within a kind,
 * the IR's slots are its entries), every location and binding the
 * generated programs declare is an entry with the same name and type, the
 * runtime's gpu_vertex is laid out as the attribute table says, and a
 * renderer's target has the output table's attachments, in its order. */
#include "gl_context_util.h"
#include "test.h"

#include <stdlib.h>

#include "emit_glsl.h"
#include "gl_context.h"
#include "gl_render_private.h"
#include "io.h"
#include "shader_contract.h"

/* No two entries of a table share a location or a name. */
static int distinct(const scg_slot_info *table, int entries, const char *what)
{
    for (int i = 0; i < entries; i++)
        for (int j = i + 1; j < entries; j++)
            if (table[i].location == table[j].location || !strcmp(table[i].name, table[j].name)) {
                fprintf(stderr, "  %s: %s and %s share a location or a name\n", what,
                        table[i].name, table[j].name);
                return 0;
            }
    return 1;
}

TEST(contract_tables_are_consistent)
{
    CHECK(distinct(scg_attribs, SCG_ATTRIB_ENTRIES, "attributes"));
    CHECK(distinct(scg_varyings, SCG_VARYING_ENTRIES, "varyings"));
    CHECK(distinct(scg_uniforms, SCG_UNIFORM_ENTRIES, "uniforms"));
    CHECK(distinct(scg_textures, SCG_TEXTURE_ENTRIES, "textures"));
    for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++) {
        const scg_frag_out_info *o = &scg_frag_outs[i];
        CHECK(o->location >= 0 && o->location < SC_GL_TARGET_MAX_COLOURS);
        CHECK(o->key_output && !(o->key_output & (o->key_output - 1)));
        for (int j = i + 1; j < SCG_FRAG_OUT_ENTRIES; j++) {
            CHECK(o->location != scg_frag_outs[j].location);
            CHECK(strcmp(o->name, scg_frag_outs[j].name) != 0);
        }
    }
    /* The IR's slots are entries of the contract; the patch textures lie
     * on consecutive units from SCG_UNIT_POINTS (sc_gpu_data_bind). */
    for (int s = 0; s < SCG_TEXTURE_COUNT; s++) {
        const scg_slot_info *t = scg_texture_info((scg_texture)s);
        CHECK_INT(t->location, SCG_UNIT_POINTS + s);
        CHECK(t == scg_contract_find(scg_textures, SCG_TEXTURE_ENTRIES, t->location));
    }
    for (int s = 0; s < SCG_INPUT_COUNT; s++) {
        const scg_slot_info *in = scg_input_info((scg_input_slot)s);
        if (s == SCG_IN_T_LIMIT)
            CHECK_INT(in->location, -1);
        else
            CHECK(in == scg_contract_find(scg_varyings, SCG_VARYING_ENTRIES, in->location));
    }
    for (int s = 0; s < SCG_UNIFORM_COUNT; s++) {
        const scg_slot_info *u = scg_uniform_info((scg_uniform_slot)s);
        CHECK(u == scg_contract_find(scg_uniforms, SCG_UNIFORM_ENTRIES, u->location));
        CHECK_STR(u->glsl_type, "float");   /* the IR's uniforms are floats */
    }
}

/* The declaration on a line of generated GLSL, if it has a layout. */
typedef struct declaration {
    int location, binding;          /* -1 when absent */
    int flat;
    char storage[16], type[32], name[64];
} declaration;

static int parse_declaration(const char *line, declaration *d)
{
    memset(d, 0, sizeof *d);
    d->location = d->binding = -1;
    int n = 0;
    if (sscanf(line, "layout(location = %d) %n", &d->location, &n) != 1 &&
        sscanf(line, "layout(binding = %d) %n", &d->binding, &n) != 1)
        return 0;
    const char *rest = line + n;
    if (!strncmp(rest, "flat ", 5)) {
        d->flat = 1;
        rest += 5;
    }
    return sscanf(rest, "%15s %31s %63[a-z_0-9];", d->storage, d->type, d->name) == 3;
}

/* The entry of `table` that `d` declares: same location, name and type. */
static int declares(const declaration *d, const scg_slot_info *table, int entries, int location)
{
    const scg_slot_info *e = scg_contract_find(table, entries, location);
    return e && !strcmp(e->name, d->name) && !strcmp(e->glsl_type, d->type) &&
           (table != scg_varyings || e->flat == d->flat);
}

/* Checks every layout line of one stage; counts the fragment outputs (by
 * location bit) and the varyings (by location, 1 + flat) it declares. */
static int check_stage(const char *glsl, int fragment, unsigned *frag_outs, int varyings[16])
{
    const char *stage = fragment ? "frag" : "vert";
    int binding = -1;
    for (const char *line = glsl; *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        char buf[256];
        snprintf(buf, sizeof buf, "%.*s", (int)(len < 255 ? len : 255), line);
        line += len + (end != NULL);
        if (strncmp(buf, "layout(", 7) || !strncmp(buf, "layout(depth_greater)", 21) ||
            (fragment && !strcmp(buf, "layout(early_fragment_tests) in;")))
            continue;
        /* Depth peeling's image of the best hit so far: fragment stage only. */
        char image[64] = "";
        if (sscanf(buf, "layout(r32f, binding = %d) uniform coherent image2D %63[a-z_0-9];", &binding,
                   image) == 2) {
            if (fragment && binding == SCG_IMAGE_BEST_DEPTH && !strcmp(image, SCG_BEST_DEPTH_NAME))
                continue;
            fprintf(stderr, "  %s: not in the contract: %s\n", stage, buf);
            return 0;
        }
        /* The counters' block: fragment stage only, its binding and names. */
        char block[64] = "";
        if (sscanf(buf, "layout(std430, binding = %d) buffer %63[a-z_0-9] {", &binding, block) == 2) {
            if (fragment && binding == SCG_BUFFER_COUNTERS && !strcmp(block, SCG_COUNTERS_BLOCK))
                continue;
            fprintf(stderr, "  %s: not in the contract: %s\n", stage, buf);
            return 0;
        }
        declaration d;
        int ok = parse_declaration(buf, &d);
        if (ok && d.binding >= 0)
            ok = !strcmp(d.storage, "uniform") &&
                 declares(&d, scg_textures, SCG_TEXTURE_ENTRIES, d.binding);
        else if (ok && !strcmp(d.storage, "uniform"))
            ok = declares(&d, scg_uniforms, SCG_UNIFORM_ENTRIES, d.location);
        else if (ok && !fragment && !strcmp(d.storage, "in"))
            ok = !d.flat && declares(&d, scg_attribs, SCG_ATTRIB_ENTRIES, d.location);
        else if (ok && fragment && !strcmp(d.storage, "out")) {
            ok = 0;
            for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++)
                if (scg_frag_outs[i].location == d.location) {
                    ok = !d.flat && !strcmp(scg_frag_outs[i].name, d.name) &&
                         !strcmp(scg_frag_outs[i].glsl_type, d.type);
                    *frag_outs |= 1u << d.location;
                }
        } else if (ok) {
            ok = declares(&d, scg_varyings, SCG_VARYING_ENTRIES, d.location) &&
                 d.location < 16;
            if (ok)
                varyings[d.location] = 1 + d.flat;
        }
        if (!ok) {
            fprintf(stderr, "  %s: not in the contract: %s\n", stage, buf);
            return 0;
        }
    }
    return 1;
}

TEST(contract_generated_glsl_declares_only_the_contract)
{
    /* Colour and none, start values (cp, view) and none, AOVs, every debug view,
     * both early terminations that read or declare something, NURBS
     * knots, the generic program. */
    static const char *const keys[] = {
        "bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "bez1x1-poly-dc-trim0-newton-mid-it1-tol0.25-ert0-out.aov",
        "bez2x3-rat-dc-trim0-newton-cp-it4-tol0.25-ert0-out.shade.aov",
        "bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade.aov.iters.uv.hull",
        "bez2x2-rat-dc-trim0-newton-cp-it4-tol0.25-ert1-out.hull",
        "bez3x3-poly-bern-trim0-newton-mid-it4-tol0.25-ert3-out.aov.uv",
        "nurbs2x2-rat-dc-trim0-newton-mid-it4-tol0.25-ert2-out.shade",
        /* depth peeling: the image of the best hit so far */
        "bez3x3-poly-dc-trim0-hybrid-cp-it6-tol0.05-ert4-out.shade.aov",
        "bezdyn-poly-loop-trim0-newton-cp-it4-tol0.25-ert0-out.iters",
        /* the vertex stage's solve of the view start */
        "nurbs2x3-rat-dc-trim0-hybrid-view-it3-tol0.25-ert1-out.shade",
    };
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        scg_key key;
        sc_error err = {0};
        CHECK_INT(scg_key_parse(keys[k], &key, &err), SC_OK);
        scg_generated gen;
        if (scg_generate(&key, &gen, &err) != SC_OK) {
            fprintf(stderr, "  %s: %s\n", keys[k], err.message);
            CHECK(0);
        }
        unsigned frag_outs = 0, unused = 0;
        int vert_out[16] = {0}, frag_in[16] = {0};
        int ok = check_stage(scg_text_str(&gen.vertex), 0, &unused, vert_out) &&
                 check_stage(scg_text_str(&gen.fragment), 1, &frag_outs, frag_in);
        scg_generated_free(&gen);
        if (!ok)
            fprintf(stderr, "  key %s\n", keys[k]);
        CHECK(ok);
        /* The outputs the key asks for, and each fragment input written by
         * the vertex program with the same interpolation. */
        unsigned expected = 0;
        for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++)
            if (key.outputs & scg_frag_outs[i].key_output)
                expected |= 1u << scg_frag_outs[i].location;
        CHECK_INT(frag_outs, expected);
        for (int l = 0; l < 16; l++)
            if (frag_in[l])
                CHECK_INT(vert_out[l], frag_in[l]);
    }
}

TEST(contract_gpu_vertex_matches_attributes)
{
    CHECK_INT(sizeof gpu_vertex_fields / sizeof gpu_vertex_fields[0], SCG_ATTRIB_ENTRIES);
    size_t total = 0;
#define X(ID, location, name, type, components, component_type)                     \
    do {                                                                               \
        const gpu_vertex_field *f = &gpu_vertex_fields[location];                      \
        CHECK_INT(f->size, (components) * sizeof(SC_C_##component_type));              \
        for (int other = 0; other < SCG_ATTRIB_ENTRIES; other++) {                     \
            const gpu_vertex_field *g = &gpu_vertex_fields[other];                     \
            if (other != (location))                                                   \
                CHECK(f->offset + f->size <= g->offset || g->offset + g->size <= f->offset); \
        }                                                                              \
        total += f->size;                                                              \
    } while (0);
#define SC_C_FLOAT float
#define SC_C_INT int32_t
    SCG_ATTRIBS(X)
#undef X
    /* Nothing in gpu_vertex that no attribute reads. */
    CHECK_INT(total, sizeof(gpu_vertex));
}

TEST(contract_render_target_has_the_output_table)
{
    TEST_NEED_GL_CONTEXT(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    static const sc_show views[] = {SC_SHOW_SHADE, SC_SHOW_UV, SC_SHOW_ITERS, SC_SHOW_HULL,
                                    SC_SHOW_DEPTH};
    for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
        sc_render_desc desc = {.view = views[v]};
        sc_renderer *r;
        CHECK_INT(sc_renderer_create(sc_gl_context_gl(ctx), &scene, &desc, &r, &err), SC_OK);
        sc_camera cam = {.eye = {0, -8, 3}, .target = {0, 0, 0.8}, .fovy_deg = 30,
                         .width = 16, .height = 12};
        sc_image img = {0};
        sc_aov aov;
        int drawn = sc_renderer_draw(r, &cam, &err) == SC_OK &&
                    sc_renderer_read(r, &img, &aov, &err) == SC_OK;
        int ok = drawn;
        /* Attachment i is output i of the table, when the view's keys
         * declare it, in the table's format; nothing else is attached. */
        GLenum expected[SC_GL_TARGET_MAX_COLOURS] = {0};
#define X(ID, location, name, type, output, format, miss, clear) \
    if (view_outputs(&desc) & SCG_OUTPUT_##output)                 \
        expected[location] = GL_##format;
        SCG_FRAG_OUTS(X)
#undef X
        for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS && ok; i++)
            ok = r->target.formats[i] == expected[i] && (r->target.colour[i] != 0) == !!expected[i];
        for (int i = 0; i < SCG_FRAG_OUT_ENTRIES && ok; i++)
            if (view_outputs(&desc) & scg_frag_outs[i].key_output)
                ok = r->keys[0].outputs & scg_frag_outs[i].key_output;
        sc_renderer_destroy(r);
        if (drawn) {
            sc_image_free(&img);
            sc_aov_free(&aov);
        }
        if (!ok)
            fprintf(stderr, "  view %d: %s\n", (int)views[v], err.message);
        CHECK(ok);
    }
    sc_scene_free(&scene);
}
