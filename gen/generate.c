/* generate.c — the pipeline for one key (emit_glsl.h): the metaprogram
 * builds the IR and the passes optimise it (ir.h), the emitter prints both
 * stages (emit_glsl.c, assemble_glsl.c), glslang parses and links them. */
#include "emit_glsl.h"

#include <stdio.h>
#include <string.h>

/* Names the key in a failure a callee reported without one. */
static int keyed(sc_error *err, const char *key_text)
{
    if (err)
        snprintf(err->key, sizeof err->key, "%s", key_text);
    return SC_FAIL;
}

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
    if (key->start == SC_START_VIEW &&
        scg_build_view_start_program(key, &gen->vertex_program, err) != SC_OK) {
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
    if (gen->vertex_program)
        scg_program_free(gen->vertex_program);
    gen->vertex_program = NULL;
    scg_text_free(&gen->fragment);
    scg_text_free(&gen->vertex);
    gen->program = NULL;
}
