/* splines.h — the quasi-interpolating quartic splines of seed 004
 * (Reis, Zeilfelder, Hering-Bertram, Farin, Hagen), section IV: from a
 * uniform grid of heights to a mesh of quartic triangular Bézier patches on
 * a type-1 triangulation. The masks and their derivation are in
 * docs/splines.md. */
#ifndef SC_SPLINES_H
#define SC_SPLINES_H

#include "heights.h"
#include "tri_bezier.h"

typedef enum sc_spline_scheme {
    SC_SPLINE_C0,       /* interpolates at every quartic domain point */
    SC_SPLINE_C1,       /* local C1 quasi-interpolant, data at cubic domain points */
    SC_SPLINE_C2,       /* the quartic C2 box spline, data at the vertices */
    SC_SPLINE_LINEAR,   /* piecewise linear interpolant, degree-elevated to 4 */
    SC_SPLINE_SCHEME_COUNT
} sc_spline_scheme;

/* "c0", "c1", "c2", "linear"; parse returns SC_FAIL on an unknown name. */
const char *sc_spline_scheme_name(sc_spline_scheme s);
int sc_spline_scheme_parse(const char *name, sc_spline_scheme *out);

/* Data samples per square side of the scheme's triangulation: 4 (c0), 3
 * (c1), 1 (c2, linear). A grid of heights with (k m + 1) samples per side
 * gives m squares per side; other sizes are cut to the largest such grid
 * (with a warning through the logger). */
int sc_spline_samples_per_square(sc_spline_scheme s);
/* Samples the scheme reads beyond the grid on every side (0, 3, 1, 0);
 * sc_spline_build extrapolates them (sc_heights_padded) when the grid has
 * fewer. */
int sc_spline_pad(sc_spline_scheme s);

/* Builds the quartic spline of scheme s from the heights: every patch has
 * degree 4 (15 coefficients), heights along z. Fails (with the grid's
 * size) when the grid is too small for the scheme. */
int sc_spline_build(const sc_heights *h, sc_spline_scheme s, sc_tri_mesh *out, sc_error *err);

/* The BB-coefficients (15 per triangle, sc_tri_index order) of the
 * centred quartic C2 box spline M (directions (1,0), (0,1), (1,1), each
 * twice; M(0) = 1/2) shifted by (di, dj), on the lower (upper = 0) or upper
 * (upper = 1) triangle of the unit square [0,1]^2: the restriction of
 * M(x - di, y - dj) there. Zero unless -1 <= di, dj <= 2. Computed once. */
const double *sc_box_spline_net(int upper, int di, int dj);
/* M itself at (x, y), from the net (zero outside its hexagonal support
 * |x|, |y|, |x - y| < 2). */
double sc_box_spline_value(double x, double y);

/* Franke's function at `points` = (k m)^2 data sites on [0,1]^2 (k from
 * sc_spline_samples_per_square), with the scheme's pad: the heights Table I
 * builds its splines from. Fails naming the counts that work. */
int sc_spline_franke_heights(sc_spline_scheme s, int points, sc_heights *out, sc_error *err);

/* The paper's Table I protocol for one scheme: Franke's function sampled at
 * `points` = (k m)^2 data sites on [0,1]^2 (144, 576, 2304, ...; k from
 * sc_spline_samples_per_square), the spline built, and the error measured
 * at `sites` points uniformly distributed on [0,1]^2 (pseudo-random, fixed
 * seed), relative to the largest |f| among the data ("relative to the
 * maximal data amplitude"). */
typedef struct sc_spline_error {
    int points;           /* N, as in Table I */
    int patches;          /* quartic pieces on [0,1]^2 */
    double rel_rms, rel_max;
} sc_spline_error;
int sc_spline_franke_error(sc_spline_scheme s, int points, int sites, sc_spline_error *out,
                           sc_error *err);

/* The same measure for a built mesh against any function f on the mesh's
 * rectangle (sites uniformly distributed on it), relative to `amplitude`. */
void sc_spline_measure(const sc_tri_mesh *m, double (*f)(double x, double y, void *user),
                       void *user, int sites, double amplitude, double *rel_rms,
                       double *rel_max);

#endif
