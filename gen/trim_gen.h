/* trim_gen.h — the trimming metaprogram (trim_gen.c): IR that classifies a
 * hit's (u, v) against the exact trim curves of its surface, read from the
 * record's trim block (gpu_layout.h, docs/trimming.md), by the parity of
 * the crossings of the ray from (u, v) towards +u with the v-monotone
 * pieces; each crossing decided by iterative Bézier clipping unrolled for
 * the key's trim degree. */
#ifndef SCG_TRIM_GEN_H
#define SCG_TRIM_GEN_H

#include "ir.h"

/* The int texel index of the record's trim block (0: untrimmed), from the
 * record's texel +3 (a vec4 value). */
scg_value scg_trim_block(scg_builder *b, scg_value record_texel3);

/* The block's normalised (u, v) of a point given as origin + local·extent
 * in surface parameters (vec2 values; origin 0 and extent 0 mean the
 * surface (u, v) is `local` itself). Bézier records pass their rectangle so
 * that the normalisation is folded into it. */
scg_value scg_trim_normalise(scg_builder *b, scg_value block, scg_value origin,
                             scg_value extent, scg_value local);

/* Writes the classification of the normalised point uv (vec2) against
 * the block (int, > 0) and returns a bool value, true when the point is
 * kept. `iters_var`, when not 0, is an int variable incremented once per
 * clipping iteration (for statistics). The key's trim mode must not be
 * SC_TRIM_NONE. */
scg_value scg_trim_kept(scg_builder *b, const scg_key *key, scg_value block, scg_value uv,
                        scg_value iters_var);

/* The trim probe of a trimmed key: a program that classifies the input
 * SCG_IN_UV0, taken as surface (u, v), against the trim block of record
 * SCG_IN_RECORD. Outputs: hit = kept, uv = the normalised point, iters =
 * clipping iterations. Built, validated and optimised; the CPU twin of
 * the trim stage for tests and measurements. */
int scg_build_trim_probe(const scg_key *key, scg_program **out, sc_error *err);

#endif
