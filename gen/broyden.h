/* broyden.h — Broyden's method for the intersection skeleton (broyden.c). */
#ifndef SCG_BROYDEN_H
#define SCG_BROYDEN_H

#include "intersect.h"

/* One full evaluation at uv0, then the key's maximum iterations of
 * Broyden steps, each evaluating the point only. */
void scg_method_broyden(scg_isect *c, scg_value uv0, scg_value behind);

#endif
