/* test_stability.c — the stability suite (examples/scenes/stability/, read
 * through examples/splinecast/stability.c as `bench --stability` reads it)
 * at 128×128, the bench's default size: for every row, the CPU reference sees the scene, and the
 * default renderer and the hybrid fail no pixel (issue 12), but for the
 * excuse below (docs/stability.md has the table at 128×128).
 *
 * The one excuse the issue allows: a pixel whose centre lies within float
 * precision of a trim curve. A failing pixel (hole or false hit) of a
 * trimmed scene is excused when the reference itself changes its answer
 * there as the view moves by EXCUSE_PX of a pixel (about 7 float ulps of
 * a parameter near 0.5 at this size): the centre is that close to an edge.
 * Excused pixels are counted, and checked against a bound too. */
#include <math.h>
#include <stdlib.h>

#include "splinecast.h"
#include "stability.h"
#include "test.h"

#define SIZE 128
#define EXCUSE_PX 1e-4

/* Failing pixels allowed (holes, false hits and off pixels, less those
 * excused) and the excused pixels expected. hybrid_refused: the compiler
 * refuses the hybrid for a key the scene needs. */
typedef struct row_bounds {
    const char *name;
    long default_px;        /* the default renderer (the hybrid from the cp map) */
    long hybrid_px;         /* the hybrid asked for by name */
    int hybrid_refused;     /* goal 0 */
    long excused_max;       /* hybrid pixels excused on a trim curve */
} row_bounds;

/* Every row at 0. cusp, fold and high-degree each had one false hit
 * until the verdict judged where the crossing lies from one more Newton
 * step, inside a record domain widened by float precision only
 * (intersect.c): the last iterate had passed a free edge by 8e-6 of the
 * parameter, a thousandth of a pixel, inside the old margin of 1e-5. */
static const row_bounds bounds[] = {
    {"grazing", 0, 0, 0, 0},
    {"silhouette", 0, 0, 0, 0},
    {"poles-top", 0, 0, 0, 0},
    {"poles-side", 0, 0, 0, 0},
    {"apex", 0, 0, 0, 0},
    {"cusp", 0, 0, 0, 0},
    {"fold", 0, 0, 0, 0},
    {"high-degree", 0, 0, 0, 0},
    {"far", 0, 0, 0, 0},
    {"tiny", 0, 0, 0, 0},
    {"coincident", 0, 0, 0, 0},
    {"knots", 0, 0, 0, 0},
    /* Pixel centres on the two trim lines, excused; none else fails. */
    {"trim-centres", 0, 0, 0, 47},
    {"sliver", 0, 0, 0, 0},
    {"sliver-tail", 0, 0, 0, 0},
};
#define NBOUNDS ((int)(sizeof bounds / sizeof bounds[0]))

/* One context for the whole file, made again when a test in between shut
 * the library down: compiling the suite's programs once, not per row. */
static sc_context_id shared_context(sc_error *err)
{
    static sc_context_id ctx;
    sc_context_info info;
    if (ctx.id && sc_query_context_info(ctx, &info, err) == SC_OK)
        return ctx;
    if (sc_make_context(NULL, &ctx, err) != SC_OK)
        ctx.id = 0;
    return ctx;
}

static int load_suite(stab_suite *suite, sc_error *err)
{
    char dir[1024];
    return stab_find_suite(test_root("examples/scenes/stability"), dir, sizeof dir, err) ||
           stab_read_suite(dir, suite, err);
}

/* The reference with the view moved by (dx, dy) pixel footprints at the
 * target's distance: both eye and target move, so every ray moves by the
 * same amount across the view. */
static int shifted_reference(sc_scene_id scene, const sc_frame_info *ref, double dx, double dy,
                             sc_frame_id *out, sc_error *err)
{
    double f[3], right[3], up[3], d = 0;
    for (int c = 0; c < 3; c++) {
        f[c] = ref->target[c] - ref->eye[c];
        d += f[c] * f[c];
    }
    d = sqrt(d);
    /* Any two unit vectors across the view span the image plane, whichever
     * up the camera chose. */
    double z[3] = {0, 0, 1}, y[3] = {0, 1, 0};
    const double *a = fabs(f[2]) < 0.9 * d ? z : y;
    right[0] = f[1] * a[2] - f[2] * a[1];
    right[1] = f[2] * a[0] - f[0] * a[2];
    right[2] = f[0] * a[1] - f[1] * a[0];
    double rn = sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    for (int c = 0; c < 3; c++)
        right[c] /= rn;
    up[0] = (right[1] * f[2] - right[2] * f[1]) / d;
    up[1] = (right[2] * f[0] - right[0] * f[2]) / d;
    up[2] = (right[0] * f[1] - right[1] * f[0]) / d;
    double footprint = d * 2 * tan(ref->fovy_deg * M_PI / 360) / ref->height;
    sc_camera_desc cam = {.fovy_deg = ref->fovy_deg, .width = ref->width, .height = ref->height};
    for (int c = 0; c < 3; c++) {
        double move = footprint * (dx * right[c] + dy * up[c]);
        cam.eye[c] = ref->eye[c] + move;
        cam.target[c] = ref->target[c] + move;
    }
    return sc_render_reference(scene, &cam, NULL, out, err);
}

/* Failing pixels of `test` (holes and false hits) at which the reference's
 * answer changes within EXCUSE_PX. */
static int excused_pixels(sc_scene_id scene, sc_frame_id ref, sc_frame_id test, long *excused,
                          sc_error *err)
{
    sc_frame_info r, t;
    *excused = 0;
    if (sc_query_frame_info(ref, &r, err) || sc_query_frame_info(test, &t, err))
        return SC_FAIL;
    /* The moved references cost a second each on trimmed close-ups: only
     * made when some pixel needs an excuse. */
    long candidates = 0;
    for (int p = 0; p < r.width * r.height; p++)
        candidates += (r.surface[p] >= 0) != (t.surface[p] >= 0);
    if (!candidates)
        return SC_OK;
    static const double moves[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    sc_frame_id shifted[4] = {{0}};
    const int32_t *surface[4];
    int status = SC_OK;
    for (int k = 0; k < 4 && status == SC_OK; k++) {
        sc_frame_info s;
        status = shifted_reference(scene, &r, EXCUSE_PX * moves[k][0], EXCUSE_PX * moves[k][1],
                                   &shifted[k], err);
        if (status == SC_OK)
            status = sc_query_frame_info(shifted[k], &s, err);
        if (status == SC_OK)
            surface[k] = s.surface;
    }
    for (int p = 0; p < r.width * r.height && status == SC_OK; p++) {
        int ref_hit = r.surface[p] >= 0;
        if (ref_hit == (t.surface[p] >= 0))
            continue;
        for (int k = 0; k < 4; k++)
            if ((surface[k][p] >= 0) != ref_hit) {
                (*excused)++;
                break;
            }
    }
    for (int k = 0; k < 4; k++)
        sc_destroy_frame(shifted[k]);
    return status;
}

static void check_row(const char *name)
{
    const row_bounds *b = NULL;
    for (int k = 0; k < NBOUNDS; k++)
        if (!strcmp(bounds[k].name, name))
            b = &bounds[k];
    CHECK(b != NULL);
    sc_error err = {0};
    stab_suite suite;
    CHECK_INT(load_suite(&suite, &err), SC_OK);
    const stab_row *row = NULL;
    for (int r = 0; r < suite.count; r++)
        if (!strcmp(suite.rows[r].name, name))
            row = &suite.rows[r];
    if (!row) {
        stab_free_suite(&suite);
        CHECK(row != NULL);
    }
    sc_context_id ctx = shared_context(&err);
    if (!ctx.id) {
        stab_free_suite(&suite);
        SKIP("no GL context: %s", err.message);
    }
    sc_scene_id scene;
    sc_camera_desc cam;
    sc_frame_id ref = {0};
    sc_frame_info ref_info;
    sc_scene_info scene_info;
    stab_result def = {0}, hyb = {0};
    /* cam.text points into the suite's row: the suite stays until the end. */
    int status = stab_load_row(&suite, row, SIZE, SIZE, &scene, &cam, &err);
    if (status != SC_OK) {
        stab_free_suite(&suite);
        TEST_FAIL_("%s: %s", name, err.message);
        return;
    }
    status = sc_render_reference(scene, &cam, NULL, &ref, &err);
    if (status == SC_OK)
        status = sc_query_frame_info(ref, &ref_info, &err);
    if (status == SC_OK)
        status = sc_query_scene_info(scene, &scene_info, &err);
    if (status == SC_OK)
        status = stab_measure(ctx, scene, &(sc_renderer_desc){0}, &cam, ref, 0, 1, &def, &err);
    int refused = status == SC_OK &&
                  stab_check_method(scene, SC_METHOD_HYBRID, SC_START_DEFAULT, NULL, &err) != SC_OK;
    if (status == SC_OK && !refused)
        status = stab_measure(ctx, scene, &(sc_renderer_desc){.method = SC_METHOD_HYBRID}, &cam,
                              ref, 0, 1, &hyb, &err);
    long def_excused = 0, hyb_excused = 0;
    if (status == SC_OK && scene_info.trimmed_surfaces) {
        status = excused_pixels(scene, ref, def.frame, &def_excused, &err);
        if (status == SC_OK && !refused)
            status = excused_pixels(scene, ref, hyb.frame, &hyb_excused, &err);
    }
    sc_destroy_frame(def.frame);
    sc_destroy_frame(hyb.frame);
    sc_destroy_frame(ref);
    sc_destroy_scene(scene);
    stab_free_suite(&suite);
    if (status != SC_OK)
        TEST_FAIL_("%s: %s", name, err.message);
    CHECK_INT(status, SC_OK);
    long hits = ref_info.reference.hits;
    long def_px = def.cmp.holes + def.cmp.false_hits + def.cmp.off - def_excused;
    long hyb_px = hyb.cmp.holes + hyb.cmp.false_hits + hyb.cmp.off - hyb_excused;
    if (def_px > b->default_px || hyb_px > b->hybrid_px || hyb_excused > b->excused_max)
        TEST_FAIL_("%s: %ld reference hits; default fails %ld pixels (%ld excused), hybrid %ld "
                   "(%ld excused)", name, hits, def_px, def_excused, hyb_px, hyb_excused);
    /* The view shows the scene: a row the reference misses tests nothing. */
    CHECK(hits > SIZE * SIZE / 100);
    CHECK(def_px <= b->default_px);
    CHECK_INT(refused, b->hybrid_refused);
    CHECK(hyb_px <= b->hybrid_px);
    CHECK(hyb_excused <= b->excused_max);
}

/* Every row of the table has bounds here, and every bound a row: a scene
 * added to the suite is tested. */
TEST(stability_table_rows_have_bounds)
{
    sc_error err = {0};
    stab_suite suite;
    CHECK_INT(load_suite(&suite, &err), SC_OK);
    int count = suite.count, missing = -1;
    for (int r = 0; r < suite.count && missing < 0; r++) {
        int found = 0;
        for (int k = 0; k < NBOUNDS; k++)
            found |= !strcmp(bounds[k].name, suite.rows[r].name);
        if (!found)
            missing = r;
    }
    if (missing >= 0)
        TEST_FAIL_("row %s of the suite has no bounds in tests/test_stability.c",
                   suite.rows[missing].name);
    stab_free_suite(&suite);
    CHECK(missing < 0);
    CHECK_INT(count, NBOUNDS);
}

/* The suite's folder is found from the working directory and refused
 * with --suite's reason when it has no table. */
TEST(stability_suite_folder)
{
    char dir[1024];
    sc_error err = {0};
    CHECK_INT(stab_find_suite(test_tmpdir(), dir, sizeof dir, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "no README.md (the suite's table) in this --suite folder");
    CHECK_STR(err.file, test_tmpdir());
    CHECK_INT(stab_find_suite(test_root("examples/scenes/stability"), dir, sizeof dir, &err),
              SC_OK);
}

TEST(stability_grazing) { check_row("grazing"); }
TEST(stability_silhouette) { check_row("silhouette"); }
TEST(stability_poles_top) { check_row("poles-top"); }
TEST(stability_poles_side) { check_row("poles-side"); }
TEST(stability_apex) { check_row("apex"); }
TEST(stability_cusp) { check_row("cusp"); }
TEST(stability_fold) { check_row("fold"); }
TEST(stability_high_degree) { check_row("high-degree"); }
TEST(stability_far) { check_row("far"); }
TEST(stability_tiny) { check_row("tiny"); }
TEST(stability_coincident) { check_row("coincident"); }
TEST(stability_knots) { check_row("knots"); }
TEST(stability_trim_centres) { check_row("trim-centres"); }
TEST(stability_sliver) { check_row("sliver"); }
TEST(stability_sliver_tail) { check_row("sliver-tail"); }

/* The hybrid from the sub-patch's middle (a start the rows above do not
 * test) on the apex scene: a crossing met grazing sends the ray through
 * the quarters for a nearer one (gen/hybrid.c, the seek); without the
 * seek one pixel converged on the farther crossing. */
TEST(stability_apex_hybrid_mid_seeks_the_nearer_crossing)
{
    sc_error err = {0};
    stab_suite suite;
    CHECK_INT(load_suite(&suite, &err), SC_OK);
    const stab_row *row = NULL;
    for (int r = 0; r < suite.count; r++)
        if (!strcmp(suite.rows[r].name, "apex"))
            row = &suite.rows[r];
    sc_context_id ctx = row ? shared_context(&err) : (sc_context_id){0};
    if (row && !ctx.id) {
        stab_free_suite(&suite);
        SKIP("no GL context: %s", err.message);
    }
    CHECK(row != NULL);
    sc_scene_id scene;
    sc_camera_desc cam;
    sc_frame_id ref = {0};
    stab_result mid = {0};
    int status = stab_load_row(&suite, row, SIZE, SIZE, &scene, &cam, &err);
    if (status == SC_OK) {
        status = sc_render_reference(scene, &cam, NULL, &ref, &err);
        sc_renderer_desc desc = {.method = SC_METHOD_HYBRID, .start = SC_START_MID};
        if (status == SC_OK)
            status = stab_measure(ctx, scene, &desc, &cam, ref, 0, 1, &mid, &err);
        sc_destroy_frame(mid.frame);
        sc_destroy_frame(ref);
        sc_destroy_scene(scene);
    }
    stab_free_suite(&suite);
    if (status != SC_OK)
        TEST_FAIL_("apex: %s", err.message);
    CHECK_INT(status, SC_OK);
    printf("  apex, hybrid from the middle: %ld holes, %ld false hits, %ld off of %ld hits\n",
           mid.cmp.holes, mid.cmp.false_hits, mid.cmp.off, mid.cmp.reference_hits);
    CHECK(mid.cmp.reference_hits > SIZE * SIZE / 100);
    CHECK_INT(mid.cmp.holes + mid.cmp.false_hits + mid.cmp.off, 0);
}
