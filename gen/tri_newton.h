/* tri_newton.h — the intersection metaprogram of triangular Bézier height
 * patches (tri keys; tri_newton.c, seed 004 section V). */
#ifndef SCG_TRI_NEWTON_H
#define SCG_TRI_NEWTON_H

#include "ir.h"

/* Writes the whole intersection program for a tri key (checked by
 * scg_key_check) at the builder's end. */
void scg_build_tri_newton(scg_builder *b, const scg_key *key);

#endif
