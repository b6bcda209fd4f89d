/* hybrid.c — Newton first, and where Newton fails, Newton again from
 * starts that cover the hull's sub-patch, inside the same hull.
 *
 * Newton (newton.c) runs from the key's start and may roam the record. Its
 * point is kept when the last step converged (the object-space step below
 * tol · SCG_STOP_FRACTION with a regular Jacobian: the residual measured
 * against the pixel footprint), the point lies in the sub-patch domain plus
 * its overlap, and the trim curves keep it. Everywhere else — no
 * convergence, a (near-)singular Jacobian, a point on a neighbouring
 * sub-patch (whose own, nearer crossing this hull would lose), a point the
 * trim curves cut away — Newton starts again from the middle of the
 * sub-patch, then from the middles of its quarters (and of its sixteenths
 * where the sub-patch is large on screen), each run confined to its piece
 * plus overlap, until one is kept. After a point the trim curves cut away,
 * or one on a neighbouring sub-patch, the restarts depend on how steeply
 * the ray meets it (a second crossing of the sub-patch needs the surface
 * to turn back towards the ray). The iteration count adds the steps of
 * every run.
 *
 * Shaped for a GPU that runs both sides of every branch under a mask and a
 * loop for as long as any ray of a group needs it (llvmpipe): everything
 * is one runtime loop whose passes take one or two unrolled Newton
 * steps each, the first passes being Newton's own run. A group whose rays
 * all converge within one pass stops after it (cheaper than Newton's
 * itN unrolled steps, which all run under the mask); a restart costs a
 * group more passes only where one of its rays needs it. A subdivision
 * search after Newton (subdiv.c) cost 1.6-1.7x Newton's frame on the
 * teapot even where no ray entered it, and its leaves at the tolerance lay
 * too deep for PRO20359-L1's close-ups within a step budget a frame can
 * afford (docs/compiler.md, "Methods"). */
#include "hybrid.h"
#include "newton.h"

/* Newton steps a pass (a run of itN steps takes ⌈itN/steps⌉ passes): one
 * for untrimmed keys, two for trimmed ones, whose pass ends with the trim
 * test. The passes change no pixel (a step after convergence is masked),
 * only what a group pays: its slowest ray's steps rounded up to whole
 * passes, every step of a pass under the mask, against one pass end per
 * pass. Measured with the same frames drawn by each set of programs
 * (docs/speed.md, "Passes of the hybrid"), against 3 steps: the teapot at
 * 1024² 0.87 with 1 step (pow), 0.84 (dc), 0.91 with 2; PRO20359-L1 (dc,
 * trimmed) 0.93 with 1 or 2; gpucast_part (trimmed) 1.04 with 1, 0.96
 * with 2.
 *
 * Restarts after Newton's own run: the sub-patch's middle and its four
 * quarters'; on to the sixteenths (21) where the sub-patch spans more than
 * HYBRID_LARGE_PIXELS; the quarters at most after a crossing the trim
 * curves cut away. Measured (docs/compiler.md, "Methods"): on the teapot at 1024²,
 * with passes of 3 steps then, 5 restarts cost 1.09-1.20x Newton's
 * frame; 21 restarts everywhere cost 1.4-1.7x, paid by
 * the rays near silhouettes that miss and so run them all, and a
 * threshold of 16, 32, 64, 128 or 256 pixels 1.57-1.69, 1.52-1.59,
 * 1.21-1.23, 1.15-1.16 and 1.04-1.15x; 512 left a hole in PRO20359-L1's
 * tail close-up that 256 closes. After a crossing cut away, 0 restarts
 * left 0.18-0.76 % of PRO20359-L1's pixels failing, 1 none, and 5 cost
 * its close-up 3.6x Newton's frame against 2.5x. Now none where the ray
 * meets the cut-away crossing above |cos| HYBRID_CUT_FACING (the quarters'
 * below), and one where it meets a neighbouring sub-patch's crossing that
 * steeply: the hammer went from 1.46x to 1.27-1.36x Newton's frame at
 * 1024², gpucast_part from 1.17x to 1.11-1.15x (medians of 3 runs),
 * failing the same pixels; with no restart at all after a cut-away point
 * PRO20359-L1's tail close-up failed 0.74 % at 512² (docs/stability.md,
 * "The hybrid on trimmed models"). */
#define HYBRID_PASS_STEPS 1
#define HYBRID_TRIMMED_PASS_STEPS 2
#define HYBRID_RESTARTS 5
#define HYBRID_RESTARTS_LARGE 21
#define HYBRID_LARGE_PIXELS 256.0f
#define HYBRID_TRIMMED_RESTARTS 5
#define HYBRID_ELSEWHERE_RESTARTS 1
#define HYBRID_CUT_FACING 0.2f

/* From the sub-patch's middle (`mid`), Newton may converge to a farther
 * crossing of a sub-patch that folds away from the ray near a silhouette,
 * where the ray crosses it twice: 0.106 % of the teapot at 512² (47 pixels,
 * all within |cos| 0.34 of grazing, 38 within 0.2), 0.13 % at 1024². There
 * a kept crossing seen at |cos(ray, normal)| below HYBRID_SEEK_FACING sends
 * the ray on through the quarters' restarts, which keep a crossing only if
 * it is nearer (by the tolerance). The cp map and the view start come from
 * the hull's front, before the nearer crossing, and fail no such pixel on
 * the tea set; they skip the search (it would cost them iterations that
 * find nothing). */
#define HYBRID_SEEK_FACING 0.3f

/* The corners lo, hi of the piece of the sub-patch domain that restart r
 * (int) starts in: r = 0 the whole domain, 1…4 its quarters, 5…20 its
 * sixteenths, row by row. */
static void restart_piece(scg_isect *c, scg_value r, scg_value *lo, scg_value *hi)
{
    scg_builder *b = c->b;
    scg_value one = scg_const_i(b, 1);
    scg_value five = scg_const_i(b, 5);
    scg_value past_whole = scg_le(b, one, r);
    scg_value past_quarters = scg_le(b, five, r);
    scg_value whole = scg_const_f(b, 1.0f);
    scg_value count = scg_select(b, past_whole, scg_const_f(b, 2.0f), whole);
    count = scg_select(b, past_quarters, scg_const_f(b, 4.0f), count);
    scg_value first = scg_select(b, past_whole, one, scg_const_i(b, 0));
    first = scg_select(b, past_quarters, five, first);
    scg_value i = scg_i2f(b, scg_sub(b, r, first));
    scg_value row = scg_floor(b, scg_div(b, i, count));
    scg_value col = scg_sub(b, i, scg_mul(b, row, count));
    scg_value cell = scg_vec2(b, col, row);
    scg_value size = scg_div(b, scg_sub(b, c->dom_hi, c->dom_lo), count);
    *lo = scg_add(b, c->dom_lo, scg_mul(b, cell, size));
    *hi = scg_add(b, *lo, size);
}

/* The restarts a ray may take: down to the quarters, or, for a Bézier
 * sub-patch that spans more than HYBRID_LARGE_PIXELS on screen (its
 * share of the box of the record's points, against the pixel footprint
 * at the hull), down to the sixteenths. */
static scg_value restart_count(scg_isect *c)
{
    scg_builder *b = c->b;
    scg_value few = scg_const_i(b, HYBRID_RESTARTS);
    if (c->key->kind != SCG_PATCH_BEZIER || c->key->eval == SCG_EVAL_LOOP)
        return few;
    scg_name(b, "extent");
    int n = (c->p + 1) * (c->q + 1);
    scg_value lo = 0, hi = 0;
    for (int k = 0; k < n; k++) {
        scg_value pt = scg_xyz(b, c->proj[k]);
        if (c->key->rational)
            pt = scg_div(b, pt, scg_comp(b, c->proj[k], 3));
        lo = k ? scg_min(b, lo, pt) : pt;
        hi = k ? scg_max(b, hi, pt) : pt;
    }
    scg_value box = scg_sub(b, hi, lo);
    scg_value box_x = scg_comp(b, box, 0), box_y = scg_comp(b, box, 1);
    scg_value box_xy = scg_max(b, box_x, box_y);
    scg_value extent = scg_max(b, box_xy, scg_comp(b, box, 2));
    scg_value dom = scg_sub(b, c->dom_hi, c->dom_lo);
    scg_value dom_u = scg_comp(b, dom, 0), dom_v = scg_comp(b, dom, 1);
    scg_value share = scg_max(b, dom_u, dom_v);
    scg_value size = scg_mul(b, extent, share);
    scg_value pixel = scg_mul(b, scg_uniform(b, SCG_UNI_FOOTPRINT), c->dir_len);
    scg_value limit = scg_mul(b, pixel, scg_const_f(b, HYBRID_LARGE_PIXELS));
    scg_value large = scg_lt(b, limit, size);
    scg_name(b, NULL);
    return scg_select(b, large, scg_const_i(b, HYBRID_RESTARTS_LARGE), few);
}

/* The next run: Newton from the middle of restart r's piece, confined to
 * the piece plus overlap (Martin et al.) within the record's domain. */
static void start_run(scg_isect *c, scg_value r, scg_value lo_var, scg_value hi_var)
{
    scg_builder *b = c->b;
    scg_name(b, "piece");
    scg_value p_lo, p_hi;
    restart_piece(c, r, &p_lo, &p_hi);
    scg_value overlap = scg_const_f(b, SCG_DOMAIN_OVERLAP);
    scg_value margin = scg_mul(b, scg_sub(b, p_hi, p_lo), overlap);
    scg_value wide_lo = scg_sub(b, p_lo, margin);
    scg_store(b, lo_var, scg_max(b, wide_lo, c->roam_lo));
    scg_value wide_hi = scg_add(b, p_hi, margin);
    scg_store(b, hi_var, scg_min(b, wide_hi, c->roam_hi));
    scg_value corners = scg_add(b, p_lo, p_hi);
    scg_value middle = scg_mul(b, corners, scg_const_f(b, 0.5f));
    scg_store(b, c->uv_var, middle);
    scg_store(b, c->done_var, scg_const_b(b, false));
    scg_store(b, c->converged_var, scg_const_b(b, false));
    scg_name(b, NULL);
}

int scg_hybrid_pass_steps(const scg_key *key)
{
    int steps = key->trim == SC_TRIM_NONE ? HYBRID_PASS_STEPS : HYBRID_TRIMMED_PASS_STEPS;
    return steps < key->max_iters ? steps : key->max_iters;
}

void scg_method_hybrid(scg_isect *c, scg_value uv0, scg_value behind)
{
    scg_builder *b = c->b;
    int steps = scg_hybrid_pass_steps(c->key);
    int passes_per_run = (c->key->max_iters + steps - 1) / steps;
    scg_isect_vars(c, uv0, behind);
    scg_name(b, "converged");
    c->converged_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
    scg_name(b, "found");
    c->found_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
    /* The first run may roam the whole record: converging back into the
     * sub-patch after a step outside it still counts. */
    scg_name(b, "run_lo");
    scg_value lo_var = scg_var(b, SCG_VEC2, 0, c->roam_lo);
    scg_name(b, "run_hi");
    scg_value hi_var = scg_var(b, SCG_VEC2, 0, c->roam_hi);
    scg_name(b, "run_pass");
    scg_value pass_var = scg_var(b, SCG_INT, 0, scg_const_i(b, 0));
    scg_name(b, "restart");
    scg_value restart_var = scg_var(b, SCG_INT, 0, scg_const_i(b, 0));
    scg_name(b, NULL);
    /* A point is kept inside the sub-patch plus overlap and inside the
     * record, which the iterates may leave (intersect.c). */
    scg_value sub_lo = scg_max(b, c->lo, c->rec_lo), sub_hi = scg_min(b, c->hi, c->rec_hi);
    scg_name(b, "restarts");
    scg_value restarts_var = scg_var(b, SCG_INT, 0, restart_count(c));
    scg_name(b, NULL);
    bool seek = c->key->start == SC_START_MID;
    scg_value best_uv_var = 0, best_depth_var = 0, best_found_var = 0, seeking_var = 0;
    scg_name(b, "facing");
    c->facing_var = scg_var(b, SCG_FLOAT, 0, scg_const_f(b, 1.0f));
    if (seek) {
        scg_name(b, "depth");
        c->depth_var = scg_var(b, SCG_FLOAT, 0, scg_const_f(b, 0.0f));
        scg_name(b, "best_uv");
        best_uv_var = scg_var(b, SCG_VEC2, 0, uv0);
        scg_name(b, "best_depth");
        best_depth_var = scg_var(b, SCG_FLOAT, 0, scg_const_f(b, 3.0e38f));
        scg_name(b, "best_found");
        best_found_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
        scg_name(b, "seeking");
        seeking_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
        scg_name(b, NULL);
    }
    scg_loop(b, scg_const_i(b, passes_per_run * (1 + HYBRID_RESTARTS_LARGE)));
    c->lo = scg_load(b, lo_var);
    c->hi = scg_load(b, hi_var);
    scg_isect_repeat(c, behind, steps, scg_newton_step, NULL);
    scg_name(b, "kept");
    scg_value uv = scg_load(b, c->uv_var);
    scg_value converged = scg_load(b, c->converged_var);
    scg_value in_sub = scg_isect_inside(b, uv, sub_lo, sub_hi);
    scg_value accepted = scg_and(b, converged, in_sub);
    scg_value kept = scg_isect_kept(c, accepted, uv);
    /* A crossing the trim curves cut away leaves the middle's and the
     * quarters' restarts where the ray meets it below |cos|
     * HYBRID_CUT_FACING, and none above: a second, kept crossing in the
     * same sub-patch needs the surface to turn back towards the ray, and
     * rays through the holes of trimmed models are many. (PRO20359-L1's
     * tail close-up with hulls of adaptive:0.001 left 52 holes at 512²
     * with the middle's restart alone, none with the quarters'.) */
    scg_value cut_away = scg_and(b, accepted, scg_not(b, kept));
    scg_value allowed = scg_load(b, restarts_var);
    scg_value facing = scg_load(b, c->facing_var);
    scg_value steep = scg_lt(b, scg_const_f(b, HYBRID_CUT_FACING), facing);
    scg_value no_restart = scg_const_i(b, 0);
    scg_value trimmed_restarts = scg_const_i(b, HYBRID_TRIMMED_RESTARTS);
    scg_value cap = scg_select(b, steep, no_restart, trimmed_restarts);
    scg_value lower = scg_and(b, cut_away, scg_lt(b, cap, allowed));
    /* So does a crossing on a neighbouring sub-patch of the record met at
     * |cos| above HYBRID_CUT_FACING: that sub-patch's hull draws it, and
     * this one may hold a nearer crossing only where the record turns
     * back towards the ray. Rays through the hull's overhang beyond its
     * sub-patch, which meet the neighbour, ran every restart before. */
    scg_value on_record = scg_isect_inside(b, uv, c->rec_lo, c->rec_hi);
    scg_value elsewhere = scg_and(b, converged, scg_and(b, scg_not(b, in_sub), on_record));
    scg_value one = scg_const_i(b, HYBRID_ELSEWHERE_RESTARTS);
    scg_value steep_elsewhere = scg_and(b, elsewhere, steep);
    scg_value above_one = scg_lt(b, one, allowed);
    scg_value lower_elsewhere = scg_and(b, steep_elsewhere, above_one);
    cap = scg_select(b, lower_elsewhere, one, cap);
    lower = scg_or(b, lower, lower_elsewhere);
    scg_store(b, restarts_var, scg_select(b, lower, cap, allowed));
    accepted = scg_and(b, accepted, kept);
    /* `found`: this run's crossing ends the search (without the seek, any
     * kept crossing). */
    scg_value found = accepted, seek_begins = 0;
    if (seek) {
        scg_name(b, "nearer");
        scg_value depth = scg_load(b, c->depth_var);
        scg_value best_depth = scg_load(b, best_depth_var);
        scg_value nearer = scg_lt(b, scg_add(b, depth, c->tol), best_depth);
        scg_value better = scg_and(b, accepted, nearer);
        scg_value best_uv = scg_load(b, best_uv_var);
        scg_store(b, best_uv_var, scg_select(b, better, uv, best_uv));
        scg_store(b, best_depth_var, scg_select(b, better, depth, best_depth));
        scg_value best_found = scg_load(b, best_found_var);
        scg_store(b, best_found_var, scg_or(b, best_found, better));
        scg_value facing_now = scg_load(b, c->facing_var);
        scg_value grazing = scg_lt(b, facing_now, scg_const_f(b, HYBRID_SEEK_FACING));
        scg_value seeking = scg_load(b, seeking_var);
        scg_value better_grazing = scg_and(b, better, grazing);
        seek_begins = scg_and(b, better_grazing, scg_not(b, seeking));
        scg_store(b, seeking_var, scg_or(b, seeking, seek_begins));
        found = scg_and(b, better, scg_not(b, seek_begins));
        /* The seek runs through the quarters at most. */
        scg_value allowed_now = scg_load(b, restarts_var);
        scg_value quarters = scg_const_i(b, HYBRID_RESTARTS);
        scg_value fewer = scg_and(b, seek_begins, scg_lt(b, quarters, allowed_now));
        scg_store(b, restarts_var, scg_select(b, fewer, quarters, allowed_now));
        scg_store(b, c->found_var, scg_or(b, best_found, better));
        scg_name(b, NULL);
    } else {
        scg_store(b, c->found_var, accepted);
    }
    /* A run is over when Newton stopped (converged, singular, left its
     * box) or spent its itN steps; then the next piece, if any. */
    scg_name(b, "run_over");
    scg_value passes_done = scg_load(b, pass_var);
    scg_value pass = scg_add(b, passes_done, scg_const_i(b, 1));
    scg_value out_of_steps = scg_eq(b, pass, scg_const_i(b, passes_per_run));
    scg_value run_over = scg_or(b, scg_load(b, c->done_var), out_of_steps);
    scg_value restart = scg_load(b, restart_var);
    if (seek) {
        /* The first run started at the sub-patch's middle already: the
         * seek goes on from the quarters. */
        scg_value first_quarter = scg_const_i(b, 1);
        scg_value skip = scg_and(b, seek_begins, scg_lt(b, restart, first_quarter));
        restart = scg_select(b, skip, first_quarter, restart);
    }
    scg_value no_more = scg_le(b, scg_load(b, restarts_var), restart);
    scg_value stop = scg_or(b, found, scg_and(b, run_over, no_more));
    if (behind)
        stop = scg_or(b, stop, behind);
    scg_name(b, NULL);
    scg_if(b, stop);
    scg_break(b);
    scg_endif(b);
    scg_store(b, pass_var, pass);
    scg_if(b, run_over);
    start_run(c, restart, lo_var, hi_var);
    scg_store(b, pass_var, scg_const_i(b, 0));
    scg_store(b, restart_var, scg_add(b, restart, scg_const_i(b, 1)));
    scg_endif(b);
    scg_endloop(b);
    if (seek) {
        /* The seek's last run may have ended elsewhere: the verdict judges
         * the nearest kept crossing. */
        scg_name(b, "nearest");
        scg_value last = scg_load(b, c->uv_var);
        scg_value best_found = scg_load(b, best_found_var);
        scg_value best_uv = scg_load(b, best_uv_var);
        scg_store(b, c->uv_var, scg_select(b, best_found, best_uv, last));
        scg_name(b, NULL);
    }
    c->trimmed_by_method = true;
}
