/* test_update.c — following a moving scene: the small incremental hull
 * against qhull (the same convex body, every point inside, flat sets
 * refused), every teapot hull bounding its piece of surface while a wave
 * moves every control point frame after frame, and a renderer updated
 * surface by surface each frame drawing what the CPU reference sees of the
 * changed scene (no holes), having sent each changed surface's data once. */
#include "test.h"

#include <libqhull_r/qhull_ra.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"
#include "gl_context_util.h"
#include "gl_render.h"
#include "hulls.h"
#include "imgdiff.h"
#include "io.h"
#include "nurbs.h"
#include "refcast.h"
#include "small_hull.h"

/* ---- the small hull against qhull ---- */

/* Volume enclosed by outward triangles (divergence theorem). */
static double tris_volume(const double *p, const int *tris, int ntris)
{
    double v = 0;
    for (int f = 0; f < ntris; f++) {
        const double *a = p + 3 * tris[3 * f], *b = p + 3 * tris[3 * f + 1],
                     *c = p + 3 * tris[3 * f + 2];
        v += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return v / 6;
}

/* qhull's volume of the points' hull; -1 when it finds none. */
static double qhull_volume(const double *p, int n)
{
    qhT qh_storage;
    qhT *qh = &qh_storage;
    FILE *devnull = fopen("/dev/null", "w");
    qh_zero(qh, devnull);
    double *coords = malloc((size_t)n * 3 * sizeof(double));
    memcpy(coords, p, (size_t)n * 3 * sizeof(double));
    char options[] = "qhull FA";
    double volume = -1;
    if (!qh_new_qhull(qh, 3, n, coords, False, options, NULL, devnull)) {
        qh_getarea(qh, qh->facet_list);
        volume = qh->totvol;
    }
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    free(coords);
    fclose(devnull);
    return volume;
}

/* The control points of a bumpy bicubic-like net (an (m+1)² grid): heights
 * from the generator, spread `bump` high over a unit square, then moved
 * to their middle. */
static void net(unsigned long long *rng, int m, double bump, double *p)
{
    int n = (m + 1) * (m + 1);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int j = 0; j <= m; j++)
        for (int i = 0; i <= m; i++) {
            double *q = p + 3 * (j * (m + 1) + i);
            q[0] = (double)i / m + 0.05 * (test_rand(rng) - 0.5);
            q[1] = (double)j / m + 0.05 * (test_rand(rng) - 0.5);
            q[2] = bump * (test_rand(rng) - 0.5);
        }
    for (int k = 0; k < n; k++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], p[3 * k + c]);
            hi[c] = fmax(hi[c], p[3 * k + c]);
        }
    for (int k = 0; k < n; k++)
        for (int c = 0; c < 3; c++)
            p[3 * k + c] -= 0.5 * (lo[c] + hi[c]);
}

/* Random nets from nearly flat (1e-5 of their size) to bumpy, of degrees 1
 * to 6, and points on a sphere: every hull the small hull returns bounds
 * every point and encloses qhull's volume (to 1e-9 of it), so it is the
 * convex hull; it returns one for every net bumpier than 1e-4 of its size;
 * flat and collinear points are refused, for qhull. */
TEST(small_hull_against_qhull)
{
    unsigned long long rng = 777;
    double p[3 * 64];
    int tried = 0, made = 0, refused_bumpy = 0, bad_bounds = 0, bad_volume = 0;
    static const double bumps[] = {1e-5, 1e-4, 1e-3, 0.01, 0.1, 1};
    for (int m = 1; m <= 6; m++)
        for (int b = 0; b < 6; b++)
            for (int trial = 0; trial < 20; trial++) {
                int n = (m + 1) * (m + 1);
                net(&rng, m, bumps[b], p);
                int *tris = NULL;
                int ntris = sc_small_hull(p, n, sqrt(2.0), &tris);
                tried++;
                if (ntris < 0) {
                    refused_bumpy += bumps[b] >= 1e-4 && m > 1;
                    continue;
                }
                made++;
                bad_bounds += !sc_small_hull_bounds(p, n, tris, ntris, 1e-3);
                double v = tris_volume(p, tris, ntris), q = qhull_volume(p, n);
                if (!(fabs(v - q) <= 1e-9 * q))
                    bad_volume++;
                free(tris);
            }
    for (int trial = 0; trial < 50; trial++) {
        int n = 40;
        for (int k = 0; k < n; k++) {
            double z = 2 * test_rand(&rng) - 1, a = 2 * M_PI * test_rand(&rng);
            p[3 * k] = sqrt(1 - z * z) * cos(a);
            p[3 * k + 1] = sqrt(1 - z * z) * sin(a);
            p[3 * k + 2] = z;
        }
        int *tris = NULL;
        int ntris = sc_small_hull(p, n, 2 * sqrt(3.0), &tris);
        CHECK(ntris > 0);
        if (ntris < 0)
            continue;
        /* Every point of a sphere is a vertex: 2n - 4 triangles. */
        CHECK_INT(ntris, 2 * n - 4);
        bad_bounds += !sc_small_hull_bounds(p, n, tris, ntris, 1e-3);
        double v = tris_volume(p, tris, ntris), q = qhull_volume(p, n);
        bad_volume += !(fabs(v - q) <= 1e-9 * q);
        free(tris);
    }
    CHECK(made > tried * 3 / 4);
    CHECK_INT(refused_bumpy, 0);
    CHECK_INT(bad_bounds, 0);
    CHECK_INT(bad_volume, 0);

    /* Flat: a plane grid, rotated out of the axes; collinear; too few. */
    for (int k = 0; k < 16; k++) {
        double x = k % 4, y = k / 4;
        p[3 * k] = 0.6 * x + 0.8 * y;
        p[3 * k + 1] = -0.8 * x + 0.6 * y;
        p[3 * k + 2] = 0.3 * x - 0.1 * y;
    }
    int *tris = NULL;
    CHECK_INT(sc_small_hull(p, 16, 6, &tris), -1);
    for (int k = 0; k < 16; k++)
        for (int c = 0; c < 3; c++)
            p[3 * k + c] = (c + 1) * (k - 7.5);
    CHECK_INT(sc_small_hull(p, 16, 60, &tris), -1);
    CHECK_INT(sc_small_hull(p, 3, 60, &tris), -1);
    /* A bound is refused once a point leaves it: the unit tetrahedron,
     * then a fifth point beyond its slanted face. */
    double tet[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, 0.2};
    int ntris = sc_small_hull(tet, 5, sqrt(3.0), &tris);
    CHECK_INT(ntris, 4);
    if (ntris == 4) {
        CHECK(sc_small_hull_bounds(tet, 5, tris, 4, sqrt(3.0)));
        tet[12] = tet[13] = tet[14] = 0.34;
        CHECK(!sc_small_hull_bounds(tet, 5, tris, 4, sqrt(3.0)));
        free(tris);
    }
}

/* ---- the wave ---- */

typedef struct wave {
    double amplitude, wavelength;
    double *rest;            /* every surface's homogeneous points as read */
    int *first;              /* per surface: its first point in rest */
} wave;

/* The chart's deforming view (examples/splinecast/deform.c): every control
 * point z += A sin(2π (x + y) / λ + phase), A 1 % of the scene's size, λ a
 * third of it. */
static void wave_init(const sc_scene *scene, wave *w)
{
    double lo[3], hi[3];
    sc_scene_bounds(scene, lo, hi);
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    w->amplitude = 0.01 * diag;
    w->wavelength = diag / 3;
    w->first = calloc((size_t)scene->nsurfaces + 1, sizeof(int));
    for (int s = 0; s < scene->nsurfaces; s++)
        w->first[s + 1] = w->first[s] + scene->surfaces[s].nu * scene->surfaces[s].nv;
    w->rest = malloc((size_t)w->first[scene->nsurfaces] * 4 * sizeof(double));
    for (int s = 0; s < scene->nsurfaces; s++)
        memcpy(w->rest + 4 * w->first[s], scene->surfaces[s].cp,
               (size_t)(w->first[s + 1] - w->first[s]) * 4 * sizeof(double));
}

static void wave_apply(sc_scene *scene, const wave *w, int s, double phase)
{
    sc_surface *surf = &scene->surfaces[s];
    for (int k = 0; k < surf->nu * surf->nv; k++) {
        const double *h = w->rest + 4 * (w->first[s] + k);
        double x = h[0] / h[3], y = h[1] / h[3], z = h[2] / h[3];
        z += w->amplitude * sin(2 * M_PI * (x + y) / w->wavelength + phase);
        surf->cp[4 * k] = h[0];
        surf->cp[4 * k + 1] = h[1];
        surf->cp[4 * k + 2] = z * h[3];
        surf->cp[4 * k + 3] = h[3];
    }
}

static void wave_free(wave *w)
{
    free(w->rest);
    free(w->first);
}

/* Largest signed distance of p outside hull h over its faces. */
static double outside(const sc_hulls *hulls, int h, const double p[3])
{
    const sc_subpatch *s = &hulls->subpatches[h];
    double worst = -INFINITY;
    for (int t = 0; t < s->index_count; t += 3) {
        const uint32_t *tri = hulls->indices + s->first_index + t;
        const double *a = hulls->vertices[tri[0]].pos, *b = hulls->vertices[tri[1]].pos,
                     *c = hulls->vertices[tri[2]].pos;
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = b[k] - a[k];
            e2[k] = c[k] - a[k];
        }
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len > 0)
            worst = fmax(worst, (n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) +
                                 n[2] * (p[2] - a[2])) / len);
    }
    return worst;
}

/* Closed and consistently oriented: every directed edge (a, b) of hull h
 * has exactly one opposite (b, a), and V - E + F = 2. */
static int closed(const sc_hulls *hulls, int h)
{
    const sc_subpatch *s = &hulls->subpatches[h];
    int ntri = s->index_count / 3;
    const uint32_t *idx = hulls->indices + s->first_index;
    for (int t = 0; t < ntri; t++)
        for (int e = 0; e < 3; e++) {
            uint32_t a = idx[3 * t + e], b = idx[3 * t + (e + 1) % 3];
            int opposite = 0;
            for (int r = 0; r < ntri; r++)
                for (int f = 0; f < 3; f++)
                    opposite += idx[3 * r + f] == b && idx[3 * r + (f + 1) % 3] == a;
            if (opposite != 1)
                return 0;
        }
    return s->vertex_count - 3 * ntri / 2 + ntri == 2;
}

/* Every control point of the teapot moved by the wave, 8 frames of it, all
 * 32 surfaces' hulls updated surface by surface each frame: every hull
 * is closed and outward and holds its piece of surface (surface points at random parameters of each
 * sub-patch, evaluated by the NURBS core, within 1e-9 of the scene's size),
 * the sub-patches and their convex bodies are those a build with the same
 * tolerance gives, and no piece needed qhull. */
TEST(hulls_update_every_surface_wave)
{
    sc_scene scene;
    sc_error err = {0};
    sc_scene_init(&scene);
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    if (test_failed_flag)
        return;
    sc_hulls hulls;
    CHECK_INT(sc_hulls_build(&scene, NULL, &hulls, &err), SC_OK);
    long qhull_at_build = hulls.qhull_pieces;
    wave w;
    wave_init(&scene, &w);
    double tol = 1e-9 * w.wavelength * 3;
    unsigned long long rng = 99;
    long outside_count = 0, samples = 0, open = 0;
    int counts_changed = 0;
    for (int frame = 0; frame < 8; frame++) {
        int before = hulls.count;
        for (int s = 0; s < scene.nsurfaces; s++) {
            wave_apply(&scene, &w, s, 2 * M_PI * (frame + 1) / 16.0);
            int moved;
            CHECK_INT(sc_hulls_update_surface(&hulls, &scene, s, &moved, &err), SC_OK);
        }
        counts_changed += hulls.count != before;
        for (int h = 0; h < hulls.count; h++) {
            const sc_subpatch *sp = &hulls.subpatches[h];
            open += !closed(&hulls, h);
            for (int k = 0; k < 8; k++, samples++) {
                double u = sp->domain[0] + (sp->domain[1] - sp->domain[0]) * test_rand(&rng);
                double v = sp->domain[2] + (sp->domain[3] - sp->domain[2]) * test_rand(&rng);
                double p[3];
                sc_surface_eval_world(&scene.surfaces[sp->surface], u, v, p, NULL, NULL);
                outside_count += outside(&hulls, h, p) > tol;
            }
        }
    }
    CHECK(samples > 8 * 8 * 1000);
    CHECK_INT(outside_count, 0);
    CHECK_INT(open, 0);
    CHECK(counts_changed > 0);   /* the wave changes the subdivision */
    CHECK_INT(hulls.qhull_pieces, qhull_at_build);
    /* The same pieces as a build of the moved scene with the tolerance the
     * hulls keep (as a fraction of the moved scene's box). */
    double lo[3], hi[3];
    sc_scene_bounds(&scene, lo, hi);
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    sc_hulls fresh;
    CHECK_INT(sc_hulls_build(&scene, &(sc_hull_desc){.tolerance = hulls.tolerance / diag},
                             &fresh, &err), SC_OK);
    CHECK_INT(fresh.count, hulls.count);
    int differ = 0;
    for (int h = 0; h < hulls.count && h < fresh.count; h++) {
        differ += memcmp(fresh.subpatches[h].local, hulls.subpatches[h].local,
                         sizeof fresh.subpatches[h].local) != 0;
        /* and the same convex bodies as the build's (qhull's) */
        for (int v = 0; v < hulls.subpatches[h].vertex_count; v++)
            differ += outside(&fresh, h, hulls.vertices[hulls.subpatches[h].first_vertex + v].pos) >
                      tol;
        for (int v = 0; v < fresh.subpatches[h].vertex_count; v++)
            differ += outside(&hulls, h, fresh.vertices[fresh.subpatches[h].first_vertex + v].pos) >
                      tol;
    }
    CHECK_INT(differ, 0);
    sc_hulls_free(&fresh);
    sc_hulls_free(&hulls);
    wave_free(&w);
    sc_scene_free(&scene);
}

/* ---- a renderer following the scene ---- */

/* The renderer's frame of cam against the CPU reference of the scene as it
 * is now; also the frame of a renderer made afresh from it. */
static int frame_against_reference(const sc_gl *gl, sc_renderer *r, const sc_scene *scene,
                                   const sc_camera *cam, sc_accuracy *updated,
                                   sc_accuracy *fresh_acc)
{
    sc_error err = {0};
    sc_aov got = {0}, fresh_aov = {0}, ref = {0};
    sc_renderer *fresh = NULL;
    sc_refcast *rc = NULL;
    int ok = sc_renderer_draw(r, cam, &err) == SC_OK &&
             sc_renderer_read(r, NULL, &got, &err) == SC_OK &&
             sc_renderer_create(gl, scene, NULL, &fresh, &err) == SC_OK &&
             sc_renderer_draw(fresh, cam, &err) == SC_OK &&
             sc_renderer_read(fresh, NULL, &fresh_aov, &err) == SC_OK &&
             sc_refcast_prepare(scene, &rc, &err) == SC_OK &&
             sc_refcast_render(rc, cam, NULL, &ref, NULL, &err) == SC_OK &&
             sc_accuracy_compare(&ref, &got, updated, &err) == SC_OK &&
             sc_accuracy_compare(&ref, &fresh_aov, fresh_acc, &err) == SC_OK;
    if (!ok)
        fprintf(stderr, "  %s\n", err.message);
    sc_refcast_free(rc);
    sc_renderer_destroy(fresh);
    sc_aov_free(&got);
    sc_aov_free(&fresh_aov);
    sc_aov_free(&ref);
    return ok;
}

/* One bicubic Bézier patch's data: 16 points and a record of 4 texels, 16
 * bytes each; a hull vertex: 13 four-byte values. */
enum { PATCH_BYTES = 16 * 16 + 4 * 16, VERTEX_BYTES = 13 * 4 };

/* The teapot under the wave, three frames, every surface updated through
 * sc_renderer_update_surface before each: each frame draws what the CPU
 * reference sees of the moved teapot — no holes (every ray that meets a
 * piece of surface enters its hull), no failing pixel, as a renderer made
 * afresh from the moved scene — and sent every surface's patch data and
 * each hull vertex at most once (not once per surface whose hulls changed
 * number, as the later ones move), from a whole close-up too. */
static void update_every_surface(sc_ray_termination ert)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_error err = {0};
    sc_scene_init(&scene);
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    if (test_failed_flag)
        return;
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    cam.width = cam.height = 96;
    sc_camera close = cam;
    close.fovy_deg /= 4;
    sc_renderer *r;
    CHECK_INT(sc_renderer_create(gl, &scene, &(sc_render_desc){.ert = ert}, &r, &err), SC_OK);
    if (test_failed_flag)
        return;
    wave w;
    wave_init(&scene, &w);
    for (int frame = 0; frame < 3; frame++) {
        sc_render_stats before, st;
        sc_renderer_stats(r, &before);
        for (int s = 0; s < scene.nsurfaces; s++) {
            wave_apply(&scene, &w, s, 2 * M_PI * (frame + 1) / 5.0);
            CHECK_INT(sc_renderer_update_surface(r, s, &err), SC_OK);
        }
        sc_accuracy acc, fresh;
        const sc_camera *c = frame == 2 ? &close : &cam;
        CHECK(frame_against_reference(gl, r, &scene, c, &acc, &fresh));
        sc_renderer_stats(r, &st);
        CHECK(acc.ref_hits > 96 * 96 / 10);
        CHECK_INT(acc.holes, 0);
        CHECK_NEAR(acc.fail_pct, 0, 0);
        CHECK_NEAR(fresh.fail_pct, 0, 0);
        size_t data = (size_t)scene.nsurfaces * PATCH_BYTES;
        size_t sent = st.bytes_uploaded_total - before.bytes_uploaded_total;
        CHECK_INT(st.bytes_uploaded, sent);
        CHECK(sent > data);
        CHECK_INT((sent - data) % VERTEX_BYTES, 0);
        sc_hulls hulls;
        CHECK_INT(sc_hulls_build(&scene, NULL, &hulls, &err), SC_OK);
        CHECK(sent <= data + (size_t)hulls.nvertices * VERTEX_BYTES * 11 / 10);
        sc_hulls_free(&hulls);
    }
    sc_renderer_destroy(r);
    wave_free(&w);
    sc_scene_free(&scene);
}

TEST(gl_render_update_every_surface) { update_every_surface(0); }

/* The same with depth peeling, whose culling on the GPU reads the hulls'
 * slots each frame: moved hulls must be culled where they are now. */
TEST(gl_render_update_every_surface_peel) { update_every_surface(SC_TERMINATION_PEEL); }

/* What surface updates send is what changed: 1, 4 and then all 32 surfaces
 * of the teapot lifted (their hulls keep their counts) send exactly their
 * patch data and their hull vertices, so the bytes grow with the surfaces
 * changed; a surface updated twice before a frame sends its data twice and
 * its vertices once; a frame with no update sends nothing. */
TEST(gl_render_update_bytes_proportional)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene scene;
    sc_error err = {0};
    sc_scene_init(&scene);
    CHECK_INT(sc_read_scene("teapot", &scene, &err), SC_OK);
    if (test_failed_flag)
        return;
    sc_hulls hulls;
    CHECK_INT(sc_hulls_build(&scene, NULL, &hulls, &err), SC_OK);
    sc_renderer *r;
    CHECK_INT(sc_renderer_create(gl, &scene, NULL, &r, &err), SC_OK);
    if (test_failed_flag)
        return;
    sc_camera cam;
    sc_camera_default(&scene, &cam);
    cam.width = cam.height = 64;
    static const int counts[] = {1, 4, 32};
    size_t previous = 0;
    for (int i = 0; i < 3; i++) {
        size_t expected = 0;
        for (int k = 0; k < counts[i]; k++) {
            /* Spread over the teapot: every 8th, then every surface. */
            int s = counts[i] == 32 ? k : (8 * k + 3) % scene.nsurfaces;
            sc_surface *surf = &scene.surfaces[s];
            CHECK_INT(surf->nu * surf->nv, 16);
            for (int p = 0; p < 16; p++)
                surf->cp[4 * p + 2] += 0.25 * surf->cp[4 * p + 3];
            CHECK_INT(sc_renderer_update_surface(r, s, &err), SC_OK);
            expected += PATCH_BYTES + (size_t)hulls.surfaces[s].vertex_count * VERTEX_BYTES;
        }
        CHECK_INT(sc_renderer_send_updates(r, &err), SC_OK);
        sc_render_stats st;
        sc_renderer_stats(r, &st);
        CHECK_INT(st.hulls, hulls.count);
        CHECK_INT(st.bytes_uploaded, expected);
        CHECK(st.bytes_uploaded > previous);
        previous = st.bytes_uploaded;
    }
    /* All 32: every vertex once, and the patch data. */
    CHECK_INT(previous, 32 * PATCH_BYTES + (size_t)hulls.nvertices * VERTEX_BYTES);

    sc_render_stats before, st;
    sc_renderer_stats(r, &before);
    for (int twice = 0; twice < 2; twice++) {
        for (int p = 0; p < 16; p++)
            scene.surfaces[7].cp[4 * p + 2] += 0.25 * scene.surfaces[7].cp[4 * p + 3];
        CHECK_INT(sc_renderer_update_surface(r, 7, &err), SC_OK);
    }
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    sc_renderer_stats(r, &st);
    size_t twice = 2 * PATCH_BYTES + (size_t)hulls.surfaces[7].vertex_count * VERTEX_BYTES;
    CHECK_INT(st.bytes_uploaded, twice);
    CHECK_INT(st.bytes_uploaded_total - before.bytes_uploaded_total, twice);
    CHECK_INT(sc_renderer_draw(r, &cam, &err), SC_OK);
    sc_render_stats after;
    sc_renderer_stats(r, &after);
    CHECK_INT(after.bytes_uploaded_total, st.bytes_uploaded_total);
    sc_renderer_destroy(r);
    sc_hulls_free(&hulls);
    sc_scene_free(&scene);
}
