/* imgdiff.h — accuracy of one AOV image against another (the reference),
 * as BRIEF "Accuracy — how it is measured" defines it: holes, false hits
 * and off pixels (both hit, points more than one pixel footprint apart at
 * the reference's distance), position and normal errors, and iterations
 * when the test image has them. Percentages are of the reference's hits;
 * false hits against a reference that hits nothing make them infinite. The
 * GPU path prints the same `accuracy` line through sc_accuracy_format. */
#ifndef SC_IMGDIFF_H
#define SC_IMGDIFF_H

#include "aov.h"

typedef struct sc_accuracy {
    long ref_hits;            /* pixels the reference hits */
    long test_hits;
    long both_hit;
    long holes;               /* reference hits, test misses */
    long false_hits;          /* reference misses, test hits */
    long off;                 /* both hit, more than one footprint apart */
    double coverage_pct;      /* (holes + false hits) / ref_hits × 100 */
    double fail_pct;          /* (holes + false hits + off) / ref_hits × 100;
                                 both 0 when neither image hits, infinite
                                 when only the test does */
    double pos_median_px;     /* position error in footprints, over both_hit */
    double pos_max_px;
    double normal_mean_deg;   /* angle between normals, over both_hit */
    double normal_max_deg;
    int has_iters;            /* the test image has iteration counts */
    double iters_mean;        /* over the test's hit pixels */
    double iters_max;
    double pos_p99_px;        /* 99th percentiles (nearest rank) over both_hit */
    double normal_p99_deg;
} sc_accuracy;

/* Fails (and fills err) when the two images differ in size or camera:
 * such images cannot be compared pixel by pixel. */
int sc_accuracy_compare(const sc_aov *ref, const sc_aov *test, sc_accuracy *acc, sc_error *err);

/* "accuracy coverage_pct=… fail_pct=… pos_median_px=… pos_max_px=…
 * normal_mean_deg=… normal_max_deg=…[ iters_mean=… iters_max=…]
 * pos_p99_px=… normal_p99_deg=…" */
void sc_accuracy_format(const sc_accuracy *acc, char *buf, size_t size);

#endif
