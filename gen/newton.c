/* newton.c — Newton's method in the intersection skeleton (intersect.c;
 * Pabst et al. 2006, §4.3): iteration on F(u, v) = (n1·S + d1, n2·S + d2)
 * with its 2×2 Jacobian (n·Su, n·Sv), from the sub-patch midpoint or the
 * interpolated hull-vertex parameters. Unrolled to the key's maximum
 * iterations, each iteration after the first guarded by `if (!done)`; the
 * generic program runs the same body in a runtime loop. An iteration stops
 * when its step, measured in object space, is below the tolerance (the step
 * is still taken), on a singular Jacobian, or when (u, v) has left the
 * sub-patch domain plus its overlap for two iterates in a row.
 *
 * As in intersect.c, no argument list holds more than one call that creates
 * instructions, so value numbers follow the source. */
#include "newton.h"

void scg_newton_step(scg_isect *c, void *user)
{
    (void)user;
    scg_builder *b = c->b;
    scg_value uv_var = c->uv_var;
    scg_name(b, "uv");
    scg_value uv = scg_load(b, uv_var);
    scg_name(b, NULL);
    scg_value f[3];
    scg_isect_eval_in_frame(c, uv, f);
    scg_name(b, "det");
    scg_value fu_x = scg_comp(b, f[1], 0), fu_y = scg_comp(b, f[1], 1);
    scg_value fv_x = scg_comp(b, f[2], 0), fv_y = scg_comp(b, f[2], 1);
    scg_value det = scg_products_difference(b, fu_x, fv_y, fv_x, fu_y);
    scg_value singular = scg_isect_singular(c, det, f[1], f[2]);
    /* J⁻¹ F = (Fv.y F.x - Fv.x F.y, Fu.x F.y - Fu.y F.x) / det. */
    scg_name(b, "step");
    scg_value fx = scg_comp(b, f[0], 0), fy = scg_comp(b, f[0], 1);
    scg_value step_u = scg_products_difference(b, fv_y, fx, fv_x, fy);
    scg_value step_v = scg_products_difference(b, fu_x, fy, fu_y, fx);
    scg_value step = scg_div(b, scg_vec2(b, step_u, step_v), det);
    /* The step in object space, Su·Δu + Sv·Δv: across the ray it is F,
     * along the ray it is 1/|cos| times larger at grazing rays, so this is
     * what the verdict measures, and what must be small to stop. */
    scg_name(b, "moved");
    scg_value moved_u = scg_mul(b, f[1], step_u);
    scg_value moved_v = scg_mul(b, f[2], step_v);
    scg_value moved = scg_div(b, scg_add(b, moved_u, moved_v), det);
    scg_name(b, "converged");
    scg_value converged = scg_lt(b, scg_length(b, moved), c->tol_stop);
    scg_name(b, "uv_next");
    scg_value next = scg_sub(b, uv, step);
    scg_name(b, NULL);
    scg_isect_take_step(c, uv, next, singular, converged);
    if (c->converged_var)
        scg_store(b, c->converged_var, scg_and(b, converged, scg_not(b, singular)));
    if (c->facing_var) {
        /* In the ray's frame the normal is Fu × Fv, whose axis component
         * is det. */
        scg_name(b, "facing");
        scg_value normal = scg_cross(b, f[1], f[2]);
        scg_value normal_len = scg_length(b, normal);
        scg_store(b, c->facing_var, scg_div(b, scg_abs(b, det), normal_len));
        scg_name(b, NULL);
    }
    if (c->depth_var)
        scg_store(b, c->depth_var, scg_comp(b, f[0], 2));
}

void scg_method_newton(scg_isect *c, scg_value uv0, scg_value behind)
{
    scg_isect_vars(c, uv0, behind);
    scg_isect_repeat(c, behind, c->key->max_iters, scg_newton_step, NULL);
}
