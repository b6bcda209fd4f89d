/* test_nurbs.c — the NURBS core's evaluation against values known
 * independently of it: The NURBS Book's example 2.3, exact conics (circle,
 * cylinder, sphere) that must stay on their quadric, central finite
 * differences for the partials, and the analytic normals of the teapot's
 * and the sphere's poles. The operations are in test_nurbs_ops.c. */
#include "test.h"

#include <stdlib.h>

#include "nurbs_util.h"

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
