/* emit_glsl.h — the GLSL emitter: prints an optimised IR program as a
 * complete GLSL 4.50 core fragment program (ray from the interpolated
 * inputs, the intersection function, discard on a miss, gl_FragDepth from
 * the hit, shading, AOVs and debug views), and prints the vertex program
 * that draws the hulls. Templates (templates/) lay the files out; the
 * emitter decides what goes into their slots. Every file begins with a
 * provenance header (generator version, key, options) and no timestamp, so
 * the same key always gives the same bytes.
 *
 * Also the whole pipeline for one key: build, optimise, emit, validate. */
#ifndef SCG_EMIT_GLSL_H
#define SCG_EMIT_GLSL_H

#include "glslang_check.h"
#include "ir.h"
#include "key.h"
#include "template.h"

#define SCG_GENERATOR_VERSION "splinecast-gen 1.0"

/* Fragment outputs (colour attachments) the runtime binds with
 * glDrawBuffers; only those the key's outputs ask for are declared. */
enum {
    SCG_FRAG_OUT_COLOUR = 0,    /* vec4 sc_colour: shaded colour (shade) */
    SCG_FRAG_OUT_SURFACE = 1,   /* int sc_aov_surface (aov, R32I) */
    SCG_FRAG_OUT_UVT = 2,       /* vec4 sc_aov_uvt: u, v, world t, iterations */
    SCG_FRAG_OUT_POINT = 3,     /* vec4 sc_aov_point: world point, 1 */
    SCG_FRAG_OUT_NORMAL = 4,    /* vec4 sc_aov_normal: world normal facing the
                                   viewer, 0 */
    SCG_FRAG_OUT_ITERS = 5,     /* vec4 sc_view_iters (iters debug view) */
    SCG_FRAG_OUT_UV = 6,        /* vec4 sc_view_uv (uv debug view) */
    SCG_FRAG_OUT_HULL = 7       /* vec4 sc_view_hull (hull debug view) */
};

/* Name of the vertex program a key's fragment program pairs with
 * ("hull-mid", "hull-cp-colour", …): keys that need the same vertex stage
 * share one. */
const char *scg_vertex_program_name(const scg_key *key);

/* The fragment program for `prog` (optimised IR; prog->key decides the
 * outputs). Fails when the program lacks a result the outputs need. */
int scg_emit_fragment(const scg_program *prog, scg_text *out, sc_error *err);

/* The vertex program for a key (scg_vertex_program_name). */
int scg_emit_vertex(const scg_key *key, scg_text *out, sc_error *err);

/* Only the intersection function (`void sc_intersect(out …)`), as it appears
 * in the fragment program. */
int scg_emit_intersect_function(const scg_program *prog, scg_text *out, sc_error *err);

/* One generated variant: both stages, validated. */
typedef struct scg_generated {
    char key[SCG_KEY_MAX];
    char vertex_name[64];
    scg_program *program;            /* the optimised IR */
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
