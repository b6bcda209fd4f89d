/* test_splines.c — the terrain splines of seed 004 (runtime/terrain):
 * triangular Bézier evaluation against polynomials, each scheme's
 * smoothness across patch edges, polynomial reproduction, the convergence
 * orders of Table I (at 2*10^4 sites instead of the paper's 10^6, to stay
 * fast), and height files refused with file:line. */
#include "test.h"

#include <stdlib.h>

#include "splines.h"

/* A polynomial sum a[p][q] x^p y^q of total degree <= 4, with derivatives. */
typedef struct poly { double a[5][5]; int degree; } poly;

static void poly_random(poly *P, int degree, unsigned long long *rng)
{
    memset(P, 0, sizeof *P);
    P->degree = degree;
    for (int p = 0; p <= degree; p++)
        for (int q = 0; p + q <= degree; q++) P->a[p][q] = 2 * test_rand(rng) - 1;
}

static double ipow(double x, int n) { double r = 1; while (n-- > 0) r *= x; return r; }

/* d^(dx+dy) / dx^dx dy^dy at (x, y). */
static double poly_d(const poly *P, int dx, int dy, double x, double y)
{
    double s = 0;
    for (int p = dx; p <= 4; p++)
        for (int q = dy; p + q <= 4; q++) {
            double c = P->a[p][q];
            for (int t = 0; t < dx; t++) c *= p - t;
            for (int t = 0; t < dy; t++) c *= q - t;
            s += c * ipow(x, p - dx) * ipow(y, q - dy);
        }
    return s;
}

static double poly_cb(double x, double y, void *user) { return poly_d(user, 0, 0, x, y); }

TEST(splines_tri_eval_polynomial)
{
    unsigned long long rng = 7;
    const double tri[6] = {0.3, -0.2, 1.7, 0.4, 0.1, 1.3};
    double inv[225], val[15], coef[15], up[21];
    CHECK(sc_tri_interp_matrix(4, inv, NULL) == SC_OK);
    for (int trial = 0; trial < 5; trial++) {
        poly P;
        poly_random(&P, 4, &rng);
        for (int i = 0; i <= 4; i++)
            for (int j = 0; i + j <= 4; j++) {
                int k = 4 - i - j;
                double x = (i * tri[0] + j * tri[2] + k * tri[4]) / 4;
                double y = (i * tri[1] + j * tri[3] + k * tri[5]) / 4;
                val[sc_tri_index(4, i, j)] = poly_d(&P, 0, 0, x, y);
            }
        for (int r = 0; r < 15; r++) {
            coef[r] = 0;
            for (int c = 0; c < 15; c++) coef[r] += inv[r * 15 + c] * val[c];
        }
        sc_tri_elevate(4, coef, up);
        for (int s = 0; s < 10; s++) {
            double x = 2 * test_rand(&rng) - 0.5, y = 2 * test_rand(&rng) - 0.5;
            sc_tri_point p, q;
            sc_tri_eval(4, coef, tri, x, y, &p);
            sc_tri_eval(5, up, tri, x, y, &q);
            CHECK_NEAR(p.value, poly_d(&P, 0, 0, x, y), 1e-11);
            CHECK_NEAR(p.grad[0], poly_d(&P, 1, 0, x, y), 1e-10);
            CHECK_NEAR(p.grad[1], poly_d(&P, 0, 1, x, y), 1e-10);
            CHECK_NEAR(p.hess[0], poly_d(&P, 2, 0, x, y), 1e-9);
            CHECK_NEAR(p.hess[1], poly_d(&P, 1, 1, x, y), 1e-9);
            CHECK_NEAR(p.hess[2], poly_d(&P, 0, 2, x, y), 1e-9);
            CHECK_NEAR(q.value, p.value, 1e-11);
            CHECK_NEAR(q.hess[1], p.hess[1], 1e-9);
        }
    }
}

TEST(splines_box_spline)
{
    CHECK_NEAR(sc_box_spline_value(0, 0), 0.5, 1e-14);
    const int nb[6][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 0}, {-1, -1}, {0, -1}};
    for (int k = 0; k < 6; k++) CHECK_NEAR(sc_box_spline_value(nb[k][0], nb[k][1]), 1.0 / 12, 1e-14);
    CHECK_NEAR(sc_box_spline_value(1, -1), 0, 1e-14);
    /* Partition of unity and non-negativity. */
    unsigned long long rng = 3;
    for (int s = 0; s < 20; s++) {
        double x = test_rand(&rng), y = test_rand(&rng), sum = 0;
        for (int i = -3; i <= 3; i++)
            for (int j = -3; j <= 3; j++) {
                double m = sc_box_spline_value(x - i, y - j);
                CHECK(m >= -1e-15);
                sum += m;
            }
        CHECK_NEAR(sum, 1, 1e-13);
    }
}

/* Largest jump of the value, gradient and Hessian across the interior
 * edges of a mesh (three points on each edge, both patches evaluated). */
static void edge_jumps(const sc_tri_mesh *m, double jump[3])
{
    jump[0] = jump[1] = jump[2] = 0;
    for (int p = 0; p < m->count; p++) {
        double ta[6];
        sc_tri_mesh_domain(m, p, ta);
        /* Each lower patch: its diagonal (to the upper), its bottom edge
         * (to the square below) and its right edge (to the square right). */
        if (p % 2) continue;
        int sq = p / 2, i = sq % m->nx, j = sq / m->nx;
        int nbr[3] = {p + 1, j > 0 ? 2 * ((j - 1) * m->nx + i) + 1 : -1,
                      i + 1 < m->nx ? 2 * (j * m->nx + i + 1) + 1 : -1};
        const double ends[3][4] = {{ta[0], ta[1], ta[4], ta[5]}, {ta[0], ta[1], ta[2], ta[3]},
                                   {ta[2], ta[3], ta[4], ta[5]}};
        for (int e = 0; e < 3; e++) {
            if (nbr[e] < 0) continue;
            double tb[6];
            sc_tri_mesh_domain(m, nbr[e], tb);
            for (int s = 1; s <= 3; s++) {
                double t = s / 4.0;
                double x = ends[e][0] + t * (ends[e][2] - ends[e][0]);
                double y = ends[e][1] + t * (ends[e][3] - ends[e][1]);
                sc_tri_point a, b;
                sc_tri_eval(4, m->coef + (size_t)p * 15, ta, x, y, &a);
                sc_tri_eval(4, m->coef + (size_t)nbr[e] * 15, tb, x, y, &b);
                jump[0] = fmax(jump[0], fabs(a.value - b.value));
                for (int c = 0; c < 2; c++) jump[1] = fmax(jump[1], fabs(a.grad[c] - b.grad[c]));
                for (int c = 0; c < 3; c++) jump[2] = fmax(jump[2], fabs(a.hess[c] - b.hess[c]));
            }
        }
    }
}

TEST(splines_continuity)
{
    /* Franke at N = 576: gradients up to ~10, second derivatives ~100. */
    for (int s = 0; s < SC_SPLINE_SCHEME_COUNT; s++) {
        int k = sc_spline_samples_per_square(s);
        sc_heights h;
        sc_heights_franke(24, sc_spline_pad(s), &h);
        sc_tri_mesh m;
        sc_error err = {0};
        CHECK(sc_spline_build(&h, s, &m, &err) == SC_OK);
        sc_heights_free(&h);
        CHECK_INT(m.count, 2 * (24 / k) * (24 / k));
        double jump[3];
        edge_jumps(&m, jump);
        sc_tri_mesh_free(&m);
        fprintf(stderr, "  %s: jumps value %.2g gradient %.2g hessian %.2g\n",
                sc_spline_scheme_name(s), jump[0], jump[1], jump[2]);
        CHECK(jump[0] < 1e-12);
        if (s == SC_SPLINE_C1 || s == SC_SPLINE_C2) CHECK(jump[1] < 1e-10);
        else CHECK(jump[1] > 1e-3);            /* the test can see a kink */
        if (s == SC_SPLINE_C2) CHECK(jump[2] < 1e-8);
        if (s == SC_SPLINE_C1) CHECK(jump[2] > 1e-3);
    }
}

/* Heights of P on the grid i/n, with the pad filled from P too. */
static void poly_heights(const poly *P, int n, int pad, sc_heights *h)
{
    sc_heights_franke(n, pad, h);
    for (int j = -pad; j <= n + pad; j++)
        for (int i = -pad; i <= n + pad; i++)
            h->z[(size_t)(j + pad) * (n + 1 + 2 * pad) + (i + pad)] =
                poly_d(P, 0, 0, (double)i / n, (double)j / n);
}

TEST(splines_reproduction)
{
    /* C0 reproduces quartics, C1 cubics, C2 and linear linear functions;
     * C0 interpolates every sample, C1 the samples at the vertices. */
    const int degree[SC_SPLINE_SCHEME_COUNT] = {4, 3, 1, 1};
    unsigned long long rng = 11;
    for (int s = 0; s < SC_SPLINE_SCHEME_COUNT; s++) {
        poly P;
        poly_random(&P, degree[s], &rng);
        sc_heights h;
        poly_heights(&P, 12, sc_spline_pad(s), &h);
        sc_tri_mesh m;
        CHECK(sc_spline_build(&h, s, &m, NULL) == SC_OK);
        double rms, mx;
        sc_spline_measure(&m, poly_cb, &P, 2000, 1, &rms, &mx);
        if (mx > 1e-12) fprintf(stderr, "  %s: max error %.3g\n", sc_spline_scheme_name(s), mx);
        int k = sc_spline_samples_per_square(s);
        poly Q;
        poly_random(&Q, 4, &rng);
        sc_heights hq;
        poly_heights(&Q, 12, sc_spline_pad(s), &hq);
        sc_tri_mesh mq;
        CHECK(sc_spline_build(&hq, s, &mq, NULL) == SC_OK);
        double worst = 0;
        for (int j = 0; j <= 12; j++)
            for (int i = 0; i <= 12; i++) {
                if (s == SC_SPLINE_C1 && (i % k || j % k)) continue;
                if (s == SC_SPLINE_C2) continue;
                sc_tri_point p;
                CHECK(sc_tri_mesh_eval(&mq, i / 12.0, j / 12.0, &p) == SC_OK);
                worst = fmax(worst, fabs(p.value - sc_heights_at(&hq, i, j)));
            }
        sc_tri_mesh_free(&m);
        sc_tri_mesh_free(&mq);
        sc_heights_free(&h);
        sc_heights_free(&hq);
        CHECK(mx < 1e-12);
        CHECK(worst < 1e-12);
    }
}

TEST(splines_convergence_orders)
{
    /* Per doubling of resolution (N x 4) the RMS error must fall by about
     * 2^5 (C0), 2^3.5 (C1), 2^2 (C2, linear): seed 004's Table I. */
    const double lo[SC_SPLINE_SCHEME_COUNT] = {4.5, 3.2, 1.8, 1.8};
    const double hi[SC_SPLINE_SCHEME_COUNT] = {5.5, 4.5, 2.2, 2.2};
    for (int s = 0; s < SC_SPLINE_SCHEME_COUNT; s++) {
        sc_spline_error a, b;
        sc_error err = {0};
        CHECK(sc_spline_franke_error(s, 576, 20000, &a, &err) == SC_OK);
        CHECK(sc_spline_franke_error(s, 2304, 20000, &b, &err) == SC_OK);
        double order = log2(a.rel_rms / b.rel_rms);
        fprintf(stderr, "  %s: rms %.3g -> %.3g, order %.2f\n", sc_spline_scheme_name(s),
                a.rel_rms, b.rel_rms, order);
        CHECK(order > lo[s]);
        CHECK(order < hi[s]);
    }
    sc_error err = {0};
    sc_spline_error e;
    CHECK(sc_spline_franke_error(SC_SPLINE_C1, 100, 10, &e, &err) == SC_FAIL);
    CHECK_CONTAINS(err.message, "multiple of 3");
}

static const char *write_bytes(const char *name, const void *data, size_t n)
{
    static char path[4][1024];
    static int next;
    char *b = path[next++ % 4];
    snprintf(b, 1024, "%s/%s", test_tmpdir(), name);
    FILE *f = fopen(b, "wb");
    if (f) {
        fwrite(data, 1, n, f);
        fclose(f);
    }
    return b;
}

TEST(splines_heights_files)
{
    sc_heights h;
    sc_error err = {0};
    /* The first row is the top (largest y); PGM levels are divided by maxval. */
    const char *p2 = test_write_tmp("h.pgm", "P2\n# a comment\n3 2\n4\n0 1 2\n3 4 4\n");
    CHECK(sc_heights_read(p2, 0.5, 8, &h, &err) == SC_OK);
    CHECK_INT(h.nx, 3);
    CHECK_INT(h.ny, 2);
    CHECK_NEAR(sc_heights_at(&h, 1, 1), 2, 0);      /* 1/4 * 8 */
    CHECK_NEAR(sc_heights_at(&h, 2, 0), 8, 0);
    CHECK_NEAR(h.dx, 0.5, 0);
    sc_heights_free(&h);
    const unsigned char p5[] = "P5 2 2 65535\n\x00\x00\xff\xff\x80\x00\x00\x01";
    CHECK(sc_heights_read(write_bytes("h16.pgm", p5, sizeof p5 - 1), 1, 1, &h, &err) == SC_OK);
    CHECK_NEAR(sc_heights_at(&h, 1, 1), 1, 0);
    CHECK_NEAR(sc_heights_at(&h, 0, 0), 32768.0 / 65535, 1e-15);
    sc_heights_free(&h);
    const unsigned char p58[] = "P5\n2 2\n200\n\x00\xc8\x64\x00";
    CHECK(sc_heights_read(write_bytes("h8.pgm", p58, sizeof p58 - 1), 1, 1, &h, &err) == SC_OK);
    CHECK_NEAR(sc_heights_at(&h, 0, 0), 0.5, 0);
    sc_heights_free(&h);
    const char *csv = test_write_tmp("h.csv", "# heights\n1, 2, 3\n\n4 5 6\n");
    CHECK(sc_heights_read(csv, 1, 2, &h, &err) == SC_OK);
    CHECK_NEAR(sc_heights_at(&h, 0, 0), 8, 0);
    CHECK_NEAR(sc_heights_at(&h, 2, 1), 6, 0);
    /* A file grid builds every scheme (cut to fit, padded by extrapolation). */
    sc_heights big;
    sc_heights_franke(13, 0, &big);
    test_warnings w = {0};
    sc_set_logger(test_gather_warnings, &w);
    for (int s = 0; s < SC_SPLINE_SCHEME_COUNT; s++) {
        sc_tri_mesh m;
        int rc = sc_spline_build(&big, s, &m, &err);
        if (rc == SC_OK) sc_tri_mesh_free(&m);
        CHECK(rc == SC_OK);
    }
    sc_set_logger(NULL, NULL);
    sc_heights_free(&big);
    CHECK_INT(w.count, 2);
    CHECK_CONTAINS(w.text, "scheme c1 uses 13 x 13 of the 14 x 14 heights");
    sc_tri_mesh m;
    CHECK(sc_spline_build(&h, SC_SPLINE_C0, &m, &err) == SC_FAIL);
    CHECK_CONTAINS(err.message, "at least 5 x 5");
    sc_heights_free(&h);
}

TEST(splines_heights_malformed)
{
    static const struct { const char *name, *text, *where; size_t len; } cases[] = {
        {"ragged.csv", "1,2,3\n4,5\n", ":2: row has 2 values", 0},
        {"word.csv", "1,2\n3,x\n", ":2: value 2 is not a number", 0},
        {"junk.csv", "1,2\n3,4q\n", ":2: value 2 is not a number", 0},
        {"nan.csv", "1,2\n\n3,nan\n", ":3: value 2 is not finite", 0},
        {"inf.csv", "1,inf\n3,4\n", ":1: value 2 is not finite", 0},
        {"empty.csv", "", ":1: empty file", 0},
        {"comments.csv", "# nothing\n\n", ":2: no heights", 0},
        {"single.csv", "1,2,3\n", ":1: 3 x 1 heights", 0},
        {"short.pgm", "P2\n3 2\n255\n1 2 3\n4 5\n", ":5: PGM has 5 samples, its header says 3 x 2", 0},
        {"long.pgm", "P2\n2 2\n255\n1 2\n3 4\n5\n", ":6: PGM has more samples", 0},
        {"maxval0.pgm", "P2\n2 2\n0\n0 0 0 0\n", ":3: PGM maxval 0", 0},
        {"maxval.pgm", "P2 2 2\n70000\n1 2 3 4\n", ":2: PGM maxval 70000", 0},
        {"above.pgm", "P2 2 2 9\n1 2\n3 10\n", ":3: PGM sample 10 is above maxval", 0},
        {"header.pgm", "P2\n2\n", ":3: PGM header ends before its height", 0},
        {"p5short.pgm", "P5\n2 2\n255\n\x01\x02\x03", ":3: PGM raster has 3 bytes", 0},
        {"p5long16.pgm", "P5\n2 2\n1000\n\x00\x01\x00\x02\x00\x03\x00\x04\x00", ":3: PGM raster has 9 bytes", 9 + 12},
        /* A short file cannot ask for a large grid: the header is checked
         * against the bytes present (and the limit) before allocating. */
        {"tall.pgm", "P2\n4000 4000\n255\n1 2 3\n", ":3: PGM has 7 bytes after its header", 0},
        {"tall5.pgm", "P5\n4000 4000\n255\n\x01", ":3: PGM raster has 1 bytes", 0},
        {"vast.pgm", "P2\n5000 5000\n255\n", ":3: PGM of 5000 x 5000 is larger than the limit", 0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        size_t n = cases[c].len ? cases[c].len : strlen(cases[c].text);
        const char *path = write_bytes(cases[c].name, cases[c].text, n);
        sc_heights h = {0};
        sc_error err = {0};
        char buf[1024], want[256];
        CHECK(sc_heights_read(path, 1, 1, &h, &err) == SC_FAIL);
        CHECK(h.z == NULL);
        snprintf(want, sizeof want, "%s%s", cases[c].name, cases[c].where);
        CHECK_CONTAINS(sc_error_text(&err, buf, sizeof buf), want);
    }
}
