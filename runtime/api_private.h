/* api_private.h — what the files of the public interface share (api.c:
 * argument checks, handle pools, scenes, surfaces and keys; api_render.c:
 * contexts, programs, renderers and frames): the one list of argument
 * problems, the pools and the objects the handles name. Not installed. */
#ifndef SC_API_PRIVATE_H
#define SC_API_PRIVATE_H

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
#include "gl_pack.h"
#include "gl_render.h"
#include "peer.h"
#include "imgdiff.h"
#include "io.h"
#include "nurbs.h"
#include "programs.h"
#include "refcast.h"
#include "scene_keys.h"
#include "shade.h"

/* ---- argument problems: one list (problem_text in api_objects.c) ---- */

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
    PROBLEM_TERRAIN_SOURCE,
    PROBLEM_NOT_APP_CONTEXT,
} problem;

/* "WHAT PROBLEM: detail" into err; returns SC_FAIL. */
int sc_api_invalid(sc_error *err, const char *what, problem p, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
int sc_api_check_enum(int value, int count, const char *what, sc_error *err);
int sc_api_check_int(int value, int lo, int hi, const char *what, sc_error *err);
/* Tolerances in pixel footprints: 0 for the default, else 0.001 to 100,
 * the range `splinecast render --tol` takes. */
int sc_api_check_tolerance(double tol, const char *what, int *tol_milli, sc_error *err);

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

extern pool sc_api_scenes, sc_api_contexts, sc_api_programs, sc_api_renderers, sc_api_frames;
extern pool sc_api_peers;   /* tessellation peers (api_peer.c) */

uint32_t sc_api_slot_id(const pool *p, int index);
/* Stores object and returns its id, or 0 (err filled) when the pool is full. */
uint32_t sc_api_pool_insert(pool *p, void *object, sc_error *err);
/* The object of a handle, or NULL with err filled. */
void *sc_api_pool_get(const pool *p, uint32_t id, sc_error *err);
/* Frees the slot; its next object gets a new generation. */
void sc_api_pool_remove(pool *p, uint32_t id);

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
    int opaque;             /* shaded from AOVs, every pixel drawn: saved as RGB */
    sc_aov aov;
    double render_ms;
    sc_reference_stats reference;
} frame_object;

/* A terrain scene from desc->heights or desc->franke (api_terrain.c). */
int sc_api_make_terrain(const sc_scene_desc *desc, sc_scene *out, sc_error *err);
/* A terrain scene's patch count and degree. */
int sc_terrain_patch_count(const sc_scene *scene);
int sc_terrain_degree(const sc_scene *scene);

/* The context whose GL calls are current, so that switching costs a call
 * only when it changes. */
extern context_object *sc_api_current_context;
int sc_api_make_current(context_object *c, sc_error *err);
/* A public renderer desc checked and turned into the internal one. */
int sc_api_render_desc(const sc_renderer_desc *d, sc_render_desc *r, sc_error *err);
/* sc_make_renderer with desc->pack (api_pack.c). */
int sc_api_make_packed_renderer(context_object *c, sc_scene_id scene,
                                const sc_renderer_desc *desc, sc_renderer_id *out,
                                sc_error *err);
void sc_api_destroy_renderer_object(renderer_object *r);
/* A renderer stopped drawing the scene: frees it once its handle is gone too. */
void sc_api_release_scene(scene_object *s);
/* The internal camera of a public one (NULL: the default), defaults filled
 * from the scene (api_objects.c). */
int sc_api_make_camera(const sc_camera_desc *desc, const sc_scene *scene, sc_camera *cam,
                       sc_error *err);
/* The same, defaults framing the box [lo, hi] (NULL: the unit cube). */
int sc_api_make_camera_framing(const sc_camera_desc *desc, const double lo[3], const double hi[3],
                               sc_camera *cam, sc_error *err);
/* Destroys the peers made on context c (NULL: all of them) (api_peer.c). */
void sc_api_destroy_peers(const context_object *c);
/* Copies n key texts into keys (at most capacity) and sets *count. */
int sc_api_count_keys(const char (*texts)[SCG_KEY_MAX], int n, sc_key *keys, int capacity,
                      int *count, sc_error *err);

#endif
