/* trim_pack.h — a surface's trim loops as GPU data: the trim block that
 * trimmed programs read (layout in gen/gpu_layout.h, docs/trimming.md).
 * The loops are cut exactly into v-monotone rational Bézier pieces with
 * half-open v ranges by the reference's preparation (trim.h), degree-
 * elevated to the key's trim degree, normalised to the domain [0,1]² and
 * rounded to float, grouped by loop, each loop with its range of pieces
 * and their bounding box (which lets the per-piece methods skip the loops
 * a point lies outside of); a uniform grid of cells, each with its parity
 * and the few pieces that may pass through it, serves the accelerated
 * method. */
#ifndef SC_TRIM_PACK_H
#define SC_TRIM_PACK_H

#include "scene.h"

typedef struct sc_trim_block {
    int degree;          /* piece degree: the key's trim degree */
    int npieces;         /* pieces (horizontal ones, in float, are left out) */
    int nloops;          /* loops with pieces: each a range of pieces and a box */
    int grid_u, grid_v;  /* grid columns and rows (powers of two) */
    int nentries;        /* entries of the cells' lists */
    int bias;            /* parity bias: 1 when the surface has only holes */
    int ntexels;         /* 0 for an untrimmed surface */
    float *texels;       /* 4 floats a texel; offsets relative to texel 0 */
} sc_trim_block;

/* Highest degree among the trim curves of s: the N of its trimmed key
 * (0 when s is untrimmed). */
int sc_surface_trim_degree(const sc_surface *s);

/* Packs the trim loops of s for programs of trim degree `degree`, which
 * must be at least sc_surface_trim_degree(s). An untrimmed surface gives an
 * empty block (ntexels 0). Fails for trim curves the preparation refuses
 * (trim.h), for a degree too low, and for
 * pieces too many to address in float even with a 1 × 1 grid (2^24
 * texels). */
int sc_trim_pack(const sc_surface *s, int degree, sc_trim_block *out, sc_error *err);
void sc_trim_block_free(sc_trim_block *block);

#endif
