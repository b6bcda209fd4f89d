/* program.c — from a key to an optimised program: the metaprogram the key
 * names, validation, then the pass list (optimize.c) with a hook after
 * every stage (--dump-ir). */
#include "bclip.h"
#include "broyden.h"
#include "hybrid.h"
#include "newton.h"
#include "subdiv.h"

/* The iteration of each method, by the key's method field. */
static scg_method_fn method_fn(const scg_key *key)
{
    switch (key->method) {
    case SC_METHOD_BROYDEN: return scg_method_broyden;
    case SC_METHOD_BCLIP: return scg_method_bclip;
    case SC_METHOD_SUBDIV: return scg_method_subdiv;
    case SC_METHOD_HYBRID: return scg_method_hybrid;
    default: return scg_method_newton;
    }
}
#include "tri_newton.h"

int scg_build_unoptimized(const scg_key *key, scg_program **out, sc_error *err)
{
    *out = NULL;
    if (scg_key_check(key, err) != SC_OK)
        return SC_FAIL;
    scg_program *prog = scg_program_create(key);
    scg_builder b;
    scg_builder_init(&b, prog);
    if (key->kind == SCG_PATCH_TRIANGLE)
        scg_build_tri_newton(&b, key);
    else
        scg_build_intersection(&b, key, method_fn(key));
    if (scg_validate(prog, err) != SC_OK) {
        scg_program_free(prog);
        return SC_FAIL;
    }
    *out = prog;
    return SC_OK;
}

int scg_compile_stages(const scg_key *key, scg_stage_fn on_stage, void *user,
                       scg_program **out, sc_error *err)
{
    scg_program *prog;
    *out = NULL;
    if (scg_build_unoptimized(key, &prog, err) != SC_OK)
        return SC_FAIL;
    if (on_stage)
        on_stage("build", prog, user);
    if (scg_optimize(prog, on_stage, user, err) != SC_OK) {
        scg_program_free(prog);
        return SC_FAIL;
    }
    *out = prog;
    return SC_OK;
}

int scg_build_program(const scg_key *key, scg_program **out, sc_error *err)
{
    return scg_compile_stages(key, NULL, NULL, out, err);
}

scg_key scg_view_start_key(const scg_key *key)
{
    scg_key k = *key;
    k.trim = SC_TRIM_NONE;
    k.trim_degree = k.trim_iters = 0;
    /* Seed 000 §4.4: the vertex rays are solved with Newton's method,
     * whatever finishes the fragment's. */
    k.method = SC_METHOD_NEWTON;
    k.ert = SCG_ERT_NONE;
    k.outputs = SCG_OUTPUT_SHADE;
    return k;
}

int scg_build_view_start_program(const scg_key *key, scg_program **out, sc_error *err)
{
    *out = NULL;
    if (scg_key_check(key, err) != SC_OK)
        return SC_FAIL;
    scg_key k = scg_view_start_key(key);
    char text[SCG_KEY_MAX];
    scg_key_format(key, text, sizeof text);
    if (k.start != SC_START_VIEW)
        return sc_fail_key(err, text, "key %s: only a 'view' start has a vertex-stage solve",
                           text);
    scg_program *prog = scg_program_create(&k);
    scg_builder b;
    scg_builder_init(&b, prog);
    scg_build_view_start(&b, &k, scg_method_newton);
    if (scg_validate(prog, err) != SC_OK || scg_optimize(prog, NULL, NULL, err) != SC_OK) {
        scg_program_free(prog);
        return SC_FAIL;
    }
    *out = prog;
    return SC_OK;
}
