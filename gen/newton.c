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

/* |det J| below this fraction of |Su|·|Sv| counts as singular: a degenerate
 * point or a ray tangent to the surface, to float precision. */
#define SINGULAR_SINE 1.0e-6f

void scg_newton_step(scg_isect *c, void *user)
{
    (void)user;
    scg_builder *b = c->b;
    scg_value uv_var = c->uv_var, iters_var = c->iters_var, done_var = c->done_var;
    scg_value lo = c->lo, hi = c->hi;
    scg_name(b, "uv");
    scg_value uv = scg_load(b, uv_var);
    scg_name(b, NULL);
    scg_value f[3];
    scg_isect_eval_in_frame(c, uv, f);
    scg_name(b, "det");
    scg_value fu_x = scg_comp(b, f[1], 0), fu_y = scg_comp(b, f[1], 1);
    scg_value fv_x = scg_comp(b, f[2], 0), fv_y = scg_comp(b, f[2], 1);
    scg_value det = scg_products_difference(b, fu_x, fv_y, fv_x, fu_y);
    /* |det J| = |Su × Sv|·|cos(ray, normal)|: relative to |Su|·|Sv| it
     * vanishes at a degenerate point and on the silhouette alike. */
    scg_name(b, "singular");
    scg_value det_size = scg_abs(b, det);
    scg_value su_len = scg_length(b, f[1]);
    scg_value sv_len = scg_length(b, f[2]);
    scg_value sine = scg_const_f(b, SINGULAR_SINE);
    scg_value parallel = scg_mul(b, sine, scg_mul(b, su_len, sv_len));
    scg_value singular = scg_le(b, det_size, parallel);
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
    /* A converged step is still taken: it costs nothing more and leaves an
     * error of second order. */
    scg_store(b, uv_var, scg_select(b, singular, uv, next));
    scg_value iters = scg_load(b, iters_var);
    scg_value no_step = scg_const_i(b, 0);
    scg_value one_step = scg_const_i(b, 1);
    scg_value counted = scg_select(b, singular, no_step, one_step);
    scg_store(b, iters_var, scg_add(b, iters, counted));
    scg_name(b, "stop");
    scg_value stop = scg_or(b, converged, singular);
    scg_name(b, NULL);
    /* An iterate may step out of the box once (near an edge of the patch
     * where the parametrisation is compressed, a step within the tolerance
     * can cross it by 1e-4) but must come back with the next step. */
    scg_value was_inside = scg_isect_inside(b, uv, lo, hi);
    scg_value is_inside = scg_isect_inside(b, next, lo, hi);
    scg_value left = scg_not(b, scg_or(b, was_inside, is_inside));
    scg_store(b, done_var, scg_or(b, stop, left));
    if (c->converged_var)
        scg_store(b, c->converged_var, scg_and(b, converged, scg_not(b, singular)));
}

void scg_method_newton(scg_isect *c, scg_value uv0, scg_value behind)
{
    scg_isect_vars(c, uv0, behind);
    scg_isect_repeat(c, behind, c->key->max_iters, scg_newton_step, NULL);
}
