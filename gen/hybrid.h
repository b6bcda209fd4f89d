/* hybrid.h — Newton with a subdivision fallback, for the intersection
 * skeleton (hybrid.c). */
#ifndef SCG_HYBRID_H
#define SCG_HYBRID_H

#include "intersect.h"

/* Newton from uv0 for the key's iterations; where it does not converge
 * inside the iteration box, subdivision of the same sub-patch. */
void scg_method_hybrid(scg_isect *c, scg_value uv0, scg_value behind);

#endif
