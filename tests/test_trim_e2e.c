/* test_trim_e2e.c — exact trimming end to end: the example trim scenes
 * rendered on real Mesa (llvmpipe) through EGL and OSMesa with every trim
 * method, each image compared with the CPU reference, whose trimming is an
 * independent double-precision classification (runtime/model/trim.c). Also the
 * render options that choose the method. One context per backend for the
 * whole run; references are cached in the run's temporary folder. */
#include "gl_context_util.h"
#include "test.h"

#include <float.h>
#include <stdlib.h>

#include "gl_context.h"
#include "gl_render.h"
#include "imgdiff.h"
#include "io.h"
#include "options.h"
#include "refcast.h"
#include "trim.h"
#include "trim_pack.h"

/* The example scenes and a close-up of each one's hardest place (eye,
 * target, field of view): the circle where a quarter arc starts, a corner
 * of the rounded pentagon, the small hole inside the island, the star's
 * top point (a v maximum), the diamond's corner on the outer loop. */
static const struct {
    const char *name;
    double close_up[7];
} example_scenes[] = {
    {"trim_hole", {0.6, -0.4, 1.3, 0.6, 0, 0.3, 10}},
    {"trim_nine", {0.535, -0.2, 1.4, 0.535, 0.165, 0.4, 10}},
    {"trim_nested", {0, -0.3, 1.5, -0.1, 0, 0.45, 20}},
    {"trim_star", {0, 0.4, 1.2, 0, 0.8, 0.1, 8}},
    {"trim_touch", {1.3, 0.4, 0.8, 0.9, 0.4, 0.05, 10}},
};
enum { EXAMPLE_COUNT = sizeof example_scenes / sizeof example_scenes[0], VIEW_SIZE = 192 };

static const sc_trim_method all_methods[] = {SC_TRIM_CLIP, SC_TRIM_LEFT, SC_TRIM_FAST};
static const char *const method_names[] = {"none", "clip", "fast", "left"};

/* The shared context of a backend (gl_context_util.h); NULL (with the
 * reason in *why) when the machine cannot make one. An EGL request that
 * fell back to OSMesa counts as no EGL context. */
static sc_gl_context *e2e_context(sc_backend backend, const char **why)
{
    static char fell_back[128];
    sc_gl_context *ctx = test_gl_context(backend, why);
    if (ctx && sc_gl_context_backend(ctx) != backend) {
        snprintf(fell_back, sizeof fell_back, "the context fell back to %s",
                 cli_backend_name(sc_gl_context_backend(ctx)));
        *why = fell_back;
        return NULL;
    }
    return ctx;
}

static const char *scene_path(const char *name)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/examples/scenes/%s.obj", test_root_dir, name);
    return path;
}

/* The three views of example scene k at VIEW_SIZE²: the default one, from
 * straight above with the patch filling most of the image, the close-up. */
static void example_views(int k, const sc_scene *scene, sc_camera cams[3])
{
    sc_camera_default(scene, &cams[0]);
    cams[1] = (sc_camera){.eye = {0, 0, 4.5}, .target = {0, 0, 0.25}, .fovy_deg = 28};
    const double *c = example_scenes[k].close_up;
    cams[2] = (sc_camera){.eye = {c[0], c[1], c[2]}, .target = {c[3], c[4], c[5]},
                          .fovy_deg = c[6]};
    for (int v = 0; v < 3; v++)
        cams[v].width = cams[v].height = VIEW_SIZE;
}

/* The scene without its trim loops. */
static void drop_loops(sc_scene *scene)
{
    for (int s = 0; s < scene->nsurfaces; s++) {
        sc_surface *surf = &scene->surfaces[s];
        for (int l = 0; l < surf->nloops; l++) {
            for (int c = 0; c < surf->loops[l].ncurves; c++)
                sc_curve_free(&surf->loops[l].curves[c]);
            free(surf->loops[l].curves);
        }
        free(surf->loops);
        surf->loops = NULL;
        surf->nloops = 0;
    }
}

/* Whether the exact classification of (u, v) holds on both sides, ±eps in
 * u: the ray towards +u crosses no curve that close, so a float program
 * must agree with it. 16 float ulps of 1.0 (the domains are [0, 1]²): the
 * trim data are the curves rounded to float, a few ulps away. */
static int clear_of_curves(const sc_trim *trim, double u, double v, int *kept)
{
    const double eps = 16 * FLT_EPSILON;
    *kept = sc_trim_inside(trim, u, v);
    return sc_trim_inside(trim, u - eps, v) == *kept && sc_trim_inside(trim, u + eps, v) == *kept;
}

typedef struct e2e_counts {
    long tested;            /* pixels whose trim decision was checked */
    long wrong;             /* GPU trim decision against the exact one */
} e2e_counts;

/* The trim stage alone, end to end: the untrimmed program's (u, v) at a
 * pixel is where the trimmed program classifies (the same Newton code, so
 * the same (u, v) up to the compiler's rounding); the trimmed image must
 * hit there exactly when the reference's classification of that (u, v)
 * keeps it. Pixels near a curve (clear_of_curves) or where the two
 * programs' (u, v) differ by more than 1e-5 are left out. */
static void count_trim_decisions(const sc_trim *trim, const sc_aov *untrimmed,
                                 const sc_aov *trimmed, const char *what, e2e_counts *c)
{
    for (int p = 0; p < untrimmed->width * untrimmed->height; p++) {
        if (untrimmed->surface[p] < 0)
            continue;
        double u = untrimmed->uv[2 * p], v = untrimmed->uv[2 * p + 1];
        int kept, hit = trimmed->surface[p] >= 0;
        if (!clear_of_curves(trim, u, v, &kept))
            continue;
        if (hit && (fabs(trimmed->uv[2 * p] - u) > 1e-5 || fabs(trimmed->uv[2 * p + 1] - v) > 1e-5))
            continue;
        c->tested++;
        if (hit != kept) {
            if (c->wrong < 3)
                fprintf(stderr, "  %s pixel (%d, %d) (u, v) = (%.9g, %.9g): GPU %s, exact %s\n",
                        what, p % untrimmed->width, p / untrimmed->width, u, v,
                        hit ? "kept" : "trimmed", kept ? "kept" : "trimmed");
            c->wrong++;
        }
    }
}

static int draw_read(sc_renderer *r, const sc_camera *cam, sc_aov *aov, sc_error *err)
{
    return sc_renderer_draw(r, cam, err) == SC_OK && sc_renderer_read(r, NULL, aov, err) == SC_OK;
}

/* The accuracy targets of the GL runtime: at most 0.1 % failing pixels,
 * median position error below 0.1 footprint. */
static int accurate(const sc_accuracy *a, const char *what)
{
    int ok = a->fail_pct <= 0.1 && a->pos_median_px < 0.1;
    if (!ok)
        fprintf(stderr, "  %s: fail_pct %g (holes %ld, false hits %ld, off %ld of %ld) "
                "pos_median_px %g\n", what, a->fail_pct, a->holes, a->false_hits, a->off,
                a->ref_hits, a->pos_median_px);
    return ok;
}

/* Example scene k with every method, in three views: against the
 * reference image, and each trim decision against the exact one. */
static void example_scene_check(sc_gl_context *ctx, int k, e2e_counts *counts, int *inaccurate)
{
    const sc_gl *gl = sc_gl_context_gl(ctx);
    const char *path = scene_path(example_scenes[k].name);
    sc_error err = {0};
    sc_scene scene, bare;
    CHECK_INT(sc_read_scene(path, &scene, &err), SC_OK);
    CHECK_INT(sc_read_scene(path, &bare, &err), SC_OK);
    drop_loops(&bare);
    sc_trim *trim;
    CHECK_INT(sc_trim_prepare(&scene.surfaces[0], &trim, &err), SC_OK);
    CHECK(trim != NULL);
    int degree = sc_surface_trim_degree(&scene.surfaces[0]);
    sc_camera cams[3];
    example_views(k, &scene, cams);
    sc_renderer *untrimmed, *trimmed[3];
    CHECK_INT(sc_renderer_create(gl, &bare, NULL, &untrimmed, &err), SC_OK);
    for (int m = 0; m < 3; m++) {
        sc_render_desc desc = {.trim_method = all_methods[m]};
        CHECK_INT(sc_renderer_create(gl, &scene, &desc, &trimmed[m], &err), SC_OK);
        const scg_key *key = sc_renderer_surface_key(trimmed[m], 0);
        CHECK_INT(key->trim, all_methods[m]);
        CHECK_INT(key->trim_degree, degree);
        CHECK_INT(key->trim_iters, SCG_DEFAULT_TRIM_ITERS);
    }
    for (int v = 0; v < 3; v++) {
        sc_aov ref, plain;
        CHECK_INT(sc_refcast_cached(path, &cams[v], test_tmpdir(), &ref, &err), SC_OK);
        CHECK(ref.surface != NULL);
        CHECK(draw_read(untrimmed, &cams[v], &plain, &err));
        for (int m = 0; m < 3; m++) {
            char what[128];
            snprintf(what, sizeof what, "%s view %d %s", example_scenes[k].name, v,
                     method_names[all_methods[m]]);
            sc_aov aov;
            sc_accuracy acc;
            CHECK(draw_read(trimmed[m], &cams[v], &aov, &err));
            CHECK_INT(sc_accuracy_compare(&ref, &aov, &acc, &err), SC_OK);
            *inaccurate += !accurate(&acc, what);
            count_trim_decisions(trim, &plain, &aov, what, &counts[m]);
            sc_aov_free(&aov);
        }
        sc_aov_free(&plain);
        sc_aov_free(&ref);
    }
    for (int m = 0; m < 3; m++)
        sc_renderer_destroy(trimmed[m]);
    sc_renderer_destroy(untrimmed);
    sc_trim_free(trim);
    sc_scene_free(&bare);
    sc_scene_free(&scene);
}

/* Every example scene × every method × three views at 192×192. The trims
 * cut large regions away (the reference misses there), so a method that
 * kept or dropped a region would fail by hundreds of pixels, far above the
 * 0.1 % allowed for grazing rays; the decision count sees single pixels. */
static void example_scenes_check(sc_backend backend)
{
    const char *why;
    sc_gl_context *ctx = e2e_context(backend, &why);
    if (!ctx)
        SKIP("no %s context: %s", cli_backend_name(backend), why);
    e2e_counts counts[3] = {{0}};
    int inaccurate = 0;
    for (int k = 0; k < EXAMPLE_COUNT; k++) {
        example_scene_check(ctx, k, counts, &inaccurate);
        if (test_failed_flag)
            return;
    }
    for (int m = 0; m < 3; m++) {
        fprintf(stderr, "  %s: %ld trim decisions checked, %ld wrong\n",
                method_names[all_methods[m]], counts[m].tested, counts[m].wrong);
        CHECK(counts[m].tested > 100000);
    }
    CHECK_INT(inaccurate, 0);
    CHECK_INT(counts[0].wrong + counts[1].wrong + counts[2].wrong, 0);
}

TEST(trime2e_example_scenes_egl) { example_scenes_check(SC_BACKEND_EGL); }
TEST(trime2e_example_scenes_osmesa) { example_scenes_check(SC_BACKEND_OSMESA); }

TEST(trime2e_method_parse)
{
    sc_trim_method mode = SC_TRIM_NONE;
    int iters = 0;
    sc_error err = {0};
    CHECK_INT(cli_trim_parse("left", &mode, &iters, &err), SC_OK);
    CHECK_INT(mode, SC_TRIM_LEFT);
    CHECK_INT(iters, 0);
    CHECK_INT(cli_trim_parse("clip:24", &mode, &iters, &err), SC_OK);
    CHECK_INT(mode, SC_TRIM_CLIP);
    CHECK_INT(iters, 24);
    CHECK_INT(cli_trim_parse("fast:64", &mode, &iters, &err), SC_OK);
    CHECK_INT(mode, SC_TRIM_FAST);
    CHECK_INT(iters, 64);
    static const char *const bad[] = {"fast:0", "fast:65", "fast:", "fast:4x", "quick", "",
                                      "clipx", "cli"};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        err.message[0] = 0;
        CHECK_INT(cli_trim_parse(bad[k], &mode, &iters, &err), SC_FAIL);
        CHECK(err.message[0] != 0);
    }
    CHECK_INT(mode, SC_TRIM_FAST);
    CHECK_INT(iters, 64);
}
