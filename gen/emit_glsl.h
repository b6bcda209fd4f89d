/* emit_glsl.h — the GLSL emitter, in three files:
 *   emit_glsl.c     prints an optimised IR program as the intersection
 *                   function;
 *   assemble_glsl.c lays out the complete GLSL 4.50 core programs around
 *                   it: the fragment program (declarations, the call, what
 *                   a miss does, gl_FragDepth, shading, AOVs and debug
 *                   views) and the vertex program that draws the hulls.
 *                   Templates (templates/) lay the files out; the emitter
 *                   decides what goes into their slots, and every
 *                   declaration comes from the shader contract
 *                   (shader_contract.h). Every file begins with a
 *                   provenance header (generator version, key, options) and
 *                   no timestamp, so the same key always gives the same
 *                   bytes;
 *   generate.c      the whole pipeline for one key: build, optimise, emit,
 *                   validate. */
#ifndef SCG_EMIT_GLSL_H
#define SCG_EMIT_GLSL_H

#include "glslang_check.h"
#include "ir.h"
#include "key.h"
#include "template.h"

#define SCG_GENERATOR_VERSION "splinecast-gen 1.0"

/* ---- emit_glsl.c ---- */

/* Only the intersection function (`void sc_intersect(out …)`), as it appears
 * in the fragment program. */
int scg_emit_intersect_function(const scg_program *prog, scg_text *out, sc_error *err);
/* The vertex stage's start of a `view` key (scg_build_view_start_program)
 * as a block of main() that assigns `vec2 start_uv`, declared before it:
 * inline, because the block reads the vertex stage's outputs, which a
 * function would read before the driver can see them written. */
int scg_emit_view_start_block(const scg_program *prog, scg_text *out, sc_error *err);

/* Which of the IR's slots a program reads (inputs, uniforms, textures) and
 * which results it writes: only those are declared. */
typedef struct scg_program_use {
    int inputs[SCG_INPUT_COUNT];
    int uniforms[SCG_UNIFORM_COUNT];
    int textures[SCG_TEXTURE_COUNT];
    int outputs[SCG_OUTPUT_COUNT];
} scg_program_use;
void scg_program_scan_use(const scg_program *prog, scg_program_use *use);

/* The shortest decimal that reads back as f, always typed float in GLSL. */
void scg_glsl_float_literal(float f, char *buf, size_t size);

/* ---- assemble_glsl.c ---- */

/* Name of the vertex program a key's fragment program pairs with
 * ("hull-mid", "hull-cp-colour", …): keys that need the same vertex stage
 * share one. */
const char *scg_vertex_program_name(const scg_key *key);

/* The fragment program for `prog` (optimised IR; prog->key decides the
 * outputs). Fails when the program lacks a result the outputs need. */
int scg_emit_fragment(const scg_program *prog, scg_text *out, sc_error *err);

/* The vertex program for a key (scg_vertex_program_name). */
int scg_emit_vertex(const scg_key *key, scg_text *out, sc_error *err);

/* ---- generate.c ---- */

/* One generated variant: both stages, validated. */
typedef struct scg_generated {
    char key[SCG_KEY_MAX];
    char vertex_name[64];
    scg_program *program;            /* the optimised IR */
    scg_program *vertex_program;     /* the vertex stage's IR (`view` keys:
                                        the start's solve), else NULL */
    scg_text fragment, vertex;
    scg_glslang_result fragment_check, vertex_check;   /* zero unless counted */
} scg_generated;

/* Build, optimise, emit, and validate both stages linked together. On
 * failure err names the key and, for a glslang rejection, the offending
 * GLSL line. `out` is filled or left empty. */
int scg_generate(const scg_key *key, scg_generated *out, sc_error *err);
/* The same, and each stage translated to SPIR-V and counted (the audit's
 * spirv-inst; the translation costs about half as much again). */
int scg_generate_counted(const scg_key *key, scg_generated *out, sc_error *err);
void scg_generated_free(scg_generated *gen);

#endif
