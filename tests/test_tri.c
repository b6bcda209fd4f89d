/* test_tri.c — triangular Bézier height patches (seed 004, sections V–VII):
 * the `tri` key, the exact double-precision tracer against brute force, the
 * generated program (interpreted in single precision) against that tracer,
 * and the prisms and Manhattan sets of a terrain. `make test T=tri_`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "heights.h"
#include "ir.h"
#include "splines.h"
#include "test.h"
#include "tri_prisms.h"
#include "tri_trace.h"

#define TRI_KEY "tri4-poly-dc-trim0-newton-secure-it6-tol0.05-ert0-out.shade"

TEST(tri_key_parse_and_check)
{
    scg_key k;
    sc_error err;
    char again[SCG_KEY_MAX];
    CHECK_INT(scg_key_parse(TRI_KEY, &k, &err), SC_OK);
    CHECK_INT(k.kind, SCG_PATCH_TRIANGLE);
    CHECK_INT(k.deg_u, 4);
    CHECK_INT(k.start, SC_START_SECURE);
    CHECK_INT(scg_key_check(&k, &err), SC_OK);
    CHECK_STR(scg_key_format(&k, again, sizeof again), TRI_KEY);
    static const struct { const char *text, *says; } refused[] = {
        {"tri4-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade", "secure only"},
        {"tri4-rat-dc-trim0-newton-secure-it6-tol0.05-ert0-out.shade", "secure only"},
        {"bez3x3-poly-dc-trim0-newton-secure-it6-tol0.05-ert0-out.shade", "triangular patches"},
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        CHECK_INT(scg_key_parse(refused[i].text, &k, &err), SC_OK);
        CHECK_INT(scg_key_check(&k, &err), SC_FAIL);
        CHECK_CONTAINS(err.message, refused[i].says);
    }
    CHECK_INT(scg_key_parse("tri5-poly-dc-trim0-newton-secure-it6-tol0.05-ert0-out.shade", &k,
                            &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "from 1 to 4");
    CHECK_INT(scg_key_parse("tri4x4-poly-dc-trim0-newton-secure-it6-tol0.05-ert0-out.shade", &k,
                            &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "tri4");
}

/* Franke's function as a C2 terrain on [0,1]² (N = 144: 12 × 12 squares,
 * 288 patches). */
static void franke_mesh(sc_tri_mesh *m)
{
    sc_heights h;
    sc_error err;
    sc_heights_franke(12, 1, &h);
    CHECK_INT(sc_spline_build(&h, SC_SPLINE_C2, m, &err), SC_OK);
    sc_heights_free(&h);
}

/* A ray from above the terrain towards a random point of it, at least
 * `min_slope` steep (sine of the angle with the horizontal). */
static void random_ray(const sc_tri_mesh *m, unsigned long long *rng, double min_slope,
                       double eye[3], double dir[3])
{
    double x = m->x0 + m->nx * m->hx * test_rand(rng), y = m->y0 + m->ny * m->hy * test_rand(rng);
    sc_tri_point p;
    sc_tri_mesh_eval(m, x, y, &p);
    double d[3], len;
    do {
        d[0] = 2 * test_rand(rng) - 1;
        d[1] = 2 * test_rand(rng) - 1;
        d[2] = -test_rand(rng);
        len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (len > 1 || len < 0.1 || -d[2] / len < min_slope);
    double dist = 1 + test_rand(rng);
    for (int k = 0; k < 3; k++)
        dir[k] = d[k] / len;
    double target[3] = {x, y, p.value};
    for (int k = 0; k < 3; k++)
        eye[k] = target[k] - dist * dir[k];
}

/* The walk over the squares finds what testing every patch finds. */
TEST(tri_trace_walk_matches_brute_force)
{
    sc_tri_mesh m;
    franke_mesh(&m);
    sc_tri_tracer tr;
    sc_tri_tracer_init(&tr, &m);
    unsigned long long rng = 7;
    int hits = 0;
    for (int r = 0; r < 300; r++) {
        double eye[3], dir[3];
        random_ray(&m, &rng, 0.05, eye, dir);
        sc_tri_hit walk, best = {.patch = -1};
        int found = sc_tri_tracer_trace(&tr, eye, dir, 0, &walk) == SC_OK;
        for (int p = 0; p < m.count; p++) {
            double tri[6];
            sc_tri_hit h;
            sc_tri_mesh_domain(&m, p, tri);
            if (sc_tri_patch_trace(m.degree, m.coef + (size_t)p * 15, tri, eye, dir, 0, &h) ==
                    SC_OK &&
                (best.patch < 0 || h.t < best.t)) {
                best = h;
                best.patch = p;
            }
        }
        CHECK_INT(found, best.patch >= 0);
        if (!found || best.patch < 0)
            continue;
        hits++;
        CHECK_NEAR(walk.t, best.t, 1e-12);
        /* On the ray and on the surface. */
        sc_tri_point p;
        CHECK_INT(sc_tri_mesh_eval(&m, walk.point[0], walk.point[1], &p), SC_OK);
        CHECK_NEAR(walk.point[2], p.value, 1e-12);
        CHECK_NEAR(eye[2] + walk.t * dir[2], walk.point[2], 1e-12);
    }
    CHECK(hits > 250);
    sc_tri_tracer_free(&tr);
    sc_tri_mesh_free(&m);
}

#define FOOTPRINT (2 * tan(M_PI / 8) / 512)  /* 45°, 512 rows */

/* One interpreted run of the program on patch p: record p, the eye
 * relative to its centre, dir scaled so that t = 1 at `hull_dist`. */
static bool run_patch(scg_interp *it, scg_interp_env *env, const float *records, int p,
                      const double eye[3], const double dir[3], double hull_dist,
                      scg_interp_result *res)
{
    const float *centre = records + 4 * (SCG_RECORD_TEXELS * p + 3);
    env->inputs[SCG_IN_RECORD][0] = (float)p;
    for (int k = 0; k < 3; k++) {
        env->inputs[SCG_IN_RAY_ORIGIN][k] = (float)(eye[k] - centre[k]);
        env->inputs[SCG_IN_RAY_DIR][k] = (float)(dir[k] * hull_dist);
    }
    sc_error err;
    if (scg_interp_run(it, env, res, &err) != SC_OK) {
        fprintf(stderr, "  patch %d: %s\n", p, err.message);
        return false;
    }
    return res->outputs[SCG_OUT_HIT][0] != 0;
}

/* Whether the ray passes the box of patch p's prism (slabs): the patches
 * a rasteriser would start the ray on, or a few more. */
static bool passes_box(const sc_tri_mesh *m, int p, const double eye[3], const double dir[3])
{
    double tri[6], lo[3], hi[3];
    sc_tri_mesh_domain(m, p, tri);
    lo[0] = fmin(tri[0], fmin(tri[2], tri[4]));
    hi[0] = fmax(tri[0], fmax(tri[2], tri[4]));
    lo[1] = fmin(tri[1], fmin(tri[3], tri[5]));
    hi[1] = fmax(tri[1], fmax(tri[3], tri[5]));
    lo[2] = INFINITY;
    hi[2] = -INFINITY;
    for (int k = 0; k < m->ncoef; k++) {
        lo[2] = fmin(lo[2], m->coef[(size_t)p * 15 + (size_t)k]);
        hi[2] = fmax(hi[2], m->coef[(size_t)p * 15 + (size_t)k]);
    }
    double t0 = 0, t1 = INFINITY;
    for (int c = 0; c < 3; c++) {
        double a = (lo[c] - 1e-6 - eye[c]) / dir[c], b = (hi[c] + 1e-6 - eye[c]) / dir[c];
        t0 = fmax(t0, fmin(a, b));
        t1 = fmin(t1, fmax(a, b));
    }
    return t0 <= t1;
}

/* Texels of the patches as the renderer packs them (gl_data.c for tri
 * records): 4 record texels and 15 points each, relative to the middle of
 * the patch's box. */
static void pack(const sc_tri_mesh *m, float **records, float **points)
{
    sc_patch_list list;
    sc_tri_patch_list(m, &list);
    *records = calloc((size_t)m->count * SCG_RECORD_TEXELS * 4, sizeof(float));
    *points = calloc((size_t)m->count * 15 * 4, sizeof(float));
    for (int p = 0; p < m->count; p++) {
        const double *cp = list.patches[p].cp;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int k = 0; k < 15; k++)
            for (int c = 0; c < 3; c++) {
                lo[c] = fmin(lo[c], cp[4 * k + c]);
                hi[c] = fmax(hi[c], cp[4 * k + c]);
            }
        float *rec = *records + 4 * SCG_RECORD_TEXELS * p;
        rec[0] = (float)(15 * p);
        for (int c = 0; c < 3; c++)
            rec[12 + c] = (float)(0.5 * (lo[c] + hi[c]));
        for (int k = 0; k < 15; k++) {
            for (int c = 0; c < 3; c++)
                (*points)[4 * (15 * p + k) + c] = (float)(cp[4 * k + c] - rec[12 + c]);
            (*points)[4 * (15 * p + k) + 3] = 1;
        }
    }
    sc_patch_list_free(&list);
}

/* The program's nearest hit over every patch whose box the ray's line
 * passes (the depth test's answer) against the exact tracer: same verdict,
 * and the point within 2 tol + float rounding of the reference. */
TEST(tri_program_matches_reference)
{
    sc_tri_mesh m;
    franke_mesh(&m);
    sc_tri_tracer tr;
    sc_tri_tracer_init(&tr, &m);
    scg_key key;
    sc_error err;
    scg_program *prog = NULL;
    scg_interp *it = NULL;
    CHECK_INT(scg_key_parse(TRI_KEY, &key, &err), SC_OK);
    CHECK_INT(scg_build_program(&key, &prog, &err), SC_OK);
    CHECK_INT(scg_interp_create(prog, &it, &err), SC_OK);
    float *records, *points;
    pack(&m, &records, &points);
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    env.texels[SCG_TEX_POINTS] = points;
    env.texel_count[SCG_TEX_POINTS] = 15 * m.count;
    env.texels[SCG_TEX_RECORDS] = records;
    env.texel_count[SCG_TEX_RECORDS] = SCG_RECORD_TEXELS * m.count;
    env.uniforms[SCG_UNI_FOOTPRINT][0] = (float)FOOTPRINT;
    env.inputs[SCG_IN_T_LIMIT][0] = 3.0e38f;
    unsigned long long rng = 11;
    int rays = 400, ref_hits = 0, holes = 0, false_hits = 0, off = 0;
    double worst = 0, iters = 0;
    for (int r = 0; r < rays; r++) {
        double eye[3], dir[3];
        random_ray(&m, &rng, r < rays / 2 ? 0.3 : 0.05, eye, dir);
        sc_tri_hit ref;
        int ref_hit = sc_tri_tracer_trace(&tr, eye, dir, 0, &ref) == SC_OK;
        double hull_dist = ref_hit ? 0.9 * ref.t : 1.0;
        double tol = 0.05 * FOOTPRINT * hull_dist;
        double best_t = INFINITY, best_point[3] = {0};
        for (int p = 0; p < m.count; p++) {
            scg_interp_result res;
            if (!passes_box(&m, p, eye, dir) || !run_patch(it, &env, records, p, eye, dir, hull_dist, &res))
                continue;
            double t = res.outputs[SCG_OUT_T][0] * hull_dist;
            if (t < best_t) {
                best_t = t;
                const float *centre = records + 4 * (SCG_RECORD_TEXELS * p + 3);
                for (int k = 0; k < 3; k++)
                    best_point[k] = res.outputs[SCG_OUT_POINT][k] + centre[k];
                iters = res.outputs[SCG_OUT_ITERS][0] > iters ? res.outputs[SCG_OUT_ITERS][0]
                                                              : iters;
            }
        }
        ref_hits += ref_hit;
        if (ref_hit && best_t == INFINITY) {
            holes++;
            continue;
        }
        if (!ref_hit) {
            false_hits += best_t < INFINITY;
            continue;
        }
        double d2 = 0;
        for (int k = 0; k < 3; k++)
            d2 += (best_point[k] - ref.point[k]) * (best_point[k] - ref.point[k]);
        double bound = 2 * tol + 16 * 1.2e-7 * 1.5;
        worst = fmax(worst, sqrt(d2) / bound);
        off += sqrt(d2) > bound;
    }
    printf("  tri4 it6: %d rays, %d reference hits, %d holes, %d false hits, %d off, "
           "worst error %.3g of the bound, most iterations %.0f\n",
           rays, ref_hits, holes, false_hits, off, worst, iters);
    CHECK(ref_hits > rays * 9 / 10);
    CHECK(holes + false_hits + off <= rays / 100);
    free(records);
    free(points);
    scg_interp_free(it);
    scg_program_free(prog);
    sc_tri_tracer_free(&tr);
    sc_tri_mesh_free(&m);
}

/* hills33.pgm as it is (8-bit heights, level over whole patches): rays of
 * the default 400 × 400 view (a block around the two pixels the GPU once missed), where
 * the hit lies on a level part of a patch at its lowest coefficient, that
 * is on the floor of its prism. The prism's height slack was relative to
 * the patch's spread (6.5e-4 here) and fell below the rounding of the
 * ray origin's height, so the clipped segment could end just above the
 * root. Every ray the reference hits is hit, on the reference's patch. */
TEST(tri_program_level_patch_floor)
{
    sc_heights h;
    sc_error err;
    CHECK_INT(sc_heights_read("examples/scenes/hills33.pgm", 1, 1, &h, &err), SC_OK);
    h.dx = h.dy = 1.0 / 32;
    sc_tri_mesh m;
    CHECK_INT(sc_spline_build(&h, SC_SPLINE_C2, &m, &err), SC_OK);
    sc_heights_free(&h);
    sc_tri_tracer tr;
    sc_tri_tracer_init(&tr, &m);
    sc_camera cam = {.width = 400, .height = 400};
    CHECK_INT(sc_camera_parse("1.6200062769270676,-1.7400125538541351,1.6285663558418926,"
                              "0.5,0.5,0.28455882352941175,30",
                              &cam, &err),
              SC_OK);
    scg_key key;
    scg_program *prog = NULL;
    scg_interp *it = NULL;
    CHECK_INT(scg_key_parse(TRI_KEY, &key, &err), SC_OK);
    CHECK_INT(scg_build_program(&key, &prog, &err), SC_OK);
    CHECK_INT(scg_interp_create(prog, &it, &err), SC_OK);
    float *records, *points;
    pack(&m, &records, &points);
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    env.texels[SCG_TEX_POINTS] = points;
    env.texel_count[SCG_TEX_POINTS] = 15 * m.count;
    env.texels[SCG_TEX_RECORDS] = records;
    env.texel_count[SCG_TEX_RECORDS] = SCG_RECORD_TEXELS * m.count;
    env.uniforms[SCG_UNI_FOOTPRINT][0] = (float)sc_camera_footprint(&cam, 1);
    env.inputs[SCG_IN_T_LIMIT][0] = 3.0e38f;
    int level = 0, holes = 0;
    for (int j = 150; j < 300; j++)
        for (int i = 40; i < 160; i++) {
            double dir[3];
            sc_camera_ray(&cam, i + 0.5, j + 0.5, dir);
            sc_tri_hit ref;
            if (sc_tri_tracer_trace(&tr, cam.eye, dir, 0, &ref) != SC_OK)
                continue;
            const double *coef = m.coef + (size_t)ref.patch * 15;
            double zmin = coef[0];
            for (int k = 1; k < 15; k++)
                zmin = fmin(zmin, coef[k]);
            if (fabs(ref.point[2] - zmin) > 1e-7)
                continue;
            level++;
            /* The fragment's ray reaches the prism near the hit, as the
             * rasterised proxy gives it. */
            scg_interp_result res;
            holes += !run_patch(it, &env, records, ref.patch, cam.eye, dir, 0.99 * ref.t, &res);
        }
    printf("  %d rays hit a patch at its lowest coefficient, %d holes\n", level, holes);
    CHECK(level >= 9);
    CHECK_INT(holes, 0);
    free(records);
    free(points);
    scg_interp_free(it);
    scg_program_free(prog);
    sc_tri_tracer_free(&tr);
    sc_tri_mesh_free(&m);
}

/* Rays that meet the surface on the shared edge of two patches: in a view
 * of Franke's C2 terrain (N = 576) from 3.6 units away, 256 × 256, the
 * GPU missed pixel (181, 190), whose hit lies 10^-6 of a square from a
 * diagonal, and so did this interpreted program: both patches' segments
 * end within the edge slack (10^-5, barycentric) of the root, where the
 * rounding of g at the ray's height (about 2·10^-7 here) is of the size of
 * g's change over the slack, and g's BB-coefficients came out of one sign
 * in both. The rejection now needs them clear of zero by 1 % of the
 * tolerance. The block of pixels around it, every patch whose box each
 * ray passes: no holes. */
TEST(tri_program_shared_edge)
{
    sc_heights h;
    sc_error err;
    CHECK_INT(sc_spline_franke_heights(SC_SPLINE_C2, 576, &h, &err), SC_OK);
    sc_tri_mesh m;
    CHECK_INT(sc_spline_build(&h, SC_SPLINE_C2, &m, &err), SC_OK);
    sc_heights_free(&h);
    sc_tri_tracer tr;
    sc_tri_tracer_init(&tr, &m);
    sc_camera cam = {.width = 256, .height = 256};
    CHECK_INT(sc_camera_parse("1.9059530054358034,-2.3119060108716067,2.2976726618008212,"
                              "0.5,0.5,0.61052905527785706,30",
                              &cam, &err),
              SC_OK);
    scg_key key;
    scg_program *prog = NULL;
    scg_interp *it = NULL;
    CHECK_INT(scg_key_parse(TRI_KEY, &key, &err), SC_OK);
    CHECK_INT(scg_build_program(&key, &prog, &err), SC_OK);
    CHECK_INT(scg_interp_create(prog, &it, &err), SC_OK);
    float *records, *points;
    pack(&m, &records, &points);
    scg_interp_env env;
    memset(&env, 0, sizeof env);
    env.texels[SCG_TEX_POINTS] = points;
    env.texel_count[SCG_TEX_POINTS] = 15 * m.count;
    env.texels[SCG_TEX_RECORDS] = records;
    env.texel_count[SCG_TEX_RECORDS] = SCG_RECORD_TEXELS * m.count;
    env.uniforms[SCG_UNI_FOOTPRINT][0] = (float)sc_camera_footprint(&cam, 1);
    env.inputs[SCG_IN_T_LIMIT][0] = 3.0e38f;
    int ref_hits = 0, holes = 0;
    for (int j = 184; j < 197; j++)
        for (int i = 175; i < 188; i++) {
            double dir[3];
            sc_camera_ray(&cam, i + 0.5, j + 0.5, dir);
            sc_tri_hit ref;
            if (sc_tri_tracer_trace(&tr, cam.eye, dir, 0, &ref) != SC_OK)
                continue;
            ref_hits++;
            int hit = 0;
            for (int p = 0; p < m.count && !hit; p++) {
                scg_interp_result res;
                hit = passes_box(&m, p, cam.eye, dir) &&
                      run_patch(it, &env, records, p, cam.eye, dir, 0.99 * ref.t, &res);
            }
            holes += !hit;
        }
    printf("  %d reference hits, %d holes\n", ref_hits, holes);
    CHECK(ref_hits > 100);
    CHECK_INT(holes, 0);
    free(records);
    free(points);
    scg_interp_free(it);
    scg_program_free(prog);
    sc_tri_tracer_free(&tr);
    sc_tri_mesh_free(&m);
}
