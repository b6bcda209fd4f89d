/* tri_newton.c — the intersection metaprogram of triangular Bézier height
 * patches (`tri` keys), after Reis, Zeilfelder, Hering-Bertram, Farin and
 * Hagen (seed 004, section V). The ray is clipped to the patch's prism (the
 * domain triangle times the range of the BB-coefficients' heights); along
 * the projected ray the patch is a univariate polynomial whose
 * BB-coefficients are blossoms b[u1^(n-i), u2^i] of the end points' barycentric
 * coordinates; minus the ray's own height (linear, so its BB-coefficients
 * are its values at i/n) it is g(s), whose roots in [0, 1] are the ray's
 * hits. Newton's method runs on g from the four secure starts
 * (0, the inflection points, 1) at once in a vec4, unrolled; the smallest
 * converged root in [0, 1] is the hit. Point and normal come from the
 * patch itself (de Casteljau in 3D at the hit), not from the ray.
 *
 * Record and point layout: gpu_layout.h ("triangular records"). As in
 * newton.c, no argument list holds more than one call that creates
 * instructions, so that value numbers follow the source. */
#include "tri_newton.h"

/* Barycentric slack at the domain's edges: a ray through a shared edge
 * must not slip between the two neighbours' clipped segments by rounding.
 * (10^-4 gave false hits: a patch's polynomial continued past a crease or
 * the mesh's border.) */
#define EDGE_SLACK 1.0e-5f
/* Fraction of the tolerance by which g's BB-coefficients must clear zero
 * for the ray to be rejected before any iteration (no_root). */
#define ROOT_MARGIN 0.01f
/* Relative slack of the prism's height range, for rays grazing its top;
 * never below the tolerance (prism_segment). */
#define HEIGHT_SLACK 1.0e-4f
/* Stand-in for "unbounded" in the clipping of the ray to the prism. */
#define FAR 1.0e30f
/* The iteration stops when every start's step, in object units, is below
 * this fraction of the tolerance (the step is taken, as in newton.c). */
#define STOP_FRACTION 0.3f
/* Newton steps are damped by g'/(g'^2 + TINY) instead of 1/g': a flat spot
 * of g gives a large step, which the clamp below keeps finite, not a NaN. */
#define TINY 1.0e-30f
/* Iterates are kept in [-CLAMP, 1 + CLAMP]: a root in [0, 1] is never
 * lost by it, and a start heading away stays finite. */
#define CLAMP 0.25f
/* Roots this far outside [0, 1] (in s) still count, for hits on the edges. */
#define S_SLACK 1.0e-4f

typedef struct tri_ctx {
    scg_builder *b;
    const scg_key *key;
    int n, ncoef;
    scg_value origin, dir, dir_len, tol, zero, one;
    scg_value rec, surface;
    scg_value pts[(SCG_MAX_TRI_DEGREE + 1) * (SCG_MAX_TRI_DEGREE + 2) / 2];   /* vec3 */
    scg_value z[(SCG_MAX_TRI_DEGREE + 1) * (SCG_MAX_TRI_DEGREE + 2) / 2];     /* heights */
} tri_ctx;

/* sc_tri_index (runtime/terrain/tri_bezier.h), which gen/ cannot include. */
static int tri_index(int n, int i, int j)
{
    int r = n - i, k = n - i - j;
    return r * (r + 1) / 2 + k;
}

/* One de Casteljau step with barycentric weights l[3] on a net of degree m
 * (scalars or vectors alike): the net of degree m - 1. */
static void casteljau_step(scg_builder *b, int m, const scg_value *net, const scg_value l[3],
                           scg_value *out)
{
    for (int i = m - 1; i >= 0; i--)
        for (int j = m - 1 - i; j >= 0; j--) {
            scg_value a = scg_mul(b, net[tri_index(m, i + 1, j)], l[0]);
            scg_value c = scg_mul(b, net[tri_index(m, i, j + 1)], l[1]);
            scg_value d = scg_mul(b, net[tri_index(m, i, j)], l[2]);
            scg_value ac = scg_add(b, a, c);
            out[tri_index(m - 1, i, j)] = scg_add(b, ac, d);
        }
}

static void split_bary(scg_builder *b, scg_value bary, scg_value l[3])
{
    for (int k = 0; k < 3; k++)
        l[k] = scg_comp(b, bary, k);
}

/* x1·y1 − x2·y2 (2D cross products). */
static scg_value products_difference(scg_builder *b, scg_value x1, scg_value y1, scg_value x2,
                                     scg_value y2)
{
    scg_value first = scg_mul(b, x1, y1);
    scg_value second = scg_mul(b, x2, y2);
    return scg_sub(b, first, second);
}

/* The half-line {t : a + b t >= 0} as bounds: raises *lo or lowers *hi.
 * b = 0 keeps everything when a >= 0 and nothing otherwise. */
static void clip(tri_ctx *c, scg_value a, scg_value slope, scg_value *lo, scg_value *hi)
{
    scg_builder *b = c->b;
    scg_value far = scg_const_f(b, FAR);
    scg_value near = scg_const_f(b, -FAR);
    scg_value minus_a = scg_neg(b, a);
    scg_value root = scg_div(b, minus_a, slope);
    scg_value rising = scg_lt(b, c->zero, slope);
    scg_value falling = scg_lt(b, slope, c->zero);
    scg_value outside = scg_lt(b, a, c->zero);
    scg_value level_outside = scg_and(b, scg_not(b, falling), outside);
    scg_value flat_lo = scg_select(b, level_outside, far, near);
    scg_value lower = scg_select(b, rising, root, flat_lo);
    scg_value upper = scg_select(b, falling, root, far);
    *lo = scg_max(b, *lo, lower);
    *hi = scg_min(b, *hi, upper);
}

/* Barycentric coordinates of the ray's origin (a) and their rates along
 * dir (slope), from the domain vertices, the xy of the corner points. */
static void ray_barycentric(tri_ctx *c, scg_value *a, scg_value *slope)
{
    scg_builder *b = c->b;
    int n = c->n;
    scg_value v[3] = {c->pts[tri_index(n, n, 0)], c->pts[tri_index(n, 0, n)],
                      c->pts[tri_index(n, 0, 0)]};
    scg_value x0 = scg_comp(b, v[0], 0), y0 = scg_comp(b, v[0], 1);
    scg_value x1 = scg_comp(b, v[1], 0), y1 = scg_comp(b, v[1], 1);
    scg_value x2 = scg_comp(b, v[2], 0), y2 = scg_comp(b, v[2], 1);
    scg_value e1x = scg_sub(b, x1, x0), e1y = scg_sub(b, y1, y0);
    scg_value e2x = scg_sub(b, x2, x0), e2y = scg_sub(b, y2, y0);
    scg_name(b, "area");
    scg_value area = products_difference(b, e1x, e2y, e1y, e2x);
    scg_name(b, "bary");
    scg_value ox = scg_comp(b, c->origin, 0), oy = scg_comp(b, c->origin, 1);
    scg_value px = scg_sub(b, ox, x0), py = scg_sub(b, oy, y0);
    scg_value dx = scg_comp(b, c->dir, 0), dy = scg_comp(b, c->dir, 1);
    /* λ1 = (p × e2) / area, λ2 = (e1 × p) / area, λ0 = 1 − λ1 − λ2. */
    scg_value l1 = scg_div(b, products_difference(b, px, e2y, py, e2x), area);
    scg_value l2 = scg_div(b, products_difference(b, e1x, py, e1y, px), area);
    scg_value l12 = scg_add(b, l1, l2);
    scg_value l0 = scg_sub(b, c->one, l12);
    *a = scg_vec3(b, l0, l1, l2);
    scg_value s1 = scg_div(b, products_difference(b, dx, e2y, dy, e2x), area);
    scg_value s2 = scg_div(b, products_difference(b, e1x, dy, e1y, dx), area);
    scg_value s12 = scg_add(b, s1, s2);
    scg_value s0 = scg_neg(b, s12);
    *slope = scg_vec3(b, s0, s1, s2);
    scg_name(b, NULL);
}

/* The ray's parameter interval inside the prism: the three barycentric
 * coordinates non-negative (with slack), the height between the lowest and
 * the highest coefficient (convex hull property), and t >= 0. */
static void prism_segment(tri_ctx *c, scg_value a, scg_value slope, scg_value *t_in,
                          scg_value *t_out)
{
    scg_builder *b = c->b;
    scg_value lo = c->zero;
    scg_value hi = scg_const_f(b, FAR);
    scg_value slack = scg_const_f(b, EDGE_SLACK);
    for (int k = 0; k < 3; k++) {
        scg_value ak = scg_comp(b, a, k);
        scg_value widened = scg_add(b, ak, slack);
        clip(c, widened, scg_comp(b, slope, k), &lo, &hi);
    }
    scg_name(b, "z_range");
    scg_value zmin = c->z[0], zmax = c->z[0];
    for (int k = 1; k < c->ncoef; k++) {
        zmin = scg_min(b, zmin, c->z[k]);
        zmax = scg_max(b, zmax, c->z[k]);
    }
    /* At least the tolerance: a hit on a level part of the patch at its
     * lowest (or highest) coefficient lies on the slab's face, and a slack
     * relative to the spread alone can fall below the rounding of the
     * origin's height, which then cuts the root off (two holes of
     * hills33.pgm, where 8-bit data are level over whole patches). */
    scg_value spread = scg_sub(b, zmax, zmin);
    scg_value relative = scg_mul(b, spread, scg_const_f(b, HEIGHT_SLACK));
    scg_value margin = scg_max(b, relative, c->tol);
    scg_value floor_z = scg_sub(b, zmin, margin);
    scg_value roof_z = scg_add(b, zmax, margin);
    scg_value oz = scg_comp(b, c->origin, 2), dz = scg_comp(b, c->dir, 2);
    scg_value above_floor = scg_sub(b, oz, floor_z);
    clip(c, above_floor, dz, &lo, &hi);
    scg_value below_roof = scg_sub(b, roof_z, oz);
    clip(c, below_roof, scg_neg(b, dz), &lo, &hi);
    scg_name(b, NULL);
    *t_in = lo;
    *t_out = hi;
}

/* BB-coefficients of the patch's heights along the segment from
 * barycentric u1 to u2: c_i = b[u1^(n-i), u2^i], from a tree of de
 * Casteljau steps (Fig. 11 of the paper, for any degree up to 4). */
static void blossom(tri_ctx *c, scg_value u1, scg_value u2, scg_value *coef)
{
    scg_builder *b = c->b;
    enum { NC = (SCG_MAX_TRI_DEGREE + 1) * (SCG_MAX_TRI_DEGREE + 2) / 2 };
    scg_value l1[3], l2[3];
    split_bary(b, u1, l1);
    split_bary(b, u2, l2);
    /* nets[j]: the net after the steps so far, j of them with u2. */
    scg_value nets[SCG_MAX_TRI_DEGREE + 1][NC], next[SCG_MAX_TRI_DEGREE + 1][NC];
    for (int k = 0; k < c->ncoef; k++)
        nets[0][k] = c->z[k];
    for (int level = 1; level <= c->n; level++) {
        int m = c->n - level + 1;
        for (int j = 0; j <= level; j++) {
            if (j < level)
                casteljau_step(b, m, nets[j], l1, next[j]);
            else
                casteljau_step(b, m, nets[j - 1], l2, next[j]);
        }
        for (int j = 0; j <= level; j++)
            for (int k = 0; k < (m * (m + 1)) / 2; k++)
                nets[j][k] = next[j][k];
    }
    for (int i = 0; i <= c->n; i++)
        coef[i] = nets[i][0];
}

/* g and g' at the four starts at once (vec4 x), by de Casteljau on the
 * scalar BB-coefficients g[0..n]. */
static void eval_univariate(tri_ctx *c, const scg_value *g, scg_value x, scg_value *value,
                            scg_value *slope)
{
    scg_builder *b = c->b;
    scg_value d[SCG_MAX_TRI_DEGREE + 1] = {0};
    for (int i = 0; i <= c->n; i++)
        d[i] = g[i];
    for (int r = c->n; r >= 1; r--) {
        if (r == 1) {
            scg_value diff = scg_sub(b, d[1], d[0]);
            if (c->n == 1)   /* constant: one value for all four starts */
                diff = scg_vec4(b, diff, diff, diff, diff);
            *slope = scg_mul(b, diff, scg_const_f(b, (float)c->n));
        }
        for (int i = 0; i < r; i++)
            d[i] = scg_lerp(b, d[i], d[i + 1], x);
    }
    *value = d[0];
}

/* The inflection points of g (roots of g'', a quadratic for n = 4, linear
 * for n = 3), where they lie in (0, 1), else the paper's defaults 1/3 and
 * 2/3: the middle two starts, ordered. */
static scg_value secure_starts(tri_ctx *c, const scg_value *g)
{
    scg_builder *b = c->b;
    scg_value third = scg_const_f(b, 1.0f / 3.0f);
    scg_value two_thirds = scg_const_f(b, 2.0f / 3.0f);
    scg_value w0 = third, w1 = two_thirds;
    scg_name(b, "inflection");
    if (c->n >= 3) {
        /* Second differences: g'' has BB-coefficients ∝ Δ²g_i. */
        scg_value e[3];
        for (int i = 0; i <= c->n - 2; i++) {
            scg_value s1 = scg_sub(b, g[i + 2], g[i + 1]);
            scg_value s0 = scg_sub(b, g[i + 1], g[i]);
            e[i] = scg_sub(b, s1, s0);
        }
        /* Monomial form A s² + B s + C of the BB quadratic (e0, e1, e2), or
         * of the line (e0, e1). */
        scg_value cc = e[0];
        scg_value bb_half = scg_sub(b, e[1], e[0]);
        scg_value aa = c->zero;
        if (c->n == 4) {
            scg_value e02 = scg_add(b, e[0], e[2]);
            scg_value twice_e1 = scg_add(b, e[1], e[1]);
            aa = scg_sub(b, e02, twice_e1);
        } else {
            bb_half = scg_mul(b, bb_half, scg_const_f(b, 0.5f));
        }
        /* Roots of A s² + 2 B' s + C: (−B' ± sqrt(B'² − A C)) / A, or −C / 2B'
         * when A vanishes. */
        scg_value disc = products_difference(b, bb_half, bb_half, aa, cc);
        scg_value root = scg_sqrt(b, scg_max(b, disc, c->zero));
        scg_value minus_b = scg_neg(b, bb_half);
        scg_value r_a = scg_div(b, scg_sub(b, minus_b, root), aa);
        scg_value r_b = scg_div(b, scg_add(b, minus_b, root), aa);
        scg_value minus_c = scg_neg(b, cc);
        scg_value lin = scg_div(b, minus_c, scg_add(b, bb_half, bb_half));
        scg_value quadratic = scg_ne(b, aa, c->zero);
        scg_value real = scg_le(b, c->zero, disc);
        scg_value q0 = scg_min(b, r_a, r_b);
        scg_value q1 = scg_max(b, r_a, r_b);
        scg_value cand0 = scg_select(b, quadratic, q0, lin);
        scg_value cand1 = scg_select(b, quadratic, q1, c->one);
        scg_value ok0 = scg_and(b, real, scg_lt(b, c->zero, cand0));
        ok0 = scg_and(b, ok0, scg_lt(b, cand0, c->one));
        scg_value ok1 = scg_and(b, real, scg_lt(b, c->zero, cand1));
        ok1 = scg_and(b, ok1, scg_lt(b, cand1, c->one));
        w0 = scg_select(b, ok0, cand0, third);
        w1 = scg_select(b, ok1, cand1, two_thirds);
        scg_value lo = scg_min(b, w0, w1);
        w1 = scg_max(b, w0, w1);
        w0 = lo;
    }
    scg_name(b, "x0");
    scg_value x0 = scg_vec4(b, c->zero, w0, w1, c->one);
    scg_name(b, NULL);
    return x0;
}

/* max of the four components of a vec4. */
static scg_value max4(scg_builder *b, scg_value v)
{
    scg_value x = scg_comp(b, v, 0), y = scg_comp(b, v, 1);
    scg_value z = scg_comp(b, v, 2), w = scg_comp(b, v, 3);
    scg_value xy = scg_max(b, x, y);
    scg_value zw = scg_max(b, z, w);
    return scg_max(b, xy, zw);
}

/* One damped Newton step on all four starts; stops when every step is
 * below the stopping length (in s units). */
static void newton_step(tri_ctx *c, const scg_value *g, scg_value x_var, scg_value iters_var,
                        scg_value done_var, scg_value s_stop)
{
    scg_builder *b = c->b;
    scg_name(b, "x");
    scg_value x = scg_load(b, x_var);
    scg_value value, slope;
    eval_univariate(c, g, x, &value, &slope);
    scg_name(b, "step");
    scg_value num = scg_mul(b, value, slope);
    scg_value slope2 = scg_mul(b, slope, slope);
    scg_value den = scg_add(b, slope2, scg_const_f(b, TINY));
    scg_value step = scg_div(b, num, den);
    scg_value moved = scg_sub(b, x, step);
    scg_value low = scg_const_f(b, -CLAMP);
    scg_value high = scg_const_f(b, 1.0f + CLAMP);
    scg_value kept = scg_max(b, moved, low);
    scg_store(b, x_var, scg_min(b, kept, high));
    scg_value iters = scg_load(b, iters_var);
    scg_store(b, iters_var, scg_add(b, iters, scg_const_i(b, 1)));
    scg_name(b, "converged");
    scg_value largest = max4(b, scg_abs(b, step));
    scg_store(b, done_var, scg_lt(b, largest, s_stop));
    scg_name(b, NULL);
}

/* True when every BB-coefficient of g has one sign, clear of zero by
 * ROOT_MARGIN of the tolerance: by the convex hull property g has no root
 * in [0, 1]. The margin keeps a root at an end of the segment (a hit on
 * the edge two patches share) from being rejected by both for the
 * rounding of g there (tri_program_shared_edge). */
static scg_value no_root(tri_ctx *c, const scg_value *g)
{
    scg_builder *b = c->b;
    scg_name(b, "no_root");
    scg_value margin = scg_mul(b, c->tol, scg_const_f(b, ROOT_MARGIN));
    scg_value minus_margin = scg_neg(b, margin);
    scg_value all_pos = scg_lt(b, margin, g[0]);
    scg_value all_neg = scg_lt(b, g[0], minus_margin);
    for (int i = 1; i <= c->n; i++) {
        all_pos = scg_and(b, all_pos, scg_lt(b, margin, g[i]));
        all_neg = scg_and(b, all_neg, scg_lt(b, g[i], minus_margin));
    }
    scg_value none = scg_or(b, all_pos, all_neg);
    scg_name(b, NULL);
    return none;
}

/* The smallest converged root in [0, 1] (slack S_SLACK), or 2 when none:
 * a component is converged when its last Newton step, in object units, is
 * below the tolerance. */
static scg_value first_root(tri_ctx *c, const scg_value *g, scg_value x, scg_value s_tol)
{
    scg_builder *b = c->b;
    scg_value value, slope;
    eval_univariate(c, g, x, &value, &slope);
    scg_name(b, "root");
    scg_value best = scg_const_f(b, 2.0f);
    scg_value lo = scg_const_f(b, -S_SLACK);
    scg_value hi = scg_const_f(b, 1.0f + S_SLACK);
    for (int k = 0; k < 4; k++) {
        scg_value xk = scg_comp(b, x, k);
        scg_value gk = scg_comp(b, value, k);
        scg_value dk = scg_comp(b, slope, k);
        scg_value residual = scg_abs(b, gk);
        scg_value scale = scg_mul(b, s_tol, scg_abs(b, dk));
        scg_value ok = scg_lt(b, residual, scale);
        ok = scg_and(b, ok, scg_le(b, lo, xk));
        ok = scg_and(b, ok, scg_le(b, xk, hi));
        ok = scg_and(b, ok, scg_lt(b, xk, best));
        best = scg_select(b, ok, xk, best);
    }
    scg_name(b, NULL);
    return best;
}

void scg_build_tri_newton(scg_builder *b, const scg_key *key)
{
    tri_ctx ctx = {.b = b, .key = key, .n = key->deg_u};
    tri_ctx *c = &ctx;
    c->ncoef = (c->n + 1) * (c->n + 2) / 2;
    scg_name(b, "origin");
    c->origin = scg_input(b, SCG_IN_RAY_ORIGIN);
    scg_name(b, "dir");
    c->dir = scg_input(b, SCG_IN_RAY_DIR);
    scg_name(b, NULL);
    c->zero = scg_const_f(b, 0.0f);
    c->one = scg_const_f(b, 1.0f);
    c->dir_len = scg_length(b, c->dir);
    scg_name(b, "tol");
    scg_value pixels = scg_const_f(b, scg_key_tolerance(key));
    scg_value at_hull = scg_mul(b, scg_uniform(b, SCG_UNI_FOOTPRINT), c->dir_len);
    c->tol = scg_mul(b, pixels, at_hull);

    scg_name(b, "record");
    scg_value record = scg_input(b, SCG_IN_RECORD);
    c->rec = scg_mul(b, record, scg_const_i(b, SCG_RECORD_TEXELS));
    scg_value r0 = scg_fetch(b, SCG_TEX_RECORDS, c->rec);
    scg_name(b, "cp_offset");
    scg_value cp_offset = scg_f2i(b, scg_comp(b, r0, 0));
    scg_name(b, NULL);
    c->surface = scg_f2i(b, scg_comp(b, r0, 3));
    scg_name(b, "P");
    for (int k = 0; k < c->ncoef; k++) {
        scg_value pt = scg_fetch(b, SCG_TEX_POINTS, scg_add(b, cp_offset, scg_const_i(b, k)));
        c->pts[k] = scg_xyz(b, pt);
        c->z[k] = scg_comp(b, pt, 2);
    }
    scg_name(b, NULL);

    scg_value a, slope, t_in, t_out;
    ray_barycentric(c, &a, &slope);
    prism_segment(c, a, slope, &t_in, &t_out);
    scg_name(b, "u1");
    scg_value u1 = scg_add(b, a, scg_mul(b, slope, t_in));
    scg_name(b, "u2");
    scg_value u2 = scg_add(b, a, scg_mul(b, slope, t_out));
    scg_name(b, "c");
    scg_value coef[SCG_MAX_TRI_DEGREE + 1] = {0}, g[SCG_MAX_TRI_DEGREE + 1] = {0};
    blossom(c, u1, u2, coef);
    /* Minus the ray's height, linear in s: its BB-coefficients are its
     * values at s = i/n. */
    scg_name(b, "g");
    scg_value oz = scg_comp(b, c->origin, 2), dz = scg_comp(b, c->dir, 2);
    scg_value span = scg_sub(b, t_out, t_in);
    for (int i = 0; i <= c->n; i++) {
        scg_value frac = scg_const_f(b, (float)i / (float)c->n);
        scg_value t_i = scg_add(b, t_in, scg_mul(b, span, frac));
        scg_value ray_z = scg_add(b, oz, scg_mul(b, dz, t_i));
        g[i] = scg_sub(b, coef[i], ray_z);
    }
    /* Tolerances along the segment, in s: object length per unit s is
     * span·|dir|. */
    scg_name(b, "s_tol");
    scg_value seg_len = scg_mul(b, span, c->dir_len);
    scg_value s_tol = scg_div(b, c->tol, seg_len);
    scg_value s_stop = scg_mul(b, s_tol, scg_const_f(b, STOP_FRACTION));
    scg_name(b, NULL);

    scg_value empty = scg_le(b, t_out, t_in);
    scg_value skip = scg_or(b, empty, no_root(c, g));
    scg_value t_limit = 0, behind = 0;
    if (key->ert == SCG_ERT_BEFORE || key->ert == SCG_ERT_BOTH) {
        t_limit = scg_input(b, SCG_IN_T_LIMIT);
        scg_name(b, "occluded");
        behind = scg_lt(b, t_limit, c->one);
        skip = scg_or(b, skip, behind);
        scg_name(b, NULL);
    }
    scg_value x0 = secure_starts(c, g);
    scg_name(b, "x");
    scg_value x_var = scg_var(b, SCG_VEC4, 0, x0);
    scg_name(b, "iters");
    scg_value iters_var = scg_var(b, SCG_INT, 0, scg_const_i(b, 0));
    scg_name(b, "done");
    scg_value done_var = scg_var(b, SCG_BOOL, 0, skip);
    scg_name(b, NULL);
    for (int k = 0; k < key->max_iters; k++) {
        scg_if(b, scg_not(b, scg_load(b, done_var)));
        newton_step(c, g, x_var, iters_var, done_var, s_stop);
        scg_endif(b);
    }

    scg_name(b, "x_final");
    scg_value x = scg_load(b, x_var);
    scg_name(b, NULL);
    scg_value s = first_root(c, g, x, s_tol);
    scg_name(b, "hit");
    scg_value found = scg_le(b, s, scg_const_f(b, 1.0f + S_SLACK));
    scg_value hit = scg_and(b, found, scg_not(b, skip));
    scg_name(b, "t");
    scg_value s_in = scg_min(b, scg_max(b, s, c->zero), c->one);
    scg_value t = scg_add(b, t_in, scg_mul(b, span, s_in));
    if (key->ert == SCG_ERT_BOTH)
        hit = scg_and(b, hit, scg_lt(b, t, t_limit));

    /* The patch at the hit's barycentric point: the surface point, and the
     * two partials along the edges from the last de Casteljau net. */
    scg_name(b, "lambda");
    scg_value lambda = scg_lerp(b, u1, u2, s_in);
    scg_value l[3];
    split_bary(b, lambda, l);
    enum { NC = (SCG_MAX_TRI_DEGREE + 1) * (SCG_MAX_TRI_DEGREE + 2) / 2 };
    scg_value net[NC], lower[NC];
    for (int k = 0; k < c->ncoef; k++)
        net[k] = c->pts[k];
    for (int m = c->n; m > 1; m--) {
        casteljau_step(b, m, net, l, lower);
        for (int k = 0; k < m * (m + 1) / 2; k++)
            net[k] = lower[k];
    }
    scg_name(b, "point");
    scg_value p100 = net[tri_index(1, 1, 0)], p010 = net[tri_index(1, 0, 1)];
    scg_value p001 = net[tri_index(1, 0, 0)];
    scg_value part0 = scg_mul(b, p100, l[0]);
    scg_value point_pair = scg_add(b, part0, scg_mul(b, p010, l[1]));
    scg_value point = scg_add(b, point_pair, scg_mul(b, p001, l[2]));
    scg_name(b, "normal");
    scg_value d1 = scg_sub(b, p010, p100);
    scg_value d2 = scg_sub(b, p001, p100);
    scg_value normal = scg_cross(b, d1, d2);
    scg_value normal_len = scg_length(b, normal);
    scg_value regular = scg_lt(b, c->zero, normal_len);
    scg_value unit_normal = scg_div(b, normal, normal_len);
    scg_value axis = scg_div(b, c->dir, c->dir_len);
    normal = scg_select(b, regular, unit_normal, scg_neg(b, axis));
    /* (u, v) is the terrain's own parameter, the absolute domain point. */
    scg_name(b, "uv_surface");
    scg_value r3 = scg_fetch(b, SCG_TEX_RECORDS, scg_add(b, c->rec, scg_const_i(b, 3)));
    scg_value px = scg_comp(b, point, 0), py = scg_comp(b, point, 1);
    scg_value u_abs = scg_add(b, px, scg_comp(b, r3, 0));
    scg_value v_abs = scg_add(b, py, scg_comp(b, r3, 1));
    scg_value uv = scg_vec2(b, u_abs, v_abs);
    scg_name(b, NULL);
    scg_output(b, SCG_OUT_HIT, hit);
    scg_output(b, SCG_OUT_UV, uv);
    scg_output(b, SCG_OUT_T, t);
    scg_output(b, SCG_OUT_POINT, point);
    scg_output(b, SCG_OUT_NORMAL, normal);
    scg_output(b, SCG_OUT_ITERS, scg_load(b, iters_var));
    scg_output(b, SCG_OUT_SURFACE, c->surface);
}
