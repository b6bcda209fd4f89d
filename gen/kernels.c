/* kernels.c — metaprograms for surface evaluation. The unrolled forms write
 * one straight-line IR sequence for exactly the degrees asked for (every
 * de Casteljau / de Boor blend and every basis product spelled out); the
 * generic form writes runtime loops over degrees read from the record, with
 * local arrays, for degrees too high to unroll profitably. As everywhere in
 * the compiler, an argument list holds at most one call that creates
 * instructions, so that the program does not depend on the order in which
 * the C compiler evaluates arguments. */
#include "kernels.h"

void scg_dir_bezier(scg_builder *b, int degree, scg_value t, scg_dir *d)
{
    d->degree = degree;
    d->t = t;
    d->one_minus_t = scg_sub(b, scg_const_f(b, 1.0f), t);
    for (int r = 1; r <= degree; r++)
        for (int j = r; j <= degree; j++)
            d->alpha[r][j] = t;
    d->scale = scg_const_f(b, (float)degree);
}

void scg_dir_nurbs(scg_builder *b, int degree, scg_value t, const scg_value *knots,
                   scg_dir *d)
{
    int p = degree;
    d->degree = p;
    d->t = t;
    d->one_minus_t = 0;
    /* alpha[r][j] = (t - τ_{k-p+j}) / (τ_{k+1+j-r} - τ_{k-p+j}); with
     * knots[m] = τ_{k-p+1+m} that is (t - knots[j-1]) / (knots[p+j-r] -
     * knots[j-1]). The denominators span at least the non-empty span k. */
    for (int r = 1; r <= p; r++)
        for (int j = r; j <= p; j++) {
            scg_value from_left = scg_sub(b, t, knots[j - 1]);
            scg_value width = scg_sub(b, knots[p + j - r], knots[j - 1]);
            d->alpha[r][j] = scg_div(b, from_left, width);
        }
    scg_value degree_f = scg_const_f(b, (float)p);
    d->scale = scg_div(b, degree_f, scg_sub(b, knots[p], knots[p - 1]));
}

/* Runs blend levels 1 … upto of the triangle on d[0 … p] in place. */
static void blend_levels(scg_builder *b, scg_value *d, const scg_dir *dir, int upto)
{
    for (int r = 1; r <= upto; r++)
        for (int j = dir->degree; j >= r; j--)
            d[j] = scg_lerp(b, d[j - 1], d[j], dir->alpha[r][j]);
}

void scg_eval_tensor_dc(scg_builder *b, const scg_value *pts, const scg_dir *u,
                        const scg_dir *v, scg_value out[3])
{
    int p = u->degree, q = v->degree;
    scg_value rows[SCG_MAX_DEGREE + 1], drows[SCG_MAX_DEGREE + 1], d[SCG_MAX_DEGREE + 1];
    /* Each row (fixed j) becomes its point and u-derivative at t_u. */
    for (int j = 0; j <= q; j++) {
        for (int i = 0; i <= p; i++)
            d[i] = pts[j * (p + 1) + i];
        blend_levels(b, d, u, p - 1);
        scg_value diff = scg_sub(b, d[p], d[p - 1]);
        rows[j] = scg_add(b, d[p - 1], scg_mul(b, diff, u->alpha[p][p]));
        drows[j] = scg_mul(b, diff, u->scale);
    }
    /* Then the column of row points gives S and Sv, the column of row
     * derivatives Su. */
    blend_levels(b, rows, v, q - 1);
    scg_name(b, "Sv");
    scg_value diff = scg_sub(b, rows[q], rows[q - 1]);
    out[2] = scg_mul(b, diff, v->scale);
    scg_name(b, "S");
    out[0] = scg_add(b, rows[q - 1], scg_mul(b, diff, v->alpha[q][q]));
    scg_name(b, NULL);
    blend_levels(b, drows, v, q - 1);
    scg_name(b, "Su");
    out[1] = scg_lerp(b, drows[q - 1], drows[q], v->alpha[q][q]);
    scg_name(b, NULL);
}

/* Bernstein basis B_i^p(t), i = 0 … p, and derivatives, by the recurrence
 * B_i^k = (1-t) B_i^{k-1} + t B_{i-1}^{k-1}; the derivative uses the
 * degree p-1 functions: p (B_{i-1}^{p-1} - B_i^{p-1}). */
static void bernstein(scg_builder *b, const scg_dir *d, scg_value *basis, scg_value *deriv)
{
    int p = d->degree;
    scg_value prev[SCG_MAX_DEGREE + 1], cur[SCG_MAX_DEGREE + 1];
    prev[0] = scg_const_f(b, 1.0f);
    for (int k = 1; k <= p; k++) {
        if (k == p) {
            deriv[0] = scg_mul(b, scg_neg(b, prev[0]), d->scale);
            for (int i = 1; i < p; i++)
                deriv[i] = scg_mul(b, scg_sub(b, prev[i - 1], prev[i]), d->scale);
            deriv[p] = scg_mul(b, prev[p - 1], d->scale);
        }
        cur[0] = scg_mul(b, d->one_minus_t, prev[0]);
        for (int i = 1; i < k; i++) {
            scg_value stays = scg_mul(b, d->one_minus_t, prev[i]);
            scg_value moves = scg_mul(b, d->t, prev[i - 1]);
            cur[i] = scg_add(b, stays, moves);
        }
        cur[k] = scg_mul(b, d->t, prev[k - 1]);
        for (int i = 0; i <= k; i++)
            prev[i] = cur[i];
    }
    for (int i = 0; i <= p; i++)
        basis[i] = prev[i];
}

/* Σ w[i] · x[i]. */
static scg_value weighted_sum(scg_builder *b, const scg_value *x, int stride,
                              const scg_value *w, int n)
{
    scg_value sum = scg_mul(b, x[0], w[0]);
    for (int i = 1; i < n; i++)
        sum = scg_add(b, sum, scg_mul(b, x[i * stride], w[i]));
    return sum;
}

void scg_eval_tensor_basis(scg_builder *b, const scg_value *pts, const scg_dir *u,
                           const scg_dir *v, scg_value out[3])
{
    int p = u->degree, q = v->degree;
    scg_value bu[SCG_MAX_DEGREE + 1], du[SCG_MAX_DEGREE + 1];
    scg_value bv[SCG_MAX_DEGREE + 1], dv[SCG_MAX_DEGREE + 1];
    scg_value rows[SCG_MAX_DEGREE + 1], drows[SCG_MAX_DEGREE + 1];
    bernstein(b, u, bu, du);
    bernstein(b, v, bv, dv);
    for (int j = 0; j <= q; j++) {
        rows[j] = weighted_sum(b, pts + j * (p + 1), 1, bu, p + 1);
        drows[j] = weighted_sum(b, pts + j * (p + 1), 1, du, p + 1);
    }
    scg_name(b, "S");
    out[0] = weighted_sum(b, rows, 1, bv, q + 1);
    scg_name(b, "Su");
    out[1] = weighted_sum(b, drows, 1, bv, q + 1);
    scg_name(b, "Sv");
    out[2] = weighted_sum(b, rows, 1, dv, q + 1);
    scg_name(b, NULL);
}

/* C(n, k) · Δ^k x[0] for k = 0 … n, stride apart in x and out. */
static void power_along(scg_builder *b, const scg_value *x, int stride, int n, scg_value *out)
{
    scg_value diff[SCG_MAX_DEGREE + 1];
    for (int i = 0; i <= n; i++)
        diff[i] = x[i * stride];
    long binom = 1;
    for (int k = 0; k <= n; k++) {
        out[k * stride] = k == 0 || binom == 1 ? diff[0]
                                               : scg_mul(b, diff[0], scg_const_f(b, (float)binom));
        binom = binom * (n - k) / (k + 1);
        for (int i = 0; i < n - k; i++)
            diff[i] = scg_sub(b, diff[i + 1], diff[i]);
    }
}

void scg_power_coefficients(scg_builder *b, const scg_value *pts, int p, int q, scg_value *out)
{
    scg_value along_u[(SCG_MAX_DEGREE + 1) * (SCG_MAX_DEGREE + 1)];
    for (int j = 0; j <= q; j++)
        power_along(b, pts + j * (p + 1), 1, p, along_u + j * (p + 1));
    for (int k = 0; k <= p; k++)
        power_along(b, along_u + k, p + 1, q, out + k);
}

/* Σ c[k·stride] t^k by Horner's rule, and its derivative from the same
 * sweep's partial sums s_k (d ← d·t + s_k), each under its own name. */
static void horner(scg_builder *b, const scg_value *c, int stride, int n, scg_value t,
                   const char *value_name, scg_value *value, const char *deriv_name,
                   scg_value *deriv)
{
    scg_value partial[SCG_MAX_DEGREE + 1];
    scg_name(b, value_name);
    partial[n] = c[n * stride];
    for (int k = n - 1; k >= 0; k--)
        partial[k] = scg_add(b, scg_mul(b, partial[k + 1], t), c[k * stride]);
    *value = partial[0];
    if (deriv) {
        scg_name(b, deriv_name);
        scg_value d = partial[n];
        for (int k = n - 1; k >= 1; k--)
            d = scg_add(b, scg_mul(b, d, t), partial[k]);
        *deriv = d;
    }
    scg_name(b, NULL);
}

void scg_eval_tensor_power(scg_builder *b, const scg_value *coef, const scg_dir *u,
                           const scg_dir *v, scg_value out[3])
{
    int p = u->degree, q = v->degree;
    scg_value rows[SCG_MAX_DEGREE + 1], drows[SCG_MAX_DEGREE + 1];
    /* Each row (fixed power of v) becomes its value and u-derivative; then
     * the column of row values gives S and Sv, that of derivatives Su. */
    for (int l = 0; l <= q; l++)
        horner(b, coef + l * (p + 1), 1, p, u->t, NULL, &rows[l], NULL, &drows[l]);
    horner(b, rows, 1, q, v->t, "S", &out[0], "Sv", &out[2]);
    horner(b, drows, 1, q, v->t, "Su", &out[1], NULL, NULL);
}

scg_value scg_span_search(scg_builder *b, scg_value t, scg_value knot_offset, scg_value n,
                          scg_value degree)
{
    /* Invariant τ_lo <= t < τ_hi, narrowed by halving: at most 24 rounds
     * for the 2^24 texels a float-indexed layout can address. */
    scg_value one = scg_const_i(b, 1);
    scg_value lo = scg_var(b, SCG_INT, 0, degree);
    scg_value hi = scg_var(b, SCG_INT, 0, n);
    scg_loop(b, scg_const_i(b, 24));
    scg_value l = scg_load(b, lo), h = scg_load(b, hi);
    scg_if(b, scg_le(b, scg_sub(b, h, l), one));
    scg_break(b);
    scg_endif(b);
    scg_value sum = scg_add(b, l, h);
    scg_value mid = scg_div(b, sum, scg_const_i(b, 2));
    scg_value knot = scg_fetch(b, SCG_TEX_KNOTS, scg_add(b, knot_offset, mid));
    scg_value below = scg_lt(b, t, knot);
    scg_store(b, hi, scg_select(b, below, mid, h));
    scg_store(b, lo, scg_select(b, below, l, mid));
    scg_endloop(b);
    scg_name(b, "span");
    scg_value span = scg_load(b, lo);
    scg_name(b, NULL);
    return span;
}

/* Runtime-loop basis of one direction: values N[0 … p] and derivatives
 * D[0 … p] of the functions N_{k-p+r}, r = 0 … p, by the Cox–de Boor
 * triangle (Piegl & Tiller A2.2) in local arrays. Bézier directions use the
 * implied knots 0 … 0 1 … 1, for which every left is t and right 1 - t. */
typedef struct generic_dir {
    bool nurbs;
    scg_value t, degree, span, knot_offset;
} generic_dir;

static scg_value knot_at(scg_builder *b, const generic_dir *d, scg_value index)
{
    return scg_fetch(b, SCG_TEX_KNOTS, scg_add(b, d->knot_offset, index));
}

static void generic_basis(scg_builder *b, const generic_dir *d, scg_value nvar, scg_value dvar)
{
    enum { LEN = SCG_MAX_DEGREE + 1 };
    scg_value one_i = scg_const_i(b, 1), one = scg_const_f(b, 1.0f), zero = scg_const_f(b, 0.0f);
    scg_value left = scg_var(b, SCG_FLOAT, LEN, 0);
    scg_value right = scg_var(b, SCG_FLOAT, LEN, 0);
    scg_value lower = scg_var(b, SCG_FLOAT, LEN, 0);   /* degree p-1 functions */
    scg_store_at(b, nvar, scg_const_i(b, 0), one);
    scg_value jj = scg_loop(b, d->degree);
    {
        scg_value j = scg_add(b, jj, one_i);
        /* Entering the last round: keep the degree p-1 functions. */
        scg_if(b, scg_eq(b, j, d->degree));
        scg_value k = scg_loop(b, d->degree);
        scg_store_at(b, lower, k, scg_load_at(b, nvar, k));
        scg_endloop(b);
        scg_endif(b);
        if (d->nurbs) {
            scg_store_at(b, left, j,
                         scg_sub(b, d->t, knot_at(b, d, scg_sub(b, scg_add(b, d->span, one_i), j))));
            scg_store_at(b, right, j, scg_sub(b, knot_at(b, d, scg_add(b, d->span, j)), d->t));
        } else {
            scg_store_at(b, left, j, d->t);
            scg_store_at(b, right, j, scg_sub(b, one, d->t));
        }
        scg_value saved = scg_var(b, SCG_FLOAT, 0, zero);
        scg_value r = scg_loop(b, j);
        {
            scg_value r1 = scg_add(b, r, one_i), jr = scg_sub(b, j, r);
            scg_value right_r1 = scg_load_at(b, right, r1), left_jr = scg_load_at(b, left, jr);
            scg_value n_r = scg_load_at(b, nvar, r);
            scg_value temp = scg_div(b, n_r, scg_add(b, right_r1, left_jr));
            scg_value carried = scg_load(b, saved);
            scg_store_at(b, nvar, r, scg_add(b, carried, scg_mul(b, right_r1, temp)));
            scg_store(b, saved, scg_mul(b, left_jr, temp));
        }
        scg_endloop(b);
        scg_store_at(b, nvar, j, scg_load(b, saved));
    }
    scg_endloop(b);
    /* N'_{k-p+r} = p (lower[r-1] / (τ_{k+r} - τ_{k-p+r})
     *              - lower[r] / (τ_{k+r+1} - τ_{k-p+r+1})), the terms with
     * lower[-1] and lower[p] being zero. */
    scg_value pf = scg_i2f(b, d->degree);
    scg_value rr = scg_loop(b, scg_add(b, d->degree, one_i));
    {
        scg_value has_left = scg_lt(b, scg_const_i(b, 0), rr);
        scg_value has_right = scg_lt(b, rr, d->degree);
        scg_value rr_before = scg_sub(b, rr, one_i);
        scg_value lo_left = scg_load_at(b, lower, scg_max(b, rr_before, scg_const_i(b, 0)));
        scg_value lo_right = scg_load_at(b, lower, scg_min(b, rr, scg_sub(b, d->degree, one_i)));
        scg_value den_left = one, den_right = one;
        if (d->nurbs) {
            scg_value base = scg_sub(b, d->span, d->degree);
            scg_value left_end = knot_at(b, d, scg_add(b, d->span, rr));
            scg_value left_start = knot_at(b, d, scg_add(b, base, rr));
            den_left = scg_sub(b, left_end, left_start);
            scg_value right_end = knot_at(b, d, scg_add(b, scg_add(b, d->span, rr), one_i));
            scg_value right_start = knot_at(b, d, scg_add(b, scg_add(b, base, rr), one_i));
            den_right = scg_sub(b, right_end, right_start);
        }
        scg_value term_left = scg_select(b, has_left, scg_div(b, lo_left, den_left), zero);
        scg_value term_right = scg_select(b, has_right, scg_div(b, lo_right, den_right), zero);
        scg_store_at(b, dvar, rr, scg_mul(b, pf, scg_sub(b, term_left, term_right)));
    }
    scg_endloop(b);
}

/* sum_var += x · weight. */
static void accumulate(scg_builder *b, scg_value sum_var, scg_value x, scg_value weight)
{
    scg_value sum = scg_load(b, sum_var);
    scg_value term = scg_mul(b, x, weight);
    scg_store(b, sum_var, scg_add(b, sum, term));
}

void scg_eval_generic(scg_builder *b, const scg_generic_patch *patch, scg_value t_u,
                      scg_value t_v, scg_value out[3])
{
    enum { LEN = SCG_MAX_DEGREE + 1 };
    generic_dir du = {patch->nurbs, t_u, patch->deg_u, patch->deg_u, patch->knot_u};
    generic_dir dv = {patch->nurbs, t_v, patch->deg_v, patch->deg_v, patch->knot_v};
    if (patch->nurbs) {
        du.span = scg_span_search(b, t_u, patch->knot_u, patch->nu, patch->deg_u);
        dv.span = scg_span_search(b, t_v, patch->knot_v, patch->nv, patch->deg_v);
    }
    scg_value nu_var = scg_var(b, SCG_FLOAT, LEN, 0), du_var = scg_var(b, SCG_FLOAT, LEN, 0);
    scg_value nv_var = scg_var(b, SCG_FLOAT, LEN, 0), dv_var = scg_var(b, SCG_FLOAT, LEN, 0);
    generic_basis(b, &du, nu_var, du_var);
    generic_basis(b, &dv, nv_var, dv_var);

    float zeros[4] = {0, 0, 0, 0};
    scg_value zero4 = scg_const_vec(b, 4, zeros);
    scg_value s = scg_var(b, SCG_VEC4, 0, zero4);
    scg_value su = scg_var(b, SCG_VEC4, 0, zero4);
    scg_value sv = scg_var(b, SCG_VEC4, 0, zero4);
    scg_value one_i = scg_const_i(b, 1);
    /* First control point of the patch's span block, then row by row. */
    scg_value first_row = scg_sub(b, dv.span, patch->deg_v);
    scg_value first_col = scg_sub(b, du.span, patch->deg_u);
    scg_value block = scg_add(b, scg_mul(b, first_row, patch->nu), first_col);
    scg_value first = scg_add(b, patch->cp_offset, block);
    scg_value j = scg_loop(b, scg_add(b, patch->deg_v, one_i));
    {
        scg_value row = scg_add(b, first, scg_mul(b, j, patch->nu));
        scg_value row_sum = scg_var(b, SCG_VEC4, 0, zero4);
        scg_value row_du = scg_var(b, SCG_VEC4, 0, zero4);
        scg_value i = scg_loop(b, scg_add(b, patch->deg_u, one_i));
        {
            scg_value pt = scg_fetch(b, SCG_TEX_POINTS, scg_add(b, row, i));
            accumulate(b, row_sum, pt, scg_load_at(b, nu_var, i));
            accumulate(b, row_du, pt, scg_load_at(b, du_var, i));
        }
        scg_endloop(b);
        scg_value bv = scg_load_at(b, nv_var, j), dbv = scg_load_at(b, dv_var, j);
        scg_value rs = scg_load(b, row_sum), rd = scg_load(b, row_du);
        accumulate(b, s, rs, bv);
        accumulate(b, su, rd, bv);
        accumulate(b, sv, rs, dbv);
    }
    scg_endloop(b);
    scg_name(b, "S");
    out[0] = scg_load(b, s);
    scg_name(b, "Su");
    out[1] = scg_load(b, su);
    scg_name(b, "Sv");
    out[2] = scg_load(b, sv);
    scg_name(b, NULL);
}
