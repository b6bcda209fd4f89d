/* scene.c — lifetime, checks and derived facts of the scene model
 * (scene.h). Loop validation lives in loops.c. */
#include "scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <stdlib.h>

void sc_scene_init(sc_scene *scene) { memset(scene, 0, sizeof *scene); }

int sc_curve_try_alloc(sc_curve *c, int dim, int degree, int ncp)
{
    c->dim = dim;
    c->degree = degree;
    c->ncp = ncp;
    c->knots = sc_try_alloc((size_t)(ncp + degree + 1), sizeof(double));
    c->cp = c->knots ? sc_try_alloc((size_t)ncp * (size_t)(dim + 1), sizeof(double)) : NULL;
    if (!c->cp) {
        sc_curve_free(c);
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_curve_alloc(sc_curve *c, int dim, int degree, int ncp)
{
    c->dim = dim;
    c->degree = degree;
    c->ncp = ncp;
    c->knots = sc_alloc((size_t)(ncp + degree + 1), sizeof(double));
    c->cp = sc_alloc((size_t)ncp * (size_t)(dim + 1), sizeof(double));
}

void sc_curve_free(sc_curve *c)
{
    free(c->knots);
    free(c->cp);
    memset(c, 0, sizeof *c);
}

static void copy_curve_arrays(sc_curve *dst, const sc_curve *src)
{
    memcpy(dst->knots, src->knots, sizeof(double) * (size_t)(src->ncp + src->degree + 1));
    memcpy(dst->cp, src->cp, sizeof(double) * (size_t)src->ncp * (size_t)(src->dim + 1));
}

void sc_curve_copy(sc_curve *dst, const sc_curve *src)
{
    sc_curve_alloc(dst, src->dim, src->degree, src->ncp);
    copy_curve_arrays(dst, src);
}

int sc_curve_try_copy(sc_curve *dst, const sc_curve *src)
{
    if (sc_curve_try_alloc(dst, src->dim, src->degree, src->ncp))
        return SC_FAIL;
    copy_curve_arrays(dst, src);
    return SC_OK;
}

static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

int sc_surface_try_alloc(sc_surface *s, int deg_u, int deg_v, int nu, int nv)
{
    s->deg_u = deg_u;
    s->deg_v = deg_v;
    s->nu = nu;
    s->nv = nv;
    s->knots_u = sc_try_alloc((size_t)(nu + deg_u + 1), sizeof(double));
    s->knots_v = sc_try_alloc((size_t)(nv + deg_v + 1), sizeof(double));
    s->cp = sc_try_alloc((size_t)nu * (size_t)nv * 4, sizeof(double));
    if (!s->knots_u || !s->knots_v || !s->cp) {
        /* The surface keeps its loops, name and transform. */
        free(s->knots_u);
        free(s->knots_v);
        free(s->cp);
        s->knots_u = s->knots_v = s->cp = NULL;
        s->nu = s->nv = 0;
        return SC_FAIL;
    }
    return SC_OK;
}

void sc_surface_alloc(sc_surface *s, int deg_u, int deg_v, int nu, int nv)
{
    s->deg_u = deg_u;
    s->deg_v = deg_v;
    s->nu = nu;
    s->nv = nv;
    s->knots_u = sc_alloc((size_t)(nu + deg_u + 1), sizeof(double));
    s->knots_v = sc_alloc((size_t)(nv + deg_v + 1), sizeof(double));
    s->cp = sc_alloc((size_t)nu * (size_t)nv * 4, sizeof(double));
}

static void free_loops(sc_surface *s)
{
    for (int l = 0; l < s->nloops; l++) {
        for (int c = 0; c < s->loops[l].ncurves; c++)
            sc_curve_free(&s->loops[l].curves[c]);
        free(s->loops[l].curves);
    }
    free(s->loops);
    s->loops = NULL;
    s->nloops = 0;
}

void sc_surface_free(sc_surface *s)
{
    free(s->knots_u);
    free(s->knots_v);
    free(s->cp);
    free_loops(s);
    memset(s, 0, sizeof *s);
}

void sc_surface_copy(sc_surface *dst, const sc_surface *src)
{
    *dst = *src;
    sc_surface_alloc(dst, src->deg_u, src->deg_v, src->nu, src->nv);
    memcpy(dst->knots_u, src->knots_u, sizeof(double) * (size_t)(src->nu + src->deg_u + 1));
    memcpy(dst->knots_v, src->knots_v, sizeof(double) * (size_t)(src->nv + src->deg_v + 1));
    memcpy(dst->cp, src->cp, sizeof(double) * (size_t)src->nu * (size_t)src->nv * 4);
    dst->loops = src->nloops ? sc_alloc((size_t)src->nloops, sizeof(sc_loop)) : NULL;
    for (int l = 0; l < src->nloops; l++) {
        dst->loops[l] = src->loops[l];
        dst->loops[l].curves = sc_alloc((size_t)src->loops[l].ncurves, sizeof(sc_curve));
        for (int c = 0; c < src->loops[l].ncurves; c++)
            sc_curve_copy(&dst->loops[l].curves[c], &src->loops[l].curves[c]);
    }
}

void sc_scene_free(sc_scene *scene)
{
    for (int i = 0; i < scene->nsurfaces; i++)
        sc_surface_free(&scene->surfaces[i]);
    free(scene->surfaces);
    free(scene->skipped);
    if (scene->terrain && scene->terrain_free)
        scene->terrain_free(scene->terrain);
    sc_scene_init(scene);
}

/* The aborting and the checked form differ only in the allocation. */
static sc_surface *add_surface(sc_scene *scene, int checked)
{
    size_t n = (size_t)scene->nsurfaces + 1;
    sc_surface *grown = checked ? sc_try_realloc(scene->surfaces, n, sizeof(sc_surface))
                                : sc_realloc(scene->surfaces, n, sizeof(sc_surface));
    if (!grown)
        return NULL;
    scene->surfaces = grown;
    sc_surface *s = &scene->surfaces[scene->nsurfaces];
    memset(s, 0, sizeof *s);
    memcpy(s->xform, identity, sizeof identity);
    s->color[0] = 0.8f;
    s->color[1] = 0.8f;
    s->color[2] = 0.8f;
    snprintf(s->name, sizeof s->name, "surface%d", scene->nsurfaces);
    scene->nsurfaces++;
    return s;
}

sc_surface *sc_scene_add_surface(sc_scene *scene) { return add_surface(scene, 0); }

sc_surface *sc_scene_try_add_surface(sc_scene *scene) { return add_surface(scene, 1); }

void sc_scene_skip(sc_scene *scene, const char *type, const char *reason, int count)
{
    for (int i = 0; i < scene->nskipped; i++)
        if (!strcmp(scene->skipped[i].type, type) && !strcmp(scene->skipped[i].reason, reason)) {
            scene->skipped[i].count += count;
            return;
        }
    scene->skipped = sc_realloc(scene->skipped, (size_t)scene->nskipped + 1, sizeof(sc_skipped));
    sc_skipped *k = &scene->skipped[scene->nskipped++];
    memset(k, 0, sizeof *k);
    snprintf(k->type, sizeof k->type, "%s", type);
    snprintf(k->reason, sizeof k->reason, "%s", reason);
    k->count = count;
}

void sc_surface_update_rational(sc_surface *s)
{
    size_t n = (size_t)s->nu * (size_t)s->nv;
    double w0 = s->cp[3];
    int rational = 0;
    for (size_t k = 0; k < n; k++)
        if (fabs(s->cp[4 * k + 3] - w0) > 1e-12 * fabs(w0))
            rational = 1;
    s->rational = rational;
    if (!rational && w0 != 1.0) {
        /* All weights equal: divide them out, the surface is the same. */
        for (size_t k = 0; k < n; k++) {
            double w = s->cp[4 * k + 3];
            for (int d = 0; d < 3; d++)
                s->cp[4 * k + d] /= w;
            s->cp[4 * k + 3] = 1.0;
        }
    }
}

static int check_knots(const double *k, int n, int degree, const char *what, sc_error *err)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(k[i]))
            return sc_fail(err, NULL, 0, "%s knot %d is not a finite number", what, i);
    for (int i = 1; i < n; i++)
        if (k[i] < k[i - 1])
            return sc_fail(err, NULL, 0, "%s knots decrease at index %d (%.17g < %.17g)", what,
                           i, k[i], k[i - 1]);
    int m = n - 1;
    for (int i = 1; i <= degree; i++)
        if (k[i] != k[0] || k[m - i] != k[m])
            return sc_fail(err, NULL, 0, "%s knot vector is not clamped (degree %d needs %d equal "
                           "knots at each end)", what, degree, degree + 1);
    if (!(k[degree] < k[m - degree]))
        return sc_fail(err, NULL, 0, "%s knot vector has an empty domain", what);
    return SC_OK;
}

static int check_points(const double *cp, size_t n, int stride, const char *what, sc_error *err)
{
    for (size_t k = 0; k < n; k++) {
        const double *p = cp + k * (size_t)stride;
        for (int d = 0; d < stride; d++)
            if (!isfinite(p[d]))
                return sc_fail(err, NULL, 0, "%s control point %zu has a coordinate that is not "
                               "a finite number", what, k);
        if (!(p[stride - 1] > 0))
            return sc_fail(err, NULL, 0, "%s control point %zu has weight %.17g (must be > 0)",
                           what, k, p[stride - 1]);
    }
    return SC_OK;
}

int sc_curve_check(const sc_curve *c, sc_error *err)
{
    if (c->degree < 1)
        return sc_fail(err, NULL, 0, "curve degree %d (must be >= 1)", c->degree);
    if (c->ncp < c->degree + 1)
        return sc_fail(err, NULL, 0, "curve of degree %d needs at least %d control points, has %d",
                       c->degree, c->degree + 1, c->ncp);
    if (check_knots(c->knots, c->ncp + c->degree + 1, c->degree, "curve", err))
        return SC_FAIL;
    return check_points(c->cp, (size_t)c->ncp, c->dim + 1, "curve", err);
}

int sc_surface_check(const sc_surface *s, sc_error *err)
{
    if (s->deg_u < 1 || s->deg_v < 1)
        return sc_fail(err, NULL, 0, "surface degree %d x %d (must be >= 1)", s->deg_u, s->deg_v);
    if (s->nu < s->deg_u + 1 || s->nv < s->deg_v + 1)
        return sc_fail(err, NULL, 0, "surface of degree %d x %d needs at least %d x %d control "
                       "points, has %d x %d", s->deg_u, s->deg_v, s->deg_u + 1, s->deg_v + 1,
                       s->nu, s->nv);
    if (check_knots(s->knots_u, s->nu + s->deg_u + 1, s->deg_u, "u", err) ||
        check_knots(s->knots_v, s->nv + s->deg_v + 1, s->deg_v, "v", err))
        return SC_FAIL;
    return check_points(s->cp, (size_t)s->nu * (size_t)s->nv, 4, "surface", err);
}

void sc_xform_point(const double m[12], const double p[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3];
    memcpy(out, r, sizeof r);
}

void sc_xform_vector(const double m[12], const double v[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = m[4 * i] * v[0] + m[4 * i + 1] * v[1] + m[4 * i + 2] * v[2];
    memcpy(out, r, sizeof r);
}

void sc_xform_normal(const double m[12], const double n[3], double out[3])
{
    /* The cofactor matrix is the inverse transpose times the determinant;
     * the determinant's sign is kept so orientation flips with mirroring. */
    double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
           k = m[10];
    double cof[9] = {e * k - f * h, f * g - d * k, d * h - e * g,
                     c * h - b * k, a * k - c * g, b * g - a * h,
                     b * f - c * e, c * d - a * f, a * e - b * d};
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = cof[3 * i] * n[0] + cof[3 * i + 1] * n[1] + cof[3 * i + 2] * n[2];
    double len = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    for (int i = 0; i < 3; i++)
        out[i] = len > 0 ? r[i] / len : 0;
}

void sc_surface_bake_xform(sc_surface *s)
{
    size_t n = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < n; k++) {
        double *p = s->cp + 4 * k, w = p[3], e[3] = {p[0] / w, p[1] / w, p[2] / w};
        sc_xform_point(s->xform, e, e);
        for (int d = 0; d < 3; d++)
            p[d] = e[d] * w;
    }
    memcpy(s->xform, identity, sizeof identity);
}

void sc_surface_bounds(const sc_surface *s, double lo[3], double hi[3])
{
    for (int d = 0; d < 3; d++) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
    }
    size_t n = (size_t)s->nu * (size_t)s->nv;
    for (size_t k = 0; k < n; k++) {
        const double *p = s->cp + 4 * k;
        double e[3] = {p[0] / p[3], p[1] / p[3], p[2] / p[3]};
        sc_xform_point(s->xform, e, e);
        for (int d = 0; d < 3; d++) {
            if (e[d] < lo[d]) lo[d] = e[d];
            if (e[d] > hi[d]) hi[d] = e[d];
        }
    }
}

int sc_scene_bounds(const sc_scene *scene, double lo[3], double hi[3])
{
    if (scene->nsurfaces == 0) {
        for (int d = 0; d < 3; d++)
            lo[d] = hi[d] = 0;
        return 0;
    }
    sc_surface_bounds(&scene->surfaces[0], lo, hi);
    for (int i = 1; i < scene->nsurfaces; i++) {
        double l[3], h[3];
        sc_surface_bounds(&scene->surfaces[i], l, h);
        for (int d = 0; d < 3; d++) {
            if (l[d] < lo[d]) lo[d] = l[d];
            if (h[d] > hi[d]) hi[d] = h[d];
        }
    }
    return 1;
}
