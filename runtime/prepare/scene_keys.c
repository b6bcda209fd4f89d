/* scene_keys.c — from surfaces to variant keys. Default GPU path: extract
 * Bézier patches. Unrolled de Casteljau needs no knot texture, no span
 * search and no per-iteration fetches (the points are fetched and projected
 * onto the ray's planes once), and the hulls are built per sub-patch of a
 * patch anyway; the price is more control points in GPU memory for surfaces
 * with many spans, which `nurbs_direct` avoids. */
#include <stdlib.h>
#include <string.h>

#include "scene_keys.h"
#include "tri_prisms.h"
#include "trim.h"
#include "trim_pack.h"

int sc_surface_drawable(const sc_scene *scene, int i, sc_error *err)
{
    const sc_surface *s = &scene->surfaces[i];
    const char *file = scene->source[0] ? scene->source : NULL;
    if (s->deg_u > SCG_MAX_DEGREE || s->deg_v > SCG_MAX_DEGREE)
        return sc_fail(err, file, 0, "surface %d (%s): degree %d×%d is above %d, the highest "
                       "the GPU programs draw", i, s->name, s->deg_u, s->deg_v, SCG_MAX_DEGREE);
    int tdeg = sc_surface_trim_degree(s);
    if (tdeg > SC_TRIM_MAX_DEGREE)
        return sc_fail(err, file, 0, "surface %d (%s): a trim curve of degree %d is above %d, "
                       "the highest the trimming draws", i, s->name, tdeg, SC_TRIM_MAX_DEGREE);
    return SC_OK;
}

scg_ert sc_key_ert(sc_ray_termination termination)
{
    switch (termination == SC_TERMINATION_DEFAULT ? SC_DEFAULT_TERMINATION : termination) {
    case SC_TERMINATION_CONSERVATIVE: return SCG_ERT_CONSERVATIVE;
    case SC_TERMINATION_MANUAL: return SCG_ERT_BEFORE;
    case SC_TERMINATION_MANUAL_BOTH: return SCG_ERT_BOTH;
    case SC_TERMINATION_PEEL: return SCG_ERT_PEEL;
    case SC_TERMINATION_LISTS: return SCG_ERT_LISTS;
    default: return SCG_ERT_NONE;
    }
}

scg_eval_form sc_bezier_eval(sc_eval asked, int p, int q)
{
    int degree = p > q ? p : q;
    switch (asked) {
    case SC_EVAL_DC: return SCG_EVAL_DC;
    case SC_EVAL_BERN: return SCG_EVAL_BASIS;
    case SC_EVAL_POW: return degree <= SC_MAX_POW_DEGREE ? SCG_EVAL_POWER : SCG_EVAL_DC;
    default: return degree <= SC_DEFAULT_POW_MAX_DEGREE ? SCG_EVAL_POWER : SCG_EVAL_DC;
    }
}

sc_eval sc_eval_option(scg_eval_form form)
{
    return form == SCG_EVAL_BASIS ? SC_EVAL_BERN : form == SCG_EVAL_POWER ? SC_EVAL_POW : SC_EVAL_DC;
}

void sc_surface_key(const sc_surface *s, const sc_key_options *opts, scg_key *key)
{
    sc_key_options defaults;
    memset(&defaults, 0, sizeof defaults);
    if (!opts)
        opts = &defaults;
    bool one_patch = s->nu == s->deg_u + 1 && s->nv == s->deg_v + 1;
    scg_patch_kind kind = opts->nurbs_direct && !one_patch ? SCG_PATCH_NURBS : SCG_PATCH_BEZIER;
    scg_key_default(key, kind, s->deg_u, s->deg_v);
    int generic_above = opts->generic_above > 0 ? opts->generic_above : SC_UNROLL_MAX_DEGREE;
    if (s->deg_u > generic_above || s->deg_v > generic_above) {
        key->eval = SCG_EVAL_LOOP;
        key->deg_u = key->deg_v = 0;
    }
    if (kind == SCG_PATCH_BEZIER && key->eval == SCG_EVAL_DC)
        key->eval = sc_bezier_eval(opts->eval, s->deg_u, s->deg_v);
    key->rational = s->rational != 0;
    int untrimmed = opts->ignore_trims || opts->trim_method == SC_TRIM_NONE;
    int tdeg = untrimmed ? 0 : sc_surface_trim_degree(s);
    if (s->nloops > 0 && tdeg > 0) {
        key->trim = opts->trim_method == SC_TRIM_DEFAULT ? SC_TRIM_FAST : opts->trim_method;
        key->trim_degree = tdeg;
        key->trim_iters = opts->trim_iters > 0 ? opts->trim_iters : SCG_DEFAULT_TRIM_ITERS;
    }
    key->method = opts->method == SC_METHOD_DEFAULT ? SC_DEFAULT_METHOD : opts->method;
    if (key->method == SC_METHOD_SUBDIV)
        key->max_iters = SCG_DEFAULT_SUBDIV_DEPTH;
    if (key->method == SC_METHOD_BCLIP)
        key->max_iters = SCG_DEFAULT_BCLIP_STEPS;
    if (opts->max_iters > 0)
        key->max_iters = opts->max_iters;
    if (opts->tol_milli > 0)
        key->tol_milli = opts->tol_milli;
    if (opts->start != SC_START_DEFAULT)
        key->start = opts->start;
    if (key->method == SC_METHOD_SUBDIV || key->method == SC_METHOD_BCLIP)
        key->start = SC_START_MID; /* the only start these keys spell */
    key->ert = sc_key_ert(opts->termination);
    key->outputs = opts->outputs ? opts->outputs : SC_KEY_DEFAULT_OUTPUTS;
    /* Candidate lists draw no hull: no start to interpolate over one, and
     * nothing for the hull view to show (it draws every hull, ert0). */
    if (key->ert == SCG_ERT_LISTS)
        key->start = SC_START_MID;
    if (key->ert == SCG_ERT_LISTS && (key->outputs & SCG_OUTPUT_HULLVIEW))
        key->ert = SCG_ERT_NONE;
}

static int compare_keys(const void *a, const void *b) { return strcmp(a, b); }

int sc_scene_keys(const sc_scene *scene, const sc_key_options *opts,
                  char (**keys)[SCG_KEY_MAX], int *count, sc_error *err)
{
    *keys = NULL;
    *count = 0;
    if (scene->nsurfaces == 0)
        return SC_OK;
    char (*all)[SCG_KEY_MAX] = sc_alloc((size_t)scene->nsurfaces, SCG_KEY_MAX);
    int drawable = 0;
    for (int i = 0; i < scene->nsurfaces; i++) {
        sc_error why = {0};
        if (sc_surface_drawable(scene, i, &why) != SC_OK) {
            if (!opts || !opts->skip_undrawable) {
                free(all);
                if (err)
                    *err = why;
                return SC_FAIL;
            }
            char text[1024];
            sc_log(SC_LOG_WARN, "%s: no variant key", sc_error_text(&why, text, sizeof text));
            continue;
        }
        scg_key key;
        sc_surface_key(&scene->surfaces[i], opts, &key);
        if (scene->terrain) {   /* its stand-in surface: the terrain's key */
            scg_key like = key;
            sc_tri_key(scene->terrain, &like, &key);
        }
        scg_key_format(&key, all[drawable++], SCG_KEY_MAX);
    }
    qsort(all, (size_t)drawable, SCG_KEY_MAX, compare_keys);
    int n = 0;
    for (int i = 0; i < drawable; i++)
        if (n == 0 || strcmp(all[n - 1], all[i]) != 0)
            memmove(all[n++], all[i], SCG_KEY_MAX);
    *keys = all;
    *count = n;
    return SC_OK;
}
