/* surface_area.h — the trimmed area of a surface of our scene model, for
 * the independent check against Open CASCADE (test_step_occt.c): what we
 * draw, integrated with our own exact trim test. */
#ifndef SC_TEST_SURFACE_AREA_H
#define SC_TEST_SURFACE_AREA_H

#include "scene.h"

/* World-space area of the kept part of `s` and its centre. Returns
 * SC_FAIL when the trim loops cannot be prepared. */
int surface_trimmed_area(const sc_surface *s, double *area, double centroid[3]);

#endif
