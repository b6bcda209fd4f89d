/* key.h — variant keys: the name of one generated program. A key has one
 * canonical text form in [a-z0-9._-], every field always present in a fixed
 * order, which serves as cache key and file name and parses back exactly:
 *
 *   bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade
 *   bez3x3-poly-dc-fast2i16-newton-mid-it4-tol0.25-ert0-out.shade
 *   <kind><du>x<dv>-<poly|rat>-<eval>-<trim>-<method>-<start>-it<N>-tol<T>-ert<E>-out.<o1>[.<o2>…]
 *
 * Triangular patches have one total degree: tri4-poly-dc-trim0-newton-
 * secure-…. Full grammar and the meaning of every value:
 * docs/variant-key.md. Values that later work will implement (the basis
 * form for NURBS) parse, so that the form is stable, but scg_key_check
 * refuses them. */
#ifndef SCG_KEY_H
#define SCG_KEY_H

#include <stdbool.h>
#include <stddef.h>

#include "sc_base.h"
#include "splinecast_options.h"

#define SCG_MAX_DEGREE SC_MAX_DEGREE /* highest degree in either direction */
#define SCG_MAX_TRI_DEGREE 4 /* tri keys: the secure starts need g'' quadratic */
#define SCG_MAX_ITERS SC_MAX_ITERS
#define SCG_MAX_TRIM_ITERS SC_MAX_TRIM_ITERS /* cap on clipping iterations per crossing */
#define SCG_DEFAULT_TRIM_ITERS 16
#define SCG_KEY_MAX 128       /* buffer size for a formatted key */

typedef enum scg_patch_kind {
    SCG_PATCH_BEZIER = 0,     /* "bez": tensor Bézier patch */
    SCG_PATCH_NURBS,          /* "nurbs": tensor NURBS, de Boor from knots */
    SCG_PATCH_TRIANGLE        /* "tri": triangular Bézier height patch, one
                                 total degree (deg_u = deg_v = n), "tri4" */
} scg_patch_kind;

typedef enum scg_eval_form {
    SCG_EVAL_DC = 0,          /* "dc": de Casteljau / de Boor, unrolled */
    SCG_EVAL_BASIS,           /* "bern": Bernstein basis sums, unrolled */
    SCG_EVAL_LOOP,            /* "loop": generic program, runtime loops over
                                 degrees read from the record; degrees are
                                 written "dyn" (bezdyn, nurbsdyn) */
    SCG_EVAL_POWER            /* "pow": the iteration evaluates the power
                                 basis by Horner's rule, its coefficients
                                 computed once a pixel from the projected
                                 net; the hit point by de Casteljau
                                 (Bézier only) */
} scg_eval_form;

/* Trimming (docs/trimming.md) is the option's sc_trim_method
 * (splinecast_options.h): SC_TRIM_NONE "trim0" untrimmed, SC_TRIM_CLIP
 * "clipNiC" every piece with two-sided iterative Bézier clipping,
 * SC_TRIM_FAST "fastNiC" a uniform grid indexed directly (a cell's parity
 * and the pieces that may pass through it; two-sided clipping for the
 * ambiguous ones), SC_TRIM_LEFT "leftNiC" every piece with left-only
 * clipping. N is the highest trim-piece degree (pieces of lower degree are
 * degree-elevated to N when packed), C the cap on Bézier-clipping
 * iterations per crossing (1 … SCG_MAX_TRIM_ITERS). A key never holds
 * SC_TRIM_DEFAULT. */

/* The method is the option's sc_method (splinecast_options.h): "newton",
 * "broyden", "bclip", "subdiv", "hybrid". A key never holds
 * SC_METHOD_DEFAULT. subdiv and bclip need an unrolled Bézier key (bez,
 * dc or bern) and take the start "mid" only, since they start from the
 * whole sub-patch, so that no two keys name one program. For subdiv, itN
 * is the depth of the stack of parameter intervals; the number of
 * subdivision steps is SCG_SUBDIV_STEPS_PER_LEVEL times it; for bclip,
 * itN is the number of clipping steps, SCG_DEFAULT_BCLIP_STEPS where the
 * renderer chooses (docs/variant-key.md). */
/* A leaf whose quad of corners the ray misses lets the search go on
 * (subdiv.c): 8 lost teaspoon pixels to the budget. */
#define SCG_SUBDIV_STEPS_PER_LEVEL 12
#define SCG_DEFAULT_SUBDIV_DEPTH 24
#define SCG_DEFAULT_BCLIP_STEPS 32

/* The start is the option's sc_start: SC_START_MID "mid" (centre of the
 * sub-patch domain), SC_START_CPMAP "cp" (interpolated hull-vertex
 * parameters), SC_START_VIEW "view" (a Newton solve per hull vertex in the
 * vertex stage, from its control-point parameters, interpolated: seed 000
 * §4.4; gen/intersect.c, scg_build_view_start). A key never holds
 * SC_START_DEFAULT. */

/* What the program does for early ray termination. This is not the
 * renderer's option sc_ray_termination, which also decides whether whole
 * hulls are culled between batches; sc_key_ert (scene_keys.h) maps the
 * option to this field. */

typedef enum scg_ert {
    SCG_ERT_NONE = 0,         /* "ert0" */
    SCG_ERT_BEFORE,           /* "ert1": skip the ray when the hull lies
                                 behind the nearest surface so far */
    SCG_ERT_BOTH,             /* "ert2": also drop a hit behind it */
    SCG_ERT_CONSERVATIVE,     /* "ert3": gl_FragDepth declared depth_greater
                                 (the hit never lies in front of the hull),
                                 so a GPU may keep its early depth test */
    SCG_ERT_PEEL,             /* "ert4": depth peeling of the hulls' entries
                                 (runtime/gl/gl_peel.c): no gl_FragDepth, the
                                 early fragment tests declared (the depth
                                 test against the layer's entry depth runs
                                 before the program); a hit is kept only
                                 when nearer than the best so far at its
                                 pixel (the image sc_best_depth), which it
                                 then becomes. Not with the hull view, which
                                 writes the hull's depth where rays miss */
    SCG_ERT_LISTS             /* "ert5": candidate lists per pixel
                                 (runtime/gl/gl_lists.c): drawn over tiles
                                 of pixels, the program runs each
                                 pixel's list of hulls, nearest box first,
                                 until the next box lies behind its nearest
                                 hit; a hit is kept only when nearer. Start
                                 `mid` only (no hull to interpolate a start
                                 over); not with the hull view */
} scg_ert;

/* Output bits; the text lists the set ones in this order, joined by '.'. */
enum {
    SCG_OUTPUT_SHADE = 1 << 0,   /* "shade": shaded colour */
    SCG_OUTPUT_AOV = 1 << 1,     /* "aov": depth, uv, surface id, normal… */
    SCG_OUTPUT_ITERS = 1 << 2,   /* "iters": iteration-count debug view */
    SCG_OUTPUT_UVVIEW = 1 << 3,  /* "uv": (u, v) debug colour */
    SCG_OUTPUT_HULLVIEW = 1 << 4, /* "hull": proxy-hull debug colour; a miss
                                    draws the hull's face instead of
                                    discarding */
    SCG_OUTPUT_ALL = (1 << 5) - 1
};

typedef struct scg_key {
    scg_patch_kind kind;
    int deg_u, deg_v;         /* 1 … SCG_MAX_DEGREE; 0 with SCG_EVAL_LOOP */
    bool rational;
    scg_eval_form eval;
    sc_trim_method trim;      /* never SC_TRIM_DEFAULT */
    int trim_degree;          /* 1 … SCG_MAX_DEGREE when trimmed, else 0 */
    int trim_iters;           /* 1 … SCG_MAX_TRIM_ITERS when trimmed, else 0 */
    sc_method method;         /* never SC_METHOD_DEFAULT */
    sc_start start;           /* never SC_START_DEFAULT */
    int max_iters;            /* 1 … SCG_MAX_ITERS */
    int tol_milli;            /* tolerance in 1/1000 pixel footprint, >= 1 */
    scg_ert ert;
    unsigned outputs;         /* SCG_OUTPUT_* bits, at least one */
} scg_key;

/* Defaults of the fields that tune Newton's method, the ones the renderer
 * draws with (measured on the tea set, docs/speed.md): from the
 * control-point parameters, at most 6 iterations, 0.05 pixel footprints. */
#define SCG_DEFAULT_START SC_START_CPMAP
#define SCG_DEFAULT_ITERS 6
#define SCG_DEFAULT_TOL_MILLI 50

/* The default key for a degree pair: polynomial, de Casteljau, untrimmed,
 * Newton with the defaults above, no early ray termination, shaded
 * output. */
void scg_key_default(scg_key *key, scg_patch_kind kind, int deg_u, int deg_v);

/* The key candidate lists draw a hull of this key with (ert5; the program
 * starts each candidate on its sub-patch's control net, whatever the key's
 * start): the renderer's and `gen --scene`'s one rule. */
void scg_key_for_lists(scg_key *key);

/* Canonical text into buf (SCG_KEY_MAX bytes are always enough). */
const char *scg_key_format(const scg_key *key, char *buf, size_t size);

/* Parses the canonical form. Malformed or non-canonical text fails with a
 * message naming the field and, where there is one, the canonical spelling.
 * Reserved values parse (see scg_key_check). */
int scg_key_parse(const char *text, scg_key *key, sc_error *err);

/* SC_OK when the compiler can build the key; otherwise a message naming
 * the reserved value ("Broyden's method (broyden) is not implemented yet")
 * or the inconsistent combination. */
int scg_key_check(const scg_key *key, sc_error *err);

/* Tolerance in pixel footprints. */
float scg_key_tolerance(const scg_key *key);

bool scg_key_equal(const scg_key *a, const scg_key *b);

#endif
