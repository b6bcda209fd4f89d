/* intersect.h — the skeleton every intersection method plugs into
 * (intersect.c): the ray as two planes, the record, the iteration box
 * (sub-patch domain plus overlap, inside the record's domain), the Bézier
 * points taken into the ray's frame, early ray termination, and the verdict
 * from one full evaluation at the final (u, v): distance to the hit,
 * trimming, the outputs. A method (newton.c, broyden.c, subdiv.c,
 * hybrid.c) writes only what moves (u, v) from the start to its final
 * value; program.c picks it by the key's method. */
#ifndef SCG_INTERSECT_H
#define SCG_INTERSECT_H

#include "ir.h"

/* What the skeleton has built before a method runs, and the variables the
 * method leaves its result in. */
typedef struct scg_isect {
    scg_builder *b;
    const scg_key *key;
    int p, q;
    scg_value origin, dir, dir_len, axis, n1, n2, d1, d2, tol, tol_stop, zero;
    scg_value rec, rect, surface;                               /* the record */
    scg_value cp_offset, nu, nv, knot_u, knot_v, deg_u, deg_v;  /* from the record */
    scg_value dom_lo, dom_hi;                /* the hull's sub-patch domain */
    scg_value lo, hi;                        /* iteration box */
    scg_value rec_lo, rec_hi;                /* the record's domain, widened a hair */
    scg_value roam_lo, roam_hi;              /* where iterates may go: the record's
                                                domain widened by the overlap */
    /* Set by the method: the final (u, v) (vec2), the iteration count
     * (int), and the `done` flag of the iteration driver (bool). */
    scg_value uv_var, iters_var, done_var;
    /* Optional, set by the method: newton_step stores its `converged` flag
     * here when non-zero (hybrid.c reads it); a method that decides the hit
     * itself (subdiv.c) stores it in found_var, and the verdict then takes
     * it instead of the distance to the hit, which needs a regular
     * Jacobian. */
    scg_value converged_var, found_var;
    /* Optional: newton_step stores here |cos| of the angle between the ray
     * and the normal at the point it evaluated (facing_var) and that
     * point's coordinate along the ray's unit axis (depth_var). */
    scg_value facing_var, depth_var;
    /* Set by a method whose found_var already excludes points the trim
     * curves cut away (scg_isect_kept), so that the verdict does not test
     * them again. */
    bool trimmed_by_method;
    scg_value pts[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)];  /* Bézier: fetched */
    scg_value proj[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)]; /* Bézier: projected */
    scg_value power[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)]; /* pow: proj's power form */
} scg_isect;

/* A method: moves (u, v) from uv0 and sets uv_var and iters_var (and
 * optionally found_var). `behind` (0 without early ray termination) is true
 * when the ray starts done. */
typedef void (*scg_method_fn)(scg_isect *c, scg_value uv0, scg_value behind);

/* Writes the whole intersection program for a key checked by
 * scg_key_check, with `method` as its iteration. */
void scg_build_intersection(scg_builder *b, const scg_key *key, scg_method_fn method);

/* The vertex stage's program of a `view` key (seed 000 §4.4): the ray from
 * the eye through the hull vertex (SCG_IN_RAY_DIR reaches the vertex at
 * t = 1), `method` (Newton) from the vertex's control-point parameters
 * (SCG_IN_UV0) within the sub-patch domain plus overlap, and the point it
 * reaches, kept in that box, as SCG_OUT_START: the fragment stage's start
 * once interpolated. */
void scg_build_view_start(scg_builder *b, const scg_key *key, scg_method_fn method);

/* Iterations stop when the object-space step |Su·Δu + Sv·Δv| is below
 * tol · SCG_STOP_FRACTION; the step is taken, so what is left is of second
 * order. (Stopping on |F| < tol/10 instead, |F| being only the distance of
 * S from the ray, let the verdict see |F|/|cos| > tol at grazing rays and
 * left holes along every silhouette.) On the tea set at 512×512, 1.0 loses
 * one of the teacup's 71,000 pixels against 0.3, and 0.1 gains nothing for
 * 5 % more iterations (docs/compiler.md, "Accuracy of the GPU path"). */
#define SCG_STOP_FRACTION 0.3f

/* ---- pieces the methods share ---- */

/* Point and partials at (u, v) in the ray's frame (vec3 each: F in x and
 * y, the coordinate along the ray's unit axis in z). */
void scg_isect_eval_in_frame(scg_isect *c, scg_value uv, scg_value f[3]);
/* Bézier keys: the record's points restricted to the interval iv = (u0,
 * u1, v0, v1) (vec4), Euclidean, in the ray's frame (vec3: F1, F2, depth),
 * into e[(p+1)(q+1)]; when `homogeneous` is not NULL, also as they were
 * before the division by w (the same as e when polynomial). */
void scg_isect_restricted_points(scg_isect *c, scg_value iv, scg_value *e, scg_value *homogeneous);
/* True when uv lies in [lo.x, hi.x] × [lo.y, hi.y]. */
scg_value scg_isect_inside(scg_builder *b, scg_value uv, scg_value lo, scg_value hi);
/* x1·y1 − x2·y2: determinants and Cramer's rule. */
scg_value scg_products_difference(scg_builder *b, scg_value x1, scg_value y1, scg_value x2,
                                  scg_value y2);
/* True when |det| ≤ SCG_SINGULAR_SINE·|ju|·|jv|: the Jacobian with columns
 * ju, jv (vec3 in the ray's frame) is singular to float precision. */
scg_value scg_isect_singular(scg_isect *c, scg_value det, scg_value ju, scg_value jv);
/* The end of a step from uv to next: next is taken unless singular, the
 * count grows, and done is set on convergence, a singular Jacobian, or
 * when uv and next both lie outside the box. Returns done. */
scg_value scg_isect_take_step(scg_isect *c, scg_value uv, scg_value next, scg_value singular,
                              scg_value converged);
/* True (bool) when uv, a (u, v) of the record, is kept by the record's
 * trim curves; the test runs only where `want` (bool) holds, and is the
 * constant true for untrimmed keys. */
scg_value scg_isect_kept(scg_isect *c, scg_value want, scg_value uv);
/* The variables uv (from uv0), iters (0) and done (`behind`, or false). */
void scg_isect_vars(scg_isect *c, scg_value uv0, scg_value behind);
/* `count` calls of step(c, user): unrolled, each after the first guarded by
 * `if (!done)` (the first too when `behind`), or in a runtime loop for the
 * generic program. */
void scg_isect_repeat(scg_isect *c, scg_value behind, int count,
                      void (*step)(scg_isect *c, void *user), void *user);

#endif
