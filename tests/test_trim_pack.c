/* test_trim_pack.c — trimmed variant keys, and the trim block layout
 * (runtime/prepare/trim_pack.c) against values known by construction. */

#include "scene_keys.h"
#include "test.h"
#include "trim_probe.h"

/* ---- keys ---- */

TEST(trimgpu_key_forms)
{
    static const char *const good[] = {
        "bez3x3-poly-dc-clip3i16-newton-cp-it6-tol0.05-ert0-out.shade",
        "bez3x3-poly-dc-left2i8-newton-cp-it6-tol0.05-ert0-out.shade",
        "nurbs5x5-rat-dc-fast11i64-newton-cp-it8-tol1-ert2-out.aov",
        "bezdyn-poly-loop-fast1i1-newton-cp-it6-tol0.05-ert0-out.shade",
    };
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        scg_key key;
        sc_error err;
        char back[SCG_KEY_MAX];
        CHECK_INT(scg_key_parse(good[i], &key, &err), SC_OK);
        CHECK_STR(scg_key_format(&key, back, sizeof back), good[i]);
        CHECK_INT(scg_key_check(&key, &err), SC_OK);
    }
    scg_key key;
    sc_error err;
    CHECK_INT(scg_key_parse(good[1], &key, &err), SC_OK);
    CHECK_INT(key.trim, SC_TRIM_LEFT);
    CHECK_INT(key.trim_degree, 2);
    CHECK_INT(key.trim_iters, 8);
    static const char *const bad[] = {"clip3", "fast0i4", "left3i0", "clip3i65", "trim1",
                                      "clip17i4", "fast3i", "clipi4", "clip03i4"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[SCG_KEY_MAX];
        snprintf(text, sizeof text, "bez3x3-poly-dc-%s-newton-cp-it6-tol0.05-ert0-out.shade",
                 bad[i]);
        CHECK_INT(scg_key_parse(text, &key, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, "trim configuration");
    }
}

TEST(trimgpu_scene_keys)
{
    sc_scene scene;
    make_shape(&scene, SHAPE_CIRCLE, 0, 1, 0, 1);
    scg_key key;
    char text[SCG_KEY_MAX];
    /* The outer polygon is of degree 1, the circle of degree 2. */
    sc_surface_key(&scene.surfaces[0], NULL, &key);
    CHECK_STR(scg_key_format(&key, text, sizeof text),
              "bez3x3-poly-pow-fast2i16-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    sc_key_options opts;
    memset(&opts, 0, sizeof opts);
    opts.trim_method = SC_TRIM_LEFT;
    opts.trim_iters = 24;
    sc_surface_key(&scene.surfaces[0], &opts, &key);
    CHECK_STR(scg_key_format(&key, text, sizeof text),
              "bez3x3-poly-pow-left2i24-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    opts.ignore_trims = 1;
    sc_surface_key(&scene.surfaces[0], &opts, &key);
    CHECK_STR(scg_key_format(&key, text, sizeof text),
              "bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov");
    /* Every trimmed key a scene asks for builds. */
    scg_program *prog;
    sc_error err;
    sc_surface_key(&scene.surfaces[0], NULL, &key);
    CHECK_INT(scg_build_program(&key, &prog, &err), SC_OK);
    scg_program_free(prog);
    sc_scene_free(&scene);
}

/* ---- layout ---- */

TEST(trimgpu_pack_layout)
{
    /* Domain [2, 6] × [-1, 1]; outer rectangle (0.25..0.75)² normalised:
     * two vertical pieces (the horizontal edges leave), a 4 × 4 grid
     * (about 4 cells a piece). */
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 2, 6, -1, 1);
    static const double rect[4][2] = {{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
    add_polygon(s, 0, rect, 4);
    sc_trim_block block;
    sc_error err;
    CHECK_INT(sc_surface_trim_degree(s), 1);
    CHECK_INT(sc_trim_pack(s, 2, &block, &err), SC_OK);
    CHECK_INT(block.degree, 2);
    CHECK_INT(block.npieces, 2);
    CHECK_INT(block.grid_u, 4);
    CHECK_INT(block.grid_v, 4);
    CHECK_INT(block.bias, 0);
    int piece = SCG_TRIM_PIECE_TEXELS(2);
    CHECK_INT(piece, 4);
    /* The edges u = 0.25 and 0.75 are column boundaries: a piece's bounds,
     * widened by a few float steps, reach into the cells on both sides, so
     * rows 1 and 2 list each piece in 2 cells. */
    CHECK_INT(block.nentries, 2 * 2 * 2);
    CHECK_INT(block.nloops, 1);
    /* Header, 16 cells, one loop, its two pieces, the entries. */
    int cells = 2, loop = cells + 16, pieces = loop + 2;
    CHECK_INT(block.ntexels, pieces + 2 * piece + SCG_TRIM_ENTRY_TEXELS * block.nentries);
    const float *t = block.texels;
    CHECK_NEAR(t[0], 1, 0);
    CHECK_NEAR(t[1], 0, 0);
    CHECK_NEAR(t[2], 4, 0);
    CHECK_NEAR(t[3], 4, 0);
    CHECK_NEAR(t[4], 0.25, 0);   /* scale_u = 1 / 4 */
    CHECK_NEAR(t[5], 0.5, 0);    /* scale_v = 1 / 2 */
    CHECK_NEAR(t[6], -0.5, 0);   /* offset_u = -2 / 4 */
    CHECK_NEAR(t[7], 0.5, 0);    /* offset_v = 1 / 2 */
    /* Both pieces run upwards from v = 0.25 to 0.75; one at u = 0.75, the
     * other at 0.25; a line elevated to degree 2 has its middle point at
     * the middle. */
    double seen_u = 0;
    int piece_u[2] = {0, 0};     /* texel offset of the piece at u = 0.25, 0.75 */
    for (int k = 0; k < 2; k++) {
        const float *h = t + 4 * (pieces + k * piece);
        CHECK_NEAR(h[0], 0.25, 0);
        CHECK_NEAR(h[1], 0.75, 0);
        CHECK(h[2] < h[3]);
        double u = h[4 + 3];                 /* u_lo in the first point's w */
        CHECK(u == 0.25 || u == 0.75);
        piece_u[u == 0.75] = pieces + k * piece;
        CHECK_NEAR(h[2], u, 1e-6);
        CHECK_NEAR(h[3], u, 1e-6);
        for (int i = 0; i < 3; i++) {
            CHECK_NEAR(h[4 + 4 * i + 0], u, 1e-7);
            CHECK_NEAR(h[4 + 4 * i + 1], 0.25 + 0.25 * i, 1e-7);
            CHECK_NEAR(h[4 + 4 * i + 2], 1.0, 0);
        }
        seen_u += u;
    }
    CHECK_NEAR(seen_u, 1.0, 0);
    /* The loop: the box of its pieces (u bounds widened by a few float
     * steps, v exact), then its range. */
    const float *box = t + 4 * loop;
    CHECK(box[0] < 0.25f && box[1] > 0.75f);
    CHECK_NEAR(box[0], 0.25, 1e-6);
    CHECK_NEAR(box[1], 0.75, 1e-6);
    CHECK_NEAR(box[2], 0.25, 0);
    CHECK_NEAR(box[3], 0.75, 0);
    CHECK_NEAR(box[4], pieces, 0);
    CHECK_NEAR(box[5], 2, 0);
    /* Cells, known by construction. Rows 0 and 3 (v < 0.25, v >= 0.75)
     * meet no piece: parity 0, no entry. In rows 1 and 2 both pieces span
     * the row. Their bounds, widened by a few float steps, reach into the
     * columns on both sides of their edge: columns 0 and 1 list the piece
     * at 0.25 and have the one at 0.75 wholly right (parity 1), columns 2
     * and 3 list the piece at 0.75 and nothing lies right (parity 0). */
    static const int parity[4] = {1, 1, 0, 0};
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++) {
            const float *cell = t + 4 * (cells + 4 * row + col);
            bool inner = row == 1 || row == 2;
            CHECK_NEAR(cell[0], inner ? parity[col] : 0, 0);
            CHECK_NEAR(cell[2], inner ? 1 : 0, 0);
            if (!inner)
                continue;
            const float *entry = t + 4 * (int)cell[1];
            double u = col < 2 ? 0.25 : 0.75;
            CHECK_INT((int)entry[4], piece_u[col >= 2]);
            CHECK_NEAR(entry[0], 0.25, 0);
            CHECK_NEAR(entry[1], 0.75, 0);
            CHECK(entry[2] < u && u < entry[3]);
            CHECK_NEAR(entry[2], u, 1e-6);
            CHECK_NEAR(entry[3], u, 1e-6);
        }
    sc_trim_block_free(&block);
    /* A degree below the curves' is refused; holes only give bias 1. */
    CHECK_INT(sc_trim_pack(s, 0, &block, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "trim degree 0");
    sc_scene_free(&scene);
    make_shape(&scene, SHAPE_HOLES_ONLY, 0, 1, 0, 1);
    CHECK_INT(sc_trim_pack(&scene.surfaces[0], 2, &block, &err), SC_OK);
    CHECK_INT(block.bias, 1);
    CHECK_NEAR(block.texels[1], 1, 0);
    /* The bottom-left cell lies outside both holes: kept by parity alone. */
    const float *corner = block.texels + 4 * 2;
    CHECK_NEAR(corner[0], 1, 0);
    CHECK_NEAR(corner[2], 0, 0);
    sc_trim_block_free(&block);
    sc_scene_free(&scene);
}

/* Runs of v where the pieces right of a cell flip its parity, on 4 × 4
 * grids; the runs' ends are the pieces' float end points. */
TEST(trimgpu_pack_runs)
{
    /* Outer loop on the domain's edges, a triangle hole with its lowest
     * corner at (0.8, 0.4) and a horizontal top edge at v = 0.9. */
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = add_patch(&scene, 0, 1, 0, 1);
    static const double outer[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const double tri[3][2] = {{0.8, 0.4}, {0.95, 0.9}, {0.65, 0.9}};
    add_polygon(s, 0, outer, 4);
    add_polygon(s, 1, tri, 3);
    sc_trim_block block;
    sc_error err;
    CHECK_INT(sc_trim_pack(s, 1, &block, &err), SC_OK);
    CHECK_INT(block.npieces, 4);
    CHECK_INT(block.grid_u, 4);
    CHECK_INT(block.grid_v, 4);
    const float *t = block.texels;
    int cells = 2;
    /* Column 1, row 1 (u, v in [0.25, 0.5)): the outer edge u = 1 spans
     * the row (parity 1); both triangle sides, right of the cell, start at
     * v = 0.4: their flips cancel. Decided by the parity alone. */
    const float *cell = t + 4 * (cells + 4 * 1 + 1);
    CHECK_NEAR(cell[0], 1, 0);
    CHECK_NEAR(cell[2], 0, 0);
    /* Column 1, row 3 (v >= 0.75, to infinity): the triangle's sides end
     * at 0.9 (cancel), the outer edge u = 1 ends at v = 1: one run from
     * 1 on, where the point leaves the outer loop. */
    cell = t + 4 * (cells + 4 * 3 + 1);
    CHECK_NEAR(cell[0], 1, 0);
    CHECK_NEAR(cell[2], 1, 0);
    const float *run = t + 4 * (int)cell[1];
    CHECK_NEAR(run[0], 1.0, 0);
    CHECK(run[1] == FLT_MAX && run[2] == FLT_MAX && run[3] == FLT_MAX);
    CHECK_NEAR(run[4], 0, 0);
    sc_trim_block_free(&block);
    sc_scene_free(&scene);

    /* Holes only (bias 1): a triangle (0.55, 0.3), (0.95, 0.9), (0.05, 0.45).
     * In column 1, row 1 the side from (0.05, 0.45) down to the corner
     * passes through the cell (listed), the side from the corner up to
     * (0.95, 0.9) lies right of it and starts in the row (a run from 0.3),
     * the top side lies left of it. */
    sc_scene_init(&scene);
    s = add_patch(&scene, 0, 1, 0, 1);
    static const double hole[3][2] = {{0.55, 0.3}, {0.95, 0.9}, {0.05, 0.45}};
    add_polygon(s, 1, hole, 3);
    CHECK_INT(sc_trim_pack(s, 1, &block, &err), SC_OK);
    CHECK_INT(block.npieces, 3);
    CHECK_INT(block.grid_u, 4);
    t = block.texels;
    cell = t + 4 * (cells + 4 * 1 + 1);
    CHECK_NEAR(cell[0], 1, 0);
    CHECK_NEAR(cell[2], 2, 0);
    int listed = 0, runs = 0;
    for (int e = 0; e < 2; e++) {
        const float *entry = t + 4 * ((int)cell[1] + SCG_TRIM_ENTRY_TEXELS * e);
        if (entry[4] > 0) {
            listed++;
            CHECK_NEAR(entry[0], 0.3f, 0);
            CHECK_NEAR(entry[1], 0.45f, 0);
            CHECK(entry[2] <= 0.05 + 1e-6 && entry[3] >= 0.55 - 1e-6);
        } else {
            runs++;
            CHECK_NEAR(entry[0], 0.3f, 0);
            CHECK(entry[1] == FLT_MAX && entry[2] == FLT_MAX);
        }
    }
    CHECK_INT(listed, 1);
    CHECK_INT(runs, 1);
    sc_trim_block_free(&block);
    sc_scene_free(&scene);
}

/* The loop table: each loop's pieces together, its range and its box,
 * known by construction; a loop left open is never skipped from the left;
 * the per-piece methods skip the loops whose box misses the point. */
TEST(trimgpu_pack_loops)
{
    /* Nested: the outer square (its two vertical edges), then circles of
     * 4 quarter arcs each (each arc monotone in v), in scene order. */
    sc_scene scene;
    sc_surface *s = make_shape(&scene, SHAPE_NESTED, 0, 1, 0, 1);
    sc_trim_block block;
    sc_error err;
    CHECK_INT(sc_trim_pack(s, 2, &block, &err), SC_OK);
    CHECK_INT(block.nloops, 4);
    CHECK_NEAR(block.texels[0], 4, 0);
    CHECK_INT(block.npieces, 2 + 3 * 4);
    static const double centre[4][2] = {{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}, {0.45, 0.5}};
    static const double radius[4] = {0.45, 0.4, 0.25, 0.1};
    static const int count[4] = {2, 4, 4, 4};
    int next = piece_at(&block, 0);
    for (int l = 0; l < 4; l++) {
        const float *box = block.texels + 4 * (loops_at(&block) + SCG_TRIM_LOOP_TEXELS * l);
        double lo_u = centre[l][0] - radius[l], hi_u = centre[l][0] + radius[l];
        double lo_v = centre[l][1] - radius[l], hi_v = centre[l][1] + radius[l];
        CHECK(box[0] <= lo_u && box[1] >= hi_u);
        CHECK_NEAR(box[0], lo_u, 1e-6);
        CHECK_NEAR(box[1], hi_u, 1e-6);
        CHECK_NEAR(box[2], lo_v, 1e-7);
        CHECK_NEAR(box[3], hi_v, 1e-7);
        CHECK_INT((int)box[4], next);
        CHECK_INT((int)box[5], count[l]);
        /* Every piece of a circle's range has both ends on that circle. */
        for (int k = 0; l > 0 && k < count[l]; k++) {
            const float *piece = block.texels + 4 * (next + k * SCG_TRIM_PIECE_TEXELS(2));
            for (int end = 0; end <= 2; end += 2) {
                const float *q = piece + 4 * (1 + end);
                double du = q[0] / q[2] - centre[l][0], dv = q[1] / q[2] - centre[l][1];
                CHECK_NEAR(sqrt(du * du + dv * dv), radius[l], 1e-6);
            }
        }
        next += count[l] * SCG_TRIM_PIECE_TEXELS(2);
    }
    sc_trim_block_free(&block);
    sc_scene_free(&scene);

    /* A curve left open (scene built in code, not validated): from (0.2,
     * 0.2) up to (0.5, 0.8), down to (0.8, 0.5). Its ends do not pair up
     * in v, so its box reaches to -FLT_MAX: the point (0.1, 0.35), left
     * of the curve, gets the crossing of its first edge, as in the
     * reference, with the outer loop's right edge: 2, not kept. */
    sc_scene_init(&scene);
    s = add_patch(&scene, 0, 1, 0, 1);
    add_polygon(s, 0, outer_square, 4);
    sc_curve *open = &add_loop(s, 1, 1)->curves[0];
    static const double bends[3][2] = {{0.2, 0.2}, {0.5, 0.8}, {0.8, 0.5}};
    static const double open_knots[5] = {0, 0, 1, 2, 2};
    sc_curve_alloc(open, 2, 1, 3);
    memcpy(open->knots, open_knots, sizeof open_knots);
    for (int i = 0; i < 3; i++) {
        open->cp[3 * i] = bends[i][0];
        open->cp[3 * i + 1] = bends[i][1];
        open->cp[3 * i + 2] = 1.0;
    }
    CHECK_INT(sc_trim_pack(s, 1, &block, &err), SC_OK);
    CHECK_INT(block.nloops, 2);
    const float *outer_box = block.texels + 4 * loops_at(&block);
    CHECK_NEAR(outer_box[0], 0.05, 1e-6);
    CHECK(outer_box[SCG_TRIM_LOOP_TEXELS * 4] == -FLT_MAX);
    CHECK_NEAR(outer_box[SCG_TRIM_LOOP_TEXELS * 4 + 1], 0.8, 1e-6);
    sc_trim_block_free(&block);
    sc_trim *trim;
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
    CHECK_INT(sc_trim_crossings(trim, 0.1, 0.35), 2);
    static const char *const methods[] = {"clip1i16", "left1i16", "fast1i16"};
    for (int m = 0; m < 3; m++) {
        probe p;
        CHECK_INT(probe_open(&p, methods[m], s, &err), SC_OK);
        CHECK_INT(probe_run(&p, 0.1f, 0.35f, NULL, NULL), 0);
        CHECK_INT(probe_run(&p, 0.3f, 0.35f, NULL, NULL), sc_trim_inside(trim, 0.3f, 0.35f));
        probe_close(&p);
    }
    sc_trim_free(trim);
    sc_scene_free(&scene);

    /* Skipping: 98 pieces of a wavy hole (radius 0.3 ± 0.11 about the
     * centre) and the outer square. Visiting a piece takes more than 4
     * instructions (its address, a fetch, two comparisons, a branch), so
     * a point inside the hole's box, which visits all 98, runs more than
     * 98 · 4; a point left of the box or above it skips the loop whole
     * and runs fewer. */
    s = make_shape(&scene, SHAPE_POLY100, 0, 1, 0, 1);
    CHECK_INT(sc_trim_prepare(s, &trim, &err), SC_OK);
    static const float points[3][2] = {{0.5f, 0.5f}, {0.07f, 0.5f}, {0.5f, 0.93f}};
    for (int m = 0; m < 2; m++) {
        probe p;
        CHECK_INT(probe_open(&p, methods[m], s, &err), SC_OK);
        for (int k = 0; k < 3; k++) {
            long long steps = 0;
            CHECK_INT(probe_run(&p, points[k][0], points[k][1], &steps, NULL),
                      sc_trim_inside(trim, points[k][0], points[k][1]));
            CHECK(k == 0 ? steps > 98 * 4 : steps < 98 * 4);
        }
        probe_close(&p);
    }
    sc_trim_free(trim);
    sc_scene_free(&scene);
}
