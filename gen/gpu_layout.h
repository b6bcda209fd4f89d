/* gpu_layout.h — what the IR reads and produces: which textures hold the
 * patch data and how it sits in them, texel by texel, which inputs the
 * vertex stage hands to the fragment stage, which uniforms the program
 * reads and which results it produces. The runtime fills this layout, the
 * compiler reads it; docs/gpu-layout.md says the same in prose. Names,
 * locations and bindings are shader_contract.h's, the one place for them.
 *
 * Coordinates. Every record (one GPU patch: an extracted Bézier patch for
 * `bez` keys, a whole NURBS surface for `nurbs` keys) has a centre c (the
 * middle of its control points' bounding box, object space). Control points
 * are stored relative to c, and the ray origin the vertex stage passes is
 * relative to c too, so float precision does not depend on where the model
 * sits.
 *
 * Integers stored in float texels (offsets, counts, degrees, ids) are exact
 * below 2^24 = 16,777,216, which bounds the number of texels per texture.
 */
#ifndef SCG_GPU_LAYOUT_H
#define SCG_GPU_LAYOUT_H

#include "shader_contract.h"

/* ---- textures: all buffer textures (GL_TEXTURE_BUFFER, samplerBuffer,
 * read with texelFetch), bound to units SCG_UNIT_POINTS, _KNOTS and
 * _RECORDS ---- */
typedef enum scg_texture {
    /* "sc_points", GL_RGBA32F: homogeneous control points
     * ((x - c.x)·w, (y - c.y)·w, (z - c.z)·w, w). A record's point (i, j),
     * i along u (0 … nu-1), j along v, is texel cp_offset + j·nu + i. */
    SCG_TEX_POINTS = 0,
    /* "sc_knots", GL_R32F: knot vectors, each in full (clamped,
     * nu + deg_u + 1 resp. nv + deg_v + 1 values) from its offset. Used by
     * `nurbs` keys only; `bez` records need no knots. */
    SCG_TEX_KNOTS = 1,
    /* "sc_records", GL_RGBA32F: SCG_RECORD_TEXELS texels per record,
     * record r from texel SCG_RECORD_TEXELS·r:
     *   +0: (cp_offset, nu, nv, surface id in the scene)
     *   +1: (knot_u_offset, knot_v_offset, deg_u, deg_v)
     *   +2: (u0, u1, v0, v1): the record's parameter rectangle in its
     *       surface's domain. `bez` programs iterate in the patch's local
     *       parameters [0,1]² and map their (u, v) result through it;
     *       `nurbs` programs iterate in surface parameters directly.
     *   +3: (c.x, c.y, c.z, trim block): the centre, for the vertex stage,
     *       and the texel index in sc_records of the record's trim block
     *       (below), 0 when the record is untrimmed. */
    SCG_TEX_RECORDS = 2,
    SCG_TEXTURE_COUNT
} scg_texture;

enum { SCG_RECORD_TEXELS = 4 };

/* Triangular records (`tri` keys, gen/tri_newton.c): one per triangular
 * height patch of degree n, the same four texels, of which the program
 * reads +0 (cp_offset, (n+1)(n+2)/2, 1, surface id) and +3 (the centre).
 * Its points are the patch's BB-coefficients as 3D points (domain point x,
 * y and the height, re-centred, w = 1) in the order of sc_tri_index
 * (runtime/terrain/tri_bezier.h): b_n00 first, b_00n last, so that the
 * domain triangle is the xy of points 0, n(n+1)/2 and (n+1)(n+2)/2 − 1. */

/* ---- trim blocks (docs/trimming.md) ----
 * The trim data of a surface is one block of RGBA32F texels appended to
 * sc_records after the records; every record of the surface names it in
 * texel +3 .w. Offsets inside a block are relative to its first texel, so
 * a block can be placed anywhere. Coordinates are normalised to the
 * surface's domain, [0,1]², so that float precision is the same for every
 * domain. For trim degree N (the key's), in this order:
 *   +0: (loop count L, parity bias, grid columns G_u, grid rows G_v)
 *   +1: (scale_u, scale_v, offset_u, offset_v): normalised (u, v) =
 *       surface (u, v) · scale + offset
 *   cells, from +2, G_u·G_v texels: the cell of column i, row j
 *       (u·G_u in [i, i+1), v·G_v in [j, j+1); the outer columns and rows
 *       reach to infinity) is texel 2 + j·G_u + i:
 *       (parity, entry offset, entry count, 0); parity (bias included) is
 *       that of the crossings with the pieces wholly right of the cell at
 *       the row's bottom.
 *   loops, from +2 + G_u·G_v, SCG_TRIM_LOOP_TEXELS each, in scene order
 *       (loops left without pieces are left out):
 *       (u_min, u_max, v_lo, v_hi): the box of the loop's pieces; a point
 *       with v outside [v_lo, v_hi) or u outside [u_min, u_max) gets an
 *       even number of crossings from the loop (u_min is -FLT_MAX for a
 *       loop whose pieces' ends do not pair up, so that it is never
 *       skipped from the left),
 *       (first piece offset, piece count, 0, 0): its pieces are
 *       consecutive.
 *   pieces, after the loops, SCG_TRIM_PIECE_TEXELS(N) texels each:
 *       (v_lo, v_hi, u_min, u_max), then N+1 homogeneous control points
 *       (u·w, v·w, w, _) in order of increasing v; the first point's .w is
 *       u_lo, the u of the end point at v_lo. The piece covers
 *       v_lo <= v < v_hi, its u lies in [u_min, u_max].
 *   entries, SCG_TRIM_ENTRY_TEXELS each, from the cell's entry offset:
 *       (v_lo, v_hi, u_min, u_max), (piece offset, 0, 0, 0): a piece that
 *       may pass through the cell, with the bounds of u over its part in
 *       the row; or, piece offset 0 and u_min = u_max = FLT_MAX, a run
 *       v_lo <= v < v_hi where the pieces right of the cell add one
 *       crossing.
 * A point is kept when the count of pieces crossed by the ray from it
 * towards +u, plus the parity bias, is odd (bias 1 when the surface has
 * only holes, 0 when it has an outer loop). */
enum { SCG_TRIM_HEADER_TEXELS = 2, SCG_TRIM_LOOP_TEXELS = 2, SCG_TRIM_ENTRY_TEXELS = 2 };
#define SCG_TRIM_PIECE_TEXELS(degree) ((degree) + 2)
/* Offsets are floats: a block stays below 2^24 texels. */
#define SCG_TRIM_MAX_TEXELS (1 << 24)

/* ---- fragment-stage inputs (vertex-stage outputs, SCG_VARYING_*) ---- */
typedef enum scg_input_slot {
    /* vec3, flat: the eye in the record's re-centred object space. */
    SCG_IN_RAY_ORIGIN = 0,
    /* vec3, smooth: hull vertex - eye (re-centred object space, not
     * normalised). Interpolated, it is the fragment's hull point minus the
     * eye, so the ray is origin + t·dir with t = 1 on the hull. */
    SCG_IN_RAY_DIR,
    /* vec2, smooth: initial (u, v) for `cp` starts (parameter values of the
     * hull's vertices, interpolated) and `view` starts (the vertex stage's
     * solve at each hull vertex, SCG_OUT_START, interpolated), in the
     * program's parameters (local [0,1]² for `bez`, surface parameters for
     * `nurbs`). In the vertex stage's program of a `view` key: the
     * vertex's own parameter values. */
    SCG_IN_UV0,
    /* vec4, flat: the hull's sub-patch domain (u0, u1, v0, v1), in the same
     * parameters. `mid` starts begin at its centre. The iteration stops
     * when two iterates in a row lie outside it widened by
     * SCG_DOMAIN_OVERLAP of its size (one iterate may step out and back:
     * near a patch edge a converging step can cross it). */
    SCG_IN_DOMAIN,
    /* int, flat: record index (see SCG_TEX_RECORDS). */
    SCG_IN_RECORD,
    /* float: early ray termination — the ray parameter t (same units as
     * SCG_IN_RAY_DIR) beyond which this pixel holds a surface already
     * drawn, or a huge value (3.0e38) when there is none. Read only by
     * ert1/ert2/ert5 keys. Not a vertex-stage output: an ert5 program's loop
     * sets it to the nearest hit of the candidates run so far; the others'
     * main() derives it from the sc_nearest_t texture before the
     * intersection. That texture has one texel per SCG_NEAREST_TILE² pixels
     * (tile (x / T, y / T) of gl_FragCoord): the largest distance along the
     * unit ray of the nearest hits of the tile's pixels, so it never lies in
     * front of any of them. */
    SCG_IN_T_LIMIT,
    SCG_INPUT_COUNT
} scg_input_slot;

/* Pixels per side of a tile of the early-termination texture sc_nearest_t. */
enum { SCG_NEAREST_TILE = 4 };

/* ---- uniforms (default block; locations SCG_LOC_*) ---- */
typedef enum scg_uniform_slot {
    /* float "sc_footprint": size of one pixel at unit distance,
     * 2·tan(fovy/2) / image height. The program's tolerance in object units
     * is key tolerance × sc_footprint × length(dir) — the footprint at the
     * hull, which lies in front of the surface, so the bound is slightly
     * stricter than the footprint at the hit. Valid for rigid and uniformly
     * scaled transforms. */
    SCG_UNI_FOOTPRINT = 0,
    SCG_UNIFORM_COUNT
} scg_uniform_slot;

/* ---- results of the intersection function ---- */
typedef enum scg_output_slot {
    SCG_OUT_HIT = 0,   /* bool: the last (u, v) lies within the tolerance of
                          the ray, and the crossing one more Newton step
                          points to inside the record's domain widened by
                          SCG_DOMAIN_EPS (anywhere on the record, not only in
                          the sub-patch domain plus overlap), in front of the
                          eye (and in front of T_LIMIT for ert2) */
    SCG_OUT_UV,        /* vec2: (u, v) in the surface's domain */
    SCG_OUT_T,         /* float: ray parameter of the hit (dir units) */
    SCG_OUT_POINT,     /* vec3: hit point, re-centred object space */
    SCG_OUT_NORMAL,    /* vec3: unit normal Su × Sv (object space, not
                          flipped); -normalize(dir) where Su × Sv vanishes */
    SCG_OUT_ITERS,     /* int: iterations taken */
    SCG_OUT_SURFACE,   /* int: surface id (record texel +0 .w) */
    SCG_OUT_START,     /* vec2: the vertex stage's program of a `view` key
                          only: the start (u, v) at a hull vertex, in the
                          program's parameters (what SCG_IN_UV0 holds) */
    SCG_OUTPUT_COUNT
} scg_output_slot;

/* Parameter overlap allowed around a sub-patch domain while iterating, as a
 * fraction of its width and height (Martin et al.: leaves overlap slightly
 * so that no crack opens between neighbouring sub-patches); the iteration
 * box is in addition cut to the record's own domain widened by
 * SCG_DOMAIN_OVERLAP of its size (a crossing just inside the record's
 * edge may be reached from outside). A hit's crossing is accepted anywhere
 * in the record's domain widened by SCG_DOMAIN_EPS of its size: a
 * converged point outside the sub-patch is still a true intersection, and
 * the depth test keeps the nearest. */
#define SCG_DOMAIN_OVERLAP 0.1f
/* Float precision, about two ulps of 1: the hit's crossing is judged
 * against it (intersect.c), and a wider margin accepted rays passing a
 * free edge. */
#define SCG_DOMAIN_EPS 2.5e-7f

/* The declaration of each IR slot: the contract's entry (shader_contract.h)
 * for textures, inputs and uniforms — sc_t_limit, a global of the fragment
 * program, has no location — and the intersection function's parameter for
 * results. */
const scg_slot_info *scg_texture_info(scg_texture tex);
const scg_slot_info *scg_input_info(scg_input_slot slot);
const scg_slot_info *scg_uniform_info(scg_uniform_slot slot);
const scg_slot_info *scg_output_info(scg_output_slot slot);

#endif
