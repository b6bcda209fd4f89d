/* spline_error.c — the approximation error of a terrain spline, measured
 * as in seed 004's Table I: RMS and maximum of s - f at uniformly
 * distributed sites, relative to the maximal data amplitude. */
#include "splines.h"

#include <math.h>
#include <stdint.h>

/* splitmix64: a fixed, portable stream, so that figures repeat exactly. */
static double next_uniform(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

void sc_spline_measure(const sc_tri_mesh *m, double (*f)(double x, double y, void *user),
                       void *user, int sites, double amplitude, double *rel_rms,
                       double *rel_max)
{
    uint64_t state = 20080101;
    double w = m->nx * m->hx, hgt = m->ny * m->hy, sum = 0, mx = 0;
    for (int k = 0; k < sites; k++) {
        double x = m->x0 + w * next_uniform(&state), y = m->y0 + hgt * next_uniform(&state);
        sc_tri_point p;
        if (sc_tri_mesh_eval(m, x, y, &p) != SC_OK) continue;   /* cannot happen inside */
        double d = fabs(p.value - f(x, y, user));
        sum += d * d;
        if (d > mx) mx = d;
    }
    *rel_rms = sites > 0 ? sqrt(sum / sites) / amplitude : 0;
    *rel_max = mx / amplitude;
}

static double franke_cb(double x, double y, void *user)
{
    (void)user;
    return sc_franke(x, y);
}

int sc_spline_franke_heights(sc_spline_scheme s, int points, sc_heights *out, sc_error *err)
{
    int k = sc_spline_samples_per_square(s);
    int n = (int)lround(sqrt((double)points));
    if (points < 1 || n * n != points || n % k != 0 || n > 4096)
        return sc_fail(err, NULL, 0, "%d data points: scheme %s needs N = n^2 with n a multiple "
                       "of %d, at most 4096 (144, 576, 2304, ...)", points,
                       sc_spline_scheme_name(s), k);
    if (sc_heights_franke(n, sc_spline_pad(s), out))
        return sc_fail_oom(err, NULL, 0, sc_alloc_failed_bytes(), 1, "the heights");
    return SC_OK;
}

int sc_spline_franke_error(sc_spline_scheme s, int points, int sites, sc_spline_error *out,
                           sc_error *err)
{
    if ((unsigned)s >= SC_SPLINE_SCHEME_COUNT)
        return sc_fail(err, NULL, 0, "unknown spline scheme %d", (int)s);
    if (sites < 1) return sc_fail(err, NULL, 0, "%d error sites: need at least one", sites);
    sc_heights h;
    if (sc_spline_franke_heights(s, points, &h, err) != SC_OK)
        return SC_FAIL;
    int n = h.nx - 1;
    double amp = 0;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) amp = fmax(amp, fabs(sc_heights_at(&h, i, j)));
    sc_tri_mesh m;
    int rc = sc_spline_build(&h, s, &m, err);
    sc_heights_free(&h);
    if (rc != SC_OK) return rc;
    out->points = points;
    out->patches = m.count;
    sc_spline_measure(&m, franke_cb, NULL, sites, amp, &out->rel_rms, &out->rel_max);
    sc_tri_mesh_free(&m);
    return SC_OK;
}
