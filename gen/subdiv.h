/* subdiv.h — object-space subdivision for the intersection skeleton
 * (subdiv.c). */
#ifndef SCG_SUBDIV_H
#define SCG_SUBDIV_H

#include "intersect.h"

/* The whole method: subdivision of the hull's sub-patch with a stack of
 * key->max_iters intervals (the key's start is `mid` and unused). */
void scg_method_subdiv(scg_isect *c, scg_value uv0, scg_value behind);

/* Subdivision of the hull's sub-patch domain with a stack of `depth`
 * intervals and at most `steps` pieces popped, where `wanted` (bool; 0:
 * always) holds: sets uv_var to the middle of the nearest leaf whose box the ray
 * passes, found_var (the caller's, false before) to true when there is
 * one, and adds the
 * subdivision steps to iters_var. With `exact`, a leaf is a hit only when
 * the ray crosses the quadrilateral of its corners (no hit at a silhouette
 * that the ray passes within the tolerance). Used by hybrid.c as its fallback. */
void scg_subdiv_search(scg_isect *c, int depth, int steps, scg_value wanted, bool exact);

#endif
