/* hybrid.h — Newton, restarted from starts that cover the sub-patch where
 * it fails, for the intersection skeleton (hybrid.c). */
#ifndef SCG_HYBRID_H
#define SCG_HYBRID_H

#include "intersect.h"

/* Newton from uv0 for the key's iterations; where its point is not a
 * converged, kept crossing inside the sub-patch, Newton again from the
 * middles of the sub-patch and of its quarters and sixteenths. */
void scg_method_hybrid(scg_isect *c, scg_value uv0, scg_value behind);

/* Newton steps one pass of the hybrid's runtime loop unrolls for key. */
int scg_hybrid_pass_steps(const scg_key *key);

#endif
