/* scene_keys.h — the runtime side of variant keys: which key each surface
 * of a scene needs, and the distinct keys of a whole scene, so that the
 * runtime compiles exactly those and never a cross product. */
#ifndef SC_SCENE_KEYS_H
#define SC_SCENE_KEYS_H

#include "key.h"
#include "scene.h"

/* Highest degree (in either direction) drawn with the unrolled program.
 * Measured (docs/speed.md, `splinecast bench --degrees 3-9`): the unrolled
 * program runs 5.5-21x faster than the generic one at every degree, and
 * compiles faster up to 9x9 (2.1 s against 2.3 s); above that its compile
 * time keeps growing while the generic one's stays flat, so the generic
 * program takes over. */
#define SC_UNROLL_MAX_DEGREE 9

/* The key's ert field for the early ray termination option. The two are not
 * one concept: the key says what the program does (ert1: skip the ray
 * behind the nearest hit so far), while the option also decides what the
 * renderer does around the programs (culling whole hulls between batches in
 * the manual modes). This is the one place that maps the one to the other;
 * SC_TERMINATION_DEFAULT is SC_DEFAULT_TERMINATION. */
scg_ert sc_key_ert(sc_ray_termination termination);

/* The outputs of a scene's keys unless asked otherwise: those the renderer
 * draws with by default (the shaded colour and the AOVs). */
#define SC_KEY_DEFAULT_OUTPUTS (SCG_OUTPUT_SHADE | SCG_OUTPUT_AOV)

typedef struct sc_key_options {
    /* 0 (default): surfaces are drawn as extracted Bézier patches (`bez`
     * keys); 1: whole NURBS surfaces with de Boor from the knot texture
     * (`nurbs` keys). A surface that is one Bézier patch is `bez` either way. */
    int nurbs_direct;
    /* Surfaces with a degree above this use the generic program (`loop`,
     * degrees `dyn`); 0 means SC_UNROLL_MAX_DEGREE. */
    int generic_above;
    /* 1: ignore trim loops (keys say trim0). Default 0: a trimmed surface
     * asks for trimming with its highest trim-curve degree. */
    int ignore_trims;
    /* Trim method of trimmed surfaces (SC_TRIM_DEFAULT: fast; SC_TRIM_NONE
     * as ignore_trims); and the cap on clipping iterations per crossing,
     * 0 meaning SCG_DEFAULT_TRIM_ITERS.
     * docs/trimming.md has the measurements behind the defaults. */
    sc_trim_method trim_method;
    int trim_iters;
    /* The remaining fields are copied into every key; 0 means the defaults
     * of scg_key_default (key.h: cp, it6, tol0.05) and the two above. */
    int max_iters;
    int tol_milli;
    sc_start start;           /* SC_START_DEFAULT: SCG_DEFAULT_START; subdiv
                                 keys always take mid */
    sc_ray_termination termination; /* keys' ert through sc_key_ert */
    unsigned outputs;         /* 0: SC_KEY_DEFAULT_OUTPUTS */
    /* 0 (default): a surface the GPU programs cannot draw makes
     * sc_scene_keys fail; 1: it gets no key and a warning through sc_log,
     * so that a scene can be described whatever it holds (`info`). */
    int skip_undrawable;
    /* The intersection method (SC_METHOD_DEFAULT: SC_DEFAULT_METHOD, the
     * hybrid). With subdiv,
     * max_iters is the subdivision stack depth (0:
     * SCG_DEFAULT_SUBDIV_DEPTH). */
    sc_method method;
    /* The evaluation form of unrolled Bézier keys (SC_EVAL_DEFAULT: pow
     * up to SC_DEFAULT_POW_MAX_DEGREE, dc above; pow above
     * SC_MAX_POW_DEGREE gives dc); keys of other kinds and the generic
     * program's are left as they are. */
    sc_eval eval;
} sc_key_options;

/* SC_OK when the GPU programs can draw surface i of the scene. Otherwise
 * SC_FAIL, with err naming the scene's file, the surface and why: a degree
 * above SCG_MAX_DEGREE in either direction (the unrolled programs and the
 * generic program's basis arrays stop there; the scene model and the
 * reference go further), or a trim curve above SC_TRIM_MAX_DEGREE (trim.h;
 * loop validation keeps those out of scenes read from files). */
int sc_surface_drawable(const sc_scene *scene, int i, sc_error *err);

/* The evaluation form of an unrolled Bézier key of degrees p × q when
 * `asked` is the option (SC_EVAL_DEFAULT: pow up to
 * SC_DEFAULT_POW_MAX_DEGREE, dc above; pow above SC_MAX_POW_DEGREE: dc). */
scg_eval_form sc_bezier_eval(sc_eval asked, int p, int q);
/* The option that asks for an unrolled form (dc, bern, pow) by name. */
sc_eval sc_eval_option(scg_eval_form form);

/* The key surface s needs under opts (NULL: defaults); a valid key only
 * for a surface sc_surface_drawable accepts. */
void sc_surface_key(const sc_surface *s, const sc_key_options *opts, scg_key *key);

/* The distinct keys of a scene's drawable surfaces, in canonical text,
 * sorted: *keys is a new array of *count entries (free with free()); an
 * empty scene gives 0. A surface that is not drawable fails, or is left
 * out with a warning under opts->skip_undrawable. */
int sc_scene_keys(const sc_scene *scene, const sc_key_options *opts,
                  char (**keys)[SCG_KEY_MAX], int *count, sc_error *err);

#endif
