/* subdiv.h — object-space subdivision for the intersection skeleton
 * (subdiv.c). */
#ifndef SCG_SUBDIV_H
#define SCG_SUBDIV_H

#include "intersect.h"

/* The whole method: subdivision of the hull's sub-patch with a stack of
 * key->max_iters intervals (the key's start is `mid` and unused). */
void scg_method_subdiv(scg_isect *c, scg_value uv0, scg_value behind);

/* ---- pieces of the record's patch: the search shared with bclip.c ---- */

/* The state of a search: a stack of `depth` parameter intervals (vec4
 * array) with, for each, its parent's box (nearest depth, L1 size; vec2
 * array), the stack's size (int variable) and the depth of the nearest
 * hit so far (float variable). */
typedef struct scg_pieces {
    scg_value stack, meta, sp, best;
    int depth;
} scg_pieces;

/* Writes what to do with a popped interval iv and its meta (vec2). */
typedef void (*scg_piece_visit)(scg_isect *c, const scg_pieces *s, scg_value iv,
                                scg_value meta);

/* A runtime loop of at most `steps` pops from a stack of `depth`,
 * starting with the domain [lo, hi] (vec2 corners) where `wanted` (bool;
 * 0: always) holds; a piece whose parent's box lies behind the nearest hit
 * is skipped, every other one goes to `on_piece`. */
void scg_piece_search(scg_isect *c, scg_value lo, scg_value hi, int depth, int steps,
                      scg_value wanted, scg_piece_visit on_piece);
/* A whole method on that search: the variables of the skeleton, found_var,
 * and the search of the hull's sub-patch (none for a ray early ray
 * termination stopped). */
void scg_piece_method(scg_isect *c, scg_value uv0, scg_value behind, int depth, int steps,
                      scg_piece_visit on_piece);
/* The points of iv (scg_isect_restricted_points: into e, and homogeneous
 * when not NULL) and their box:
 * returns whether the box holds the ray and begins before the nearest
 * hit; near and size get its nearest depth and L1 size. */
scg_value scg_piece_box(scg_isect *c, const scg_pieces *s, scg_value iv, scg_value *e,
                        scg_value *homogeneous, scg_value *near, scg_value *size);
/* A hit at the middle of iv, at depth near: the nearest so far. */
void scg_piece_hit(scg_isect *c, const scg_pieces *s, scg_value iv, scg_value near);
/* Pushes interval iv (vec4) with meta (vec2). */
void scg_piece_push(scg_builder *b, const scg_pieces *s, scg_value iv, scg_value meta);

#endif
