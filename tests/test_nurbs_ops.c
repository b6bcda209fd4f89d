/* test_nurbs_ops.c — the NURBS core's operations: every shape-preserving
 * one (insertion, refinement, extraction, splitting, elevation) is checked
 * by evaluating before and after at random parameters, Bézier pieces
 * against a Bernstein / de Casteljau evaluation written here; clamping an
 * unclamped B-spline, against the Cox–de Boor recursion as defined, summed
 * over the original's points. */
#include "test.h"

#include <stdlib.h>

#include "nurbs_util.h"

TEST(nurbs_curve_knot_insertion_keeps_curve)
{
    unsigned long long rng = 31;
    for (int trial = 0; trial < 40; trial++) {
        int p = 1 + trial % 5, dim = 2 + trial % 2;
        sc_curve c, out;
        random_curve(&rng, dim, p, p + 4, &c);
        /* Half the time at an existing interior knot. */
        double u = trial % 2 ? c.knots[p + 1] : 0.05 + 0.9 * test_rand(&rng);
        int s = 0;
        for (int i = 0; i < c.ncp + p + 1; i++)
            s += c.knots[i] == u;
        int times = 1 + trial % 3, expect = times < p - s ? times : p - s;
        if (expect < 0)
            expect = 0;
        sc_curve_insert_knot(&c, u, times, &out);
        CHECK_INT(out.ncp, c.ncp + expect);
        CHECK(curve_distance(&c, &out, 0, 1, &rng) < 1e-12);
        sc_curve_free(&c);
        sc_curve_free(&out);
    }
}

TEST(nurbs_curve_refinement_keeps_curve)
{
    unsigned long long rng = 37;
    for (int trial = 0; trial < 30; trial++) {
        int p = 1 + trial % 4;
        sc_curve c, out;
        random_curve(&rng, 3, p, p + 5, &c);
        double x[8];
        int nx = 1 + trial % 8;
        for (int i = 0; i < nx; i++)
            x[i] = test_rand(&rng);
        /* Unsorted, with a duplicate and an existing knot. */
        if (nx > 2) {
            x[1] = x[0];
            x[2] = c.knots[p + 1];
        }
        sc_curve_refine(&c, x, nx, &out);
        CHECK_INT(out.ncp, c.ncp + nx);
        for (int i = 1; i < out.ncp + p + 1; i++)
            CHECK(out.knots[i - 1] <= out.knots[i]);
        CHECK(curve_distance(&c, &out, 0, 1, &rng) < 1e-12);
        sc_curve_free(&c);
        sc_curve_free(&out);
    }
}

/* Bézier curve by de Casteljau on homogeneous points (an evaluation that
 * shares nothing with the B-spline code): the homogeneous result, then the
 * Euclidean one. */
static void de_casteljau_h(const double *cp, int degree, int stride, double t, double *out)
{
    double tmp[64 * 4];
    memcpy(tmp, cp, sizeof(double) * (size_t)(degree + 1) * (size_t)stride);
    for (int r = 1; r <= degree; r++)
        for (int i = 0; i <= degree - r; i++)
            for (int k = 0; k < stride; k++)
                tmp[i * stride + k] = (1 - t) * tmp[i * stride + k] + t * tmp[(i + 1) * stride + k];
    memcpy(out, tmp, sizeof(double) * (size_t)stride);
}

static void de_casteljau(const double *cp, int degree, int stride, double t, double *out)
{
    double h[4];
    de_casteljau_h(cp, degree, stride, t, h);
    for (int k = 0; k < stride - 1; k++)
        out[k] = h[k] / h[stride - 1];
}

TEST(nurbs_curve_bezier_extraction)
{
    unsigned long long rng = 41;
    for (int trial = 0; trial < 30; trial++) {
        int p = 1 + trial % 5, ncp = p + 1 + trial % 6;
        sc_curve c, *segs;
        int nseg;
        random_curve(&rng, 3, p, ncp, &c);
        sc_curve_to_bezier(&c, &segs, &nseg);
        int distinct = 0;
        for (int i = p; i < ncp; i++)
            distinct += c.knots[i] < c.knots[i + 1];
        CHECK_INT(nseg, distinct);
        double covered = 0;
        for (int s = 0; s < nseg; s++) {
            const sc_curve *b = &segs[s];
            CHECK_INT(b->ncp, p + 1);
            double a = b->knots[0], e = b->knots[p + 1];
            CHECK(b->knots[p] == a && b->knots[2 * p + 1] == e);
            covered += e - a;
            for (int k = 0; k < 20; k++) {
                double t = test_rand(&rng), x[3], y[3];
                de_casteljau(b->cp, p, 4, t, x);
                sc_curve_eval(&c, a + t * (e - a), y, NULL);
                CHECK(dist3(x, y) < 1e-12);
            }
            sc_curve_free(&segs[s]);
        }
        free(segs);
        CHECK_NEAR(covered, 1.0, 1e-15);
        sc_curve_free(&c);
    }
}

TEST(nurbs_curve_split_keeps_curve)
{
    unsigned long long rng = 43;
    for (int trial = 0; trial < 30; trial++) {
        int p = 1 + trial % 5;
        sc_curve c, left, right;
        random_curve(&rng, 2, p, p + 1 + trial % 5, &c);
        double t = trial % 3 == 0 && c.ncp > p + 1 ? c.knots[p + 1] : 0.05 + 0.9 * test_rand(&rng);
        sc_curve_split(&c, t, &left, &right);
        double l0, l1, r0, r1;
        sc_curve_domain(&left, &l0, &l1);
        sc_curve_domain(&right, &r0, &r1);
        CHECK(l0 == 0 && l1 == t && r0 == t && r1 == 1);
        CHECK(curve_distance(&c, &left, 0, t, &rng) < 1e-12);
        CHECK(curve_distance(&c, &right, t, 1, &rng) < 1e-12);
        sc_curve_free(&c);
        sc_curve_free(&left);
        sc_curve_free(&right);
    }
}

TEST(nurbs_curve_degree_elevation)
{
    unsigned long long rng = 47;
    for (int trial = 0; trial < 40; trial++) {
        int p = 1 + trial % 5, ncp = p + 1 + trial % 7, times = 1 + trial % 3;
        sc_curve c, out;
        random_curve(&rng, trial % 2 ? 3 : 2, p, ncp, &c);
        sc_curve_elevate(&c, times, &out);
        /* Each distinct knot's multiplicity grows by `times` (The NURBS
         * Book, §5.5): ncp grows by times × (distinct interior knots + 1). */
        int distinct = 0;
        for (int i = p + 1; i < ncp; i++)
            distinct += c.knots[i] != c.knots[i - 1];
        CHECK_INT(out.degree, p + times);
        CHECK_INT(out.ncp, ncp + times * (distinct + 1));
        CHECK(curve_distance(&c, &out, 0, 1, &rng) < 1e-12);
        sc_curve_free(&c);
        sc_curve_free(&out);
    }
}

TEST(nurbs_curve_elevation_at_a_break)
{
    /* Degree 2 with an interior knot of multiplicity 3: a jump at 0.5 the
     * elevated curve must keep on both sides. */
    const double knots[9] = {0, 0, 0, .5, .5, .5, 1, 1, 1};
    const double xy[6][2] = {{0, 0}, {1, 2}, {2, 0}, {3, 5}, {4, 1}, {5, 5}};
    const double w[6] = {1, 2, 1, 1, 0.5, 1};
    sc_curve c, out;
    make_curve(&c, 2, 2, 6, knots, &xy[0][0], w);
    sc_curve_elevate(&c, 2, &out);
    CHECK_INT(out.ncp, 10);
    unsigned long long rng = 53;
    CHECK(curve_distance(&c, &out, 0, 0.4999, &rng) < 1e-12);
    CHECK(curve_distance(&c, &out, 0.5, 1, &rng) < 1e-12);
    sc_curve_free(&c);
    sc_curve_free(&out);
}

TEST(nurbs_high_degree_beyond_stack_buffers)
{
    /* A quarter circle raised to degree 40 (evaluation then allocates):
     * still exactly on the circle. */
    const double knots[6] = {0, 0, 0, 1, 1, 1};
    const double xy[3][2] = {{1, 0}, {1, 1}, {0, 1}}, w[3] = {1, R2, 1};
    sc_curve c, high;
    make_curve(&c, 2, 2, 3, knots, &xy[0][0], w);
    sc_curve_elevate(&c, 38, &high);
    CHECK_INT(high.degree, 40);
    unsigned long long rng = 59;
    for (int k = 0; k < 200; k++) {
        double p[2], d[2];
        sc_curve_eval(&high, test_rand(&rng), p, d);
        CHECK_NEAR(hypot(p[0], p[1]), 1.0, 1e-13);
        CHECK_NEAR(p[0] * d[0] + p[1] * d[1], 0.0, 1e-11);
    }
    sc_curve_free(&c);
    sc_curve_free(&high);
    /* The sphere raised to degree 36 in v. */
    sc_surface s, t;
    make_sphere(&s);
    sc_surface_elevate(&s, 1, 34, &t);
    CHECK_INT(t.deg_v, 36);
    for (int k = 0; k < 200; k++) {
        double p[3], n[3], u = test_rand(&rng), v = test_rand(&rng);
        sc_surface_eval(&t, u, v, p, NULL, NULL);
        CHECK_NEAR(len3(p), 1.0, 1e-12);
        CHECK_INT(sc_surface_normal(&t, u, v, n), 0);
        CHECK_NEAR(fabs(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]), 1.0, 1e-9);
    }
    sc_surface_free(&s);
    sc_surface_free(&t);
}

TEST(nurbs_surface_operations_keep_surface)
{
    unsigned long long rng = 61;
    for (int trial = 0; trial < 6; trial++) {
        sc_surface s, out;
        random_surface(&rng, 2 + trial % 2, 3 - trial % 2, 6, 5, &s);
        for (int dir = 0; dir < 2; dir++) {
            double t = 0.1 + 0.8 * test_rand(&rng);
            sc_surface_insert_knot(&s, dir, t, 2, &out);
            CHECK_INT(dir ? out.nv : out.nu, (dir ? s.nv : s.nu) + 2);
            CHECK(surface_distance(&s, &out, 0, 1, 0, 1, &rng) < 1e-12);
            sc_surface_free(&out);

            double x[3] = {0.7 * t, t, 0.5 + 0.4 * t};
            sc_surface_refine(&s, dir, x, 3, &out);
            CHECK_INT(dir ? out.nv : out.nu, (dir ? s.nv : s.nu) + 3);
            CHECK(surface_distance(&s, &out, 0, 1, 0, 1, &rng) < 1e-12);
            sc_surface_free(&out);

            sc_surface_elevate(&s, dir, 2, &out);
            CHECK_INT(dir ? out.deg_v : out.deg_u, (dir ? s.deg_v : s.deg_u) + 2);
            CHECK(surface_distance(&s, &out, 0, 1, 0, 1, &rng) < 1e-12);
            sc_surface_free(&out);

            sc_surface lo, hi;
            sc_surface_split(&s, dir, t, &lo, &hi);
            CHECK(surface_distance(&s, &lo, 0, dir ? 1 : t, 0, dir ? t : 1, &rng) < 1e-12);
            CHECK(surface_distance(&s, &hi, dir ? 0 : t, 1, dir ? t : 0, 1, &rng) < 1e-12);
            sc_surface_free(&lo);
            sc_surface_free(&hi);
        }
        sc_surface_free(&s);
    }
}

TEST(nurbs_surface_bezier_extraction)
{
    unsigned long long rng = 67;
    for (int trial = 0; trial < 6; trial++) {
        sc_surface s;
        int p = 1 + trial % 3, q = 3 - trial % 3;
        random_surface(&rng, p, q, p + 3, q + 2, &s);
        sc_bezier_patch *patches;
        int count;
        sc_surface_to_bezier(&s, &patches, &count);
        int su = 0, sv = 0;
        for (int i = p; i < s.nu; i++)
            su += s.knots_u[i] < s.knots_u[i + 1];
        for (int j = q; j < s.nv; j++)
            sv += s.knots_v[j] < s.knots_v[j + 1];
        CHECK_INT(count, su * sv);
        double area = 0;
        for (int k = 0; k < count; k++) {
            const sc_bezier_patch *bp = &patches[k];
            CHECK(bp->deg_u == p && bp->deg_v == q);
            area += (bp->u1 - bp->u0) * (bp->v1 - bp->v0);
            for (int r = 0; r < 10; r++) {
                double a = test_rand(&rng), b = test_rand(&rng), col[64 * 4], x[3], y[3];
                /* Tensor de Casteljau: each row (fixed v index) at a, the
                 * column of results at b. */
                for (int j = 0; j <= q; j++)
                    de_casteljau_h(bp->cp + 4 * j * (p + 1), p, 4, a, col + 4 * j);
                de_casteljau(col, q, 4, b, x);
                sc_surface_eval(&s, bp->u0 + a * (bp->u1 - bp->u0), bp->v0 + b * (bp->v1 - bp->v0),
                                y, NULL, NULL);
                CHECK(dist3(x, y) < 1e-12);
            }
            sc_bezier_patch_free(&patches[k]);
        }
        free(patches);
        CHECK_NEAR(area, 1.0, 1e-14);
        sc_surface_free(&s);
    }
}

/* ---- the collapsed edges of the teapot ---- */

/* The 32 bicubic patches of teapot32.bpt: index within a row is u, the row
 * number is v (data/README). */
static double cox_de_boor(const double *U, int i, int p, double u)
{
    if (p == 0)
        return U[i] <= u && u < U[i + 1] ? 1.0 : 0.0;
    double left = 0, right = 0;
    if (U[i + p] > U[i])
        left = (u - U[i]) / (U[i + p] - U[i]) * cox_de_boor(U, i, p - 1, u);
    if (U[i + p + 1] > U[i + 1])
        right = (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * cox_de_boor(U, i + 1, p - 1, u);
    return left + right;
}

/* The curve point as the plain sum Σ N_i(u)·P_i of homogeneous points. At
 * the domain's upper end the half-open definition still gives the limit
 * from the left: every N_{i,p} with p >= 1 vanishes at its first knot. */
static void curve_by_definition(const sc_curve *c, double u, double *point)
{
    double A[4] = {0};
    int stride = c->dim + 1;
    for (int i = 0; i < c->ncp; i++) {
        double N = cox_de_boor(c->knots, i, c->degree, u);
        for (int k = 0; k < stride; k++)
            A[k] += N * c->cp[i * stride + k];
    }
    for (int k = 0; k < c->dim; k++)
        point[k] = A[k] / A[c->dim];
}

static void surface_by_definition(const sc_surface *s, double u, double v, double p[3])
{
    double A[4] = {0};
    for (int j = 0; j < s->nv; j++) {
        double Nv = cox_de_boor(s->knots_v, j, s->deg_v, v);
        for (int i = 0; i < s->nu; i++) {
            double N = cox_de_boor(s->knots_u, i, s->deg_u, u) * Nv;
            for (int k = 0; k < 4; k++)
                A[k] += N * s->cp[4 * (j * s->nu + i) + k];
        }
    }
    for (int k = 0; k < 3; k++)
        p[k] = A[k] / A[3];
}

static int is_clamped(const double *knots, int degree, int ncp, double t0, double t1)
{
    for (int i = 0; i <= degree; i++)
        if (knots[i] != t0 || knots[ncp + i] != t1)
            return 0;
    return 1;
}

/* A uniform cubic B-spline in the plane: knots 0, 1, …, ncp + 3, domain
 * [3, ncp], with the given weights (NULL: polynomial). */
static void uniform_cubic(unsigned long long *rng, int ncp, const double *w, sc_curve *c)
{
    double knots[32], cp[64];
    for (int i = 0; i < ncp + 4; i++)
        knots[i] = i;
    for (int i = 0; i < 2 * ncp; i++)
        cp[i] = 4 * test_rand(rng) - 2;
    make_curve(c, 2, 3, ncp, knots, cp, w);
}

TEST(nurbs_clamp_uniform_cubic_curve)
{
    unsigned long long rng = 71;
    const double weights[8] = {1, 0.6, 1.8, 0.9, 1.3, 0.5, 1.1, 2.0};
    for (int rational = 0; rational < 2; rational++) {
        sc_curve c, out;
        uniform_cubic(&rng, 8, rational ? weights : NULL, &c);
        sc_curve_clamp(&c, &out);
        /* Five spans of a cubic: 5 + 3 control points, as before. */
        CHECK_INT(out.degree, 3);
        CHECK_INT(out.ncp, 8);
        CHECK(is_clamped(out.knots, 3, out.ncp, 3.0, 8.0));
        for (int k = 4; k <= 7; k++)
            CHECK_NEAR(out.knots[k], k, 0);
        for (int k = 0; k <= 100; k++) {
            double u = 3 + 5 * k / 100.0, want[2], got[2], direct[2];
            curve_by_definition(&c, u, want);
            sc_curve_eval(&out, u, got, NULL);
            /* The core's own evaluation works on the unclamped vector too. */
            sc_curve_eval(&c, u, direct, NULL);
            for (int d = 0; d < 2; d++) {
                CHECK_NEAR(got[d], want[d], 1e-12);
                CHECK_NEAR(direct[d], want[d], 1e-12);
            }
        }
        if (!rational) {
            /* A uniform cubic passes through (P0 + 4 P1 + P2) / 6 at its
             * first knot of the domain, which the clamped curve
             * interpolates with its first control point (and likewise at
             * the end). */
            const double *P = c.cp, *Q = out.cp;
            for (int d = 0; d < 2; d++) {
                CHECK_NEAR(Q[d], (P[d] + 4 * P[3 + d] + P[6 + d]) / 6, 1e-14);
                CHECK_NEAR(Q[21 + d], (P[15 + d] + 4 * P[18 + d] + P[21 + d]) / 6, 1e-14);
            }
        }
        sc_curve_free(&c);
        sc_curve_free(&out);
    }
}

TEST(nurbs_insert_knot_at_domain_ends)
{
    unsigned long long rng = 73;
    sc_curve c, out;
    uniform_cubic(&rng, 7, NULL, &c);
    const double ends[2] = {3, 7};
    for (int e = 0; e < 2; e++) {
        /* Once, then more than the degree allows: multiplicity stops at 3. */
        const int times[2] = {1, 10}, added[2] = {1, 2};
        for (int t = 0; t < 2; t++) {
            sc_curve_insert_knot(&c, ends[e], times[t], &out);
            CHECK_INT(out.ncp, c.ncp + added[t]);
            int mult = 0;
            for (int i = 0; i < out.ncp + 4; i++)
                mult += out.knots[i] == ends[e];
            CHECK_INT(mult, 1 + added[t]);
            double t0, t1;
            sc_curve_domain(&out, &t0, &t1);
            CHECK_NEAR(t0, 3, 0);
            CHECK_NEAR(t1, 7, 0);
            CHECK(curve_distance(&c, &out, 3, 7, &rng) < 1e-12);
            sc_curve_free(&out);
        }
    }
    /* Outside the domain, or at a clamped end: nothing to insert. */
    sc_curve_insert_knot(&c, 2.5, 1, &out);
    CHECK_INT(out.ncp, c.ncp);
    sc_curve_free(&out);
    sc_curve clamped;
    sc_curve_clamp(&c, &clamped);
    sc_curve_insert_knot(&clamped, 3, 1, &out);
    CHECK_INT(out.ncp, clamped.ncp);
    CHECK(memcmp(out.cp, clamped.cp, sizeof(double) * 3 * (size_t)out.ncp) == 0);
    sc_curve_free(&out);
    /* Clamping a clamped curve copies it. */
    sc_curve_clamp(&clamped, &out);
    CHECK_INT(out.ncp, clamped.ncp);
    CHECK(memcmp(out.knots, clamped.knots, sizeof(double) * (size_t)(out.ncp + 4)) == 0);
    CHECK(memcmp(out.cp, clamped.cp, sizeof(double) * 3 * (size_t)out.ncp) == 0);
    sc_curve_free(&out);
    sc_curve_free(&clamped);
    sc_curve_free(&c);
}

TEST(nurbs_clamp_uniform_bicubic_surface)
{
    unsigned long long rng = 79;
    sc_surface s, out;
    memset(&s, 0, sizeof s);
    s.xform[0] = s.xform[5] = s.xform[10] = 1;
    snprintf(s.name, sizeof s.name, "uniform");
    /* 7 × 6 points, uniform knots 0 … 10 in u and 0 … 9 in v: domain
     * [3, 7] × [3, 6]; rational. */
    sc_surface_alloc(&s, 3, 3, 7, 6);
    for (int i = 0; i < 11; i++)
        s.knots_u[i] = i;
    for (int i = 0; i < 10; i++)
        s.knots_v[i] = i;
    for (int k = 0; k < 42; k++) {
        double w = 0.5 + 1.5 * test_rand(&rng);
        for (int d = 0; d < 3; d++)
            s.cp[4 * k + d] = (2 * test_rand(&rng) - 1) * w;
        s.cp[4 * k + 3] = w;
    }
    s.rational = 1;
    sc_surface_clamp(&s, &out);
    CHECK_STR(out.name, "uniform");
    CHECK_INT(out.nu, 7);
    CHECK_INT(out.nv, 6);
    CHECK(is_clamped(out.knots_u, 3, out.nu, 3.0, 7.0));
    CHECK(is_clamped(out.knots_v, 3, out.nv, 3.0, 6.0));
    for (int a = 0; a <= 20; a++)
        for (int b = 0; b <= 15; b++) {
            double u = 3 + a / 5.0, v = 3 + b / 5.0, want[3], got[3], direct[3];
            surface_by_definition(&s, u, v, want);
            sc_surface_eval(&out, u, v, got, NULL, NULL);
            sc_surface_eval(&s, u, v, direct, NULL, NULL);
            for (int d = 0; d < 3; d++) {
                CHECK_NEAR(got[d], want[d], 1e-12);
                CHECK_NEAR(direct[d], want[d], 1e-12);
            }
        }
    sc_surface_free(&out);
    sc_surface_free(&s);
}
