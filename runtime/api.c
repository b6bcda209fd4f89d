/* api.c — the public interface (splinecast.h) over the internal modules:
 * scenes, surfaces, keys and generation (contexts, programs, renderers and
 * frames are in api_render.c; the pools and argument checks both use are in
 * api_objects.c).
 * Objects live in small pools and are named by typed handles: an id is the
 * slot's index + 1 in the low 16 bits and the slot's generation in the high
 * 16, so a handle to a destroyed object stays invalid after its slot is
 * reused. The options' enums (splinecast_options.h) are the ones the
 * runtime works with, so descs are checked here and passed on, never
 * translated. Every problem with an argument is reported through one list
 * of messages. */
#include "api_private.h"
#include "step.h"
#include "trim_pack.h"

_Static_assert(SC_KEY_SIZE == SCG_KEY_MAX, "public and internal key sizes differ");
_Static_assert((int)SC_OUTPUT_SHADE == (int)SCG_OUTPUT_SHADE &&
                   (int)SC_OUTPUT_AOV == (int)SCG_OUTPUT_AOV &&
                   (int)SC_OUTPUT_ITERS == (int)SCG_OUTPUT_ITERS &&
                   (int)SC_OUTPUT_UV == (int)SCG_OUTPUT_UVVIEW &&
                   (int)SC_OUTPUT_HULL == (int)SCG_OUTPUT_HULLVIEW,
               "public output bits are the key's output bits");
_Static_assert(sizeof(((sc_shader_audit *)0)->line) >= SCG_KEY_MAX + 100,
               "an audit line holds a key and its figures");

/* ---- scenes ---- */

static int has_extension(const char *name, const char *ext)
{
    size_t n = strlen(name), e = strlen(ext);
    return n > e && !strcasecmp(name + n - e, ext);
}

static int read_scene_text(const sc_scene_desc *desc, sc_scene *scene, sc_error *err)
{
    const char *name = desc->name;
    if (!name)
        return sc_api_invalid(err, "sc_scene_desc.name", PROBLEM_SCENE_NAME, NULL);
    if (has_extension(name, ".bpt"))
        return sc_read_bpt(desc->text, desc->size, name, scene, err);
    if (has_extension(name, ".obj"))
        return sc_read_obj(desc->text, desc->size, name, scene, err);
    if (has_extension(name, ".igs") || has_extension(name, ".iges"))
        return sc_read_iges(desc->text, desc->size, name, scene, err);
    if (has_extension(name, ".stp") || has_extension(name, ".step"))
        return sc_read_step(desc->text, desc->size, name, scene, err);
    return sc_api_invalid(err, "sc_scene_desc.name", PROBLEM_SCENE_NAME, "'%s'", name);
}

int sc_make_scene(const sc_scene_desc *desc, sc_scene_id *out, sc_error *err)
{
    static const sc_scene_desc defaults = {0};
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!desc)
        desc = &defaults;
    if (desc->path && desc->text)
        return sc_api_invalid(err, "sc_scene_desc", PROBLEM_SCENE_SOURCE, NULL);
    int terrain = desc->heights || desc->franke;
    if (terrain && (desc->path || desc->text || (desc->heights && desc->franke)))
        return sc_api_invalid(err, "sc_scene_desc", PROBLEM_TERRAIN_SOURCE, NULL);
    scene_object *s = sc_alloc(1, sizeof *s);
    int status = terrain      ? sc_api_make_terrain(desc, &s->scene, err)
                 : desc->text ? read_scene_text(desc, &s->scene, err)
                              : sc_read_scene(desc->path ? desc->path : "teapot", &s->scene, err);
    if (status == SC_OK && (out->id = sc_api_pool_insert(&sc_api_scenes, s, err)) != 0)
        return SC_OK;
    sc_scene_free(&s->scene);
    free(s);
    return SC_FAIL;
}

void sc_destroy_scene(sc_scene_id scene)
{
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, NULL);
    if (!s)
        return;
    sc_api_pool_remove(&sc_api_scenes, scene.id);
    if (s->users > 0) {
        s->orphaned = 1;
        return;
    }
    sc_scene_free(&s->scene);
    free(s);
}

int sc_query_scene_info(sc_scene_id scene, sc_scene_info *info, sc_error *err)
{
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    memset(info, 0, sizeof *info);
    const sc_scene *sc = &s->scene;
    info->surfaces = sc->nsurfaces;
    for (int i = 0; i < sc->nsurfaces; i++) {
        const sc_surface *surf = &sc->surfaces[i];
        info->rational_surfaces += surf->rational != 0;
        info->trimmed_surfaces += surf->nloops > 0;
        int degree = surf->deg_u > surf->deg_v ? surf->deg_u : surf->deg_v;
        if (degree > info->max_degree)
            info->max_degree = degree;
    }
    for (int i = 0; i < sc->nskipped; i++)
        info->skipped += sc->skipped[i].count;
    info->skipped_kinds = sc->nskipped;
    info->dropped_loops = sc->dropped_loops;
    info->projected_loops = sc->projected_loops;
    info->projection_dev = sc->projection_dev;
    info->offset_surfaces = sc->offset_surfaces;
    info->offset_dev = sc->offset_dev;
    sc_scene_bounds(sc, info->lo, info->hi);
    if (sc->terrain) {
        info->terrain_patches = sc_terrain_patch_count(sc);
        info->max_degree = sc_terrain_degree(sc);
    }
    return SC_OK;
}

int sc_query_scene_skipped(sc_scene_id scene, int index, sc_skipped_info *info,
                           sc_error *err)
{
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    if (!info)
        return sc_api_invalid(err, "info", PROBLEM_NULL, NULL);
    if (index < 0 || index >= s->scene.nskipped)
        return sc_api_invalid(err, "index", PROBLEM_RANGE, "%d (0 to %d)", index,
                              s->scene.nskipped - 1);
    const sc_skipped *k = &s->scene.skipped[index];
    _Static_assert(sizeof info->type == sizeof k->type && sizeof info->reason == sizeof k->reason,
                   "public and internal skipped records hold the same texts");
    memset(info, 0, sizeof *info);
    memcpy(info->type, k->type, sizeof info->type);
    memcpy(info->reason, k->reason, sizeof info->reason);
    info->count = k->count;
    return SC_OK;
}

int sc_save_obj(sc_scene_id scene, const char *path, sc_error *err)
{
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    if (!path)
        return sc_api_invalid(err, "path", PROBLEM_NULL, NULL);
    if (!has_extension(path, ".obj"))
        return sc_api_invalid(err, "path", PROBLEM_RANGE, "'%s' (a name ending in .obj)", path);
    return sc_write_obj(path, &s->scene, err);
}

/* ---- surfaces ---- */

/* Surface `surface` of a scene handle, or NULL with err filled. */
static sc_surface *scene_surface(sc_scene_id scene, int surface, sc_error *err)
{
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return NULL;
    if (surface < 0 || surface >= s->scene.nsurfaces) {
        sc_api_invalid(err, "surface", PROBLEM_RANGE, "%d (0 to %d)", surface, s->scene.nsurfaces - 1);
        return NULL;
    }
    return &s->scene.surfaces[surface];
}

/* The same for a query that writes to `out`, named `out_name`: NULL too
 * when out is NULL, so the queries check their arguments in one order. */
static const sc_surface *queried_surface(sc_scene_id scene, int surface, const void *out,
                                         const char *out_name, sc_error *err)
{
    const sc_surface *surf = scene_surface(scene, surface, err);
    if (surf && !out) {
        sc_api_invalid(err, out_name, PROBLEM_NULL, NULL);
        return NULL;
    }
    return surf;
}

int sc_query_surface_info(sc_scene_id scene, int surface, sc_surface_info *info,
                          sc_error *err)
{
    const sc_surface *surf = queried_surface(scene, surface, info, "info", err);
    if (!surf)
        return SC_FAIL;
    *info = (sc_surface_info){.deg_u = surf->deg_u, .deg_v = surf->deg_v, .nu = surf->nu,
                              .nv = surf->nv, .rational = surf->rational != 0,
                              .trim_loops = surf->nloops};
    snprintf(info->name, sizeof info->name, "%s", surf->name);
    for (int l = 0; l < surf->nloops; l++)
        info->trim_curves += surf->loops[l].ncurves;
    sc_surface_domain(surf, &info->u_min, &info->u_max, &info->v_min, &info->v_max);
    return SC_OK;
}

int sc_query_surface_trim(sc_scene_id scene, int surface, sc_surface_trim_info *info,
                          sc_error *err)
{
    const sc_surface *surf = queried_surface(scene, surface, info, "info", err);
    if (!surf)
        return SC_FAIL;
    memset(info, 0, sizeof *info);
    /* Packed at the surface's own trim degree, the one its key names
     * (scene_keys.c), so the figures are those of the block a renderer
     * uploads. */
    int degree = sc_surface_trim_degree(surf);
    sc_trim_block block;
    if (sc_trim_pack(surf, degree, &block, err) != SC_OK)
        return SC_FAIL;
    if (block.ntexels)
        *info = (sc_surface_trim_info){.degree = degree, .loops = block.nloops,
                                       .pieces = block.npieces, .grid_u = block.grid_u,
                                       .grid_v = block.grid_v, .entries = block.nentries,
                                       .texels = block.ntexels,
                                       .bytes = 16 * (size_t)block.ntexels};
    sc_trim_block_free(&block);
    return SC_OK;
}

int sc_eval_surface(sc_scene_id scene, int surface, double u, double v, sc_surface_point *out,
                    sc_error *err)
{
    const sc_surface *surf = queried_surface(scene, surface, out, "out", err);
    if (!surf)
        return SC_FAIL;
    memset(out, 0, sizeof *out);
    double u0, u1, v0, v1;
    sc_surface_domain(surf, &u0, &u1, &v0, &v1);
    if (!(u >= u0 && u <= u1 && v >= v0 && v <= v1))
        return sc_api_invalid(err, "(u, v)", PROBLEM_RANGE,
                              "(%.17g, %.17g) (u in [%.17g, %.17g], v in [%.17g, %.17g])", u, v,
                              u0, u1, v0, v1);
    sc_surface_eval_world(surf, u, v, out->point, out->du, out->dv);
    if (sc_surface_normal(surf, u, v, out->normal) == 0) {
        sc_xform_normal(surf->xform, out->normal, out->normal);
        out->has_normal = 1;
    } else {
        memset(out->normal, 0, sizeof out->normal);
    }
    return SC_OK;
}

static int check_count(int count, const sc_surface *surf, const char *what, sc_error *err)
{
    if (count != surf->nu * surf->nv)
        return sc_api_invalid(err, what, PROBLEM_RANGE, "%d (the surface has %d x %d control points)",
                       count, surf->nu, surf->nv);
    return SC_OK;
}

int sc_query_surface_points(sc_scene_id scene, int surface, double *points, double *weights,
                            int count, sc_error *err)
{
    const sc_surface *surf = scene_surface(scene, surface, err);
    if (!surf || ((points || weights) && check_count(count, surf, "count", err) != SC_OK))
        return SC_FAIL;
    for (int k = 0; k < count && (points || weights); k++) {
        const double *h = surf->cp + 4 * k;
        for (int c = 0; c < 3 && points; c++)
            points[3 * k + c] = h[c] / h[3];
        if (weights)
            weights[k] = h[3];
    }
    return SC_OK;
}

int sc_update_surface(sc_scene_id scene, const sc_surface_desc *desc, sc_error *err)
{
    static const sc_surface_desc nothing = {0};
    if (!desc)
        desc = &nothing;
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    if (!desc->points && !desc->weights)
        return SC_OK;
    sc_surface *surf = scene_surface(scene, desc->surface, err);
    if (!surf)
        return SC_FAIL;
    if (check_count(desc->count, surf, "sc_surface_desc.count", err) != SC_OK)
        return SC_FAIL;
    int n = desc->count;
    for (int k = 0; k < 3 * n && desc->points; k++)
        if (!isfinite(desc->points[k]))
            return sc_api_invalid(err, "sc_surface_desc.points", PROBLEM_RANGE,
                           "coordinate %d of point %d is %g", k % 3, k / 3, desc->points[k]);
    for (int k = 0; k < n && desc->weights; k++)
        if (!(desc->weights[k] > 0 && isfinite(desc->weights[k])))
            return sc_api_invalid(err, "sc_surface_desc.weights", PROBLEM_RANGE,
                           "weight %d is %g (positive and finite)", k, desc->weights[k]);
    /* The new net beside the old one, so that a refusal changes nothing. */
    sc_surface fresh = *surf;
    fresh.cp = sc_alloc((size_t)n * 4, sizeof(double));
    for (int k = 0; k < n; k++) {
        const double *old = surf->cp + 4 * k;
        double w = desc->weights ? desc->weights[k] : old[3];
        for (int c = 0; c < 3; c++)
            fresh.cp[4 * k + c] = (desc->points ? desc->points[3 * k + c] : old[c] / old[3]) * w;
        fresh.cp[4 * k + 3] = w;
    }
    sc_surface_update_rational(&fresh);
    if (s->users > 0 && (fresh.rational != 0) != (surf->rational != 0)) {
        free(fresh.cp);
        return sc_fail(err, NULL, 0,
                       "surface %d would become %s, which changes its variant key: the "
                       "scene's renderers cannot follow (destroy them first)",
                       desc->surface, fresh.rational ? "rational" : "polynomial");
    }
    free(surf->cp);
    surf->cp = fresh.cp;
    surf->rational = fresh.rational;
    int status = SC_OK;
    for (int i = 0; i < sc_api_renderers.count; i++) {
        renderer_object *r = sc_api_renderers.slots[i].object;
        if (!r || r->scene != s || status != SC_OK)
            continue;
        if (sc_api_make_current(r->context, err) != SC_OK ||
            sc_renderer_update_surface(r->renderer, desc->surface, err) != SC_OK)
            status = SC_FAIL;
    }
    return status;
}

/* ---- keys and generation ---- */

/* A key's text parsed, err naming the key when it is not one. */
static int parse_key(const char *text, scg_key *key, sc_error *err)
{
    if (scg_key_parse(text, key, err) == SC_OK)
        return SC_OK;
    if (err && !err->key[0])
        snprintf(err->key, sizeof err->key, "%s", text);
    return SC_FAIL;
}

/* What `like` gives where the desc left zeros: every field but those each
 * surface decides (kind, degrees, rationality, the generic program where a
 * degree needs it, whether it is trimmed and its trim-curve degree). Its
 * ertN is what the programs do; each ertN is sc_key_ert of exactly one
 * termination, so the option that gives it back is found, not guessed. */
static int like_options(const char *like, sc_key_options *opts, sc_error *err)
{
    scg_key key;
    if (parse_key(like, &key, err) != SC_OK)
        return SC_FAIL;
    opts->nurbs_direct |= key.kind == SCG_PATCH_NURBS;
    if (!opts->max_iters)
        opts->max_iters = key.max_iters;
    if (!opts->tol_milli)
        opts->tol_milli = key.tol_milli;
    if (!opts->start)
        opts->start = key.start;
    if (!opts->method)
        opts->method = key.method;
    if (!opts->outputs)
        opts->outputs = key.outputs;
    /* An unrolled Bézier key names its form; nurbs, loop and tri keys
     * name none that the Bézier keys of the scene could take. */
    if (!opts->eval && key.kind == SCG_PATCH_BEZIER && key.eval != SCG_EVAL_LOOP)
        opts->eval = sc_eval_option(key.eval);
    if (key.trim != SC_TRIM_NONE && !opts->trim_method) {
        opts->trim_method = key.trim;
        if (!opts->trim_iters)
            opts->trim_iters = key.trim_iters;
    }
    if ((opts->eval == SC_EVAL_BERN || opts->eval == SC_EVAL_POW) && opts->nurbs_direct) {
        sc_fail(err, NULL, 0, "evaluation form '%s' cannot apply: it is for Bézier patches, "
                "and these keys draw whole NURBS surfaces (nurbs)",
                opts->eval == SC_EVAL_BERN ? "bern" : "pow");
        if (err)
            snprintf(err->key, sizeof err->key, "%s", like);
        return SC_FAIL;
    }
    for (int t = SC_TERMINATION_NONE; !opts->termination && t <= SC_TERMINATION_LISTS; t++)
        if (sc_key_ert((sc_ray_termination)t) == key.ert)
            opts->termination = (sc_ray_termination)t;
    return SC_OK;
}

static int key_options(const sc_keys_desc *desc, sc_key_options *opts, sc_error *err)
{
    memset(opts, 0, sizeof *opts);
    if (sc_api_check_int(desc->generic_above, 0, SCG_MAX_DEGREE, "sc_keys_desc.generic_above", err) ||
        sc_api_check_int(desc->trim_iters, 0, SCG_MAX_TRIM_ITERS, "sc_keys_desc.trim_iters", err) ||
        sc_api_check_int(desc->max_iters, 0, SCG_MAX_ITERS, "sc_keys_desc.max_iters", err) ||
        sc_api_check_enum(desc->termination, SC_TERMINATION_LISTS + 1,
                   "sc_keys_desc.termination", err) ||
        sc_api_check_enum(desc->start, SC_START_VIEW + 1, "sc_keys_desc.start", err) ||
        sc_api_check_enum(desc->trim, SC_TRIM_NONE + 1, "sc_keys_desc.trim", err) ||
        sc_api_check_enum(desc->method, SC_METHOD_HYBRID + 1, "sc_keys_desc.method", err) ||
        sc_api_check_enum(desc->eval, SC_EVAL_POW + 1, "sc_keys_desc.eval", err) ||
        sc_api_check_tolerance(desc->tolerance_px, "sc_keys_desc.tolerance_px", &opts->tol_milli, err))
        return SC_FAIL;
    if (desc->outputs & ~(unsigned)SCG_OUTPUT_ALL)
        return sc_api_invalid(err, "sc_keys_desc.outputs", PROBLEM_RANGE, "0x%x (SC_OUTPUT_* bits)",
                       desc->outputs);
    opts->nurbs_direct = desc->nurbs_direct != 0;
    opts->generic_above = desc->generic_above;
    opts->ignore_trims = desc->ignore_trims != 0;
    opts->trim_method = desc->trim;
    opts->trim_iters = desc->trim_iters;
    opts->max_iters = desc->max_iters;
    opts->start = desc->start;
    opts->termination = desc->termination;
    opts->outputs = desc->outputs;
    opts->skip_undrawable = desc->skip_undrawable != 0;
    opts->method = desc->method;
    opts->eval = desc->eval;
    return desc->like ? like_options(desc->like, opts, err) : SC_OK;
}

int sc_query_scene_keys(sc_scene_id scene, const sc_keys_desc *desc, sc_key *keys,
                        int capacity, int *count, sc_error *err)
{
    static const sc_keys_desc defaults = {0};
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    sc_key_options opts;
    if (key_options(desc ? desc : &defaults, &opts, err) != SC_OK)
        return SC_FAIL;
    char (*texts)[SCG_KEY_MAX] = NULL;
    int n = 0;
    if (sc_scene_keys(&s->scene, &opts, &texts, &n, err) != SC_OK)
        return SC_FAIL;
    int status = sc_api_count_keys((const char (*)[SCG_KEY_MAX])texts, n, keys, capacity, count, err);
    free(texts);
    return status;
}

int sc_query_surface_key(sc_scene_id scene, int surface, const sc_keys_desc *desc, sc_key *out,
                         sc_error *err)
{
    static const sc_keys_desc defaults = {0};
    scene_object *s = sc_api_pool_get(&sc_api_scenes, scene.id, err);
    if (!s || !scene_surface(scene, surface, err))
        return SC_FAIL;
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    sc_key_options opts;
    if (key_options(desc ? desc : &defaults, &opts, err) != SC_OK ||
        sc_surface_drawable(&s->scene, surface, err) != SC_OK)
        return SC_FAIL;
    scg_key key;
    sc_surface_key(&s->scene.surfaces[surface], &opts, &key);
    scg_key_format(&key, out->text, sizeof out->text);
    return SC_OK;
}

int sc_check_key(const char *key, sc_error *err)
{
    if (!key)
        return sc_api_invalid(err, "key", PROBLEM_NULL, NULL);
    scg_key parsed;
    if (parse_key(key, &parsed, err) != SC_OK)
        return SC_FAIL;
    if (scg_key_check(&parsed, err) != SC_OK) {
        if (err && !err->key[0])
            snprintf(err->key, sizeof err->key, "%s", key);
        return SC_FAIL;
    }
    return SC_OK;
}

int sc_make_key(const sc_key_desc *desc, sc_key *out, sc_error *err)
{
    static const sc_key_desc defaults = {0};
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    if (!desc)
        desc = &defaults;
    if (sc_api_check_int(desc->deg_u, 0, SCG_MAX_DEGREE, "sc_key_desc.deg_u", err) ||
        sc_api_check_int(desc->deg_v, 0, SCG_MAX_DEGREE, "sc_key_desc.deg_v", err) ||
        sc_api_check_int(desc->rational, 0, 2, "sc_key_desc.rational", err) ||
        sc_api_check_int(desc->max_iters, 0, SCG_MAX_ITERS, "sc_key_desc.max_iters", err) ||
        sc_api_check_int(desc->lists, 0, 1, "sc_key_desc.lists", err))
        return SC_FAIL;
    scg_key key;
    if (desc->like) {
        if (parse_key(desc->like, &key, err) != SC_OK)
            return SC_FAIL;
    } else {
        /* The key sc_surface_key gives such a patch under default options,
         * but with scg_key_default's method, Newton. */
        scg_key_default(&key, SCG_PATCH_BEZIER, 3, 3);
        key.ert = sc_key_ert(SC_TERMINATION_DEFAULT);
        key.outputs = SC_KEY_DEFAULT_OUTPUTS;
    }
    /* Without like, or unrolling like's generic program, the evaluation
     * form is the one sc_surface_key gives these degrees. */
    bool default_form = !desc->like;
    if (desc->deg_u || desc->deg_v) {
        key.deg_u = desc->deg_u ? desc->deg_u : key.deg_u;
        key.deg_v = desc->deg_v ? desc->deg_v : key.deg_v;
        if (key.eval == SCG_EVAL_LOOP) {
            key.eval = SCG_EVAL_DC;
            default_form = true;
        }
    }
    if (default_form && key.kind == SCG_PATCH_BEZIER)
        key.eval = sc_bezier_eval(SC_EVAL_DEFAULT, key.deg_u, key.deg_v);
    if (desc->rational)
        key.rational = desc->rational == 1;
    if (desc->max_iters)
        key.max_iters = desc->max_iters;
    if (desc->lists)
        scg_key_for_lists(&key);
    /* Only now: like may be out's own text. */
    memset(out, 0, sizeof *out);
    scg_key_format(&key, out->text, sizeof out->text);
    return SC_OK;
}

static void print_stage(const char *stage, const scg_program *prog, void *user)
{
    fprintf(user, "# after %s\n", stage);
    scg_dump_ir(user, prog);
}

int sc_dump_ir(const char *key, FILE *out, sc_error *err)
{
    if (!key || !out)
        return sc_api_invalid(err, key ? "out" : "key", PROBLEM_NULL, NULL);
    scg_key parsed;
    scg_program *prog = NULL;
    if (parse_key(key, &parsed, err) != SC_OK)
        return SC_FAIL;
    int status = scg_compile_stages(&parsed, print_stage, out, &prog, err);
    if (prog)
        scg_program_free(prog);
    return status;
}

static char *copy_text(const scg_text *t, size_t *size)
{
    const char *s = scg_text_str(t);
    *size = strlen(s);
    char *copy = sc_alloc(*size + 1, 1);
    memcpy(copy, s, *size + 1);
    return copy;
}

static void fill_audit(sc_shader_audit *audit, const scg_generated *gen, scg_stage stage)
{
    scg_audit_line line;
    int fragment = stage == SCG_STAGE_FRAGMENT;
    /* Keys share vertex programs: a vertex line names its program. */
    scg_audit_fill(&line, fragment ? gen->key : gen->vertex_name, stage,
                   fragment ? gen->program : gen->vertex_program,
                   fragment ? &gen->fragment_check : &gen->vertex_check,
                   scg_text_str(fragment ? &gen->fragment : &gen->vertex));
    audit->inst = line.value[SCG_AUDIT_INST];
    audit->spirv_inst = line.value[SCG_AUDIT_SPIRV_INST];
    audit->vec4_regs = line.value[SCG_AUDIT_VEC4_REGS];
    audit->tex = line.value[SCG_AUDIT_TEX];
    audit->bytes = line.value[SCG_AUDIT_BYTES];
    audit->register_bound = line.register_bound;
    scg_audit_format(&line, audit->line, sizeof audit->line);
}

int sc_generate_glsl(const sc_glsl_desc *desc, sc_glsl *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    memset(out, 0, sizeof *out);
    if (!desc || !desc->key)
        return sc_api_invalid(err, "sc_glsl_desc.key", PROBLEM_NULL, NULL);
    if (sc_check_key(desc->key, err) != SC_OK)
        return SC_FAIL;
    scg_key key;
    scg_key_parse(desc->key, &key, NULL);
    scg_generated gen;
    int status = desc->audit ? scg_generate_counted(&key, &gen, err)
                             : scg_generate(&key, &gen, err);
    if (status != SC_OK)
        return SC_FAIL;
    snprintf(out->key, sizeof out->key, "%s", gen.key);
    snprintf(out->vertex_name, sizeof out->vertex_name, "%s", gen.vertex_name);
    out->vertex = copy_text(&gen.vertex, &out->vertex_size);
    out->fragment = copy_text(&gen.fragment, &out->fragment_size);
    if (desc->audit) {
        fill_audit(&out->vertex_audit, &gen, SCG_STAGE_VERTEX);
        fill_audit(&out->fragment_audit, &gen, SCG_STAGE_FRAGMENT);
        scg_text kinds = {0};
        scg_audit_format_kinds(gen.program, gen.key, &kinds);
        size_t size;
        out->ir_kinds = copy_text(&kinds, &size);
        scg_text_free(&kinds);
    }
    scg_generated_free(&gen);
    return SC_OK;
}

void sc_free_glsl(sc_glsl *glsl)
{
    if (!glsl)
        return;
    free(glsl->vertex);
    free(glsl->fragment);
    free(glsl->ir_kinds);
    memset(glsl, 0, sizeof *glsl);
}

int sc_compare_audits(const sc_audit_text *before, const sc_audit_text *after, FILE *out,
                      sc_error *err)
{
    return sc_compare_audits_matching(before, after, NULL, out, err);
}

int sc_compare_audits_matching(const sc_audit_text *before, const sc_audit_text *after,
                               const char *ignore_fields, FILE *out, sc_error *err)
{
    const sc_audit_text *texts[2] = {before, after};
    const char *what[2] = {"before", "after"};
    for (int k = 0; k < 2; k++)
        if (!texts[k] || !texts[k]->name || (!texts[k]->text && texts[k]->size))
            return sc_api_invalid(err, what[k], PROBLEM_NULL, NULL);
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    scg_audit_line *lines[2] = {NULL, NULL};
    int count[2] = {0, 0};
    for (int k = 0; k < 2; k++)
        if (scg_audit_read(texts[k]->name, texts[k]->text, texts[k]->size, &lines[k], &count[k],
                           err) != SC_OK) {
            free(lines[0]);
            return SC_FAIL;
        }
    unsigned ignore = 0;
    int *old_of_new = NULL, status = SC_OK;
    if (ignore_fields) {
        old_of_new = sc_alloc((size_t)count[1] + 1, sizeof *old_of_new);
        status = scg_audit_match_fields(ignore_fields, &ignore, err);
        if (status == SC_OK)
            status = scg_audit_pair(lines[0], count[0], lines[1], count[1], ignore, old_of_new,
                                    err);
    }
    if (status == SC_OK)
        scg_audit_compare(out, lines[0], count[0], lines[1], count[1], old_of_new, NULL);
    free(old_of_new);
    free(lines[0]);
    free(lines[1]);
    return status;
}
