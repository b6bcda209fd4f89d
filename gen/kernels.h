/* kernels.h — the metaprograms' building blocks: C functions that write IR
 * evaluating a tensor patch and its first partials, unrolled for given
 * degrees (de Casteljau / de Boor, or Bernstein basis sums), the knot-span
 * search over the knot texture, and the generic evaluation with runtime
 * loops over degrees read from the record. The Newton metaprogram
 * (newton.c) assembles them into whole programs.
 *
 * Control points are IR values of any float type (vec2 after projection
 * onto the ray's planes, vec3/vec4 homogeneous); `pts` holds
 * (deg_u+1)·(deg_v+1) of them, point (i, j) at pts[j·(deg_u+1) + i]. */
#ifndef SCG_KERNELS_H
#define SCG_KERNELS_H

#include "ir.h"

/* One parameter direction of an unrolled evaluation at parameter t. De
 * Casteljau and de Boor are the same triangle of blends d_j ← d_{j-1} +
 * (d_j - d_{j-1})·alpha[r][j] (level r = 1 … p, j = r … p); they differ only
 * in alpha: t for Bézier, (t - τ_{k-p+j}) / (τ_{k+1+j-r} - τ_{k-p+j}) in
 * span k for B-splines. After level p-1 two points a, b remain; the value
 * is a + (b - a)·alpha[p][p] and the derivative (b - a)·scale, scale being
 * p for Bézier and p / (τ_{k+1} - τ_k) for B-splines. */
typedef struct scg_dir {
    int degree;
    scg_value t, one_minus_t;          /* float */
    scg_value alpha[SCG_MAX_DEGREE + 1][SCG_MAX_DEGREE + 1];
    scg_value scale;                   /* float */
} scg_dir;

/* A Bézier direction (parameter in [0, 1]). */
void scg_dir_bezier(scg_builder *b, int degree, scg_value t, scg_dir *d);
/* A B-spline direction in span k: knots[m] = τ_{k-p+1+m}, m = 0 … 2p-1. */
void scg_dir_nurbs(scg_builder *b, int degree, scg_value t, const scg_value *knots,
                   scg_dir *d);

/* Point and partials: out[0] = S, out[1] = ∂S/∂u, out[2] = ∂S/∂v (the
 * points' type). De Casteljau / de Boor form: */
void scg_eval_tensor_dc(scg_builder *b, const scg_value *pts, const scg_dir *u,
                        const scg_dir *v, scg_value out[3]);
/* Bernstein basis form (Bézier directions only): basis functions by their
 * recurrence, derivatives from the degree p-1 basis, then weighted sums. */
void scg_eval_tensor_basis(scg_builder *b, const scg_value *pts, const scg_dir *u,
                           const scg_dir *v, scg_value out[3]);

/* Power form (Bézier directions only). scg_power_coefficients turns the
 * net into the coefficients of Σ a_kl u^k v^l, a_kl at out[l·(p+1) + k]:
 * along each direction the k-th forward difference of the points times
 * C(degree, k). scg_eval_tensor_power evaluates them and the partials by
 * Horner's rule, value and derivative in one sweep. Far fewer operations
 * than de Casteljau for low degrees; the coefficients grow with the degree
 * (up to 2^degree times the points' size each way), so the rounding error
 * does too (docs/compiler.md, "The power form"). */
void scg_power_coefficients(scg_builder *b, const scg_value *pts, int p, int q, scg_value *out);
void scg_eval_tensor_power(scg_builder *b, const scg_value *coef, const scg_dir *u,
                           const scg_dir *v, scg_value out[3]);

/* Index k of the knot span holding t (τ_k <= t < τ_{k+1}, clamped to
 * [p, n-1]) by binary search over the knot texture from knot_offset, as a
 * runtime loop. n = number of control points; ints p, n, knot_offset. */
scg_value scg_span_search(scg_builder *b, scg_value t, scg_value knot_offset, scg_value n,
                          scg_value degree);

/* Generic evaluation (runtime loops, degrees from the record): homogeneous
 * vec4 point and partials of the record's patch at (t_u, t_v). For NURBS
 * the spans are searched in the knot texture; for Bézier records the
 * parameters are local [0, 1]. All arguments are IR values; cp_offset, nu,
 * the knot offsets and degrees are ints. */
typedef struct scg_generic_patch {
    bool nurbs;
    scg_value cp_offset, nu, nv, deg_u, deg_v, knot_u, knot_v;
} scg_generic_patch;
void scg_eval_generic(scg_builder *b, const scg_generic_patch *patch, scg_value t_u,
                      scg_value t_v, scg_value out[3]);

#endif
