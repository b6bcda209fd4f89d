/* subdiv.h — object-space subdivision for the intersection skeleton
 * (subdiv.c). */
#ifndef SCG_SUBDIV_H
#define SCG_SUBDIV_H

#include "intersect.h"

/* The whole method: subdivision of the hull's sub-patch with a stack of
 * key->max_iters intervals (the key's start is `mid` and unused). */
void scg_method_subdiv(scg_isect *c, scg_value uv0, scg_value behind);

#endif
