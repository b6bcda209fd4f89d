/* bclip.h — Bézier clipping of the surface against the ray's two planes,
 * for the intersection skeleton (bclip.c). */
#ifndef SCG_BCLIP_H
#define SCG_BCLIP_H

#include "intersect.h"

/* The whole method: clipping of the hull's sub-patch, at most
 * key->max_iters steps (the key's start is `mid` and unused). */
void scg_method_bclip(scg_isect *c, scg_value uv0, scg_value behind);

#endif
