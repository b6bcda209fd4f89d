/* newton.h — the Newton intersection metaprogram (newton.c). */
#ifndef SCG_NEWTON_H
#define SCG_NEWTON_H

#include "ir.h"

/* Writes the whole intersection program for a Newton key (checked by
 * scg_key_check) at the builder's end. */
void scg_build_newton(scg_builder *b, const scg_key *key);

#endif
