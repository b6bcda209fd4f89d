/* trim_gen.c — the trimming metaprogram (Pabst et al. 2006, §5): is a hit's
 * (u, v) kept by the trim loops? The parity of the crossings of the ray
 * from (u, v) towards +u with the loops' pieces decides. The pieces are
 * v-monotone rational Bézier curves with half-open v ranges
 * [v_lo, v_hi) (runtime/prepare/trim_pack.c), so a ray through a shared end point,
 * an extremum or along a horizontal run counts right, and each piece is
 * crossed at most once.
 *
 * A piece whose u bounds lie on one side of the point is decided by the
 * bounds alone. Otherwise the crossing is located by iterative Bézier
 * clipping (§5.1–5.3) on d(t) = V(t) − v·W(t), whose sign is that of
 * v(t) − v: the sub-curve on the current interval [a, b] is recomputed
 * from the piece's points each iteration (two de Casteljau triangles), the
 * convex hull of (i/N, d_i) cut with the t axis narrows [a, b] from both
 * sides (two-sided) or from the left only (left-only), and an interval
 * that shrinks by less than 20 % is split (Nishita et al.). Because the
 * piece is monotone it holds the one root, so the split keeps the half
 * where d changes sign (d at the split point by one scalar de Casteljau)
 * and the paper's second interval of roots still to search is never
 * needed: the state is [a, b] and the verdict. The search stops as soon as
 * the sub-curve's u values all lie on one side of the point, which is the
 * verdict. Defined results: at the piece's lower end v == v_lo the end
 * point's u decides; when the hull misses the axis (rounding at an end)
 * the end where d is nearest zero decides; when [a, b] stops shrinking in
 * float, or the key's iteration cap is reached, the point where the last
 * sub-curve's chord meets the ray's line decides.
 *
 * The hull's cut with the axis is the smallest (largest) crossing of the
 * segments between points of opposite sign: the cut is on a hull edge,
 * whose end points have opposite signs, and every such segment lies in the
 * hull. Unrolled, that is N(N+1)/2 candidate crossings for degree N.
 *
 * The clipping iterations, unlike the degree loops, stay a runtime loop
 * that ends when every pixel of a SIMD group has its verdict: unrolled,
 * each iteration up to the cap is on the path, guarded or not, and
 * llvmpipe runs masked code at about half cost.
 * Measured, unrolling made trimmed frames 2–9 times slower and programs
 * 3 times larger (docs/trimming.md).
 *
 * The per-piece methods (clipN, leftN) walk the loops: a point outside a
 * loop's box gets an even number of crossings from it, so the loop is
 * skipped whole.
 *
 * The accelerated method (fastN) reads the grid cell of the point
 * (runtime/prepare/trim_pack.c): its parity and few entries decide most points by
 * comparisons alone. llvmpipe masks rather than skips code that no pixel of
 * a SIMD group needs, so what counts is the code on the path: the clipping
 * code appears once, after the scan, never inside a loop that every pixel
 * repeats (docs/trimming.md).
 *
 * C leaves the order in which a call's arguments are evaluated open, so no
 * argument list here holds more than one call that creates instructions:
 * value numbers, and the bytes of the GLSL, follow the source whichever
 * compiler built splinecast. */
#include <float.h>

#include "trim_gen.h"

/* Nishita et al.: when a clip keeps more than this fraction of the
 * interval, split it instead. */
#define SPLIT_FRACTION 0.8f

typedef struct trim_ctx {
    scg_builder *b;
    const scg_key *key;
    int n;                     /* piece degree */
    scg_value block, u, v;     /* int; normalised point */
    scg_value iters_var;       /* int variable or 0 */
} trim_ctx;

static scg_value offset(scg_builder *b, scg_value base, int k)
{
    return k ? scg_add(b, base, scg_const_i(b, k)) : base;
}

/* De Casteljau at t of n+1 points (any float type): the control points of
 * [0, t] into left, of [t, 1] into right (either may be NULL); returns the
 * point at t. */
static scg_value split(scg_builder *b, int n, const scg_value *pts, scg_value t, scg_value *left,
                       scg_value *right)
{
    scg_value work[SCG_MAX_DEGREE + 1] = {0};
    for (int i = 0; i <= n; i++)
        work[i] = pts[i];
    if (left)
        left[0] = work[0];
    if (right)
        right[n] = work[n];
    for (int r = 1; r <= n; r++) {
        for (int i = 0; i <= n - r; i++)
            work[i] = scg_lerp(b, work[i], work[i + 1], t);
        if (left)
            left[r] = work[0];
        if (right)
            right[n - r] = work[n - r];
    }
    return work[0];
}

/* The and of n bool values. */
static scg_value all_of(scg_builder *b, const scg_value *x, int n)
{
    scg_value r = x[0];
    for (int i = 1; i < n; i++)
        r = scg_and(b, r, x[i]);
    return r;
}

/* Whether the ray from (u, v) towards +u crosses the piece at texel
 * `piece`, given v_lo <= v < v_hi and u_min <= u < u_max. */
static scg_value piece_crosses(trim_ctx *c, scg_value piece)
{
    scg_builder *b = c->b;
    int n = c->n;
    bool two_sided = c->key->trim != SC_TRIM_LEFT;
    scg_value zero = scg_const_f(b, 0.0f);
    scg_value one = scg_const_f(b, 1.0f);

    scg_name(b, "piece");
    scg_value head = scg_fetch(b, SCG_TEX_RECORDS, piece);
    scg_value pts[SCG_MAX_DEGREE + 1];
    scg_value first = scg_fetch(b, SCG_TEX_RECORDS, offset(b, piece, 1));
    pts[0] = scg_xyz(b, first);
    for (int i = 1; i <= n; i++)
        pts[i] = scg_xyz(b, scg_fetch(b, SCG_TEX_RECORDS, offset(b, piece, 1 + i)));
    scg_value u_lo = scg_comp(b, first, 3);
    scg_name(b, "cross");
    scg_value cross_var = scg_var(b, SCG_BOOL, 0, scg_lt(b, c->u, u_lo));
    scg_name(b, "clipped");
    scg_value at_v_lo = scg_eq(b, c->v, scg_comp(b, head, 0));
    scg_value done_var = scg_var(b, SCG_BOOL, 0, at_v_lo);
    scg_name(b, "t_lo");
    scg_value a_var = scg_var(b, SCG_FLOAT, 0, zero);
    scg_name(b, "t_hi");
    scg_value b_var = scg_var(b, SCG_FLOAT, 0, one);
    scg_name(b, NULL);

    /* A runtime loop, not unrolled (see the top of the file). On a line
     * the chord guess of the first iteration is the crossing itself: more
     * iterations would only halve towards it. */
    scg_loop(b, scg_const_i(b, n == 1 ? 1 : c->key->trim_iters));
    scg_if(b, scg_load(b, done_var));
    scg_break(b);
    scg_endif(b);
    if (c->iters_var) {
        scg_value iters = scg_load(b, c->iters_var);
        scg_store(b, c->iters_var, scg_add(b, iters, scg_const_i(b, 1)));
    }
    scg_value ta = scg_load(b, a_var);
    scg_value tb = scg_load(b, b_var);

    /* The sub-curve on [a, b]: [0, b] of the piece, then its part from a/b. */
    scg_name(b, "sub");
    scg_value head_part[SCG_MAX_DEGREE + 1], q[SCG_MAX_DEGREE + 1];
    split(b, n, pts, tb, head_part, NULL);
    scg_value tb_positive = scg_max(b, tb, scg_const_f(b, FLT_MIN));
    scg_value s = scg_div(b, ta, tb_positive);
    split(b, n, head_part, s, NULL, q);

    /* d_i: signed distances of the points from the ray's line (times w);
     * e_i: their side of the point (times w). */
    scg_value d[SCG_MAX_DEGREE + 1], e[SCG_MAX_DEGREE + 1], w[SCG_MAX_DEGREE + 1];
    scg_value left_of[SCG_MAX_DEGREE + 1] = {0}, right_of[SCG_MAX_DEGREE + 1] = {0};
    scg_value above[SCG_MAX_DEGREE + 1];
    for (int i = 0; i <= n; i++) {
        w[i] = scg_comp(b, q[i], 2);
        scg_name(b, "d");
        scg_value vw = scg_comp(b, q[i], 1);
        d[i] = scg_sub(b, vw, scg_mul(b, c->v, w[i]));
        scg_name(b, "e");
        scg_value uw = scg_comp(b, q[i], 0);
        e[i] = scg_sub(b, uw, scg_mul(b, c->u, w[i]));
        scg_name(b, NULL);
        left_of[i] = scg_le(b, e[i], zero);
        right_of[i] = scg_lt(b, zero, e[i]);
        above[i] = scg_lt(b, zero, d[i]);
    }
    scg_name(b, "all_left");
    scg_value all_left = all_of(b, left_of, n + 1);
    scg_name(b, "all_right");
    scg_value all_right = all_of(b, right_of, n + 1);
    /* Where the chord between the sub-curve's ends meets the ray's line
     * (the homogeneous chord is the straight segment, d and e are linear
     * on it): right of the point or not. Exact for a line, so a stalled
     * or capped search on a line still decides right; the chord's midpoint
     * would be wrong for points nearer the curve than half the last
     * interval. Ends of equal d: the midpoint. */
    scg_name(b, "chord_s");
    scg_value chord_den = scg_sub(b, d[0], d[n]);
    scg_value chord_slanted = scg_ne(b, chord_den, zero);
    scg_value chord_ratio = scg_max(b, scg_div(b, d[0], chord_den), zero);
    scg_value chord_clamped = scg_min(b, chord_ratio, one);
    scg_value half = scg_const_f(b, 0.5f);
    scg_value chord_s = scg_select(b, chord_slanted, chord_clamped, half);
    scg_name(b, "guess");
    scg_value e_rise = scg_sub(b, e[n], e[0]);
    scg_value e_chord = scg_add(b, e[0], scg_mul(b, chord_s, e_rise));
    scg_value guess = scg_lt(b, zero, e_chord);
    scg_name(b, "end_side");
    scg_value end_side = scg_select(b, above[0], right_of[0], right_of[n]);

    /* The hull's cut with the t axis. */
    scg_name(b, "hull");
    scg_value beyond_right = scg_const_f(b, 2.0f);
    scg_value beyond_left = scg_const_f(b, -1.0f);
    scg_value t_min = beyond_right, t_max = beyond_left;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j <= n; j++) {
            /* Opposite signs, or one point on the axis. */
            scg_value product = scg_mul(b, d[i], d[j]);
            scg_value not_same_side = scg_le(b, product, zero);
            scg_value distinct = scg_ne(b, d[i], d[j]);
            scg_value opposite = scg_and(b, not_same_side, distinct);
            scg_value ratio = scg_div(b, d[i], scg_sub(b, d[i], d[j]));
            scg_value start = scg_const_f(b, (float)i / (float)n);
            scg_value span = scg_const_f(b, (float)(j - i) / (float)n);
            scg_value x = scg_add(b, start, scg_mul(b, span, ratio));
            t_min = scg_min(b, t_min, scg_select(b, opposite, x, beyond_right));
            if (two_sided)
                t_max = scg_max(b, t_max, scg_select(b, opposite, x, beyond_left));
        }
    scg_value missed = scg_lt(b, scg_const_f(b, 1.5f), t_min);
    scg_value lo = scg_max(b, t_min, zero);
    scg_value hi = two_sided ? scg_min(b, t_max, one) : one;

    /* Too little progress: split, keeping the half where d changes sign. */
    scg_name(b, "split");
    scg_value lo_hi = scg_add(b, lo, hi);
    scg_value mid = scg_mul(b, lo_hi, scg_const_f(b, 0.5f));
    scg_value d_mid = split(b, n, d, mid, NULL, NULL);
    scg_value kept_width = scg_sub(b, hi, lo);
    scg_value split_now = scg_lt(b, scg_const_f(b, SPLIT_FRACTION), kept_width);
    scg_value rises = scg_lt(b, zero, d_mid);
    scg_value keep_upper = scg_and(b, split_now, scg_not(b, rises));
    scg_value keep_lower = scg_and(b, split_now, rises);
    lo = scg_select(b, keep_upper, mid, lo);
    hi = scg_select(b, keep_lower, mid, hi);
    scg_value width = scg_sub(b, tb, ta);
    scg_name(b, "t_lo");
    scg_value next_a = scg_add(b, ta, scg_mul(b, width, lo));
    scg_name(b, "t_hi");
    scg_value next_b = scg_add(b, ta, scg_mul(b, width, hi));
    scg_name(b, "stalled");
    scg_value a_stalled = scg_eq(b, next_a, ta);
    scg_value b_stalled = scg_eq(b, next_b, tb);
    scg_value stalled = scg_and(b, a_stalled, b_stalled);
    scg_name(b, NULL);
    scg_value decided = scg_or(b, all_left, all_right);
    scg_value finished = scg_or(b, decided, scg_or(b, missed, stalled));
    scg_value undecided_side = scg_select(b, missed, end_side, guess);
    scg_store(b, cross_var, scg_select(b, decided, all_right, undecided_side));
    scg_store(b, done_var, finished);
    scg_store(b, a_var, next_a);
    scg_store(b, b_var, next_b);
    scg_endloop(b);
    return scg_load(b, cross_var);
}

/* Crossing of a piece whose u bounds are (u_min, u_max), in a block that
 * already knows v lies in its range: bounds first, clipping when the point
 * lies between them. Returns a bool value. */
static scg_value bounded_crossing(trim_ctx *c, scg_value piece, scg_value u_min, scg_value u_max)
{
    scg_builder *b = c->b;
    scg_name(b, "cross");
    scg_value cross_var = scg_var(b, SCG_BOOL, 0, scg_lt(b, c->u, u_min));
    scg_name(b, NULL);
    scg_value right_of_min = scg_le(b, u_min, c->u);
    scg_value left_of_max = scg_lt(b, c->u, u_max);
    scg_if(b, scg_and(b, right_of_min, left_of_max));
    scg_store(b, cross_var, piece_crosses(c, piece));
    scg_endif(b);
    return scg_load(b, cross_var);
}

/* Odd (count + bias) keeps the point. */
static scg_value odd(scg_builder *b, scg_value count)
{
    scg_value two = scg_const_i(b, 2);
    scg_value half = scg_div(b, count, two);
    scg_value rest = scg_sub(b, count, scg_mul(b, half, two));
    return scg_eq(b, rest, scg_const_i(b, 1));
}

/* The crossings of the pieces of the loops whose box holds the point, in
 * runtime loops (clipN, leftN): a point outside a loop's box gets an even
 * number of crossings from it (gpu_layout.h), so the loop is skipped
 * whole. */
static scg_value crossings_all(trim_ctx *c, scg_value header, scg_value bias)
{
    scg_builder *b = c->b;
    scg_name(b, "crossings");
    scg_value count_var = scg_var(b, SCG_INT, 0, bias);
    scg_name(b, "loops");
    scg_value cols = scg_comp(b, header, 2);
    scg_value rows = scg_comp(b, header, 3);
    scg_value ncells = scg_f2i(b, scg_mul(b, cols, rows));
    scg_value loops = scg_add(b, offset(b, c->block, SCG_TRIM_HEADER_TEXELS), ncells);
    scg_name(b, NULL);
    scg_value l = scg_loop(b, scg_f2i(b, scg_comp(b, header, 0)));
    scg_name(b, "loop");
    scg_value loop_texels = scg_const_i(b, SCG_TRIM_LOOP_TEXELS);
    scg_value loop = scg_add(b, loops, scg_mul(b, l, loop_texels));
    scg_value box = scg_fetch(b, SCG_TEX_RECORDS, loop);
    scg_name(b, NULL);
    scg_value right_of_min = scg_le(b, scg_comp(b, box, 0), c->u);
    scg_value left_of_max = scg_lt(b, c->u, scg_comp(b, box, 1));
    scg_value above_lo = scg_le(b, scg_comp(b, box, 2), c->v);
    scg_value below_hi = scg_lt(b, c->v, scg_comp(b, box, 3));
    scg_value in_u = scg_and(b, right_of_min, left_of_max);
    scg_value in_v = scg_and(b, above_lo, below_hi);
    scg_if(b, scg_and(b, in_u, in_v));
    scg_name(b, "loop");
    scg_value range = scg_fetch(b, SCG_TEX_RECORDS, offset(b, loop, 1));
    scg_value first = scg_add(b, c->block, scg_f2i(b, scg_comp(b, range, 0)));
    scg_name(b, NULL);
    scg_value k = scg_loop(b, scg_f2i(b, scg_comp(b, range, 1)));
    scg_name(b, "piece");
    scg_value piece_texels = scg_const_i(b, SCG_TRIM_PIECE_TEXELS(c->n));
    scg_value piece = scg_add(b, first, scg_mul(b, k, piece_texels));
    scg_value head = scg_fetch(b, SCG_TEX_RECORDS, piece);
    scg_name(b, NULL);
    scg_value piece_above_lo = scg_le(b, scg_comp(b, head, 0), c->v);
    scg_value piece_below_hi = scg_lt(b, c->v, scg_comp(b, head, 1));
    scg_if(b, scg_and(b, piece_above_lo, piece_below_hi));
    scg_value u_min = scg_comp(b, head, 2);
    scg_value u_max = scg_comp(b, head, 3);
    scg_value cross = bounded_crossing(c, piece, u_min, u_max);
    scg_value count = scg_load(b, count_var);
    scg_value count_plus = scg_add(b, count, scg_const_i(b, 1));
    scg_store(b, count_var, scg_select(b, cross, count_plus, count));
    scg_endif(b);
    scg_endloop(b);
    scg_endif(b);
    scg_endloop(b);
    return scg_load(b, count_var);
}

/* Whether entry e (its first texel) is ambiguous for the point: v in its
 * range, u between its bounds, so that only clipping can tell. */
static scg_value entry_ambiguous(trim_ctx *c, scg_value e)
{
    scg_builder *b = c->b;
    scg_value v_lo = scg_comp(b, e, 0);
    scg_value v_hi = scg_comp(b, e, 1);
    scg_value u_min = scg_comp(b, e, 2);
    scg_value u_max = scg_comp(b, e, 3);
    scg_value above_lo = scg_le(b, v_lo, c->v);
    scg_value below_hi = scg_lt(b, c->v, v_hi);
    scg_value in_range = scg_and(b, above_lo, below_hi);
    scg_value right_of_min = scg_le(b, u_min, c->u);
    scg_value left_of_max = scg_lt(b, c->u, u_max);
    scg_value between = scg_and(b, right_of_min, left_of_max);
    return scg_and(b, in_range, between);
}

/* The grid cell holding the point, indexed directly; its parity, then its
 * entries scanned by their bounds alone; the ambiguous ones, usually none,
 * clipped after the scan, so that the clipping code appears once and the
 * scan stays a loop of a fetch and a few comparisons (fastN). */
static scg_value crossings_grid(trim_ctx *c, scg_value header)
{
    scg_builder *b = c->b;
    scg_value zero = scg_const_i(b, 0);
    scg_value one = scg_const_i(b, 1);
    scg_name(b, "cell");
    scg_value cols = scg_f2i(b, scg_comp(b, header, 2));
    scg_value rows = scg_f2i(b, scg_comp(b, header, 3));
    scg_value u_scaled = scg_mul(b, c->u, scg_comp(b, header, 2));
    scg_value v_scaled = scg_mul(b, c->v, scg_comp(b, header, 3));
    scg_value col_last = scg_sub(b, cols, one);
    scg_value row_last = scg_sub(b, rows, one);
    scg_value col_low = scg_max(b, scg_f2i(b, u_scaled), zero);
    scg_value col = scg_min(b, col_low, col_last);
    scg_value row_low = scg_max(b, scg_f2i(b, v_scaled), zero);
    scg_value row = scg_min(b, row_low, row_last);
    scg_value cells = offset(b, c->block, SCG_TRIM_HEADER_TEXELS);
    scg_value row_start = scg_add(b, cells, scg_mul(b, row, cols));
    scg_value cell = scg_fetch(b, SCG_TEX_RECORDS, scg_add(b, row_start, col));
    scg_name(b, "crossings");
    scg_value count_var = scg_var(b, SCG_INT, 0, scg_f2i(b, scg_comp(b, cell, 0)));
    scg_name(b, "entries");
    scg_value entries = scg_add(b, c->block, scg_f2i(b, scg_comp(b, cell, 1)));
    scg_value nentries = scg_f2i(b, scg_comp(b, cell, 2));
    scg_name(b, "ambiguous");
    scg_value namb_var = scg_var(b, SCG_INT, 0, zero);
    scg_name(b, "first_ambiguous");
    scg_value first_var = scg_var(b, SCG_INT, 0, zero);
    scg_value stride = scg_const_i(b, SCG_TRIM_ENTRY_TEXELS);
    scg_name(b, NULL);

    /* The scan: bounds decide all but the ambiguous entries. */
    scg_value k = scg_loop(b, nentries);
    scg_name(b, "entry");
    scg_value e = scg_fetch(b, SCG_TEX_RECORDS, scg_add(b, entries, scg_mul(b, k, stride)));
    scg_name(b, NULL);
    scg_value v_lo = scg_comp(b, e, 0);
    scg_value v_hi = scg_comp(b, e, 1);
    scg_value above_lo = scg_le(b, v_lo, c->v);
    scg_value below_hi = scg_lt(b, c->v, v_hi);
    scg_value in_range = scg_and(b, above_lo, below_hi);
    scg_value left_of_min = scg_lt(b, c->u, scg_comp(b, e, 2));
    scg_value crossed = scg_and(b, in_range, left_of_min);
    scg_value count = scg_load(b, count_var);
    scg_value count_plus = scg_add(b, count, one);
    scg_store(b, count_var, scg_select(b, crossed, count_plus, count));
    scg_value ambiguous = entry_ambiguous(c, e);
    scg_value namb = scg_load(b, namb_var);
    scg_value none_yet = scg_eq(b, namb, zero);
    scg_value first_here = scg_and(b, ambiguous, none_yet);
    scg_value first = scg_load(b, first_var);
    scg_store(b, first_var, scg_select(b, first_here, k, first));
    scg_value namb_plus = scg_add(b, namb, one);
    scg_store(b, namb_var, scg_select(b, ambiguous, namb_plus, namb));
    scg_endloop(b);

    /* The ambiguous entries, one clipping each: after each, the next
     * ambiguous entry by a scan from the one just clipped. */
    scg_loop(b, scg_load(b, namb_var));
    scg_value at = scg_load(b, first_var);
    scg_name(b, "piece");
    scg_value second = scg_add(b, entries, scg_mul(b, at, stride));
    scg_value link = scg_fetch(b, SCG_TEX_RECORDS, scg_add(b, second, one));
    scg_value piece = scg_add(b, c->block, scg_f2i(b, scg_comp(b, link, 0)));
    scg_name(b, NULL);
    scg_value cross = piece_crosses(c, piece);
    count = scg_load(b, count_var);
    count_plus = scg_add(b, count, one);
    scg_store(b, count_var, scg_select(b, cross, count_plus, count));
    scg_value after = scg_add(b, at, one);
    scg_store(b, first_var, nentries);
    scg_value i = scg_loop(b, scg_sub(b, nentries, after));
    scg_value next = scg_add(b, after, i);
    scg_name(b, "entry");
    scg_value next_entry = scg_fetch(b, SCG_TEX_RECORDS, scg_add(b, entries, scg_mul(b, next, stride)));
    scg_name(b, NULL);
    scg_if(b, entry_ambiguous(c, next_entry));
    scg_store(b, first_var, next);
    scg_break(b);
    scg_endif(b);
    scg_endloop(b);
    scg_endloop(b);
    return scg_load(b, count_var);
}

scg_value scg_trim_block(scg_builder *b, scg_value record_texel3)
{
    scg_name(b, "trim_block");
    scg_value block = scg_f2i(b, scg_comp(b, record_texel3, 3));
    scg_name(b, NULL);
    return block;
}

scg_value scg_trim_normalise(scg_builder *b, scg_value block, scg_value origin, scg_value extent,
                             scg_value local)
{
    scg_value map = scg_fetch(b, SCG_TEX_RECORDS, scg_add(b, block, scg_const_i(b, 1)));
    scg_value scale_u = scg_comp(b, map, 0);
    scg_value scale_v = scg_comp(b, map, 1);
    scg_value scale = scg_vec2(b, scale_u, scale_v);
    scg_value shift_u = scg_comp(b, map, 2);
    scg_value shift_v = scg_comp(b, map, 3);
    scg_value shift = scg_vec2(b, shift_u, shift_v);
    scg_name(b, "uv_trim");
    scg_value uv;
    if (origin) {
        scg_value base = scg_add(b, scg_mul(b, origin, scale), shift);
        scg_value extent_scaled = scg_mul(b, extent, scale);
        uv = scg_add(b, base, scg_mul(b, local, extent_scaled));
    } else {
        uv = scg_add(b, scg_mul(b, local, scale), shift);
    }
    scg_name(b, NULL);
    return uv;
}

scg_value scg_trim_kept(scg_builder *b, const scg_key *key, scg_value block, scg_value uv,
                        scg_value iters_var)
{
    trim_ctx c = {.b = b, .key = key, .n = key->trim_degree, .block = block,
                  .iters_var = iters_var};
    c.u = scg_comp(b, uv, 0);
    c.v = scg_comp(b, uv, 1);
    scg_name(b, "trim_header");
    scg_value header = scg_fetch(b, SCG_TEX_RECORDS, block);
    scg_name(b, NULL);
    scg_value count;
    if (key->trim == SC_TRIM_FAST) {
        count = crossings_grid(&c, header);
    } else {
        scg_name(b, "trim_bias");
        scg_value bias = scg_f2i(b, scg_comp(b, header, 1));
        scg_name(b, NULL);
        count = crossings_all(&c, header, bias);
    }
    scg_name(b, "kept");
    scg_value kept = odd(b, count);
    scg_name(b, NULL);
    return kept;
}

int scg_build_trim_probe(const scg_key *key, scg_program **out, sc_error *err)
{
    *out = NULL;
    if (scg_key_check(key, err) != SC_OK)
        return SC_FAIL;
    if (key->trim == SC_TRIM_NONE) {
        char text[SCG_KEY_MAX];
        scg_key_format(key, text, sizeof text);
        return sc_fail_key(err, text, "variant key '%s': the trim probe needs a trimmed key",
                           text);
    }
    scg_program *prog = scg_program_create(key);
    scg_builder b;
    scg_builder_init(&b, prog);
    scg_value record = scg_input(&b, SCG_IN_RECORD);
    scg_value rec = scg_mul(&b, record, scg_const_i(&b, SCG_RECORD_TEXELS));
    scg_value texel3 = scg_fetch(&b, SCG_TEX_RECORDS, scg_add(&b, rec, scg_const_i(&b, 3)));
    scg_value block = scg_trim_block(&b, texel3);
    scg_name(&b, "iters");
    scg_value iters = scg_var(&b, SCG_INT, 0, scg_const_i(&b, 0));
    scg_name(&b, NULL);
    scg_value uv0 = scg_input(&b, SCG_IN_UV0);
    scg_value uv = scg_trim_normalise(&b, block, 0, 0, uv0);
    scg_value kept = scg_trim_kept(&b, key, block, uv, iters);
    scg_output(&b, SCG_OUT_HIT, kept);
    scg_output(&b, SCG_OUT_UV, uv);
    scg_output(&b, SCG_OUT_ITERS, scg_load(&b, iters));
    if (scg_validate(prog, err) != SC_OK || scg_optimize(prog, NULL, NULL, err) != SC_OK) {
        scg_program_free(prog);
        return SC_FAIL;
    }
    *out = prog;
    return SC_OK;
}
