/* test_hulls.c — sub-patches and convex hulls: every hull holds its piece of
 * surface (points evaluated by the NURBS core), is closed and outward
 * oriented, its vertices carry the parameters of their control points, the
 * uniform mode gives n × n pieces per Bézier patch and the adaptive mode
 * stops at its flatness tolerance. */
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "hulls.h"
#include "io.h"
#include "nurbs.h"
#include "options.h"

/* Signed distance of p outside hull h (<= 0 inside), over its faces. */
static double outside_distance(const sc_hulls *hulls, int h, const double p[3])
{
    const sc_subpatch *s = &hulls->subpatches[h];
    double worst = -INFINITY;
    for (int t = 0; t < s->index_count; t += 3) {
        const uint32_t *tri = hulls->indices + s->first_index + t;
        const double *a = hulls->vertices[tri[0]].pos, *b = hulls->vertices[tri[1]].pos,
                     *c = hulls->vertices[tri[2]].pos;
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = b[k] - a[k];
            e2[k] = c[k] - a[k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (len == 0)
            continue;
        double d = (n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2])) / len;
        worst = fmax(worst, d);
    }
    return worst;
}

static double scene_diag(const sc_scene *scene)
{
    double lo[3], hi[3];
    sc_scene_bounds(scene, lo, hi);
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* Surface points at random parameters of each sub-patch lie in its hull. */
static void check_containment(const sc_scene *scene, const sc_hulls *hulls, int samples,
                              int *bad)
{
    unsigned long long rng = 12345;
    double tol = 1e-9 * scene_diag(scene);
    for (int h = 0; h < hulls->count; h++) {
        const sc_subpatch *s = &hulls->subpatches[h];
        for (int k = 0; k < samples; k++) {
            double u = s->domain[0] + (s->domain[1] - s->domain[0]) * test_rand(&rng);
            double v = s->domain[2] + (s->domain[3] - s->domain[2]) * test_rand(&rng);
            double p[3];
            sc_surface_eval_world(&scene->surfaces[s->surface], u, v, p, NULL, NULL);
            if (outside_distance(hulls, h, p) > tol)
                (*bad)++;
        }
    }
}

/* Closed and consistently oriented: every directed edge (a, b) of a hull
 * has exactly one opposite (b, a), and V - E + F = 2. */
static int hull_is_closed(const sc_hulls *hulls, int h)
{
    const sc_subpatch *s = &hulls->subpatches[h];
    int ntri = s->index_count / 3;
    const uint32_t *idx = hulls->indices + s->first_index;
    for (int t = 0; t < ntri; t++)
        for (int e = 0; e < 3; e++) {
            uint32_t a = idx[3 * t + e], b = idx[3 * t + (e + 1) % 3];
            int opposite = 0, same = 0;
            for (int r = 0; r < ntri; r++)
                for (int f = 0; f < 3; f++) {
                    uint32_t c = idx[3 * r + f], d = idx[3 * r + (f + 1) % 3];
                    opposite += c == b && d == a;
                    same += c == a && d == b;
                }
            if (opposite != 1 || same != 1)
                return 0;
        }
    int edges = 3 * ntri / 2;
    return s->vertex_count - edges + ntri == 2;
}

static int load_teapot(sc_scene *scene)
{
    sc_error err = {0};
    sc_scene_init(scene);
    if (sc_read_scene(TEST_TEAPOT32, scene, &err) != SC_OK) {
        fprintf(stderr, "  %s\n", err.message);
        return 0;
    }
    return 1;
}

TEST(hulls_parse)
{
    sc_hull_desc d;
    sc_error err = {0};
#define PARSE(text) cli_hulls_parse(text, &d.mode, &d.divisions, &d.tolerance, &err)
    CHECK_INT(PARSE("uniform:3"), SC_OK);
    CHECK_INT(d.mode, SC_SPLIT_UNIFORM);
    CHECK_INT(d.divisions, 3);
    CHECK_INT(PARSE("adaptive:0.01"), SC_OK);
    CHECK_INT(d.mode, SC_SPLIT_ADAPTIVE);
    CHECK_NEAR(d.tolerance, 0.01, 0);
    CHECK_INT(PARSE("uniform:0"), SC_FAIL);
    CHECK_INT(PARSE("uniform:2x"), SC_FAIL);
    CHECK_INT(PARSE("adaptive:-1"), SC_FAIL);
    CHECK_INT(PARSE("cubes"), SC_FAIL);
#undef PARSE
    CHECK_CONTAINS(err.message, "uniform:N or adaptive:TOL");
}

/* uniform:N cuts each of the teapot's 32 bicubic patches into N × N; every
 * hull is closed, holds its surface piece, and its corner vertices are the
 * surface's corner points at the parameters they carry. */
TEST(hulls_uniform_teapot)
{
    sc_scene scene;
    CHECK(load_teapot(&scene));
    if (test_failed_flag)
        return;
    sc_hulls hulls;
    sc_error err = {0};
    sc_hull_desc desc = {.mode = SC_SPLIT_UNIFORM, .divisions = 3};
    CHECK_INT(sc_hulls_build(&scene, &desc, &hulls, &err), SC_OK);
    CHECK_INT(hulls.npatches, 32);
    CHECK_INT(hulls.count, 32 * 9);
    int open = 0, corner_bad = 0, corners = 0;
    for (int h = 0; h < hulls.count; h++) {
        open += !hull_is_closed(&hulls, h);
        const sc_subpatch *s = &hulls.subpatches[h];
        CHECK_NEAR(s->local[1] - s->local[0], 1.0 / 3, 1e-12);
        for (int k = 0; k < s->vertex_count; k++) {
            const sc_hull_vertex *v = &hulls.vertices[s->first_vertex + k];
            int at_u = v->uv[0] == s->local[0] || v->uv[0] == s->local[1];
            int at_v = v->uv[1] == s->local[2] || v->uv[1] == s->local[3];
            if (!at_u || !at_v)
                continue;
            /* teapot32 patches are whole surfaces: local = domain */
            double p[3];
            sc_surface_eval_world(&scene.surfaces[s->surface], v->uv[0], v->uv[1], p, NULL,
                                  NULL);
            corners++;
            corner_bad += fabs(p[0] - v->pos[0]) + fabs(p[1] - v->pos[1]) +
                              fabs(p[2] - v->pos[2]) > 1e-9;
        }
    }
    int outside = 0;
    check_containment(&scene, &hulls, 20, &outside);
    sc_hulls_free(&hulls);
    sc_scene_free(&scene);
    CHECK_INT(open, 0);
    CHECK_INT(outside, 0);
    CHECK(corners > 0);
    CHECK_INT(corner_bad, 0);
}

/* Adaptive pieces are flat within the tolerance: the surface differs from
 * the bilinear patch through its four corner points by at most the
 * tolerance (for polynomial patches the control mesh bounds it: linear
 * precision of the Bernstein basis). A tighter tolerance gives more hulls. */
TEST(hulls_adaptive_flatness)
{
    sc_scene scene;
    CHECK(load_teapot(&scene));
    if (test_failed_flag)
        return;
    double diag = scene_diag(&scene);
    int counts[2];
    double tols[2] = {0.01, 0.002};
    for (int r = 0; r < 2; r++) {
        sc_hulls hulls;
        sc_error err = {0};
        sc_hull_desc desc = {.mode = SC_SPLIT_ADAPTIVE, .tolerance = tols[r], .max_depth = 30};
        CHECK_INT(sc_hulls_build(&scene, &desc, &hulls, &err), SC_OK);
        counts[r] = hulls.count;
        double worst = 0;
        unsigned long long rng = 7;
        for (int h = 0; h < hulls.count; h++) {
            const sc_subpatch *s = &hulls.subpatches[h];
            const sc_surface *surf = &scene.surfaces[s->surface];
            double c[4][3];
            sc_surface_eval_world(surf, s->domain[0], s->domain[2], c[0], NULL, NULL);
            sc_surface_eval_world(surf, s->domain[1], s->domain[2], c[1], NULL, NULL);
            sc_surface_eval_world(surf, s->domain[0], s->domain[3], c[2], NULL, NULL);
            sc_surface_eval_world(surf, s->domain[1], s->domain[3], c[3], NULL, NULL);
            for (int k = 0; k < 8; k++) {
                double a = test_rand(&rng), b = test_rand(&rng), p[3], d = 0;
                sc_surface_eval_world(surf, s->domain[0] + a * (s->domain[1] - s->domain[0]),
                                      s->domain[2] + b * (s->domain[3] - s->domain[2]), p,
                                      NULL, NULL);
                for (int x = 0; x < 3; x++) {
                    double q = (1 - b) * ((1 - a) * c[0][x] + a * c[1][x]) +
                               b * ((1 - a) * c[2][x] + a * c[3][x]);
                    d += (p[x] - q) * (p[x] - q);
                }
                worst = fmax(worst, sqrt(d));
            }
        }
        int outside = 0;
        check_containment(&scene, &hulls, 4, &outside);
        sc_hulls_free(&hulls);
        CHECK_INT(outside, 0);
        CHECK(worst <= tols[r] * diag * (1 + 1e-9));
    }
    CHECK(counts[1] > counts[0]);
    CHECK(counts[0] >= 32);
    sc_scene_free(&scene);
}

/* A planar bilinear patch has no 3D hull: it gets a thin slab that still
 * holds it; a patch collapsed to a point gets no hull at all. */
TEST(hulls_flat_and_collapsed)
{
    sc_scene scene;
    sc_scene_init(&scene);
    for (int k = 0; k < 2; k++) {
        sc_surface *s = sc_scene_add_surface(&scene);
        sc_surface_alloc(s, 1, 1, 2, 2);
        double knots[4] = {0, 0, 1, 1};
        memcpy(s->knots_u, knots, sizeof knots);
        memcpy(s->knots_v, knots, sizeof knots);
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                double *cp = s->cp + 4 * (j * 2 + i);
                cp[0] = k == 0 ? i : 5;
                cp[1] = k == 0 ? 2 * j : 5;
                cp[2] = k == 0 ? 1 : 5;
                cp[3] = 1;
            }
    }
    sc_hulls hulls;
    sc_error err = {0};
    sc_hull_desc desc = {.mode = SC_SPLIT_UNIFORM, .divisions = 1};
    CHECK_INT(sc_hulls_build(&scene, &desc, &hulls, &err), SC_OK);
    CHECK_INT(hulls.npatches, 2);
    CHECK_INT(hulls.count, 1);
    CHECK_INT(hulls.subpatches[0].surface, 0);
    CHECK(hull_is_closed(&hulls, 0));
    double inside[3] = {0.5, 1.0, 1.0}, above[3] = {0.5, 1.0, 1.01};
    CHECK(sc_hull_contains(&hulls, 0, inside));
    CHECK(!sc_hull_contains(&hulls, 0, above));
    /* The slab is thin: its z extent is a tiny fraction of the patch. */
    CHECK(hulls.subpatches[0].hi[2] - hulls.subpatches[0].lo[2] < 1e-3);
    sc_hulls_free(&hulls);
    sc_scene_free(&scene);
}

/* The hulls of a multi-span NURBS surface follow its Bézier patches: the
 * sub-patch domains tile the surface's domain exactly. */
TEST(hulls_nurbs_tiling)
{
    sc_scene scene;
    sc_scene_init(&scene);
    sc_surface *s = sc_scene_add_surface(&scene);
    /* degree (2, 3), 4 × 5 control points: 2 spans in u, 2 in v */
    sc_surface_alloc(s, 2, 3, 4, 5);
    double ku[7] = {0, 0, 0, 0.4, 1, 1, 1};
    double kv[9] = {0, 0, 0, 0, 2, 3, 3, 3, 3};
    memcpy(s->knots_u, ku, sizeof ku);
    memcpy(s->knots_v, kv, sizeof kv);
    unsigned long long rng = 99;
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 4; i++) {
            double *cp = s->cp + 4 * (j * 4 + i);
            cp[0] = i;
            cp[1] = j;
            cp[2] = test_rand(&rng);
            cp[3] = 1;
        }
    sc_hulls hulls;
    sc_error err = {0};
    sc_hull_desc desc = {.mode = SC_SPLIT_UNIFORM, .divisions = 2};
    CHECK_INT(sc_hulls_build(&scene, &desc, &hulls, &err), SC_OK);
    CHECK_INT(hulls.npatches, 4);
    CHECK_INT(hulls.count, 16);
    double area = 0;
    for (int h = 0; h < hulls.count; h++) {
        const double *d = hulls.subpatches[h].domain;
        area += (d[1] - d[0]) * (d[3] - d[2]);
    }
    CHECK_NEAR(area, 1.0 * 3.0, 1e-12);
    int outside = 0;
    check_containment(&scene, &hulls, 30, &outside);
    CHECK_INT(outside, 0);
    sc_hulls_free(&hulls);
    sc_scene_free(&scene);
}

/* Two hull sets are the same, number for number. */
static int hulls_differ(const sc_hulls *a, const sc_hulls *b)
{
    if (a->count != b->count || a->nvertices != b->nvertices || a->nindices != b->nindices ||
        a->npatches != b->npatches || a->nsurfaces != b->nsurfaces)
        return 1;
    int differ = 0;
    for (int k = 0; k < a->count; k++) {
        const sc_subpatch *x = &a->subpatches[k], *y = &b->subpatches[k];
        differ += x->surface != y->surface || x->patch != y->patch ||
                  x->first_vertex != y->first_vertex || x->vertex_count != y->vertex_count ||
                  x->first_index != y->first_index || x->index_count != y->index_count;
        for (int c = 0; c < 3; c++)
            differ += x->lo[c] != y->lo[c] || x->hi[c] != y->hi[c];
        for (int c = 0; c < 4; c++)
            differ += x->local[c] != y->local[c] || x->domain[c] != y->domain[c];
    }
    for (int v = 0; v < a->nvertices; v++)
        for (int c = 0; c < 3; c++)
            differ += a->vertices[v].pos[c] != b->vertices[v].pos[c] ||
                      (c < 2 && a->vertices[v].uv[c] != b->vertices[v].uv[c]);
    for (int i = 0; i < a->nindices; i++)
        differ += a->indices[i] != b->indices[i];
    for (int s = 0; s < a->nsurfaces; s++)
        differ += memcmp(&a->surfaces[s], &b->surfaces[s], sizeof a->surfaces[s]) != 0;
    return differ;
}

/* Two hull sets bound the same pieces with the same convex bodies: the
 * same sub-patches (surface, patch, rectangles, boxes) and every vertex of
 * each hull on or inside the other's, to tol — an update's new hulls come
 * from the small hull, which may triangulate coplanar faces otherwise
 * than qhull, or make a vertex of a control point lying on a face. */
static int hulls_bodies_differ(const sc_hulls *a, const sc_hulls *b, double tol)
{
    if (a->count != b->count || a->npatches != b->npatches || a->nsurfaces != b->nsurfaces)
        return 1;
    int differ = 0;
    for (int k = 0; k < a->count; k++) {
        const sc_subpatch *x = &a->subpatches[k], *y = &b->subpatches[k];
        differ += x->surface != y->surface || x->patch != y->patch;
        for (int c = 0; c < 3; c++)
            differ += fabs(x->lo[c] - y->lo[c]) > tol || fabs(x->hi[c] - y->hi[c]) > tol;
        for (int c = 0; c < 4; c++)
            differ += x->local[c] != y->local[c] || x->domain[c] != y->domain[c];
        for (int v = 0; v < x->vertex_count; v++)
            differ += outside_distance(b, k, a->vertices[x->first_vertex + v].pos) > tol;
        for (int v = 0; v < y->vertex_count; v++)
            differ += outside_distance(a, k, b->vertices[y->first_vertex + v].pos) > tol;
    }
    return differ;
}

/* Rebuilding one surface gives what a build of the changed scene gives
 * when the scene's box stays: a body patch of the teapot lifted keeps its
 * triangles (the same hulls, number for number: only its ranges change),
 * then bent inwards until adaptive subdivision needs more pieces (the
 * hulls after it move; the new ones, from the small hull, the same convex
 * bodies as the build's). */
TEST(hulls_update_one_surface)
{
    sc_scene scene;
    CHECK(load_teapot(&scene));
    if (test_failed_flag)
        return;
    sc_hulls hulls, fresh;
    sc_error err = {0};
    CHECK_INT(sc_hulls_build(&scene, NULL, &hulls, &err), SC_OK);
    double lo0[3], hi0[3], lo[3], hi[3];
    sc_scene_bounds(&scene, lo0, hi0);
    sc_surface *body = &scene.surfaces[4];
    for (int k = 0; k < body->nu * body->nv; k++)
        body->cp[4 * k + 2] += 0.2 * body->cp[4 * k + 3];
    int moved = -1;
    CHECK_INT(sc_hulls_update_surface(&hulls, &scene, 4, &moved, &err), SC_OK);
    CHECK_INT(moved, 0);
    CHECK_INT(hulls.kept_pieces, hulls.surfaces[4].subpatch_count);
    sc_scene_bounds(&scene, lo, hi);
    CHECK(!memcmp(lo, lo0, sizeof lo) && !memcmp(hi, hi0, sizeof hi));
    CHECK_INT(sc_hulls_build(&scene, NULL, &fresh, &err), SC_OK);
    CHECK_INT(hulls_differ(&hulls, &fresh), 0);
    sc_hulls_free(&fresh);

    int before = hulls.surfaces[4].subpatch_count;
    for (int k = 5; k <= 6; k++)  /* the two inner control points of row 1 */
        for (int c = 0; c < 2; c++)
            body->cp[4 * k + c] *= 0.2;
    CHECK_INT(sc_hulls_update_surface(&hulls, &scene, 4, &moved, &err), SC_OK);
    CHECK_INT(moved, 1);
    CHECK(hulls.surfaces[4].subpatch_count > before);
    sc_scene_bounds(&scene, lo, hi);
    CHECK(!memcmp(lo, lo0, sizeof lo) && !memcmp(hi, hi0, sizeof hi));
    CHECK_INT(sc_hulls_build(&scene, NULL, &fresh, &err), SC_OK);
    CHECK_INT(hulls_bodies_differ(&hulls, &fresh, 1e-9 * scene_diag(&scene)), 0);
    sc_hulls_free(&fresh);

    /* The tolerance stays the one the hulls were built with, though the
     * scene's box grows: moved far up, the patch keeps its pieces, where a
     * build of the grown scene, with a tolerance twice as large, cuts it
     * into fewer. */
    int bent = hulls.surfaces[4].subpatch_count;
    for (int k = 0; k < body->nu * body->nv; k++)
        body->cp[4 * k + 2] += 10 * body->cp[4 * k + 3];
    CHECK_INT(sc_hulls_update_surface(&hulls, &scene, 4, &moved, &err), SC_OK);
    CHECK_INT(hulls.surfaces[4].subpatch_count, bent);
    CHECK_INT(sc_hulls_build(&scene, NULL, &fresh, &err), SC_OK);
    CHECK(fresh.tolerance > 1.5 * hulls.tolerance);
    CHECK(fresh.surfaces[4].subpatch_count < bent);
    sc_hulls_free(&fresh);
    CHECK_INT(sc_hulls_update_surface(&hulls, &scene, 32, &moved, &err), SC_FAIL);
    sc_hulls_free(&hulls);
    sc_scene_free(&scene);
}
