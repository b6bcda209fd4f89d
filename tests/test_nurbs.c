/* test_nurbs.c — the NURBS core against values known independently of it:
 * The NURBS Book's example 2.3, exact conics (circle, cylinder, sphere)
 * that must stay on their quadric, central finite differences for the
 * partials, a Bernstein / de Casteljau evaluation written here for the
 * Bézier pieces, and the analytic normals of the teapot's and the sphere's
 * poles. Every shape-preserving operation (insertion, refinement,
 * extraction, splitting, elevation) is checked by evaluating before and
 * after at random parameters; clamping an unclamped B-spline, against the
 * Cox–de Boor recursion as defined, summed over the original's points. */
#include "test.h"

#include <stdlib.h>

#include "nurbs.h"

static const double R2 = 0.70710678118654752440; /* √2 / 2 */

/* ---- builders ---- */

/* cp: Euclidean coordinates (dim per point), w: weights (NULL = 1). */
static void make_curve(sc_curve *c, int dim, int degree, int ncp, const double *knots,
                       const double *cp, const double *w)
{
    sc_curve_alloc(c, dim, degree, ncp);
    memcpy(c->knots, knots, sizeof(double) * (size_t)(ncp + degree + 1));
    for (int i = 0; i < ncp; i++) {
        double wi = w ? w[i] : 1.0;
        for (int d = 0; d < dim; d++)
            c->cp[i * (dim + 1) + d] = cp[i * dim + d] * wi;
        c->cp[i * (dim + 1) + dim] = wi;
    }
}

/* Clamped knots with random interior knots (some repeated up to `degree`). */
static void random_knots(unsigned long long *rng, int degree, int ncp, double *knots)
{
    int m = ncp + degree;
    for (int i = 0; i <= degree; i++) {
        knots[i] = 0.0;
        knots[m - i] = 1.0;
    }
    double t = 0.0;
    int run = 0;
    for (int i = degree + 1; i < ncp; i++) {
        if (run == 0 || run >= degree || test_rand(rng) < 0.7) {
            t += 0.2 + test_rand(rng);
            run = 0;
        }
        knots[i] = t;
        run++;
    }
    double scale = t + 0.2 + test_rand(rng);
    for (int i = degree + 1; i < ncp; i++)
        knots[i] /= scale;
}

static void random_curve(unsigned long long *rng, int dim, int degree, int ncp, sc_curve *c)
{
    sc_curve_alloc(c, dim, degree, ncp);
    random_knots(rng, degree, ncp, c->knots);
    for (int i = 0; i < ncp; i++) {
        double w = 0.5 + 1.5 * test_rand(rng);
        for (int d = 0; d < dim; d++)
            c->cp[i * (dim + 1) + d] = (2 * test_rand(rng) - 1) * w;
        c->cp[i * (dim + 1) + dim] = w;
    }
}

static void random_surface(unsigned long long *rng, int deg_u, int deg_v, int nu, int nv,
                           sc_surface *s)
{
    memset(s, 0, sizeof *s);
    s->xform[0] = s->xform[5] = s->xform[10] = 1;
    sc_surface_alloc(s, deg_u, deg_v, nu, nv);
    random_knots(rng, deg_u, nu, s->knots_u);
    random_knots(rng, deg_v, nv, s->knots_v);
    for (int k = 0; k < nu * nv; k++) {
        double w = 0.5 + 1.5 * test_rand(rng);
        for (int d = 0; d < 3; d++)
            s->cp[4 * k + d] = (2 * test_rand(rng) - 1) * w;
        s->cp[4 * k + 3] = w;
    }
    s->rational = 1;
}

/* A full unit sphere as a surface of revolution: u runs round the z axis
 * (full circle, 9 points), v from the south to the north pole (half
 * circle, 5 points). Rows v = 0 and v = 1 collapse to the poles. */
static void make_sphere(sc_surface *s)
{
    static const double ku[12] = {0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1};
    static const double kv[8] = {0, 0, 0, .5, .5, 1, 1, 1};
    static const double circle[9][3] = {{1, 0, 1}, {1, 1, R2}, {0, 1, 1}, {-1, 1, R2},
                                        {-1, 0, 1}, {-1, -1, R2}, {0, -1, 1}, {1, -1, R2},
                                        {1, 0, 1}};
    static const double profile[5][3] = {{0, -1, 1}, {1, -1, R2}, {1, 0, 1}, {1, 1, R2},
                                         {0, 1, 1}};
    memset(s, 0, sizeof *s);
    s->xform[0] = s->xform[5] = s->xform[10] = 1;
    sc_surface_alloc(s, 2, 2, 9, 5);
    memcpy(s->knots_u, ku, sizeof ku);
    memcpy(s->knots_v, kv, sizeof kv);
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 9; i++) {
            double r = profile[j][0], z = profile[j][1], w = circle[i][2] * profile[j][2];
            double *P = s->cp + 4 * (j * 9 + i);
            P[0] = circle[i][0] * r * w;
            P[1] = circle[i][1] * r * w;
            P[2] = z * w;
            P[3] = w;
        }
    s->rational = 1;
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static double len3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Largest distance between two curves over random parameters in [a, b]. */
static double curve_distance(const sc_curve *x, const sc_curve *y, double a, double b,
                             unsigned long long *rng)
{
    double worst = 0;
    for (int k = 0; k < 200; k++) {
        double t = k == 0 ? a : k == 1 ? b : a + (b - a) * test_rand(rng);
        double p[3] = {0}, q[3] = {0}, dp[3] = {0}, dq[3] = {0};
        sc_curve_eval(x, t, p, dp);
        sc_curve_eval(y, t, q, dq);
        worst = fmax(worst, dist3(p, q));
    }
    return worst;
}

static double surface_distance(const sc_surface *x, const sc_surface *y, double u0, double u1,
                               double v0, double v1, unsigned long long *rng)
{
    double worst = 0;
    for (int k = 0; k < 200; k++) {
        double u = u0 + (u1 - u0) * test_rand(rng), v = v0 + (v1 - v0) * test_rand(rng);
        double p[3], q[3];
        sc_surface_eval(x, u, v, p, NULL, NULL);
        sc_surface_eval(y, u, v, q, NULL, NULL);
        worst = fmax(worst, dist3(p, q));
    }
    return worst;
}

/* ---- basis ---- */

TEST(nurbs_span_and_basis_book_example_2_3)
{
    const double U[11] = {0, 0, 0, 1, 2, 3, 4, 4, 5, 5, 5};
    CHECK_INT(sc_find_span(2, U, 8, 2.5), 4);
    CHECK_INT(sc_find_span(2, U, 8, 0.0), 2);
    CHECK_INT(sc_find_span(2, U, 8, -1.0), 2);
    CHECK_INT(sc_find_span(2, U, 8, 1.0), 3);
    CHECK_INT(sc_find_span(2, U, 8, 4.0), 7);
    CHECK_INT(sc_find_span(2, U, 8, 5.0), 7);
    CHECK_INT(sc_find_span(2, U, 8, 7.0), 7);
    double N[3];
    sc_basis(4, 2.5, 2, U, N);
    CHECK_NEAR(N[0], 1.0 / 8, 1e-15);
    CHECK_NEAR(N[1], 6.0 / 8, 1e-15);
    CHECK_NEAR(N[2], 1.0 / 8, 1e-15);
    double D[4 * 3];
    sc_basis_ders(4, 2.5, 2, U, 3, D);
    const double want[4][3] = {{0.125, 0.75, 0.125}, {-0.5, 0, 0.5}, {1, -2, 1}, {0, 0, 0}};
    for (int k = 0; k < 4; k++)
        for (int j = 0; j < 3; j++)
            CHECK_NEAR(D[k * 3 + j], want[k][j], 1e-14);
}

TEST(nurbs_span_skips_empty_last_span)
{
    /* An interior knot of multiplicity degree+1 at the domain's end: the
     * span [1, 1) is empty, u = 1 belongs to span 2. */
    const double U[7] = {0, 0, 0, 1, 1, 1, 1};
    CHECK_INT(sc_find_span(2, U, 4, 1.0), 2);
    const double V[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    CHECK_INT(sc_find_span(2, V, 6, 1.0), 5);
    CHECK_INT(sc_find_span(2, V, 6, 0.999), 2);
    CHECK_INT(sc_find_span(2, V, 6, 2.0), 5);
}

TEST(nurbs_basis_partition_of_unity_random)
{
    unsigned long long rng = 11;
    for (int trial = 0; trial < 50; trial++) {
        int p = 1 + (int)(6 * test_rand(&rng)), ncp = p + 1 + (int)(8 * test_rand(&rng));
        double U[32];
        random_knots(&rng, p, ncp, U);
        double u = test_rand(&rng);
        int span = sc_find_span(p, U, ncp, u);
        CHECK(U[span] <= u && u < U[span + 1]);
        double D[3 * 8];
        sc_basis_ders(span, u, p, U, 2, D);
        double sum0 = 0, sum1 = 0, sum2 = 0;
        for (int j = 0; j <= p; j++) {
            CHECK(D[j] >= 0);
            sum0 += D[j];
            sum1 += D[(p + 1) + j];
            sum2 += D[2 * (p + 1) + j];
        }
        CHECK_NEAR(sum0, 1.0, 1e-14);
        CHECK_NEAR(sum1, 0.0, 1e-9);
        CHECK_NEAR(sum2, 0.0, 1e-6);
    }
}

/* ---- exact conics ---- */

TEST(nurbs_quarter_cylinder_book_value)
{
    /* u (degree 1) along x from -1 to 1; v (degree 2) the quarter circle
     * y² + z² = 1 from (y, z) = (1, 0) to (0, 1) with weights 1, 1, 2: the
     * parametrisation ((1 − t²), 2t) / (1 + t²), so (0.5, 0.5) ↦ (0, 0.6, 0.8). */
    sc_surface s = {0};
    s.xform[0] = s.xform[5] = s.xform[10] = 1;
    sc_surface_alloc(&s, 1, 2, 2, 3);
    const double ku[4] = {0, 0, 1, 1}, kv[6] = {0, 0, 0, 1, 1, 1};
    memcpy(s.knots_u, ku, sizeof ku);
    memcpy(s.knots_v, kv, sizeof kv);
    const double yz[3][2] = {{1, 0}, {1, 1}, {0, 1}}, w[3] = {1, 1, 2};
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 2; i++) {
            double *P = s.cp + 4 * (j * 2 + i);
            P[0] = (i ? 1.0 : -1.0) * w[j];
            P[1] = yz[j][0] * w[j];
            P[2] = yz[j][1] * w[j];
            P[3] = w[j];
        }
    double p[3], su[3], sv[3];
    sc_surface_eval(&s, 0.5, 0.5, p, su, sv);
    CHECK_NEAR(p[0], 0.0, 1e-15);
    CHECK_NEAR(p[1], 0.6, 1e-15);
    CHECK_NEAR(p[2], 0.8, 1e-15);
    /* d/dt of ((1 − t²), 2t) / (1 + t²) = (−4t, 2 − 2t²) / (1 + t²)², at
     * t = 1/2: (−1.28, 0.96). */
    CHECK_NEAR(su[0], 2.0, 1e-14);
    CHECK_NEAR(sv[1], -1.28, 1e-14);
    CHECK_NEAR(sv[2], 0.96, 1e-14);
    unsigned long long rng = 5;
    for (int k = 0; k < 1000; k++) {
        sc_surface_eval(&s, test_rand(&rng), test_rand(&rng), p, NULL, NULL);
        CHECK_NEAR(p[1] * p[1] + p[2] * p[2], 1.0, 1e-14);
    }
    /* The weights 1, √2/2, 1 trace the same arc at uniform angle: the
     * middle is at 45°. */
    for (int i = 0; i < 2; i++)
        for (int d = 0; d < 4; d++)
            s.cp[4 * (1 * 2 + i) + d] *= R2;
    for (int i = 0; i < 2; i++)
        for (int d = 0; d < 4; d++)
            s.cp[4 * (2 * 2 + i) + d] /= 2;
    sc_surface_eval(&s, 0.5, 0.5, p, NULL, NULL);
    CHECK_NEAR(p[1], R2, 1e-15);
    CHECK_NEAR(p[2], R2, 1e-15);
    sc_surface_free(&s);
}

TEST(nurbs_circle_exact)
{
    /* A full circle of radius 2 from four rational quadratic arcs. */
    const double knots[12] = {0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1};
    const double xy[9][2] = {{2, 0}, {2, 2}, {0, 2}, {-2, 2}, {-2, 0},
                             {-2, -2}, {0, -2}, {2, -2}, {2, 0}};
    const double w[9] = {1, R2, 1, R2, 1, R2, 1, R2, 1};
    sc_curve c;
    make_curve(&c, 2, 2, 9, knots, &xy[0][0], w);
    unsigned long long rng = 3;
    for (int k = 0; k < 2000; k++) {
        double t = test_rand(&rng), p[2], d[2];
        sc_curve_eval(&c, t, p, d);
        CHECK_NEAR(hypot(p[0], p[1]), 2.0, 1e-14);
        /* The tangent is perpendicular to the radius... */
        CHECK_NEAR((p[0] * d[0] + p[1] * d[1]) / hypot(d[0], d[1]), 0.0, 1e-13);
        /* ... and matches a central difference. */
        double h = 1e-6, a[2], b[2];
        sc_curve_eval(&c, t - h, a, NULL);
        sc_curve_eval(&c, t + h, b, NULL);
        if (t > h && t < 1 - h && fabs(t - 0.25) > h && fabs(t - 0.5) > h && fabs(t - 0.75) > h) {
            CHECK_NEAR((b[0] - a[0]) / (2 * h), d[0], 1e-6);
            CHECK_NEAR((b[1] - a[1]) / (2 * h), d[1], 1e-6);
        }
    }
    double p[2];
    sc_curve_eval(&c, 0.125, p, NULL);
    CHECK_NEAR(p[0], 2 * R2, 1e-15);
    CHECK_NEAR(p[1], 2 * R2, 1e-15);
    sc_curve_free(&c);
}

TEST(nurbs_sphere_exact_points_and_normals)
{
    sc_surface s;
    make_sphere(&s);
    unsigned long long rng = 17;
    int outward = 0, inward = 0;
    for (int k = 0; k < 2000; k++) {
        double u = test_rand(&rng), v = test_rand(&rng);
        if (k < 40) /* the poles, at many u */
            v = k % 2 ? 1.0 : 0.0;
        double p[3], n[3];
        sc_surface_eval(&s, u, v, p, NULL, NULL);
        CHECK_NEAR(len3(p), 1.0, 1e-14);
        CHECK_INT(sc_surface_normal(&s, u, v, n), 0);
        CHECK_NEAR(len3(n), 1.0, 1e-14);
        /* Parallel to the radius: the sine (linear in the angle, unlike
         * the cosine) vanishes. */
        double cosine = n[0] * p[0] + n[1] * p[1] + n[2] * p[2], sine[3];
        sine[0] = n[1] * p[2] - n[2] * p[1];
        sine[1] = n[2] * p[0] - n[0] * p[2];
        sine[2] = n[0] * p[1] - n[1] * p[0];
        CHECK_NEAR(len3(sine), 0.0, 1e-12);
        if (cosine > 0)
            outward++;
        else
            inward++;
    }
    /* One orientation everywhere, poles included. */
    CHECK(outward == 0 || inward == 0);
    sc_surface_free(&s);
}

TEST(nurbs_partials_match_finite_differences)
{
    unsigned long long rng = 23;
    for (int trial = 0; trial < 10; trial++) {
        sc_surface s;
        random_surface(&rng, 3, 2, 6, 5, &s);
        for (int k = 0; k < 50; k++) {
            double u = 0.01 + 0.98 * test_rand(&rng), v = 0.01 + 0.98 * test_rand(&rng);
            double h = 1e-6, p[3], su[3], sv[3], a[3], b[3], c[3], d[3];
            int span_u = sc_find_span(3, s.knots_u, 6, u), span_v = sc_find_span(2, s.knots_v, 5, v);
            /* Central differences only inside one polynomial piece. */
            if (u - h < s.knots_u[span_u] || u + h >= s.knots_u[span_u + 1] ||
                v - h < s.knots_v[span_v] || v + h >= s.knots_v[span_v + 1])
                continue;
            sc_surface_eval(&s, u, v, p, su, sv);
            sc_surface_eval(&s, u - h, v, a, NULL, NULL);
            sc_surface_eval(&s, u + h, v, b, NULL, NULL);
            sc_surface_eval(&s, u, v - h, c, NULL, NULL);
            sc_surface_eval(&s, u, v + h, d, NULL, NULL);
            double scale = 1 + len3(su) + len3(sv);
            for (int i = 0; i < 3; i++) {
                CHECK_NEAR((b[i] - a[i]) / (2 * h), su[i], 1e-6 * scale);
                CHECK_NEAR((d[i] - c[i]) / (2 * h), sv[i], 1e-6 * scale);
            }
        }
        sc_surface_free(&s);
    }
}

TEST(nurbs_eval_world_applies_transform)
{
    sc_surface s;
    make_sphere(&s);
    /* Scale by 2 in x, rotate 90° about z, translate by (1, 2, 3). */
    const double m[12] = {0, -1, 0, 1, 2, 0, 0, 2, 0, 0, 1, 3};
    memcpy(s.xform, m, sizeof m);
    double p[3], su[3], sv[3], q[3], qu[3], qv[3];
    sc_surface_eval(&s, 0.3, 0.6, p, su, sv);
    sc_surface_eval_world(&s, 0.3, 0.6, q, qu, qv);
    CHECK_NEAR(q[0], 1 - p[1], 1e-15);
    CHECK_NEAR(q[1], 2 + 2 * p[0], 1e-15);
    CHECK_NEAR(q[2], 3 + p[2], 1e-15);
    CHECK_NEAR(qu[0], -su[1], 1e-15);
    CHECK_NEAR(qv[1], 2 * sv[0], 1e-15);
    sc_surface_free(&s);
}

/* ---- shape-preserving operations ---- */

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
static int read_teapot(sc_surface *patches, int max)
{
    FILE *f = fopen(TEST_TEAPOT32, "r");
    if (!f)
        return 0;
    int n = 0;
    if (fscanf(f, "%d", &n) != 1 || n > max)
        n = 0;
    static const double k[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    for (int s = 0; s < n; s++) {
        int du, dv;
        sc_surface *p = &patches[s];
        memset(p, 0, sizeof *p);
        p->xform[0] = p->xform[5] = p->xform[10] = 1;
        if (fscanf(f, "%d %d", &du, &dv) != 2 || du != 3 || dv != 3) {
            n = s;
            break;
        }
        sc_surface_alloc(p, 3, 3, 4, 4);
        memcpy(p->knots_u, k, sizeof k);
        memcpy(p->knots_v, k, sizeof k);
        for (int i = 0; i < 16; i++) {
            if (fscanf(f, "%lf %lf %lf", &p->cp[4 * i], &p->cp[4 * i + 1], &p->cp[4 * i + 2]) != 3)
                n = s;
            p->cp[4 * i + 3] = 1;
        }
    }
    fclose(f);
    return n;
}

TEST(nurbs_normal_at_teapot_poles)
{
    sc_surface patches[32];
    int n = read_teapot(patches, 32);
    CHECK_INT(n, 32);
    if (n != 32)
        return;
    int poles = 0, ok = 1;
    for (int s = 0; s < n && ok; s++) {
        const sc_surface *p = &patches[s];
        /* A collapsed edge v = 0: the first row's four points coincide. */
        int collapsed = 1;
        for (int i = 1; i < 4; i++)
            collapsed &= dist3(p->cp, p->cp + 4 * i) == 0;
        if (!collapsed)
            continue;
        poles++;
        for (int k = 0; k <= 20 && ok; k++) {
            double u = k / 20.0, n0[3], n1[3], su[3], sv[3], pt[3];
            sc_surface_eval(p, u, 0, pt, su, sv);
            ok = len3(su) < 1e-12 * len3(sv);   /* the pole really is singular */
            ok = ok && sc_surface_normal(p, u, 0, n0) == 0;
            ok = ok && fabs(len3(n0) - 1) < 1e-14 && hypot(n0[0], n0[1]) < 1e-12;
            /* Same side as the ordinary normal just off the pole. */
            ok = ok && sc_surface_normal(p, u, 1e-3, n1) == 0;
            ok = ok && n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] > 0.99;
            if (!ok)
                fprintf(stderr, "  patch %d u=%g: n=(%g %g %g) off-pole (%g %g %g)\n", s, u,
                        n0[0], n0[1], n0[2], n1[0], n1[1], n1[2]);
        }
    }
    for (int s = 0; s < n; s++)
        sc_surface_free(&patches[s]);
    CHECK(ok);
    CHECK_INT(poles, 8); /* four lid-knob patches, four bottom patches */
}

TEST(nurbs_normal_fallback_on_degenerate_corner)
{
    /* A bilinear patch S = (u, uv, 0) whose edge u = 0 collapses to the
     * origin (sv vanishes there): the flat triangle (0,0,0), (1,0,0),
     * (1,1,0), normal +z everywhere, the collapsed edge included. */
    sc_surface s = {0};
    s.xform[0] = s.xform[5] = s.xform[10] = 1;
    sc_surface_alloc(&s, 1, 1, 2, 2);
    const double k[4] = {0, 0, 1, 1};
    memcpy(s.knots_u, k, sizeof k);
    memcpy(s.knots_v, k, sizeof k);
    const double P[4][4] = {{0, 0, 0, 1}, {1, 0, 0, 1}, {0, 0, 0, 1}, {1, 1, 0, 1}};
    memcpy(s.cp, P, sizeof P);
    double n[3];
    for (int k2 = 0; k2 <= 4; k2++) {
        CHECK_INT(sc_surface_normal(&s, 0, k2 / 4.0, n), 0);
        CHECK_NEAR(n[2], 1.0, 1e-12);
    }
    /* A surface collapsed to a point has no normal. */
    for (int i = 0; i < 16; i++)
        s.cp[i] = i % 4 == 3 ? 1 : 0.5;
    CHECK_INT(sc_surface_normal(&s, 0.5, 0.5, n), -1);
    sc_surface_free(&s);
}

/* ---- unclamped knot vectors ---- */

/* N_{i,p}(u) by the Cox–de Boor recursion as defined (half-open intervals,
 * 0/0 taken as 0) over the whole knot vector: independent of sc_find_span
 * and sc_basis, and of whether the vector is clamped. */
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
