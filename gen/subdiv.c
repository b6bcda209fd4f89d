/* subdiv.c — object-space subdivision (Dammertz & Keller, "Improving Ray
 * Tracing Precision by Object Space Intersection Computation") on the GPU,
 * in the intersection skeleton (intersect.c). The hull's sub-patch is split
 * by de Casteljau at 0.5 along its longer direction; a piece whose
 * axis-aligned box (in the ray's frame: the two plane distances and the
 * depth along the ray) does not hold the ray is dropped; a piece whose box
 * is smaller than the tolerance, or no smaller in L1 norm than its parent's
 * (the box stopped shrinking in float), is a leaf, a hit at its middle.
 * The nearer half is searched first and a piece behind the nearest leaf so
 * far is dropped, so the first leaf is usually the nearest and the rest
 * costs little.
 *
 * Constant memory, as seed 000 treats trim curves: the stack holds only
 * parameter intervals (and two numbers each), and every popped piece is
 * recomputed from the record's control points (already in the ray's frame)
 * by restricting them to its interval, two de Casteljau splits per
 * direction. The loop is a runtime loop (its trip count is the number of
 * pieces popped); the restriction and the box are unrolled for the key's
 * degrees. */
#include "subdiv.h"

#define HUGE_DEPTH 3.0e38f
/* How far, as a fraction of the tolerance, a ray may pass outside a leaf's
 * quad of corners and still cross it: the surface bulges out of the quad
 * by its curvature times the leaf's size squared, most beside a
 * silhouette. */
#define QUAD_SLACK 0.01f

/* |x − y| for two points. */
static scg_value distance(scg_builder *b, scg_value x, scg_value y)
{
    return scg_length(b, scg_sub(b, x, y));
}

void scg_piece_push(scg_builder *b, const scg_pieces *s, scg_value iv, scg_value meta)
{
    scg_value sp = scg_load(b, s->sp);
    scg_store_at(b, s->stack, sp, iv);
    scg_store_at(b, s->meta, sp, meta);
    scg_store(b, s->sp, scg_add(b, sp, scg_const_i(b, 1)));
}

scg_value scg_piece_box(scg_isect *c, const scg_pieces *s, scg_value iv, scg_value *e,
                        scg_value *homogeneous, scg_value *near, scg_value *size)
{
    scg_builder *b = c->b;
    int n = (c->p + 1) * (c->q + 1);
    scg_isect_restricted_points(c, iv, e, homogeneous);
    scg_name(b, "box");
    scg_value lo = e[0], hi = e[0];
    for (int k = 1; k < n; k++) {
        lo = scg_min(b, lo, e[k]);
        hi = scg_max(b, hi, e[k]);
    }
    scg_value lo_x = scg_comp(b, lo, 0), lo_y = scg_comp(b, lo, 1);
    *near = scg_comp(b, lo, 2);
    scg_value hi_x = scg_comp(b, hi, 0), hi_y = scg_comp(b, hi, 1);
    scg_value x_above = scg_le(b, lo_x, c->zero);
    scg_value x_in = scg_and(b, x_above, scg_le(b, c->zero, hi_x));
    scg_value y_above = scg_le(b, lo_y, c->zero);
    scg_value y_in = scg_and(b, y_above, scg_le(b, c->zero, hi_y));
    scg_value best = scg_load(b, s->best);
    scg_value nearer = scg_lt(b, *near, best);
    scg_value on_ray = scg_and(b, x_in, y_in);
    scg_value holds = scg_and(b, on_ray, nearer);
    scg_name(b, "size");
    scg_value extent = scg_sub(b, hi, lo);
    scg_value ex = scg_comp(b, extent, 0), ey = scg_comp(b, extent, 1);
    scg_value ez = scg_comp(b, extent, 2);
    *size = scg_add(b, scg_add(b, ex, ey), ez);
    scg_name(b, NULL);
    return holds;
}

void scg_piece_hit(scg_isect *c, const scg_pieces *s, scg_value iv, scg_value near)
{
    scg_builder *b = c->b;
    scg_store(b, s->best, near);
    scg_value half = scg_const_f(b, 0.5f);
    scg_value u0 = scg_comp(b, iv, 0), v0 = scg_comp(b, iv, 2);
    scg_value u_ends = scg_add(b, u0, scg_comp(b, iv, 1));
    scg_value u_mid = scg_mul(b, u_ends, half);
    scg_value v_ends = scg_add(b, v0, scg_comp(b, iv, 3));
    scg_value v_mid = scg_mul(b, v_ends, half);
    scg_store(b, c->uv_var, scg_vec2(b, u_mid, v_mid));
    scg_store(b, c->found_var, scg_const_b(b, true));
}

/* True when the ray (the origin of the frame's first two coordinates)
 * passes within `slack` of the quad a, b, c, d (corners in order): each
 * edge's cross product with the origin, its distance from the edge's line
 * times the edge's length, keeps one sign but for slack · length. A
 * collapsed edge gives 0 and does not decide. */
static scg_value quad_holds_ray(scg_builder *b, scg_value a, scg_value bb, scg_value c,
                                scg_value d, scg_value slack)
{
    scg_value corners[5] = {a, bb, c, d, a};
    scg_value none_neg = 0, none_pos = 0;
    scg_name(b, "quad");
    for (int k = 0; k < 4; k++) {
        scg_value x0 = scg_comp(b, corners[k], 0), y0 = scg_comp(b, corners[k], 1);
        scg_value x1 = scg_comp(b, corners[k + 1], 0), y1 = scg_comp(b, corners[k + 1], 1);
        scg_value side = scg_products_difference(b, x0, y1, y0, x1);
        scg_value edge_x = scg_sub(b, x1, x0);
        scg_value edge = scg_vec2(b, edge_x, scg_sub(b, y1, y0));
        scg_value give = scg_mul(b, slack, scg_length(b, edge));
        scg_value not_neg = scg_le(b, scg_neg(b, give), side);
        scg_value not_pos = scg_le(b, side, give);
        none_neg = k ? scg_and(b, none_neg, not_neg) : not_neg;
        none_pos = k ? scg_and(b, none_pos, not_pos) : not_pos;
    }
    scg_name(b, NULL);
    return scg_or(b, none_neg, none_pos);
}

/* Popped piece iv (its parent's box nearest at meta.x, of L1 size meta.y):
 * box test, leaf or split. */
static void visit(scg_isect *c, const scg_pieces *s, scg_value iv, scg_value meta_v)
{
    scg_builder *b = c->b;
    scg_value e[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)];
    int p = c->p, q = c->q, n = (p + 1) * (q + 1);
    scg_value near, size;
    scg_value holds = scg_piece_box(c, s, iv, e, NULL, &near, &size);
    scg_if(b, holds);
    scg_value iters = scg_load(b, c->iters_var);
    scg_store(b, c->iters_var, scg_add(b, iters, scg_const_i(b, 1)));
    scg_name(b, "leaf");
    scg_value small = scg_lt(b, size, c->tol);
    scg_value stuck = scg_le(b, scg_comp(b, meta_v, 1), size);
    /* Two more entries must fit; a full stack ends the descent here. */
    scg_value sp = scg_load(b, s->sp);
    scg_value full = scg_lt(b, scg_const_i(b, s->depth - 2), sp);
    scg_value fine = scg_or(b, small, stuck);
    scg_value leaf = scg_or(b, fine, full);
    scg_name(b, NULL);
    scg_value half = scg_const_f(b, 0.5f);
    scg_value c00 = e[0], c10 = e[p], c01 = e[q * (p + 1)], c11 = e[n - 1];
    scg_if(b, leaf);
    /* A leaf this small is flat to second order: the ray crosses it when
     * it passes inside the quad of its corners, which the box of its
     * points, a tolerance wide, overstates. Beside a silhouette the box
     * alone drew rays that pass the surface by a fraction of the tolerance
     * as hits (the teaspoon at 256x256: 0.22 % of its pixels). A piece the
     * full stack stops keeps the box's answer. */
    scg_value never = scg_const_b(b, false);
    scg_value slack = scg_mul(b, c->tol, scg_const_f(b, QUAD_SLACK));
    scg_value crosses = scg_or(b, never, quad_holds_ray(b, c00, c10, c11, c01, slack));
    scg_if(b, crosses);
    scg_piece_hit(c, s, iv, near);
    scg_endif(b);
    scg_else(b);
    /* The longer direction, by the lengths of the net's boundary edges;
     * the nearer half, by the depths of its corners. */
    scg_name(b, "split");
    scg_value len_u = scg_add(b, distance(b, c10, c00), distance(b, c11, c01));
    scg_value len_v = scg_add(b, distance(b, c01, c00), distance(b, c11, c10));
    scg_value along_u = scg_le(b, len_v, len_u);
    scg_value z00 = scg_comp(b, c00, 2), z10 = scg_comp(b, c10, 2);
    scg_value z01 = scg_comp(b, c01, 2), z11 = scg_comp(b, c11, 2);
    scg_value first_u = scg_lt(b, scg_add(b, z00, z01), scg_add(b, z10, z11));
    scg_value first_v = scg_lt(b, scg_add(b, z00, z10), scg_add(b, z01, z11));
    scg_value low_first = scg_select(b, along_u, first_u, first_v);
    scg_value u0 = scg_comp(b, iv, 0), u1 = scg_comp(b, iv, 1);
    scg_value v0 = scg_comp(b, iv, 2), v1 = scg_comp(b, iv, 3);
    scg_value um = scg_mul(b, scg_add(b, u0, u1), half);
    scg_value vm = scg_mul(b, scg_add(b, v0, v1), half);
    scg_value low_u = scg_vec4(b, u0, um, v0, v1), high_u = scg_vec4(b, um, u1, v0, v1);
    scg_value low_v = scg_vec4(b, u0, u1, v0, vm), high_v = scg_vec4(b, u0, u1, vm, v1);
    scg_value low = scg_select(b, along_u, low_u, low_v);
    scg_value high = scg_select(b, along_u, high_u, high_v);
    scg_value near_size = scg_vec2(b, near, size);
    scg_name(b, NULL);
    /* The nearer half goes on top, so it is searched first. */
    scg_piece_push(b, s, scg_select(b, low_first, high, low), near_size);
    scg_piece_push(b, s, scg_select(b, low_first, low, high), near_size);
    scg_endif(b);
    scg_endif(b);
}

void scg_piece_search(scg_isect *c, scg_value lo, scg_value hi, int depth, int steps,
                      scg_value wanted, scg_piece_visit on_piece)
{
    scg_builder *b = c->b;
    scg_value lo_u = scg_comp(b, lo, 0), hi_u = scg_comp(b, hi, 0);
    scg_value lo_v = scg_comp(b, lo, 1), hi_v = scg_comp(b, hi, 1);
    scg_value root = scg_vec4(b, lo_u, hi_u, lo_v, hi_v);
    scg_pieces s = {.depth = depth};
    scg_name(b, "stack");
    s.stack = scg_var(b, SCG_VEC4, depth, 0);
    s.meta = scg_var(b, SCG_VEC2, depth, 0);
    s.sp = scg_var(b, SCG_INT, 0, scg_const_i(b, 0));
    scg_name(b, "best");
    s.best = scg_var(b, SCG_FLOAT, 0, scg_const_f(b, HUGE_DEPTH));
    scg_name(b, NULL);
    scg_value far = scg_const_f(b, HUGE_DEPTH);
    scg_piece_push(b, &s, root, scg_vec2(b, scg_neg(b, far), far));
    /* A ray that needs no search starts with an empty stack rather than
     * inside an `if`: the loop's first test then ends it, where an `if`
     * would still cost a pass of the loop on a GPU that runs both sides
     * of a branch under a mask (llvmpipe). */
    if (wanted)
        scg_store(b, s.sp, scg_select(b, wanted, scg_const_i(b, 1), scg_const_i(b, 0)));
    scg_loop(b, scg_const_i(b, steps));
    scg_value sp = scg_load(b, s.sp);
    scg_if(b, scg_le(b, sp, scg_const_i(b, 0)));
    scg_break(b);
    scg_endif(b);
    scg_value top = scg_sub(b, sp, scg_const_i(b, 1));
    scg_store(b, s.sp, top);
    scg_name(b, "piece");
    scg_value iv = scg_load_at(b, s.stack, top);
    scg_value meta_v = scg_load_at(b, s.meta, top);
    scg_name(b, NULL);
    /* The parent's box bounds the piece's: behind the best leaf, skip it
     * without recomputing it. */
    scg_if(b, scg_lt(b, scg_comp(b, meta_v, 0), scg_load(b, s.best)));
    on_piece(c, &s, iv, meta_v);
    scg_endif(b);
    scg_endloop(b);
}

void scg_piece_method(scg_isect *c, scg_value uv0, scg_value behind, int depth, int steps,
                      scg_piece_visit on_piece)
{
    scg_builder *b = c->b;
    scg_isect_vars(c, uv0, behind);
    scg_name(b, "found");
    c->found_var = scg_var(b, SCG_BOOL, 0, scg_const_b(b, false));
    scg_name(b, NULL);
    scg_value wanted = behind ? scg_not(b, behind) : 0;
    scg_piece_search(c, c->dom_lo, c->dom_hi, depth, steps, wanted, on_piece);
}

void scg_method_subdiv(scg_isect *c, scg_value uv0, scg_value behind)
{
    int depth = c->key->max_iters;
    scg_piece_method(c, uv0, behind, depth, depth * SCG_SUBDIV_STEPS_PER_LEVEL, visit);
}
