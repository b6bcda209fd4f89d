/* bclip.c — Bézier clipping of the surface against the ray's two planes
 * (Nishita, Sederberg & Kakimoto 1990), in the intersection skeleton
 * (intersect.c), in the iterative, constant-memory form seed 000 uses for
 * trim curves.
 *
 * The record's control points, already in the ray's frame, give two
 * scalar Bézier patches: the signed distances from the two planes, both
 * zero where the ray meets the surface. Each step restricts the patch to
 * the current parameter interval (subdiv.c's restriction), drops the piece
 * when its box in the ray's frame does not hold the ray or lies behind the
 * nearest hit so far, and otherwise clips the interval, in u and in v at
 * once, to where the convex hull of each distance's control polygon (the
 * points (i/p, d_ij)) meets zero: a zero of the patch can lie nowhere
 * else. A piece whose box is below the tolerance is a hit at its middle;
 * one that clipping did not shrink to BCLIP_STALL of its size in either
 * direction (two crossings, or a silhouette) is split in two along the
 * direction that shrank less. The intervals wait on a small stack of
 * BCLIP_STACK entries, so the memory is constant; the loop is a runtime
 * loop of at most itN steps, and the restriction, box and hulls are
 * unrolled for the key's degrees.
 *
 * As in intersect.c, no argument list holds more than one call that
 * creates instructions, so value numbers follow the source. */
#include "bclip.h"
#include "subdiv.h"

#define HUGE_DEPTH 3.0e38f
/* Entries of the stack of intervals: every split pushes two and the
 * search is depth first, so this bounds the splits pending at once. */
#define BCLIP_STACK 16
/* Clipping that keeps more than this fraction of the interval in both
 * directions has stalled: split. Nishita et al. split below 20 %
 * reduction; the same here. */
#define BCLIP_STALL 0.8f
/* Relative widening of the hull's interval, for the rounding of the
 * crossings themselves. */
#define BCLIP_MARGIN 1e-4f
/* Absolute widening of every clipped interval (parameters are in [0, 1]
 * or the record's rectangle): without it 1 % of the interpreter's random
 * rays lost their crossing; with it none (tests/test_kernels.c). */
#define BCLIP_SLACK 2e-6f

/* The interval [lo, hi] (two floats, in [0, 1] of the piece) where the
 * convex hull of the points (i/n, d_i) for d_i in {low[i], high[i]} meets
 * zero: the hull of a set meets a line in the hull of the crossings of
 * the segments between its points on either side. Empty when lo > hi. */
static void hull_zero(scg_builder *b, const scg_value *low, const scg_value *high, int n,
                      scg_value *lo, scg_value *hi)
{
    scg_value none_lo = scg_const_f(b, HUGE_DEPTH);
    scg_value none_hi = scg_const_f(b, -HUGE_DEPTH);
    *lo = none_lo;
    *hi = none_hi;
    scg_value zero = scg_const_f(b, 0.0f);
    int count = 2 * (n + 1);
    for (int x = 0; x < count; x++)
        for (int y = x + 1; y < count; y++) {
            float tx = (float)(x / 2) / (float)n, ty = (float)(y / 2) / (float)n;
            scg_value dx = (x & 1) ? high[x / 2] : low[x / 2];
            scg_value dy = (y & 1) ? high[y / 2] : low[y / 2];
            scg_value straddles = scg_le(b, scg_mul(b, dx, dy), zero);
            scg_value t;
            if (x / 2 == y / 2) {
                t = scg_const_f(b, tx);
            } else {
                /* tx + (ty − tx)·dx/(dx − dy); both zero: tx. */
                scg_value gap = scg_sub(b, dx, dy);
                scg_value flat = scg_eq(b, gap, zero);
                scg_value share = scg_div(b, dx, gap);
                scg_value along = scg_mul(b, share, scg_const_f(b, ty - tx));
                scg_value from = scg_const_f(b, tx);
                t = scg_select(b, flat, from, scg_add(b, along, from));
            }
            scg_value t_lo = scg_select(b, straddles, t, none_lo);
            *lo = scg_min(b, *lo, t_lo);
            scg_value t_hi = scg_select(b, straddles, t, none_hi);
            *hi = scg_max(b, *hi, t_hi);
        }
}

/* Clips [0, 1] of one direction of the piece: e holds the piece's
 * points, `n` + 1 lines of `m` + 1 points across the direction, point
 * (line k, across l) at e[k·line + l·across]; their distances from the
 * plane through the ray whose normal in the frame's xy is `normal` (vec2).
 * Returns vec2 (lo, hi). */
static scg_value clip_direction(scg_builder *b, const scg_value *e, int n, int m, int line,
                                int across, scg_value normal)
{
    scg_value low[SCG_MAX_DEGREE + 1], high[SCG_MAX_DEGREE + 1];
    for (int k = 0; k <= n; k++) {
        for (int l = 0; l <= m; l++) {
            scg_value x = scg_comp(b, e[k * line + l * across], 0);
            scg_value xy = scg_vec2(b, x, scg_comp(b, e[k * line + l * across], 1));
            scg_value d = scg_dot(b, normal, xy);
            low[k] = l ? scg_min(b, low[k], d) : d;
            high[k] = l ? scg_max(b, high[k], d) : d;
        }
    }
    scg_value lo, hi;
    hull_zero(b, low, high, n, &lo, &hi);
    /* Widened by BCLIP_MARGIN, so that float rounding in the restriction
     * cannot clip away a crossing on the piece's edge. */
    scg_value margin = scg_const_f(b, BCLIP_MARGIN);
    scg_value lo_wide = scg_sub(b, lo, margin);
    scg_value from = scg_max(b, lo_wide, scg_const_f(b, 0.0f));
    scg_value hi_wide = scg_add(b, hi, margin);
    scg_value to = scg_min(b, hi_wide, scg_const_f(b, 1.0f));
    return scg_vec2(b, from, to);
}

/* The normal (in the frame's xy) of the plane through the ray that runs
 * along the piece's direction from a to b and from c to d (corner points):
 * distances from it change across that direction only, so it clips the
 * other one best (Nishita et al.). Unnormalised: only signs matter. */
static scg_value across_normal(scg_builder *b, scg_value pa, scg_value pb, scg_value pc,
                               scg_value pd)
{
    scg_value first = scg_sub(b, pb, pa);
    scg_value along = scg_add(b, first, scg_sub(b, pd, pc));
    scg_value x = scg_comp(b, along, 0), y = scg_comp(b, along, 1);
    return scg_vec2(b, scg_neg(b, y), x);
}

/* The sub-interval [lo, hi] (fractions) of [a, b], widened by
 * BCLIP_SLACK on each side: the restriction to [a, b] is computed in
 * float, so the points describe the patch on an interval a few ulps off,
 * which for the narrow intervals clipping soon reaches is more than any
 * fraction of them; a crossing on the edge would be clipped away. */
static scg_value part(scg_builder *b, scg_value a, scg_value bnd, scg_value fractions)
{
    scg_value length = scg_sub(b, bnd, a);
    scg_value scaled = scg_mul(b, fractions, length);
    scg_value a2 = scg_vec2(b, a, a);
    scg_value inside = scg_add(b, a2, scaled);
    scg_value slack = scg_const_vec(b, 2, (float[]){-BCLIP_SLACK, BCLIP_SLACK});
    return scg_add(b, inside, slack);
}

/* One popped interval iv: box test, leaf, or clip and push what is left
 * (split in two when clipping stalled). */
static void clip_step(scg_isect *c, const scg_pieces *s, scg_value iv, scg_value meta)
{
    (void)meta;
    scg_builder *b = c->b;
    int p = c->p, q = c->q;
    scg_value e[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)];
    scg_value h[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)];
    scg_value near, size;
    scg_value holds = scg_piece_box(c, s, iv, e, h, &near, &size);
    scg_if(b, holds);
    scg_value iters = scg_load(b, c->iters_var);
    scg_store(b, c->iters_var, scg_add(b, iters, scg_const_i(b, 1)));
    scg_if(b, scg_lt(b, size, c->tol));
    scg_piece_hit(c, s, iv, near);
    scg_else(b);
    scg_name(b, "clip");
    /* u: the columns (p + 1 of them, q + 1 points each), against the
     * plane along v; v: the rows, against the plane along u. */
    int n = (p + 1) * (q + 1);
    scg_value c00 = e[0], c10 = e[p], c01 = e[q * (p + 1)], c11 = e[n - 1];
    scg_value along_v = across_normal(b, c00, c01, c10, c11);
    scg_value along_u_plane = across_normal(b, c00, c10, c01, c11);
    /* A rational patch's distance is w·d / w with w > 0: the zeros are
     * those of the polynomial numerator, whose control values are the
     * homogeneous points' w·d. */
    scg_value cu = clip_direction(b, h, p, q, 1, p + 1, along_v);
    scg_value cv = clip_direction(b, h, q, p, p + 1, 1, along_u_plane);
    scg_value cu_lo = scg_comp(b, cu, 0), cu_hi = scg_comp(b, cu, 1);
    scg_value cv_lo = scg_comp(b, cv, 0), cv_hi = scg_comp(b, cv, 1);
    scg_value u_kept = scg_le(b, cu_lo, cu_hi);
    scg_value kept = scg_and(b, u_kept, scg_le(b, cv_lo, cv_hi));
    scg_value u0 = scg_comp(b, iv, 0), u1 = scg_comp(b, iv, 1);
    scg_value v0 = scg_comp(b, iv, 2), v1 = scg_comp(b, iv, 3);
    scg_value u_part = part(b, u0, u1, cu);
    scg_value v_part = part(b, v0, v1, cv);
    scg_value u_a = scg_comp(b, u_part, 0), u_b = scg_comp(b, u_part, 1);
    scg_value v_a = scg_comp(b, v_part, 0), v_b = scg_comp(b, v_part, 1);
    scg_value clipped = scg_vec4(b, u_a, u_b, v_a, v_b);
    scg_value u_left = scg_sub(b, cu_hi, cu_lo);
    scg_value v_left = scg_sub(b, cv_hi, cv_lo);
    scg_value stall = scg_const_f(b, BCLIP_STALL);
    scg_value u_stalled = scg_lt(b, stall, u_left);
    scg_value stalled = scg_and(b, u_stalled, scg_lt(b, stall, v_left));
    scg_value sp = scg_load(b, s->sp);
    scg_value room = scg_lt(b, sp, scg_const_i(b, s->depth - 1));
    scg_value along_u = scg_le(b, v_left, u_left);
    scg_value half = scg_const_f(b, 0.5f);
    scg_value um = scg_mul(b, scg_add(b, u_a, u_b), half);
    scg_value vm = scg_mul(b, scg_add(b, v_a, v_b), half);
    scg_value low_u = scg_vec4(b, u_a, um, v_a, v_b), high_u = scg_vec4(b, um, u_b, v_a, v_b);
    scg_value low_v = scg_vec4(b, u_a, u_b, v_a, vm), high_v = scg_vec4(b, u_a, u_b, vm, v_b);
    /* The nearer half, by the depths of the piece's corners, is searched
     * first, so that the first leaf is mostly the nearest. */
    scg_value z00 = scg_comp(b, c00, 2), z10 = scg_comp(b, c10, 2);
    scg_value z01 = scg_comp(b, c01, 2), z11 = scg_comp(b, c11, 2);
    scg_value z_u_low = scg_add(b, z00, z01);
    scg_value u_low_near = scg_lt(b, z_u_low, scg_add(b, z10, z11));
    scg_value z_v_low = scg_add(b, z00, z10);
    scg_value v_low_near = scg_lt(b, z_v_low, scg_add(b, z01, z11));
    scg_value low_near = scg_select(b, along_u, u_low_near, v_low_near);
    scg_value low_split = scg_select(b, along_u, low_u, low_v);
    scg_value high_split = scg_select(b, along_u, high_u, high_v);
    scg_value low = scg_select(b, low_near, low_split, high_split);
    scg_value high = scg_select(b, low_near, high_split, low_split);
    scg_value near_size = scg_vec2(b, near, size);
    scg_name(b, NULL);
    scg_if(b, kept);
    /* Either the clipped interval, or, when clipping stalled, its two
     * halves (the nearer on top); with the stack full, the farther half
     * is given up rather than the search stopped. */
    scg_if(b, scg_and(b, stalled, room));
    scg_piece_push(b, s, high, near_size);
    scg_endif(b);
    scg_piece_push(b, s, scg_select(b, stalled, low, clipped), near_size);
    scg_endif(b);
    scg_endif(b);
    scg_endif(b);
}

void scg_method_bclip(scg_isect *c, scg_value uv0, scg_value behind)
{
    scg_piece_method(c, uv0, behind, BCLIP_STACK, c->key->max_iters, clip_step);
}
