/* hybrid.c — Newton first, a robust method where Newton fails, inside the
 * same hull. Newton (newton.c) runs its unrolled iterations from the key's
 * start; its answer is kept when its last step converged (the object-space
 * step below tol · SCG_STOP_FRACTION with a regular Jacobian: the residual
 * measured against the pixel footprint) at a point inside the iteration box
 * (the sub-patch domain plus its overlap). Everywhere else — no
 * convergence within the iterations, an iterate that left the box, a
 * (near-)singular Jacobian at a silhouette or a collapsed edge — the
 * object-space subdivision of subdiv.c searches the hull's sub-patch, and
 * its leaf decides. The iteration count adds both methods' steps.
 *
 * Subdivision, not Bézier clipping, is the fallback because it is the one
 * built (bclip is not implemented); its stack depth is
 * SCG_DEFAULT_SUBDIV_DEPTH, as for the subdiv keys the renderer makes. */
#include "hybrid.h"
#include "newton.h"
#include "subdiv.h"

/* Pieces the fallback may pop: two per level of its stack. Rays that miss
 * the surface near a silhouette also reach the fallback, and on a GPU that
 * runs a loop for as long as any ray of a group needs it (llvmpipe), their
 * search sets the cost: on the teapot at 1024², 4 per level cost 4.1× the
 * Newton frame, 2 per level 3.1×, and the 14 hits that needed the fallback
 * took at most 30 steps (docs/compiler.md). */
#define HYBRID_STEPS (2 * SCG_DEFAULT_SUBDIV_DEPTH)

void scg_method_hybrid(scg_isect *c, scg_value uv0, scg_value behind)
{
    scg_builder *b = c->b;
    scg_isect_vars(c, uv0, behind);
    scg_name(b, "converged");
    c->converged_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
    scg_name(b, "found");
    c->found_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
    scg_name(b, NULL);
    /* Newton may roam the whole record: converging into a neighbouring
     * sub-patch finds that neighbour's hit (its hull would find the same,
     * and the depth test keeps the nearest), where stopping at the
     * sub-patch's box would send the ray to the fallback for nothing. */
    c->lo = c->rec_lo;
    c->hi = c->rec_hi;
    scg_isect_repeat(c, behind, c->key->max_iters, scg_newton_step, NULL);

    scg_name(b, "newton_hit");
    scg_value uv = scg_load(b, c->uv_var);
    scg_value in_box = scg_isect_inside(b, uv, c->rec_lo, c->rec_hi);
    scg_value newton_hit = scg_and(b, scg_load(b, c->converged_var), in_box);
    scg_store(b, c->found_var, newton_hit);
    scg_value fallback = scg_not(b, newton_hit);
    if (behind)
        fallback = scg_and(b, fallback, scg_not(b, behind));
    scg_name(b, NULL);
    scg_subdiv_search(c, SCG_DEFAULT_SUBDIV_DEPTH, HYBRID_STEPS, fallback, true);
}
