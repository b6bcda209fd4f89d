/* broyden.c — Broyden's method in the intersection skeleton (intersect.c;
 * Martin et al., "Practical Ray Tracing of Trimmed NURBS Surfaces"): the
 * Jacobian of F(u, v) = (n1·S + d1, n2·S + d2) comes from one full
 * evaluation at the start (the middle of the leaf's parameter interval, here
 * the hull's sub-patch domain, or the control-point start); every later
 * iteration evaluates the point alone and corrects the Jacobian by a
 * rank-one update. The leaves' overlap is the skeleton's iteration box
 * (SCG_DOMAIN_OVERLAP), so no crack opens between neighbouring sub-patches.
 *
 * The Jacobian is kept as two columns in the ray's frame (vec3: the two
 * plane distances and the coordinate along the ray), so the step can be
 * measured in object space as Newton's is, and the update is the good
 * Broyden update of that 3×2 matrix: J ← J + (y − J s) sᵀ / (sᵀ s), with
 * s the step in (u, v) and y the change of the frame point. Stopping rules
 * are Newton's (newton.c): the object-space step below tol ·
 * SCG_STOP_FRACTION, a singular Jacobian, or two iterates in a row outside
 * the box. Unrolled like Newton; the generic program loops. */
#include "broyden.h"

typedef struct broyden_vars {
    scg_value point, ju, jv;   /* vec3 variables: F with depth, the columns */
} broyden_vars;

/* One Broyden step from uv_var with the Jacobian held in the variables. */
static void broyden_step(scg_isect *c, void *user)
{
    const broyden_vars *bv = user;
    scg_builder *b = c->b;
    scg_name(b, "uv");
    scg_value uv = scg_load(b, c->uv_var);
    scg_name(b, "F");
    scg_value f = scg_load(b, bv->point);
    scg_name(b, "Ju");
    scg_value ju = scg_load(b, bv->ju);
    scg_name(b, "Jv");
    scg_value jv = scg_load(b, bv->jv);
    scg_name(b, "det");
    scg_value ju_x = scg_comp(b, ju, 0), ju_y = scg_comp(b, ju, 1);
    scg_value jv_x = scg_comp(b, jv, 0), jv_y = scg_comp(b, jv, 1);
    scg_value det = scg_products_difference(b, ju_x, jv_y, jv_x, ju_y);
    scg_value singular = scg_isect_singular(c, det, ju, jv);
    scg_name(b, "step");
    scg_value fx = scg_comp(b, f, 0), fy = scg_comp(b, f, 1);
    scg_value num_u = scg_products_difference(b, jv_y, fx, jv_x, fy);
    scg_value num_v = scg_products_difference(b, ju_x, fy, ju_y, fx);
    scg_value step_u = scg_div(b, num_u, det);
    scg_value step_v = scg_div(b, num_v, det);
    /* The step in the frame, J·Δ: what the object-space stopping rule
     * measures, and minus J·s in the update. */
    scg_name(b, "moved");
    scg_value moved_u = scg_mul(b, ju, step_u);
    scg_value moved_v = scg_mul(b, jv, step_v);
    scg_value moved = scg_add(b, moved_u, moved_v);
    scg_name(b, "converged");
    scg_value converged = scg_lt(b, scg_length(b, moved), c->tol_stop);
    scg_name(b, "uv_next");
    scg_value step = scg_vec2(b, step_u, step_v);
    scg_value next = scg_sub(b, uv, step);
    scg_name(b, NULL);
    scg_value done = scg_isect_take_step(c, uv, next, singular, converged);
    /* The point alone at the new iterate (the partials the evaluation also
     * builds are dead and go with dce), then the rank-one update with
     * s = −Δ: y − J s = F_new − F + J·Δ. */
    scg_if(b, scg_not(b, done));
    scg_value fr[3];
    scg_isect_eval_in_frame(c, next, fr);
    scg_name(b, "update");
    scg_value change = scg_sub(b, fr[0], f);
    scg_value r = scg_add(b, change, moved);
    scg_value s2 = scg_dot(b, step, step);
    scg_value r_scaled = scg_div(b, r, s2);
    scg_value du = scg_mul(b, r_scaled, scg_neg(b, step_u));
    scg_value dv = scg_mul(b, r_scaled, scg_neg(b, step_v));
    scg_store(b, bv->ju, scg_add(b, ju, du));
    scg_store(b, bv->jv, scg_add(b, jv, dv));
    scg_store(b, bv->point, fr[0]);
    scg_name(b, NULL);
    scg_endif(b);
}

void scg_method_broyden(scg_isect *c, scg_value uv0, scg_value behind)
{
    scg_builder *b = c->b;
    scg_isect_vars(c, uv0, behind);
    broyden_vars bv;
    scg_name(b, "F");
    bv.point = scg_var(b, SCG_VEC3, 0, 0);
    scg_name(b, "Ju");
    bv.ju = scg_var(b, SCG_VEC3, 0, 0);
    scg_name(b, "Jv");
    bv.jv = scg_var(b, SCG_VEC3, 0, 0);
    scg_name(b, NULL);
    /* The one full evaluation: the point and the true Jacobian at the
     * start. */
    if (behind)
        scg_if(b, scg_not(b, scg_load(b, c->done_var)));
    scg_value f[3];
    scg_isect_eval_in_frame(c, uv0, f);
    scg_store(b, bv.point, f[0]);
    scg_store(b, bv.ju, f[1]);
    scg_store(b, bv.jv, f[2]);
    if (behind)
        scg_endif(b);
    scg_isect_repeat(c, behind, c->key->max_iters, broyden_step, &bv);
}
