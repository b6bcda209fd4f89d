/* nurbs_util.c — builders and distances shared by the NURBS core's tests
 * (test_nurbs.c: evaluation; test_nurbs_ops.c: operations). */
#include "nurbs_util.h"

#include <math.h>
#include <stdlib.h>

#include "test.h"

/* ---- builders ---- */

/* cp: Euclidean coordinates (dim per point), w: weights (NULL = 1). */
void make_curve(sc_curve *c, int dim, int degree, int ncp, const double *knots,
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
void random_knots(unsigned long long *rng, int degree, int ncp, double *knots)
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

void random_curve(unsigned long long *rng, int dim, int degree, int ncp, sc_curve *c)
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

void random_surface(unsigned long long *rng, int deg_u, int deg_v, int nu, int nv,
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
void make_sphere(sc_surface *s)
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

double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

double len3(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* Largest distance between two curves over random parameters in [a, b]. */
double curve_distance(const sc_curve *x, const sc_curve *y, double a, double b,
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

double surface_distance(const sc_surface *x, const sc_surface *y, double u0, double u1,
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
