/* api_pick.c — sc_pick: what lies under an image point of a renderer's
 * last frame. The GPU says which surface and roughly where: the frame's
 * AOVs hold the surface id and (u, v) of every pixel, in float, from the
 * very programs that drew what the user sees (so the pick agrees with the
 * picture, trims and occlusion included, and costs no scene-wide search).
 * That answer is then refined on the CPU in double precision by Newton's
 * method on the ray against the surface's NURBS (runtime/model), so that
 * sc_eval_surface at the returned (u, v) gives the returned point. Where
 * Newton does not settle on a kept point of that surface (a pick right on
 * a silhouette or a trim edge), the CPU reference ray caster traces the
 * ray instead: exact, slower, and still the same scene. A pixel the frame
 * did not hit is a miss, as the picture shows. The IR interpreter would
 * only repeat the GPU's float arithmetic, so it is not used. */
#include "api_private.h"
#include "gl_state.h"
#include "trim.h"

enum { NEWTON_MAX = 40 };

/* Solves the 3×3 system [a b c] x = r by Cramer's rule; 0 when singular. */
static int solve3(const double a[3], const double b[3], const double c[3], const double r[3],
                  double x[3])
{
    double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (a[1] * c[2] - a[2] * c[1]) +
                 c[0] * (a[1] * b[2] - a[2] * b[1]);
    if (!(fabs(det) > 0) || !isfinite(det))
        return 0;
    x[0] = (r[0] * (b[1] * c[2] - b[2] * c[1]) - b[0] * (r[1] * c[2] - r[2] * c[1]) +
            c[0] * (r[1] * b[2] - r[2] * b[1])) / det;
    x[1] = (a[0] * (r[1] * c[2] - r[2] * c[1]) - r[0] * (a[1] * c[2] - a[2] * c[1]) +
            c[0] * (a[1] * r[2] - a[2] * r[1])) / det;
    x[2] = (a[0] * (b[1] * r[2] - b[2] * r[1]) - b[0] * (a[1] * r[2] - a[2] * r[1]) +
            r[0] * (a[1] * b[2] - a[2] * b[1])) / det;
    return 1;
}

/* Newton on S(u, v) − (o + t·d) = 0 from the GPU's (u, v, t). Converged
 * when the step stops shrinking the residual below 1e-12 of the scene's
 * size; *iters counts the steps. */
static int refine(const sc_surface *s, const double o[3], const double d[3], double scale,
                  double *u, double *v, double *t, int *iters)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    double best = INFINITY;
    for (*iters = 0; *iters < NEWTON_MAX; (*iters)++) {
        double p[3], su[3], sv[3], r[3], nd[3] = {-d[0], -d[1], -d[2]}, x[3];
        sc_surface_eval_world(s, *u, *v, p, su, sv);
        double norm = 0;
        for (int k = 0; k < 3; k++) {
            r[k] = o[k] + *t * d[k] - p[k];
            norm += r[k] * r[k];
        }
        norm = sqrt(norm);
        if (norm <= 1e-13 * scale)
            return 1;
        if (*iters > 4 && norm >= best)
            return norm <= 1e-9 * scale;   /* rounding floor reached */
        best = fmin(best, norm);
        if (!solve3(su, sv, nd, r, x))
            return 0;
        *u = fmin(fmax(*u + x[0], u0), u1);
        *v = fmin(fmax(*v + x[1], v0), v1);
        *t += x[2];
    }
    return 0;
}

static void fill_from_surface(const sc_surface *s, int surface, double u, double v,
                              const double o[3], const double d[3], sc_pick_result *out)
{
    out->hit = 1;
    out->surface = surface;
    out->u = u;
    out->v = v;
    sc_surface_eval_world(s, u, v, out->point, NULL, NULL);
    out->t = 0;
    for (int k = 0; k < 3; k++)
        out->t += (out->point[k] - o[k]) * d[k];
    double n[3] = {0, 0, 0};
    if (sc_surface_normal(s, u, v, n) == 0)
        sc_xform_normal(s->xform, n, n);
    if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0)
        n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    memcpy(out->normal, n, sizeof n);
}

int sc_pick(sc_renderer_id renderer, double x, double y, sc_pick_result *out, sc_error *err)
{
    if (!out)
        return sc_api_invalid(err, "out", PROBLEM_NULL, NULL);
    memset(out, 0, sizeof *out);
    out->surface = -1;
    renderer_object *r = sc_api_pool_get(&sc_api_renderers, renderer.id, err);
    if (!r || sc_api_make_current(r->context, err) != SC_OK)
        return SC_FAIL;
    sc_image image = {0};
    sc_aov aov = {0};
    /* The read may draw the frame again with its AOVs: in an application's
     * context, what that changes is put back. */
    sc_gl_state saved;
    int app = sc_gl_context_is_app(r->context->gl);
    const sc_gl *gl = sc_gl_context_gl(r->context->gl);
    if (app)
        sc_gl_state_save(gl, &saved);
    int read = sc_renderer_read(r->renderer, &image, &aov, err);
    if (app)
        sc_gl_state_restore(gl, &saved);
    if (read != SC_OK) {
        sc_image_free(&image);
        sc_aov_free(&aov);
        return SC_FAIL;
    }
    sc_image_free(&image);
    int status = SC_OK;
    if (!(x >= 0 && x < aov.width && y >= 0 && y < aov.height)) {
        status = sc_api_invalid(err, "(x, y)", PROBLEM_RANGE,
                                "(%g, %g) is outside the %dx%d frame (columns and rows from "
                                "the top left, pixel centres at +0.5)", x, y, aov.width,
                                aov.height);
        sc_aov_free(&aov);
        return status;
    }
    size_t px = (size_t)(int)y * (size_t)aov.width + (size_t)(int)x;
    const sc_scene *scene = &r->scene->scene;
    double o[3], d[3], lo[3], hi[3];
    memcpy(o, aov.camera.eye, sizeof o);
    sc_camera_ray(&aov.camera, x, y, d);
    sc_scene_bounds(scene, lo, hi);
    double scale = 0;
    for (int k = 0; k < 3; k++)
        scale = fmax(scale, fmax(fabs(lo[k]), fabs(hi[k])));
    scale = fmax(scale, 1e-300);
    int surface = aov.surface[px];
    out->gpu_surface = surface;
    if (surface < 0 || surface >= scene->nsurfaces) {
        sc_aov_free(&aov);
        return SC_OK;   /* nothing drawn there: a miss, as the picture shows */
    }
    const sc_surface *s = &scene->surfaces[surface];
    double u = aov.uv[2 * px], v = aov.uv[2 * px + 1], t = aov.t[px];
    out->gpu_u = u;
    out->gpu_v = v;
    sc_trim *trim = NULL;
    int kept = 0;
    if (refine(s, o, d, scale, &u, &v, &t, &out->newton_iters) && t > 0 &&
        sc_trim_prepare(s, &trim, NULL) == SC_OK) {
        kept = sc_trim_inside(trim, u, v);
        sc_trim_free(trim);
    }
    if (kept) {
        fill_from_surface(s, surface, u, v, o, d, out);
        sc_aov_free(&aov);
        return SC_OK;
    }
    /* Newton left the surface's kept region (a pick on a silhouette or a
     * trim edge): the exact reference answers for this one ray. */
    out->by_reference = 1;
    sc_refcast *rc = NULL;
    if (sc_refcast_prepare(scene, &rc, err) != SC_OK) {
        sc_aov_free(&aov);
        return SC_FAIL;
    }
    sc_ref_hit hit;
    sc_refcast_trace(rc, o, d, &hit);
    sc_refcast_free(rc);
    if (hit.surface >= 0) {
        const sc_surface *hs = &scene->surfaces[hit.surface];
        double hu = hit.u, hv = hit.v, ht = hit.t;
        int iters = 0;
        /* Polish the reference's box-sized hit the same way. */
        if (!refine(hs, o, d, scale, &hu, &hv, &ht, &iters))
            hu = hit.u, hv = hit.v;
        fill_from_surface(hs, hit.surface, hu, hv, o, d, out);
    }
    sc_aov_free(&aov);
    return SC_OK;
}
