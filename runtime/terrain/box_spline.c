/* box_spline.c — the quartic C2 box spline on the three-direction mesh
 * (directions (1,0), (0,1), (1,1), each twice) and its BB-net: 24 quartic
 * pieces, of which the C2 scheme of splines.c takes the coefficients. The
 * paper (section IV) derives the net from the smoothness conditions; here
 * the spline is evaluated by the de Boor–Höllig recurrence at 15 points
 * inside each triangle and converted to BB-form by the collocation inverse,
 * which gives the same net (the tests check C2 continuity and the known
 * values M(0) = 1/2, M(neighbour) = 1/12). */
#include "splines.h"

#include <math.h>
#include <pthread.h>

/* The uncentred box spline with a, b, c copies of (1,0), (0,1), (1,1):
 * support sum of [0,1] xi. Half-open cells at the base, so that a point on
 * a mesh line gets one one-sided value. */
static double box(int a, int b, int c, double x, double y)
{
    int n = a + b + c;
    if ((a > 0) + (b > 0) + (c > 0) < 2) return 0;   /* does not span: a line measure */
    if (n == 2) {
        double s, t;
        if (a && b) { s = x; t = y; }
        else if (a) { t = y; s = x - y; }             /* s e1 + t e3 */
        else { t = x; s = y - x; }                    /* s e2 + t e3 */
        return (s >= 0 && s < 1 && t >= 0 && t < 1) ? 1.0 : 0.0;
    }
    /* x = a t1 e1 + b t2 e2 + c t3 e3, each copy of a direction with the
     * same t, so that the sum over copies is a multiple. */
    double t1 = 0, t2 = 0, t3 = 0;
    if (a && b) { t1 = x / a; t2 = y / b; }
    else if (!a) { t3 = x / c; t2 = (y - x) / b; }
    else { t3 = y / c; t1 = (x - y) / a; }
    double sum = 0;
    if (a) sum += a * (t1 * box(a - 1, b, c, x, y) + (1 - t1) * box(a - 1, b, c, x - 1, y));
    if (b) sum += b * (t2 * box(a, b - 1, c, x, y) + (1 - t2) * box(a, b - 1, c, x, y - 1));
    if (c) sum += c * (t3 * box(a, b, c - 1, x, y) + (1 - t3) * box(a, b, c - 1, x - 1, y - 1));
    return sum / (n - 2);
}

/* The recurrence is exact only off the mesh lines (the lower-order box
 * splines it sums jump there), so it runs at points inside triangles. */
static double box_centred(double x, double y)
{
    return box(2, 2, 2, x + 2, y + 2);
}

/* net[upper][di + 1][dj + 1][15] */
static double net[2][4][4][15];
static pthread_once_t net_once = PTHREAD_ONCE_INIT;

static void build_net(void)
{
    /* Collocation at the domain points shrunk halfway to the centroid:
     * inside the triangle, off every mesh line, still unisolvent. */
    double bary[3 * 15], inv[15 * 15];
    for (int i = 0; i <= 4; i++)
        for (int j = 0; i + j <= 4; j++) {
            double *b = bary + 3 * sc_tri_index(4, i, j);
            b[0] = (1.0 / 3 + i / 4.0) / 2;
            b[1] = (1.0 / 3 + j / 4.0) / 2;
            b[2] = 1 - b[0] - b[1];
        }
    if (sc_tri_collocation_inverse(4, bary, inv, NULL) != SC_OK) return;
    const double tris[2][6] = {{0, 0, 1, 0, 1, 1}, {0, 0, 1, 1, 0, 1}};
    for (int up = 0; up < 2; up++)
        for (int di = -1; di <= 2; di++)
            for (int dj = -1; dj <= 2; dj++) {
                double val[15];
                const double *t = tris[up];
                for (int p = 0; p < 15; p++) {
                    const double *b = bary + 3 * p;
                    double x = b[0] * t[0] + b[1] * t[2] + b[2] * t[4];
                    double y = b[0] * t[1] + b[1] * t[3] + b[2] * t[5];
                    val[p] = box_centred(x - di, y - dj);
                }
                double *out = net[up][di + 1][dj + 1];
                for (int r = 0; r < 15; r++) {
                    double s = 0;
                    for (int p = 0; p < 15; p++) s += inv[r * 15 + p] * val[p];
                    /* The exact net is rational with denominator 24; snap
                     * the collocation's rounding away. */
                    double q = round(s * 24);
                    out[r] = fabs(s * 24 - q) < 1e-6 ? q / 24 : s;
                }
            }
}

const double *sc_box_spline_net(int upper, int di, int dj)
{
    static const double zero[15];
    if (di < -1 || di > 2 || dj < -1 || dj > 2 || upper < 0 || upper > 1) return zero;
    pthread_once(&net_once, build_net);
    return net[upper][di + 1][dj + 1];
}

/* From the net, so that points on mesh lines (the lattice included) get
 * the continuous spline's value. */
double sc_box_spline_value(double x, double y)
{
    double fi = floor(x), fj = floor(y);
    double lx = x - fi, ly = y - fj;
    int up = ly > lx;
    const double tri[2][6] = {{0, 0, 1, 0, 1, 1}, {0, 0, 1, 1, 0, 1}};
    sc_tri_point p;
    /* M(x - k) on the unit square: shift -k with k = (fi, fj). */
    if (fi < -3 || fi > 3 || fj < -3 || fj > 3) return 0;
    sc_tri_eval(4, sc_box_spline_net(up, -(int)fi, -(int)fj), tri[up], lx, ly, &p);
    return p.value;
}
