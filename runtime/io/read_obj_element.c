/* read_obj_element.c — the OBJ reader's element assembly: a finished
 * `curv2` or `surf` (read_obj.c collects its statements) checked and turned
 * into the scene model's clamped form: knot vectors from `parm`, homogeneous
 * control points from the vertices, the surf range cut out, and trim and
 * hole loops built from pieces of the defined curves. */
#include "read_obj.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs.h"

/* The knot vector of one direction of the element, checked, into a new
 * array; *ncp receives the number of control points it implies. */
static int element_knots(obj_reader *r, int dir, double **knots, int *ncp)
{
    obj_element *el = &r->el;
    const char *elname = el->kind == EL_SURF ? "surf" : "curv2";
    int p = el->deg[dir], np = el->nparm[dir], line = el->parm_line[dir];
    const double *parm = el->parm[dir];
    char d = "uv"[dir];
    *knots = NULL;
    if (!parm)
        return fail(r, el->line, "%s has no parm %c statement before its end", elname, d);
    if (el->cstype == CS_BSPLINE) {
        if (np < 2 * (p + 1))
            return fail(r, line, "parm %c has %d knots; degree %d needs at least %d", d, np, p,
                        2 * (p + 1));
        for (int i = 1; i < np; i++)
            if (parm[i] < parm[i - 1])
                return fail(r, line, "parm %c knots decrease at position %d (%.17g after %.17g)",
                            d, i + 1, parm[i], parm[i - 1]);
        for (int i = 0; i < np;) {
            int m = 1;
            while (i + m < np && parm[i + m] == parm[i])
                m++;
            if (m > p + 1)
                return fail(r, line, "parm %c: knot %.17g repeats %d times; degree %d allows at "
                            "most %d", d, parm[i], m, p, p + 1);
            i += m;
        }
        *ncp = np - p - 1;
        if (!(parm[p] < parm[*ncp]))
            return fail(r, line, "parm %c: the knots give an empty parameter range", d);
        if (!(*knots = sc_try_alloc((size_t)np, sizeof(double))))
            return sc_fail_oom(r->err, r->name, line, (size_t)np, sizeof(double), "knots");
        memcpy(*knots, parm, sizeof(double) * (size_t)np);
        return SC_OK;
    }
    /* Bézier: break points of the segments, which share their end points. */
    for (int i = 1; i < np; i++)
        if (!(parm[i] > parm[i - 1]))
            return fail(r, line, "parm %c values must increase (position %d: %.17g after %.17g)",
                        d, i + 1, parm[i], parm[i - 1]);
    int segments = np - 1;
    if ((size_t)segments * (size_t)p + 1 > (size_t)r->el.nidx)
        return fail(r, line, "parm %c gives %d Bezier segments of degree %d: more than the %d "
                    "control points can hold", d, segments, p, r->el.nidx);
    *ncp = segments * p + 1;
    double *k = sc_try_alloc((size_t)(*ncp + p + 1), sizeof(double));
    if (!k)
        return sc_fail_oom(r->err, r->name, line, (size_t)(*ncp + p + 1), sizeof(double), "knots");
    int n = 0;
    for (int i = 0; i <= p; i++)
        k[n++] = parm[0];
    for (int sgm = 1; sgm < segments; sgm++)
        for (int i = 0; i < p; i++)
            k[n++] = parm[sgm];
    for (int i = 0; i <= p; i++)
        k[n++] = parm[segments];
    *knots = k;
    return SC_OK;
}

/* Homogeneous control point from a vertex; weights only count for `rat`. */
static int vertex_point(obj_reader *r, const obj_vertex *v, int index, int dim, double *out)
{
    double w = r->el.rational ? v->x[dim] : 1.0;
    if (!(w > 0))
        return fail(r, v->line, "control point %d of the %s at line %d has weight %.17g: weights "
                    "must be > 0", index + 1, r->el.kind == EL_SURF ? "surf" : "curv2", r->el.line,
                    w);
    for (int d = 0; d < dim; d++)
        out[d] = v->x[d] * w;
    out[dim] = w;
    return SC_OK;
}

/* Fails unless the element (a `what`) has a cstype this reader reads. */
static int check_cstype(obj_reader *r, const char *what)
{
    const obj_element *el = &r->el;
    const char *problem = el->cstype == CS_NONE ? "no cstype statement comes before it"
                          : el->cstype == CS_UNSUPPORTED
                              ? "its cstype is not supported (only bezier and bspline are)"
                              : NULL;
    if (!problem)
        return SC_OK;
    return fail(r, el->cstype_line ? el->cstype_line : el->line, "%s at line %d: %s%s%s", what,
                el->line, problem, el->cstype_name[0] ? ": " : "", el->cstype_name);
}

int sc_obj_finish_curv2(obj_reader *r)
{
    obj_element *el = &r->el;
    if (check_cstype(r, "curv2") != SC_OK)
        return SC_FAIL;
    if (el->deg[0] < 1)
        return fail(r, el->line, "curv2 has no degree (deg statement missing)");
    double *knots;
    int ncp;
    if (element_knots(r, 0, &knots, &ncp))
        return SC_FAIL;
    if (ncp != el->nidx) {
        free(knots);
        return fail(r, el->line, "curv2 has %d control points; degree %d with its parm u needs %d",
                    el->nidx, el->deg[0], ncp);
    }
    if (sc_budget_charge(&r->budget, sc_curve_bytes(2, el->deg[0], ncp), "curv2", r->name,
                         el->line, r->err)) {
        free(knots);
        return SC_FAIL;
    }
    sc_curve c;
    if (sc_curve_try_alloc(&c, 2, el->deg[0], ncp)) {
        free(knots);
        return sc_fail_oom(r->err, r->name, el->line, 1, sc_curve_bytes(2, el->deg[0], ncp),
                           "curv2");
    }
    memcpy(c.knots, knots, sizeof(double) * (size_t)(ncp + el->deg[0] + 1));
    free(knots);
    for (int i = 0; i < ncp; i++) {
        const obj_vertex *v = &r->pverts.v[el->idx[i]];
        if (v->ncoords < 2) {
            sc_curve_free(&c);
            return fail(r, el->line, "control point %d (vp at line %d) has no v coordinate: "
                        "2D curves need u and v", i + 1, v->line);
        }
        if (vertex_point(r, v, i, 2, c.cp + 3 * i)) {
            sc_curve_free(&c);
            return SC_FAIL;
        }
    }
    sc_curve clamped;
    int status = sc_curve_clamp(&c, &clamped);
    sc_curve_free(&c);
    if (status)
        return sc_fail_oom(r->err, r->name, el->line, 1, sc_alloc_failed_bytes(),
                           "clamping curv2");
    c = clamped;
    sc_error check;
    if (sc_curve_check(&c, &check)) {
        sc_curve_free(&c);
        return fail(r, el->line, "curv2: %s", check.message);
    }
    sc_curve *grown = sc_try_realloc(r->curves, (size_t)r->ncurves + 1, sizeof *r->curves);
    if (!grown) {
        sc_curve_free(&c);
        return sc_fail_oom(r->err, r->name, el->line, (size_t)r->ncurves + 1, sizeof *r->curves,
                           "the curv2 list");
    }
    r->curves = grown;
    r->curves[r->ncurves++] = c;
    return SC_OK;
}

/* The piece of a defined curve a trim statement refers to. */
static int trim_piece(obj_reader *r, const obj_loop_ref *loop, const obj_trim_ref *ref,
                      sc_curve *out)
{
    const sc_curve *c = &r->curves[ref->curve];
    double t0, t1;
    sc_curve_domain(c, &t0, &t1);
    double lo = fmin(ref->t0, ref->t1), hi = fmax(ref->t0, ref->t1);
    double tol = 1e-9 * (t1 - t0);
    if (!(hi > lo))
        return fail(r, loop->line, "%s uses curve %d over the empty range [%.17g, %.17g]",
                    loop->is_hole ? "hole" : "trim", ref->curve + 1, ref->t0, ref->t1);
    if (lo < t0 - tol || hi > t1 + tol)
        return fail(r, loop->line, "%s range [%.17g, %.17g] lies outside the parameter range "
                    "[%.17g, %.17g] of curve %d", loop->is_hole ? "hole" : "trim", ref->t0,
                    ref->t1, t0, t1, ref->curve + 1);
    /* A curve may be used by many pieces: each copy is charged. */
    if (sc_budget_charge(&r->budget, sc_curve_bytes(2, c->degree, c->ncp),
                         loop->is_hole ? "hole" : "trim", r->name, loop->line, r->err))
        return SC_FAIL;
    /* Ends within the tolerance of the domain's are the domain's. */
    if (sc_curve_try_alloc(out, c->dim, c->degree, c->ncp))
        return sc_fail_oom(r->err, r->name, loop->line, 1, sc_curve_bytes(2, c->degree, c->ncp),
                           loop->is_hole ? "hole" : "trim");
    memcpy(out->knots, c->knots, sizeof(double) * (size_t)(c->ncp + c->degree + 1));
    memcpy(out->cp, c->cp, sizeof(double) * (size_t)c->ncp * (size_t)(c->dim + 1));
    if (sc_curve_restrict(out, lo > t0 + tol ? lo : t0, hi < t1 - tol ? hi : t1)) {
        sc_curve_free(out);
        return sc_fail_oom(r->err, r->name, loop->line, 1, sc_alloc_failed_bytes(),
                           loop->is_hole ? "the piece of a hole" : "the piece of a trim");
    }
    if (ref->t0 > ref->t1)
        sc_curve_reverse(out);
    return SC_OK;
}

/* Knots with degree+1 equal ends that are the range `lim` (two values). */
static int is_clamped(const double *knots, int ncp, int p, const double *lim)
{
    for (int i = 1; i <= p; i++)
        if (knots[i] != knots[0] || knots[ncp + p - i] != knots[ncp + p])
            return 0;
    return knots[0] == lim[0] && knots[ncp + p] == lim[1];
}

int sc_obj_finish_surf(obj_reader *r)
{
    obj_element *el = &r->el;
    if (check_cstype(r, "surf") != SC_OK)
        return SC_FAIL;
    if (el->deg[0] < 1 || el->deg[1] < 1)
        return fail(r, el->line, "surf needs a degree in u and in v (deg DU DV before it)");
    double *knots[2] = {NULL, NULL};
    int n[2];
    if (element_knots(r, 0, &knots[0], &n[0]) || element_knots(r, 1, &knots[1], &n[1])) {
        free(knots[0]);
        return SC_FAIL;
    }
    if ((long long)n[0] * n[1] != el->nidx) {
        free(knots[0]);
        free(knots[1]);
        return fail(r, el->line, "surf has %d control points; degrees %d x %d with its parm u and "
                    "parm v need %d x %d = %lld", el->nidx, el->deg[0], el->deg[1], n[0], n[1],
                    (long long)n[0] * n[1]);
    }
    /* The range the surface is evaluated over: surf's s0 s1 t0 t1 within
     * the knot vectors' own range. A wider range asks for a surface the
     * knots do not define, so cutting it is worth a warning; by 1e-9 of the
     * knots' range (as for trim ranges) it is only a writer's rounding. */
    double lim[4];
    for (int dir = 0; dir < 2; dir++) {
        int p = el->deg[dir];
        double k0 = knots[dir][p], k1 = knots[dir][n[dir]];
        double a = fmax(el->range[2 * dir], k0), b = fmin(el->range[2 * dir + 1], k1);
        if (!(a < b)) {
            free(knots[0]);
            free(knots[1]);
            return fail(r, el->line, "surf %c range [%.17g, %.17g] does not overlap the knots' "
                        "range [%.17g, %.17g]", "uv"[dir], el->range[2 * dir],
                        el->range[2 * dir + 1], k0, k1);
        }
        double tol = 1e-9 * (k1 - k0);
        if (el->range[2 * dir] < k0 - tol || el->range[2 * dir + 1] > k1 + tol)
            sc_log(SC_LOG_WARN, "%s:%d: surf %c range [%.17g, %.17g] is wider than the knots' "
                   "range [%.17g, %.17g]; cut to [%.17g, %.17g]", r->name, el->line, "uv"[dir],
                   el->range[2 * dir], el->range[2 * dir + 1], k0, k1, a, b);
        lim[2 * dir] = a;
        lim[2 * dir + 1] = b;
    }
    if (sc_budget_charge(&r->budget, sc_surface_bytes(el->deg[0], el->deg[1], n[0], n[1]),
                         "surf", r->name, el->line, r->err)) {
        free(knots[0]);
        free(knots[1]);
        return SC_FAIL;
    }
    sc_surface s;
    memset(&s, 0, sizeof s);
    if (sc_surface_try_alloc(&s, el->deg[0], el->deg[1], n[0], n[1])) {
        free(knots[0]);
        free(knots[1]);
        return sc_fail_oom(r->err, r->name, el->line, 1,
                           sc_surface_bytes(el->deg[0], el->deg[1], n[0], n[1]), "surf");
    }
    memcpy(s.knots_u, knots[0], sizeof(double) * (size_t)(n[0] + el->deg[0] + 1));
    memcpy(s.knots_v, knots[1], sizeof(double) * (size_t)(n[1] + el->deg[1] + 1));
    free(knots[0]);
    free(knots[1]);
    for (int k = 0; k < el->nidx; k++)
        if (vertex_point(r, &r->verts.v[el->idx[k]], k, 3, s.cp + 4 * k)) {
            sc_surface_free(&s);
            return SC_FAIL;
        }
    static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    memcpy(s.xform, identity, sizeof identity);
    /* Most surfaces (every Bézier patch) are clamped and used whole
     * already: clamping and restricting them would copy them unchanged. */
    int as_is = is_clamped(s.knots_u, n[0], el->deg[0], lim) &&
                is_clamped(s.knots_v, n[1], el->deg[1], lim + 2);
    sc_surface clamped;
    int status = as_is ? SC_OK : sc_surface_try_clamp(&s, &clamped);
    if (!as_is) {
        sc_surface_free(&s);
        s = clamped;
    }
    if (status || (!as_is && (sc_surface_try_restrict(&s, 0, lim[0], lim[1]) ||
                              sc_surface_try_restrict(&s, 1, lim[2], lim[3])))) {
        sc_surface_free(&s);
        return sc_fail_oom(r->err, r->name, el->line, 3,
                           sc_surface_bytes(el->deg[0], el->deg[1], n[0], n[1]), "surf");
    }
    sc_surface_update_rational(&s);
    sc_error check;
    if (sc_surface_check(&s, &check)) {
        sc_surface_free(&s);
        return fail(r, el->line, "surf: %s", check.message);
    }
    if (el->nloops) {
        if (!(s.loops = sc_try_alloc((size_t)el->nloops, sizeof(sc_loop)))) {
            sc_surface_free(&s);
            return sc_fail_oom(r->err, r->name, el->line, (size_t)el->nloops, sizeof(sc_loop),
                               "trim loops");
        }
        for (int l = 0; l < el->nloops; l++) {
            const obj_loop_ref *ref = &el->loops[l];
            sc_loop *loop = &s.loops[s.nloops++];
            loop->is_hole = ref->is_hole;
            if (!(loop->curves = sc_try_alloc((size_t)ref->nrefs, sizeof(sc_curve)))) {
                sc_surface_free(&s);
                return sc_fail_oom(r->err, r->name, ref->line, (size_t)ref->nrefs,
                                   sizeof(sc_curve), "a trim loop");
            }
            for (int c = 0; c < ref->nrefs; c++) {
                if (trim_piece(r, ref, &ref->refs[c], &loop->curves[c])) {
                    sc_surface_free(&s);
                    return SC_FAIL;
                }
                loop->ncurves++;
            }
        }
    }
    sc_surface *dst = sc_scene_try_add_surface(r->scene);
    if (!dst) {
        sc_surface_free(&s);
        return sc_fail_oom(r->err, r->name, el->line, (size_t)r->scene->nsurfaces + 1,
                           sizeof(sc_surface), "the scene's surfaces");
    }
    if (r->cur_name[0])
        snprintf(s.name, sizeof s.name, "%s", r->cur_name);
    else
        snprintf(s.name, sizeof s.name, "%s", dst->name);
    memcpy(s.color, r->cur_color, sizeof s.color);
    *dst = s;
    return SC_OK;
}
