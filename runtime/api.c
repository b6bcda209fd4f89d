/* api.c — the public interface (splinecast.h) over the internal modules.
 * Objects live in small pools and are named by typed handles: an id is the
 * slot's index + 1 in the low 16 bits and the slot's generation in the high
 * 16, so a handle to a destroyed object stays invalid after its slot is
 * reused. The options' enums (splinecast_options.h) are the ones the
 * runtime works with, so descs are checked here and passed on, never
 * translated. Every problem with an argument is reported through one list
 * of messages. */
#include "splinecast.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "audit.h"
#include "emit_glsl.h"
#include "gl_context.h"
#include "gl_render.h"
#include "imgdiff.h"
#include "io.h"
#include "programs.h"
#include "refcast.h"
#include "scene_keys.h"
#include "shade.h"

_Static_assert(SC_KEY_SIZE == SCG_KEY_MAX, "public and internal key sizes differ");
_Static_assert((int)SC_OUTPUT_SHADE == (int)SCG_OUTPUT_SHADE &&
                   (int)SC_OUTPUT_AOV == (int)SCG_OUTPUT_AOV &&
                   (int)SC_OUTPUT_ITERS == (int)SCG_OUTPUT_ITERS &&
                   (int)SC_OUTPUT_UV == (int)SCG_OUTPUT_UVVIEW &&
                   (int)SC_OUTPUT_HULL == (int)SCG_OUTPUT_HULLVIEW,
               "public output bits are the key's output bits");
_Static_assert(sizeof(((sc_shader_audit *)0)->line) >= SCG_KEY_MAX + 100,
               "an audit line holds a key and its figures");

/* ---- argument problems: one list ---- */

typedef enum problem {
    PROBLEM_NULL,
    PROBLEM_ZERO_HANDLE,
    PROBLEM_STALE_HANDLE,
    PROBLEM_UNKNOWN_HANDLE,
    PROBLEM_POOL_FULL,
    PROBLEM_SCENE_SOURCE,
    PROBLEM_SCENE_NAME,
    PROBLEM_ENUM,
    PROBLEM_RANGE,
    PROBLEM_CAMERA,
    PROBLEM_CONTEXT,
} problem;

static const char *const problem_text[] = {
    [PROBLEM_NULL] = "is NULL",
    [PROBLEM_ZERO_HANDLE] = "is the zero handle (never made)",
    [PROBLEM_STALE_HANDLE] = "names an object that was destroyed",
    [PROBLEM_UNKNOWN_HANDLE] = "names no object ever made",
    [PROBLEM_POOL_FULL] = "cannot be made: too many live objects of its kind",
    [PROBLEM_SCENE_SOURCE] = "gives both path and text: give one",
    [PROBLEM_SCENE_NAME] = "needs a name whose extension picks the reader (.bpt, .obj, .igs)",
    [PROBLEM_ENUM] = "is not a value of its enum",
    [PROBLEM_RANGE] = "is out of range",
    [PROBLEM_CAMERA] = "is not a usable view",
    [PROBLEM_CONTEXT] = "belongs to a different context",
};

/* "WHAT PROBLEM: detail". */
static int invalid(sc_error *err, const char *what, problem p, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int invalid(sc_error *err, const char *what, problem p, const char *fmt, ...)
{
    char detail[256] = "";
    if (fmt) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(detail, sizeof detail, fmt, ap);
        va_end(ap);
    }
    return sc_fail(err, NULL, 0, "%s %s%s%s", what, problem_text[p], detail[0] ? ": " : "",
                   detail);
}

static int check_enum(int value, int count, const char *what, sc_error *err)
{
    if (value < 0 || value >= count)
        return invalid(err, what, PROBLEM_ENUM, "%d", value);
    return SC_OK;
}

static int check_int(int value, int lo, int hi, const char *what, sc_error *err)
{
    if (value < lo || value > hi)
        return invalid(err, what, PROBLEM_RANGE, "%d (%d to %d)", value, lo, hi);
    return SC_OK;
}

/* Tolerances in pixel footprints: 0 for the default, else 0.001 to 100,
 * the range `splinecast render --tol` takes. */
static int check_tolerance(double tol, const char *what, int *tol_milli, sc_error *err)
{
    if (tol == 0) {
        *tol_milli = 0;
        return SC_OK;
    }
    if (!(tol >= 0.001 && tol <= 100))
        return invalid(err, what, PROBLEM_RANGE, "%g (0 for the default, or 0.001 to 100)", tol);
    *tol_milli = (int)lround(tol * 1000);
    return SC_OK;
}

/* ---- pools ---- */

enum { POOL_MAX_SLOTS = 0xffff };

typedef struct slot {
    void *object;           /* NULL: free */
    uint16_t generation;
} slot;

typedef struct pool {
    const char *kind;       /* "scene", … for messages */
    int count;
    slot *slots;
} pool;

static pool scenes = {"scene", 0, NULL};
static pool contexts = {"context", 0, NULL};
static pool programs = {"program", 0, NULL};
static pool renderers = {"renderer", 0, NULL};
static pool frames = {"frame", 0, NULL};

static uint32_t slot_id(const pool *p, int index)
{
    return (uint32_t)p->slots[index].generation << 16 | (uint32_t)(index + 1);
}

/* Stores object and returns its id, or 0 (err filled) when the pool is full. */
static uint32_t pool_insert(pool *p, void *object, sc_error *err)
{
    int i = 0;
    while (i < p->count && p->slots[i].object)
        i++;
    if (i == p->count) {
        if (p->count == POOL_MAX_SLOTS) {
            invalid(err, p->kind, PROBLEM_POOL_FULL, "%d", POOL_MAX_SLOTS);
            return 0;
        }
        p->slots = sc_realloc(p->slots, (size_t)p->count + 1, sizeof *p->slots);
        p->slots[p->count++] = (slot){NULL, 1};
    }
    p->slots[i].object = object;
    return slot_id(p, i);
}

static int slot_index(const pool *p, uint32_t id)
{
    int index = (int)(id & 0xffff) - 1;
    if (index < 0 || index >= p->count || !p->slots[index].object ||
        p->slots[index].generation != id >> 16)
        return -1;
    return index;
}

/* The object of a handle, or NULL with err filled. */
static void *pool_get(const pool *p, uint32_t id, sc_error *err)
{
    char what[48];
    snprintf(what, sizeof what, "%s handle", p->kind);
    if (id == 0) {
        invalid(err, what, PROBLEM_ZERO_HANDLE, NULL);
        return NULL;
    }
    int index = slot_index(p, id);
    if (index < 0) {
        /* A slot's generation grows when its object is destroyed: an older
         * one named an object of that slot, a later one was never given. */
        int i = (int)(id & 0xffff) - 1;
        int destroyed = i >= 0 && i < p->count && id >> 16 < p->slots[i].generation;
        invalid(err, what, destroyed ? PROBLEM_STALE_HANDLE : PROBLEM_UNKNOWN_HANDLE, "0x%08x",
                (unsigned)id);
        return NULL;
    }
    return p->slots[index].object;
}

/* Frees the slot; its next object gets a new generation (never 0, so that
 * no live id is 0). */
static void pool_remove(pool *p, uint32_t id)
{
    int index = slot_index(p, id);
    if (index < 0)
        return;
    p->slots[index].object = NULL;
    if (++p->slots[index].generation == 0)
        p->slots[index].generation = 1;
}

/* ---- objects ---- */

typedef struct scene_object {
    sc_scene scene;
    int users;              /* renderers drawing it */
    int orphaned;           /* its handle was destroyed while in use */
} scene_object;

typedef struct context_object {
    sc_gl_context *gl;
    sc_program_cache *programs;
} context_object;

typedef struct program_object {
    context_object *context;
    sc_program program;
} program_object;

typedef struct renderer_object {
    context_object *context;
    scene_object *scene;
    sc_renderer *renderer;
} renderer_object;

typedef struct frame_object {
    sc_image rgba;
    sc_aov aov;
    double render_ms;
} frame_object;

/* The context whose GL calls are current, so that switching costs a call
 * only when it changes. */
static context_object *current_context;

static int make_current(context_object *c, sc_error *err)
{
    if (c == current_context)
        return SC_OK;
    if (sc_gl_context_make_current(c->gl, err) != SC_OK)
        return SC_FAIL;
    current_context = c;
    return SC_OK;
}

static void release_scene(scene_object *s)
{
    if (--s->users == 0 && s->orphaned) {
        sc_scene_free(&s->scene);
        free(s);
    }
}

static int count_keys(const char (*texts)[SCG_KEY_MAX], int n, sc_key *keys, int capacity,
                      int *count, sc_error *err)
{
    if (!count)
        return invalid(err, "count", PROBLEM_NULL, NULL);
    if (capacity < 0 || (capacity > 0 && !keys))
        return invalid(err, "capacity", PROBLEM_RANGE, "%d with keys %s", capacity,
                       keys ? "given" : "NULL");
    for (int k = 0; k < n && k < capacity; k++)
        memcpy(keys[k].text, texts[k], SC_KEY_SIZE);
    *count = n;
    return SC_OK;
}

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
        return invalid(err, "sc_scene_desc.name", PROBLEM_SCENE_NAME, NULL);
    if (has_extension(name, ".bpt"))
        return sc_read_bpt(desc->text, desc->size, name, scene, err);
    if (has_extension(name, ".obj"))
        return sc_read_obj(desc->text, desc->size, name, scene, err);
    if (has_extension(name, ".igs") || has_extension(name, ".iges"))
        return sc_read_iges(desc->text, desc->size, name, scene, err);
    return invalid(err, "sc_scene_desc.name", PROBLEM_SCENE_NAME, "'%s'", name);
}

int sc_make_scene(const sc_scene_desc *desc, sc_scene_id *out, sc_error *err)
{
    static const sc_scene_desc defaults = {0};
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!desc)
        desc = &defaults;
    if (desc->path && desc->text)
        return invalid(err, "sc_scene_desc", PROBLEM_SCENE_SOURCE, NULL);
    scene_object *s = sc_alloc(1, sizeof *s);
    int status = desc->text ? read_scene_text(desc, &s->scene, err)
                            : sc_read_scene(desc->path ? desc->path : "teapot", &s->scene, err);
    if (status == SC_OK && (out->id = pool_insert(&scenes, s, err)) != 0)
        return SC_OK;
    sc_scene_free(&s->scene);
    free(s);
    return SC_FAIL;
}

void sc_destroy_scene(sc_scene_id scene)
{
    scene_object *s = pool_get(&scenes, scene.id, NULL);
    if (!s)
        return;
    pool_remove(&scenes, scene.id);
    if (s->users > 0) {
        s->orphaned = 1;
        return;
    }
    sc_scene_free(&s->scene);
    free(s);
}

int sc_query_scene_info(sc_scene_id scene, sc_scene_info *info, sc_error *err)
{
    scene_object *s = pool_get(&scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    if (!info)
        return invalid(err, "info", PROBLEM_NULL, NULL);
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
    sc_scene_bounds(sc, info->lo, info->hi);
    return SC_OK;
}

/* ---- surfaces ---- */

/* Surface `surface` of a scene handle, or NULL with err filled. */
static sc_surface *scene_surface(sc_scene_id scene, int surface, sc_error *err)
{
    scene_object *s = pool_get(&scenes, scene.id, err);
    if (!s)
        return NULL;
    if (surface < 0 || surface >= s->scene.nsurfaces) {
        invalid(err, "surface", PROBLEM_RANGE, "%d (0 to %d)", surface, s->scene.nsurfaces - 1);
        return NULL;
    }
    return &s->scene.surfaces[surface];
}

int sc_query_surface_info(sc_scene_id scene, int surface, sc_surface_info *info,
                          sc_error *err)
{
    const sc_surface *surf = scene_surface(scene, surface, err);
    if (!surf)
        return SC_FAIL;
    if (!info)
        return invalid(err, "info", PROBLEM_NULL, NULL);
    *info = (sc_surface_info){.deg_u = surf->deg_u, .deg_v = surf->deg_v, .nu = surf->nu,
                              .nv = surf->nv, .rational = surf->rational != 0,
                              .trim_loops = surf->nloops};
    snprintf(info->name, sizeof info->name, "%s", surf->name);
    return SC_OK;
}

static int check_count(int count, const sc_surface *surf, const char *what, sc_error *err)
{
    if (count != surf->nu * surf->nv)
        return invalid(err, what, PROBLEM_RANGE, "%d (the surface has %d x %d control points)",
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
    scene_object *s = pool_get(&scenes, scene.id, err);
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
            return invalid(err, "sc_surface_desc.points", PROBLEM_RANGE,
                           "coordinate %d of point %d is %g", k % 3, k / 3, desc->points[k]);
    for (int k = 0; k < n && desc->weights; k++)
        if (!(desc->weights[k] > 0 && isfinite(desc->weights[k])))
            return invalid(err, "sc_surface_desc.weights", PROBLEM_RANGE,
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
    for (int i = 0; i < renderers.count; i++) {
        renderer_object *r = renderers.slots[i].object;
        if (!r || r->scene != s || status != SC_OK)
            continue;
        if (make_current(r->context, err) != SC_OK ||
            sc_renderer_update_surface(r->renderer, desc->surface, err) != SC_OK)
            status = SC_FAIL;
    }
    return status;
}

/* ---- keys and generation ---- */

static int key_options(const sc_keys_desc *desc, sc_key_options *opts, sc_error *err)
{
    memset(opts, 0, sizeof *opts);
    if (check_int(desc->generic_above, 0, SCG_MAX_DEGREE, "sc_keys_desc.generic_above", err) ||
        check_int(desc->trim_iters, 0, SCG_MAX_TRIM_ITERS, "sc_keys_desc.trim_iters", err) ||
        check_int(desc->max_iters, 0, SCG_MAX_ITERS, "sc_keys_desc.max_iters", err) ||
        check_enum(desc->termination, SC_TERMINATION_MANUAL_BOTH + 1,
                   "sc_keys_desc.termination", err) ||
        check_enum(desc->start, SC_START_CPMAP + 1, "sc_keys_desc.start", err) ||
        check_enum(desc->trim, SC_TRIM_NONE + 1, "sc_keys_desc.trim", err) ||
        check_tolerance(desc->tolerance_px, "sc_keys_desc.tolerance_px", &opts->tol_milli, err))
        return SC_FAIL;
    if (desc->outputs & ~(unsigned)SCG_OUTPUT_ALL)
        return invalid(err, "sc_keys_desc.outputs", PROBLEM_RANGE, "0x%x (SC_OUTPUT_* bits)",
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
    return SC_OK;
}

int sc_query_scene_keys(sc_scene_id scene, const sc_keys_desc *desc, sc_key *keys,
                        int capacity, int *count, sc_error *err)
{
    static const sc_keys_desc defaults = {0};
    scene_object *s = pool_get(&scenes, scene.id, err);
    if (!s)
        return SC_FAIL;
    sc_key_options opts;
    if (key_options(desc ? desc : &defaults, &opts, err) != SC_OK)
        return SC_FAIL;
    char (*texts)[SCG_KEY_MAX] = NULL;
    int n = 0;
    if (sc_scene_keys(&s->scene, &opts, &texts, &n, err) != SC_OK)
        return SC_FAIL;
    int status = count_keys((const char (*)[SCG_KEY_MAX])texts, n, keys, capacity, count, err);
    free(texts);
    return status;
}

int sc_check_key(const char *key, sc_error *err)
{
    if (!key)
        return invalid(err, "key", PROBLEM_NULL, NULL);
    scg_key parsed;
    if (scg_key_parse(key, &parsed, err) != SC_OK || scg_key_check(&parsed, err) != SC_OK) {
        if (err && !err->key[0])
            snprintf(err->key, sizeof err->key, "%s", key);
        return SC_FAIL;
    }
    return SC_OK;
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
    scg_audit_fill(&line, gen->key, stage, fragment ? gen->program : NULL,
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
        return invalid(err, "out", PROBLEM_NULL, NULL);
    memset(out, 0, sizeof *out);
    if (!desc || !desc->key)
        return invalid(err, "sc_glsl_desc.key", PROBLEM_NULL, NULL);
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
    memset(glsl, 0, sizeof *glsl);
}

/* ---- contexts and programs ---- */

int sc_make_context(const sc_context_desc *desc, sc_context_id *out, sc_error *err)
{
    static const sc_context_desc defaults = {0};
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!desc)
        desc = &defaults;
    if (check_enum(desc->backend, SC_BACKEND_OSMESA + 1, "sc_context_desc.backend", err))
        return SC_FAIL;
    sc_gl_context_desc gl_desc = {.backend = desc->backend, .debug = desc->debug};
    context_object *c = sc_alloc(1, sizeof *c);
    if (sc_gl_context_create(&gl_desc, &c->gl, err) != SC_OK) {
        current_context = NULL;  /* a failed attempt may have changed it */
        free(c);
        return SC_FAIL;
    }
    current_context = c;  /* creating made it current */
    c->programs = sc_program_cache_create(sc_gl_context_gl(c->gl));
    if ((out->id = pool_insert(&contexts, c, err)) == 0) {
        sc_program_cache_destroy(c->programs);
        sc_gl_context_destroy(c->gl);
        current_context = NULL;
        free(c);
        return SC_FAIL;
    }
    return SC_OK;
}

static void destroy_renderer_object(renderer_object *r)
{
    if (make_current(r->context, NULL) == SC_OK)
        sc_renderer_destroy(r->renderer);
    release_scene(r->scene);
    free(r);
}

void sc_destroy_context(sc_context_id ctx)
{
    context_object *c = pool_get(&contexts, ctx.id, NULL);
    if (!c)
        return;
    for (int i = 0; i < renderers.count; i++) {
        renderer_object *r = renderers.slots[i].object;
        if (r && r->context == c) {
            pool_remove(&renderers, slot_id(&renderers, i));
            destroy_renderer_object(r);
        }
    }
    for (int i = 0; i < programs.count; i++) {
        program_object *p = programs.slots[i].object;
        if (p && p->context == c) {
            pool_remove(&programs, slot_id(&programs, i));
            free(p);
        }
    }
    if (make_current(c, NULL) == SC_OK)
        sc_program_cache_destroy(c->programs);
    sc_gl_context_destroy(c->gl);
    current_context = NULL;
    pool_remove(&contexts, ctx.id);
    free(c);
}

int sc_query_context_info(sc_context_id ctx, sc_context_info *info, sc_error *err)
{
    context_object *c = pool_get(&contexts, ctx.id, err);
    if (!c)
        return SC_FAIL;
    if (!info)
        return invalid(err, "info", PROBLEM_NULL, NULL);
    memset(info, 0, sizeof *info);
    info->backend = sc_gl_context_backend(c->gl);
    snprintf(info->description, sizeof info->description, "%s",
             sc_gl_context_description(c->gl));
    return SC_OK;
}

int sc_make_program(sc_context_id ctx, const char *key, sc_program_id *out, sc_error *err)
{
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    context_object *c = pool_get(&contexts, ctx.id, err);
    if (!c || sc_check_key(key, err) != SC_OK || make_current(c, err) != SC_OK)
        return SC_FAIL;
    scg_key parsed;
    scg_key_parse(key, &parsed, NULL);
    sc_program program;
    if (sc_program_for_key(c->programs, &parsed, &program, err) != SC_OK)
        return SC_FAIL;
    for (int i = 0; i < programs.count; i++) {
        const program_object *p = programs.slots[i].object;
        if (p && p->context == c && p->program.id == program.id) {
            out->id = slot_id(&programs, i);
            return SC_OK;
        }
    }
    program_object *p = sc_alloc(1, sizeof *p);
    p->context = c;
    p->program = program;
    if ((out->id = pool_insert(&programs, p, err)) == 0) {
        free(p);
        return SC_FAIL;
    }
    return SC_OK;
}

int sc_query_program_info(sc_program_id program, sc_program_info *info, sc_error *err)
{
    program_object *p = pool_get(&programs, program.id, err);
    if (!p)
        return SC_FAIL;
    if (!info)
        return invalid(err, "info", PROBLEM_NULL, NULL);
    memset(info, 0, sizeof *info);
    sc_program_cache *cache = p->context->programs;
    scg_key_format(sc_program_key(cache, p->program), info->key, sizeof info->key);
    info->gl_program = sc_program_gl_name(cache, p->program);
    sc_program_times(cache, p->program, &info->generate_ms, &info->compile_ms);
    return SC_OK;
}

/* ---- renderers ---- */

static int render_desc(const sc_renderer_desc *d, sc_render_desc *r, sc_error *err)
{
    memset(r, 0, sizeof *r);
    if (check_enum(d->hull_split, SC_SPLIT_UNIFORM + 1, "sc_renderer_desc.hull_split", err) ||
        check_int(d->hull_divisions, 0, SC_MAX_HULL_DIVISIONS, "sc_renderer_desc.hull_divisions", err) ||
        check_int(d->hull_max_depth, 0, 32, "sc_renderer_desc.hull_max_depth", err) ||
        check_enum(d->start, SC_START_CPMAP + 1, "sc_renderer_desc.start", err) ||
        check_int(d->max_iters, 0, SCG_MAX_ITERS, "sc_renderer_desc.max_iters", err) ||
        check_enum(d->show, SC_SHOW_HULL + 1, "sc_renderer_desc.show", err) ||
        check_int(d->unroll_max_degree, 0, SCG_MAX_DEGREE, "sc_renderer_desc.unroll_max_degree",
                  err) ||
        check_enum(d->trim, SC_TRIM_NONE + 1, "sc_renderer_desc.trim", err) ||
        check_enum(d->termination, SC_TERMINATION_MANUAL_BOTH + 1,
                   "sc_renderer_desc.termination", err) ||
        check_enum(d->order, SC_HULL_ORDER_HYBRID + 1, "sc_renderer_desc.order", err) ||
        check_int(d->trim_iters, 0, SCG_MAX_TRIM_ITERS, "sc_renderer_desc.trim_iters", err) ||
        check_int(d->batch_hulls, 0, 1 << 24, "sc_renderer_desc.batch_hulls", err) ||
        check_tolerance(d->tolerance_px, "sc_renderer_desc.tolerance_px", &r->tol_milli, err))
        return SC_FAIL;
    if (!(d->hull_tolerance >= 0 && d->hull_tolerance < 1))
        return invalid(err, "sc_renderer_desc.hull_tolerance", PROBLEM_RANGE,
                       "%g (0 for the default, or a fraction of the scene's size below 1)",
                       d->hull_tolerance);
    r->hulls.mode = d->hull_split;
    r->hulls.divisions = d->hull_divisions;
    r->hulls.tolerance = d->hull_tolerance;
    r->hulls.max_depth = d->hull_max_depth;
    r->start = d->start;
    r->max_iters = d->max_iters;
    r->view = d->show;
    r->generic = d->generic != 0;
    r->unroll_max_degree = d->unroll_max_degree;
    r->trim_method = d->trim;
    r->trim_iters = d->trim_iters;
    r->ert = d->termination;
    r->order = d->order;
    r->batch_hulls = d->batch_hulls;
    return SC_OK;
}

int sc_make_renderer(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
                     sc_renderer_id *out, sc_error *err)
{
    static const sc_renderer_desc defaults = {0};
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    context_object *c = pool_get(&contexts, ctx.id, err);
    scene_object *s = c ? pool_get(&scenes, scene.id, err) : NULL;
    sc_render_desc internal;
    if (!s || render_desc(desc ? desc : &defaults, &internal, err) != SC_OK ||
        make_current(c, err) != SC_OK)
        return SC_FAIL;
    /* The context's cache: sc_make_program on the renderer's keys returns
     * the very programs it draws with. */
    internal.programs = c->programs;
    renderer_object *r = sc_alloc(1, sizeof *r);
    r->context = c;
    r->scene = s;
    if (sc_renderer_create(sc_gl_context_gl(c->gl), &s->scene, &internal, &r->renderer, err) !=
        SC_OK) {
        free(r);
        return SC_FAIL;
    }
    s->users++;
    if ((out->id = pool_insert(&renderers, r, err)) == 0) {
        destroy_renderer_object(r);
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_destroy_renderer(sc_renderer_id renderer)
{
    renderer_object *r = pool_get(&renderers, renderer.id, NULL);
    if (!r)
        return;
    pool_remove(&renderers, renderer.id);
    destroy_renderer_object(r);
}

int sc_query_renderer_keys(sc_renderer_id renderer, sc_key *keys, int capacity, int *count,
                           sc_error *err)
{
    renderer_object *r = pool_get(&renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    int nsurfaces = r->scene->scene.nsurfaces, n = 0;
    char (*texts)[SCG_KEY_MAX] = sc_alloc((size_t)(nsurfaces ? nsurfaces : 1), SCG_KEY_MAX);
    for (int s = 0; s < nsurfaces; s++) {
        scg_key_format(sc_renderer_surface_key(r->renderer, s), texts[n], SCG_KEY_MAX);
        int seen = 0;
        for (int k = 0; k < n && !seen; k++)
            seen = !strcmp(texts[k], texts[n]);
        n += !seen;
    }
    int status = count_keys((const char (*)[SCG_KEY_MAX])texts, n, keys, capacity, count, err);
    free(texts);
    return status;
}

int sc_query_renderer_info(sc_renderer_id renderer, sc_renderer_info *info, sc_error *err)
{
    renderer_object *r = pool_get(&renderers, renderer.id, err);
    if (!r)
        return SC_FAIL;
    if (!info)
        return invalid(err, "info", PROBLEM_NULL, NULL);
    sc_render_stats stats;
    sc_renderer_stats(r->renderer, &stats);
    *info = (sc_renderer_info){
        .programs = stats.programs,
        .hulls = stats.hulls,
        .triangles = stats.triangles,
        .gpu_bytes = stats.gpu_bytes,
        .uploaded_bytes = stats.bytes_uploaded,
        .compile_ms = stats.compile_ms,
    };
    return SC_OK;
}

/* The internal camera of a public one, defaults filled from the scene. */
static int make_camera(const sc_camera_desc *desc, const sc_scene *scene, sc_camera *cam,
                       sc_error *err)
{
    static const sc_camera_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    sc_camera_default(scene, cam);
    if (desc->text) {
        if (sc_camera_parse(desc->text, cam, err) != SC_OK)
            return SC_FAIL;
    } else {
        int given = 0;
        for (int c = 0; c < 3; c++)
            given |= desc->eye[c] != 0 || desc->target[c] != 0;
        if (given) {
            memcpy(cam->eye, desc->eye, sizeof cam->eye);
            memcpy(cam->target, desc->target, sizeof cam->target);
        }
        if (desc->fovy_deg != 0)
            cam->fovy_deg = desc->fovy_deg;
    }
    if (check_int(desc->width, 0, 16384, "sc_camera_desc.width", err) ||
        check_int(desc->height, 0, 16384, "sc_camera_desc.height", err))
        return SC_FAIL;
    cam->width = desc->width ? desc->width : 512;
    cam->height = desc->height ? desc->height : 512;
    double dist2 = 0;
    int finite = isfinite(cam->fovy_deg);
    for (int c = 0; c < 3; c++) {
        finite &= isfinite(cam->eye[c]) && isfinite(cam->target[c]);
        dist2 += (cam->target[c] - cam->eye[c]) * (cam->target[c] - cam->eye[c]);
    }
    if (!finite || !(dist2 > 0) || !(cam->fovy_deg > 0 && cam->fovy_deg < 180))
        return invalid(err, "sc_camera_desc", PROBLEM_CAMERA,
                       "the eye must differ from the target and fovy_deg lie in (0, 180)");
    return SC_OK;
}

static void expand_to_rgba(const sc_image *rgb, sc_image *rgba)
{
    sc_image_alloc(rgba, rgb->width, rgb->height, 4);
    size_t n = (size_t)rgb->width * (size_t)rgb->height;
    for (size_t p = 0; p < n; p++) {
        memcpy(rgba->pixels + 4 * p, rgb->pixels + (size_t)rgb->channels * p, 3);
        rgba->pixels[4 * p + 3] = rgb->channels == 4 ? rgb->pixels[4 * p + 3] : 255;
    }
}

static int add_frame(frame_object *f, sc_frame_id *out, sc_error *err)
{
    if ((out->id = pool_insert(&frames, f, err)) != 0)
        return SC_OK;
    sc_image_free(&f->rgba);
    sc_aov_free(&f->aov);
    free(f);
    return SC_FAIL;
}

int sc_render(sc_renderer_id renderer, const sc_camera_desc *camera, sc_frame_id *out,
              sc_error *err)
{
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    renderer_object *r = pool_get(&renderers, renderer.id, err);
    sc_camera cam;
    if (!r || make_camera(camera, &r->scene->scene, &cam, err) != SC_OK ||
        make_current(r->context, err) != SC_OK)
        return SC_FAIL;
    frame_object *f = sc_alloc(1, sizeof *f);
    double t0 = sc_now();
    sc_image image = {0};
    if (sc_renderer_draw(r->renderer, &cam, err) != SC_OK ||
        sc_renderer_read(r->renderer, &image, &f->aov, err) != SC_OK) {
        sc_image_free(&image);
        sc_aov_free(&f->aov);
        free(f);
        return SC_FAIL;
    }
    f->render_ms = 1e3 * (sc_now() - t0);
    if (image.channels == 4) {
        f->rgba = image;
    } else {
        expand_to_rgba(&image, &f->rgba);
        sc_image_free(&image);
    }
    return add_frame(f, out, err);
}

int sc_render_reference(sc_scene_id scene, const sc_camera_desc *camera,
                        const sc_reference_desc *desc, sc_frame_id *out, sc_error *err)
{
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    scene_object *s = pool_get(&scenes, scene.id, err);
    sc_camera cam;
    if (!s || make_camera(camera, &s->scene, &cam, err) != SC_OK)
        return SC_FAIL;
    if (desc && check_int(desc->threads, 0, 1024, "sc_reference_desc.threads", err))
        return SC_FAIL;
    sc_refcast *rc;
    if (sc_refcast_prepare(&s->scene, &rc, err) != SC_OK)
        return SC_FAIL;
    frame_object *f = sc_alloc(1, sizeof *f);
    sc_refcast_options opt = {.threads = desc ? desc->threads : 0};
    double t0 = sc_now();
    int status = sc_refcast_render(rc, &cam, &opt, &f->aov, NULL, err);
    sc_refcast_free(rc);
    if (status != SC_OK) {
        sc_aov_free(&f->aov);
        free(f);
        return SC_FAIL;
    }
    f->render_ms = 1e3 * (sc_now() - t0);
    sc_image rgb;
    sc_shade_aov(&f->aov, &s->scene, &rgb);
    expand_to_rgba(&rgb, &f->rgba);
    sc_image_free(&rgb);
    return add_frame(f, out, err);
}

/* ---- frames ---- */

int sc_load_frame(const char *aov_path, sc_frame_id *out, sc_error *err)
{
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    out->id = 0;
    if (!aov_path)
        return invalid(err, "aov_path", PROBLEM_NULL, NULL);
    frame_object *f = sc_alloc(1, sizeof *f);
    if (sc_aov_read(aov_path, &f->aov, err) != SC_OK) {
        sc_aov_free(&f->aov);
        free(f);
        return SC_FAIL;
    }
    sc_image rgb;
    sc_shade_aov(&f->aov, NULL, &rgb);
    expand_to_rgba(&rgb, &f->rgba);
    sc_image_free(&rgb);
    return add_frame(f, out, err);
}

void sc_destroy_frame(sc_frame_id frame)
{
    frame_object *f = pool_get(&frames, frame.id, NULL);
    if (!f)
        return;
    pool_remove(&frames, frame.id);
    sc_image_free(&f->rgba);
    sc_aov_free(&f->aov);
    free(f);
}

int sc_query_frame_info(sc_frame_id frame, sc_frame_info *info, sc_error *err)
{
    frame_object *f = pool_get(&frames, frame.id, err);
    if (!f)
        return SC_FAIL;
    if (!info)
        return invalid(err, "info", PROBLEM_NULL, NULL);
    const sc_aov *a = &f->aov;
    *info = (sc_frame_info){
        .width = a->width,
        .height = a->height,
        .fovy_deg = a->camera.fovy_deg,
        .rgba = f->rgba.pixels,
        .surface = a->surface,
        .uv = a->uv,
        .t = a->t,
        .point = a->point,
        .normal = a->normal,
        .iters = a->has_iters ? a->iters : NULL,
        .render_ms = f->render_ms,
    };
    memcpy(info->eye, a->camera.eye, sizeof info->eye);
    memcpy(info->target, a->camera.target, sizeof info->target);
    return SC_OK;
}

int sc_save_png(sc_frame_id frame, const char *path, sc_error *err)
{
    frame_object *f = pool_get(&frames, frame.id, err);
    if (!f)
        return SC_FAIL;
    if (!path)
        return invalid(err, "path", PROBLEM_NULL, NULL);
    return sc_png_write(path, &f->rgba, err);
}

int sc_save_aov(sc_frame_id frame, const char *path, sc_error *err)
{
    frame_object *f = pool_get(&frames, frame.id, err);
    if (!f)
        return SC_FAIL;
    if (!path)
        return invalid(err, "path", PROBLEM_NULL, NULL);
    return sc_aov_write(path, &f->aov, err);
}

int sc_compare_frames(sc_frame_id reference, sc_frame_id test, sc_comparison *out,
                      sc_error *err)
{
    if (!out)
        return invalid(err, "out", PROBLEM_NULL, NULL);
    memset(out, 0, sizeof *out);
    frame_object *ref = pool_get(&frames, reference.id, err);
    frame_object *tst = ref ? pool_get(&frames, test.id, err) : NULL;
    sc_accuracy acc;
    if (!tst || sc_accuracy_compare(&ref->aov, &tst->aov, &acc, err) != SC_OK)
        return SC_FAIL;
    *out = (sc_comparison){
        .reference_hits = acc.ref_hits,
        .test_hits = acc.test_hits,
        .both_hit = acc.both_hit,
        .holes = acc.holes,
        .false_hits = acc.false_hits,
        .off = acc.off,
        .coverage_pct = acc.coverage_pct,
        .fail_pct = acc.fail_pct,
        .pos_median_px = acc.pos_median_px,
        .pos_max_px = acc.pos_max_px,
        .normal_mean_deg = acc.normal_mean_deg,
        .normal_max_deg = acc.normal_max_deg,
        .has_iters = acc.has_iters,
        .iters_mean = acc.iters_mean,
        .iters_max = acc.iters_max,
    };
    sc_accuracy_format(&acc, out->line, sizeof out->line);
    return SC_OK;
}

/* ---- shutdown ---- */

static void destroy_all(pool *p, void (*destroy)(uint32_t id))
{
    for (int i = 0; i < p->count; i++)
        if (p->slots[i].object)
            destroy(slot_id(p, i));
    free(p->slots);
    p->slots = NULL;
    p->count = 0;
}

static void destroy_frame_id(uint32_t id) { sc_destroy_frame((sc_frame_id){id}); }
static void destroy_renderer_id(uint32_t id) { sc_destroy_renderer((sc_renderer_id){id}); }
static void destroy_context_id(uint32_t id) { sc_destroy_context((sc_context_id){id}); }
static void destroy_scene_id(uint32_t id) { sc_destroy_scene((sc_scene_id){id}); }

void sc_shutdown(void)
{
    destroy_all(&frames, destroy_frame_id);
    destroy_all(&renderers, destroy_renderer_id);
    /* Contexts take their programs with them. */
    destroy_all(&contexts, destroy_context_id);
    free(programs.slots);
    programs.slots = NULL;
    programs.count = 0;
    destroy_all(&scenes, destroy_scene_id);
}
