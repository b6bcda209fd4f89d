/* api_objects.c — what both files of the public interface use (api.c,
 * api_render.c): the one list of argument problems and the checks that
 * report them, and the pools of objects named by typed handles. A file of
 * its own so that the two call it and not each other. */
#include "api_private.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- argument problems: one list ---- */

static const char *const problem_text[] = {
    [PROBLEM_NULL] = "is NULL",
    [PROBLEM_ZERO_HANDLE] = "is the zero handle (never made)",
    [PROBLEM_STALE_HANDLE] = "names an object that was destroyed",
    [PROBLEM_UNKNOWN_HANDLE] = "names no object ever made",
    [PROBLEM_POOL_FULL] = "cannot be made: too many live objects of its kind",
    [PROBLEM_SCENE_SOURCE] = "gives both path and text: give one",
    [PROBLEM_SCENE_NAME] = "needs a name whose extension picks the reader (.bpt, .obj, .igs, .stp)",
    [PROBLEM_ENUM] = "is not a value of its enum",
    [PROBLEM_RANGE] = "is out of range",
    [PROBLEM_CAMERA] = "is not a usable view",
    [PROBLEM_CONTEXT] = "belongs to a different context",
    [PROBLEM_NOT_APP_CONTEXT] = "is not on an application's context",
    [PROBLEM_TERRAIN_SOURCE] = "gives more than one of path, text, heights and franke: give one",
};

/* "WHAT PROBLEM: detail". */
int sc_api_invalid(sc_error *err, const char *what, problem p, const char *fmt, ...)
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

int sc_api_check_enum(int value, int count, const char *what, sc_error *err)
{
    if (value < 0 || value >= count)
        return sc_api_invalid(err, what, PROBLEM_ENUM, "%d", value);
    return SC_OK;
}

int sc_api_check_int(int value, int lo, int hi, const char *what, sc_error *err)
{
    if (value < lo || value > hi)
        return sc_api_invalid(err, what, PROBLEM_RANGE, "%d (%d to %d)", value, lo, hi);
    return SC_OK;
}

/* Tolerances in pixel footprints: 0 for the default, else 0.001 to 100,
 * the range `splinecast render --tol` takes. */
int sc_api_check_tolerance(double tol, const char *what, int *tol_milli, sc_error *err)
{
    if (tol == 0) {
        *tol_milli = 0;
        return SC_OK;
    }
    if (!(tol >= 0.001 && tol <= 100))
        return sc_api_invalid(err, what, PROBLEM_RANGE, "%g (0 for the default, or 0.001 to 100)", tol);
    *tol_milli = (int)lround(tol * 1000);
    return SC_OK;
}

/* ---- pools ---- */

pool sc_api_scenes = {"scene", 0, NULL};
pool sc_api_contexts = {"context", 0, NULL};
pool sc_api_programs = {"program", 0, NULL};
pool sc_api_renderers = {"renderer", 0, NULL};
pool sc_api_frames = {"frame", 0, NULL};
pool sc_api_peers = {"peer", 0, NULL};

uint32_t sc_api_slot_id(const pool *p, int index)
{
    return (uint32_t)p->slots[index].generation << 16 | (uint32_t)(index + 1);
}

/* Stores object and returns its id, or 0 (err filled) when the pool is full. */
uint32_t sc_api_pool_insert(pool *p, void *object, sc_error *err)
{
    int i = 0;
    while (i < p->count && p->slots[i].object)
        i++;
    if (i == p->count) {
        if (p->count == POOL_MAX_SLOTS) {
            sc_api_invalid(err, p->kind, PROBLEM_POOL_FULL, "%d", POOL_MAX_SLOTS);
            return 0;
        }
        p->slots = sc_realloc(p->slots, (size_t)p->count + 1, sizeof *p->slots);
        p->slots[p->count++] = (slot){NULL, 1};
    }
    p->slots[i].object = object;
    return sc_api_slot_id(p, i);
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
void *sc_api_pool_get(const pool *p, uint32_t id, sc_error *err)
{
    char what[48];
    snprintf(what, sizeof what, "%s handle", p->kind);
    if (id == 0) {
        sc_api_invalid(err, what, PROBLEM_ZERO_HANDLE, NULL);
        return NULL;
    }
    int index = slot_index(p, id);
    if (index < 0) {
        /* A slot's generation grows when its object is destroyed: an older
         * one named an object of that slot, a later one was never given. */
        int i = (int)(id & 0xffff) - 1;
        int destroyed = i >= 0 && i < p->count && id >> 16 < p->slots[i].generation;
        sc_api_invalid(err, what, destroyed ? PROBLEM_STALE_HANDLE : PROBLEM_UNKNOWN_HANDLE, "0x%08x",
                (unsigned)id);
        return NULL;
    }
    return p->slots[index].object;
}

/* Frees the slot; its next object gets a new generation (never 0, so that
 * no live id is 0). */
void sc_api_pool_remove(pool *p, uint32_t id)
{
    int index = slot_index(p, id);
    if (index < 0)
        return;
    p->slots[index].object = NULL;
    if (++p->slots[index].generation == 0)
        p->slots[index].generation = 1;
}

/* ---- objects ---- */

/* The context whose GL calls are current, so that switching costs a call
 * only when it changes. */
context_object *sc_api_current_context;

int sc_api_make_current(context_object *c, sc_error *err)
{
    /* An application's context is current whenever a call names it (the
     * application's doing); which context is current afterwards is then
     * unknown, so the next call on one of the library's makes it current. */
    if (sc_gl_context_is_app(c->gl)) {
        sc_api_current_context = NULL;
        return SC_OK;
    }
    /* The program may have made a context of its own current since (a
     * window's): then the library's is made current again. */
    if (c == sc_api_current_context && sc_gl_context_is_current(c->gl))
        return SC_OK;
    if (sc_gl_context_make_current(c->gl, err) != SC_OK)
        return SC_FAIL;
    sc_api_current_context = c;
    return SC_OK;
}

void sc_api_release_scene(scene_object *s)
{
    if (--s->users == 0 && s->orphaned) {
        sc_scene_free(&s->scene);
        free(s);
    }
}

int sc_api_count_keys(const char (*texts)[SCG_KEY_MAX], int n, sc_key *keys, int capacity,
                      int *count, sc_error *err)
{
    if (!count)
        return sc_api_invalid(err, "count", PROBLEM_NULL, NULL);
    if (capacity < 0 || (capacity > 0 && !keys))
        return sc_api_invalid(err, "capacity", PROBLEM_RANGE, "%d with keys %s", capacity,
                       keys ? "given" : "NULL");
    for (int k = 0; k < n && k < capacity; k++)
        memcpy(keys[k].text, texts[k], SC_KEY_SIZE);
    *count = n;
    return SC_OK;
}

/* ---- renderers: the desc checked, and one destroyed (api_render.c and
 * api_pack.c both make them) ---- */

int sc_api_render_desc(const sc_renderer_desc *d, sc_render_desc *r, sc_error *err)
{
    memset(r, 0, sizeof *r);
    if (sc_api_check_enum(d->hull_split, SC_SPLIT_UNIFORM + 1, "sc_renderer_desc.hull_split", err) ||
        sc_api_check_int(d->hull_divisions, 0, SC_MAX_HULL_DIVISIONS, "sc_renderer_desc.hull_divisions", err) ||
        sc_api_check_int(d->hull_max_depth, 0, 32, "sc_renderer_desc.hull_max_depth", err) ||
        sc_api_check_enum(d->start, SC_START_VIEW + 1, "sc_renderer_desc.start", err) ||
        sc_api_check_int(d->max_iters, 0, SCG_MAX_ITERS, "sc_renderer_desc.max_iters", err) ||
        sc_api_check_enum(d->show, SC_SHOW_REFLECT + 1, "sc_renderer_desc.show", err) ||
        sc_api_check_int(d->unroll_max_degree, 0, SCG_MAX_DEGREE, "sc_renderer_desc.unroll_max_degree",
                  err) ||
        sc_api_check_enum(d->trim, SC_TRIM_NONE + 1, "sc_renderer_desc.trim", err) ||
        sc_api_check_enum(d->termination, SC_TERMINATION_LISTS + 1,
                   "sc_renderer_desc.termination", err) ||
        sc_api_check_enum(d->order, SC_HULL_ORDER_HYBRID + 1, "sc_renderer_desc.order", err) ||
        sc_api_check_int(d->trim_iters, 0, SCG_MAX_TRIM_ITERS, "sc_renderer_desc.trim_iters", err) ||
        sc_api_check_int(d->batch_hulls, 0, 1 << 24, "sc_renderer_desc.batch_hulls", err) ||
        sc_api_check_int(d->list_below_px, SC_LISTS_OFF, 1 << 16, "sc_renderer_desc.list_below_px", err) ||
        sc_api_check_int(d->threads, 0, 1 << 10, "sc_renderer_desc.threads", err) ||
        sc_api_check_enum(d->method, SC_METHOD_HYBRID + 1, "sc_renderer_desc.method", err) ||
        sc_api_check_enum(d->eval, SC_EVAL_POW + 1, "sc_renderer_desc.eval", err) ||
        sc_api_check_tolerance(d->tolerance_px, "sc_renderer_desc.tolerance_px", &r->tol_milli, err))
        return SC_FAIL;
    if (!(d->hull_tolerance >= 0 && d->hull_tolerance < 1))
        return sc_api_invalid(err, "sc_renderer_desc.hull_tolerance", PROBLEM_RANGE,
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
    r->list_below_px = d->list_below_px;
    r->threads = d->threads;
    r->gpu_memory_budget = d->gpu_memory_budget;
    r->method = d->method;
    r->eval = d->eval;
    r->deferred = d->deferred != 0;
    r->time_intersection = d->time_intersection != 0;
    if (d->aovs != SC_AOVS_ON_DEMAND && d->aovs != SC_AOVS_ALWAYS)
        return sc_api_invalid(err, "sc_renderer_desc.aovs", PROBLEM_RANGE,
                              "SC_AOVS_ON_DEMAND (0) or SC_AOVS_ALWAYS (1)");
    r->aovs_on_demand = d->aovs == SC_AOVS_ON_DEMAND;
    return SC_OK;
}

void sc_api_destroy_renderer_object(renderer_object *r)
{
    if (sc_api_make_current(r->context, NULL) == SC_OK)
        sc_renderer_destroy(r->renderer);
    if (r->scene)   /* NULL for a packed renderer */
        sc_api_release_scene(r->scene);
    free(r);
}

/* The internal camera of a public one, defaults filled from the scene
 * (api_private.h). */
int sc_api_make_camera(const sc_camera_desc *desc, const sc_scene *scene, sc_camera *cam,
                       sc_error *err)
{
    double lo[3], hi[3];
    int any = scene && sc_scene_view_bounds(scene, lo, hi);
    return sc_api_make_camera_framing(desc, any ? lo : NULL, any ? hi : NULL, cam, err);
}

int sc_api_make_camera_framing(const sc_camera_desc *desc, const double lo[3], const double hi[3],
                               sc_camera *cam, sc_error *err)
{
    static const sc_camera_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    memset(cam, 0, sizeof *cam);
    memcpy(cam->up, desc->up, sizeof cam->up);
    sc_camera_default_box(lo, hi, desc->from, cam);
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
    if (sc_api_check_int(desc->width, 0, 16384, "sc_camera_desc.width", err) ||
        sc_api_check_int(desc->height, 0, 16384, "sc_camera_desc.height", err))
        return SC_FAIL;
    cam->width = desc->width ? desc->width : 512;
    cam->height = desc->height ? desc->height : 512;
    double dist2 = 0;
    int finite = isfinite(cam->fovy_deg);
    for (int c = 0; c < 3; c++) {
        finite &= isfinite(cam->eye[c]) && isfinite(cam->target[c]) && isfinite(cam->up[c]);
        dist2 += (cam->target[c] - cam->eye[c]) * (cam->target[c] - cam->eye[c]);
    }
    if (!finite || !(dist2 > 0) || !(cam->fovy_deg > 0 && cam->fovy_deg < 180))
        return sc_api_invalid(err, "sc_camera_desc", PROBLEM_CAMERA,
                       "the eye must differ from the target and fovy_deg lie in (0, 180)");
    return SC_OK;
}
