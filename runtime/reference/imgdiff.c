/* imgdiff.c — per-pixel accuracy of a test AOV against a reference AOV
 * (imgdiff.h). The pixel footprint comes from the reference's camera and
 * distance, so an error is measured in pixels of the image being judged. */
#include "imgdiff.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

static int compare_doubles(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Cameras agree when every number matches to 1e-9 of the view's scale: the
 * file keeps 17 digits, so only a genuinely different view fails. */
static int same_camera(const sc_camera *a, const sc_camera *b)
{
    double scale = 0.0;
    for (int k = 0; k < 3; k++)
        scale = fmax(scale, fmax(fabs(a->eye[k]), fabs(a->target[k])));
    double tol = 1e-9 * (scale + 1.0);
    for (int k = 0; k < 3; k++)
        if (fabs(a->eye[k] - b->eye[k]) > tol || fabs(a->target[k] - b->target[k]) > tol)
            return 0;
    /* The up each view resolves to, so that an explicit +z equals none. */
    double fa[3], ra[3], ua[3], fb[3], rb[3], ub[3];
    sc_camera_frame(a, fa, ra, ua);
    sc_camera_frame(b, fb, rb, ub);
    for (int k = 0; k < 3; k++)
        if (fabs(ua[k] - ub[k]) > 1e-9)
            return 0;
    return fabs(a->fovy_deg - b->fovy_deg) <= 1e-9 * a->fovy_deg;
}

/* Index of the p-th percentile in m sorted values, by nearest rank: the
 * smallest value that at least p % of the values do not exceed. */
static size_t percentile_rank(size_t m, int p)
{
    size_t rank = (m * (size_t)p + 99) / 100;  /* ceil(m p / 100), at least 1 */
    return rank ? rank - 1 : 0;
}

int sc_accuracy_compare(const sc_aov *ref, const sc_aov *test, sc_accuracy *acc, sc_error *err)
{
    memset(acc, 0, sizeof *acc);
    if (ref->width != test->width || ref->height != test->height)
        return sc_fail(err, NULL, 0, "the images differ in size: %dx%d against %dx%d", ref->width,
                       ref->height, test->width, test->height);
    if (!same_camera(&ref->camera, &test->camera)) {
        char a[512], b[512];
        sc_camera_format(&ref->camera, a, sizeof a);
        sc_camera_format(&test->camera, b, sizeof b);
        return sc_fail(err, NULL, 0, "the images differ in camera: %s against %s", a, b);
    }
    size_t n = (size_t)ref->width * (size_t)ref->height;
    double *pos_err = sc_alloc(n, sizeof(double));
    double *normal_err = sc_alloc(n, sizeof(double));
    double normal_sum = 0.0, iters_sum = 0.0;
    acc->has_iters = test->has_iters && test->iters;
    for (size_t px = 0; px < n; px++) {
        int rh = ref->surface[px] >= 0, th = test->surface[px] >= 0;
        acc->ref_hits += rh;
        acc->test_hits += th;
        if (th && acc->has_iters) {
            iters_sum += test->iters[px];
            acc->iters_max = fmax(acc->iters_max, test->iters[px]);
        }
        if (rh && !th)
            acc->holes++;
        if (!rh && th)
            acc->false_hits++;
        if (!rh || !th)
            continue;
        double dist2 = 0.0, dot = 0.0, len_r = 0.0, len_t = 0.0;
        for (int k = 0; k < 3; k++) {
            double d = (double)test->point[3 * px + k] - (double)ref->point[3 * px + k];
            dist2 += d * d;
            dot += (double)ref->normal[3 * px + k] * test->normal[3 * px + k];
            len_r += (double)ref->normal[3 * px + k] * ref->normal[3 * px + k];
            len_t += (double)test->normal[3 * px + k] * test->normal[3 * px + k];
        }
        double footprint = sc_camera_footprint(&ref->camera, ref->t[px]);
        double e = footprint > 0.0 ? sqrt(dist2) / footprint : (dist2 > 0.0 ? INFINITY : 0.0);
        pos_err[acc->both_hit] = e;
        if (e > 1.0)
            acc->off++;
        acc->pos_max_px = fmax(acc->pos_max_px, e);
        double c = len_r > 0.0 && len_t > 0.0 ? dot / sqrt(len_r * len_t) : 1.0;
        double angle = acos(fmax(-1.0, fmin(1.0, c))) * 180.0 / pi;
        normal_sum += angle;
        acc->normal_max_deg = fmax(acc->normal_max_deg, angle);
        normal_err[acc->both_hit++] = angle;
    }
    if (acc->both_hit) {
        qsort(pos_err, (size_t)acc->both_hit, sizeof(double), compare_doubles);
        size_t m = (size_t)acc->both_hit;
        acc->pos_median_px = m % 2 ? pos_err[m / 2] : 0.5 * (pos_err[m / 2 - 1] + pos_err[m / 2]);
        acc->normal_mean_deg = normal_sum / (double)acc->both_hit;
        acc->pos_p99_px = pos_err[percentile_rank(m, 99)];
        qsort(normal_err, m, sizeof(double), compare_doubles);
        acc->normal_p99_deg = normal_err[percentile_rank(m, 99)];
    }
    free(pos_err);
    free(normal_err);
    /* Percentages of the reference's hits (BRIEF). False hits against a
     * reference that hits nothing are infinitely many of its none: the line
     * says `inf` rather than hiding them behind a 0. */
    if (acc->ref_hits) {
        double base = (double)acc->ref_hits;
        acc->coverage_pct = 100.0 * (double)(acc->holes + acc->false_hits) / base;
        acc->fail_pct = 100.0 * (double)(acc->holes + acc->false_hits + acc->off) / base;
    } else if (acc->false_hits) {
        acc->coverage_pct = acc->fail_pct = INFINITY;
    }
    if (acc->has_iters && acc->test_hits)
        acc->iters_mean = iters_sum / (double)acc->test_hits;
    return SC_OK;
}

void sc_accuracy_format(const sc_accuracy *acc, char *buf, size_t size)
{
    int n = snprintf(buf, size,
                     "accuracy coverage_pct=%.6g fail_pct=%.6g pos_median_px=%.6g pos_max_px=%.6g "
                     "normal_mean_deg=%.6g normal_max_deg=%.6g",
                     acc->coverage_pct, acc->fail_pct, acc->pos_median_px, acc->pos_max_px,
                     acc->normal_mean_deg, acc->normal_max_deg);
    if (acc->has_iters && n > 0 && (size_t)n < size)
        n += snprintf(buf + n, size - (size_t)n, " iters_mean=%.6g iters_max=%.6g",
                      acc->iters_mean, acc->iters_max);
    /* Appended last: scripts read the fields above in their old places. */
    if (n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, " pos_p99_px=%.6g normal_p99_deg=%.6g",
                 acc->pos_p99_px, acc->normal_p99_deg);
}
