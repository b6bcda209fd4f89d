/* api_flops.c — sc_count_key_flops: the FLOPs of a key's intersection
 * program, counted by the compiler from its IR (gen/flops.c), for
 * `bench --peak`'s achieved rate. */
#include "api_private.h"

#include "flops.h"
#include "gl_peak.h"

int sc_count_key_flops(const char *key, sc_key_flops *out, sc_error *err)
{
    if (!key || !out)
        return sc_api_invalid(err, key ? "out" : "key", PROBLEM_NULL, NULL);
    if (sc_check_key(key, err) != SC_OK)
        return SC_FAIL;
    scg_key parsed;
    scg_flops f;
    if (scg_key_parse(key, &parsed, err) != SC_OK || scg_key_flops(&parsed, &f, err) != SC_OK)
        return SC_FAIL;
    *out = (sc_key_flops){.total = f.total, .per_iter = f.per_iter, .fixed = f.fixed};
    return SC_OK;
}

int sc_measure_peak(sc_context_id ctx, const sc_peak_desc *desc, sc_peak_info *out,
                    sc_error *err)
{
    static const sc_peak_desc defaults = {0};
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    if (!desc)
        desc = &defaults;
    context_object *c = sc_api_pool_get(&sc_api_contexts, ctx.id, err);
    if (!c || sc_api_make_current(c, err) != SC_OK)
        return SC_FAIL;
    if (desc->width < 0 || desc->height < 0 || desc->chains < 0 || desc->length < 0 ||
        desc->frames < 0 || desc->width > 16384 || desc->height > 16384 || desc->chains > 64 ||
        desc->length > 4096 || desc->frames > 1000)
        return sc_fail(err, NULL, 0, "sc_measure_peak: a field of desc is out of range "
                                     "(sizes 0 … 16384, chains 0 … 64, length 0 … 4096, "
                                     "frames 0 … 1000)");
    sc_gl_peak p = {
        .width = desc->width ? desc->width : 1024,
        .height = desc->height ? desc->height : 1024,
        .chains = desc->chains ? desc->chains : 2,
        .length = desc->length ? desc->length : 256,
        .frames = desc->frames ? desc->frames : 5,
    };
    if (sc_gl_measure_peak(sc_gl_context_gl(c->gl), &p, err) != SC_OK)
        return SC_FAIL;
    double ms = p.wall_ms;
    *out = (sc_peak_info){.flops = p.flops, .gpu_ms = p.gpu_ms, .wall_ms = p.wall_ms,
                          .gflops = ms > 0 ? p.flops / (ms * 1e6) : 0};
    return SC_OK;
}
