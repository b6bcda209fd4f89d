/* read_iges.c — reader for IGES 5.x fixed-format (80-column) files: the
 * trimmed surfaces of CAD models (144 trimmed surfaces, 143 bounded
 * surfaces, 510 B-rep faces, 308/408 subfigure instances, and every surface
 * that nothing references), with their trim loops in parameter space. This
 * file is the top of the reader: the loops, the faces, the subfigure
 * instances and the whole file; parameters are read in iges_params.c,
 * records and sections in iges_sections.c, curves in iges_curves.c,
 * surfaces in iges_surfaces.c, the model-space curves of a loop in
 * iges_faces.c, and loops given only in model space are projected with
 * runtime/model/project.c.
 *
 * Real files are sloppy where it costs nothing to forgive (no line breaks,
 * CRLF, wrong sequence numbers and status flags, a global section without a
 * terminator), so the record layer and the global section are read
 * leniently. Entity data is read strictly: a count larger than the data, a
 * pointer outside the directory or a reference cycle fails the file with a
 * message naming the entity, because reading on would mean interpreting
 * someone else's numbers. Allocations are bounded by the data and by envelope.h.
 * Entities are parsed on demand from the surfaces down. */
#include "analytic.h"
#include "iges_local.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------ */
/* Trim loops: 142 (under 144), 141 (under 143), 508 (under 510)        */
/* ------------------------------------------------------------------ */

static int expect_type(reader *r, const params *p, int i, int target, int type)
{
    if (r->ent[target].type != type)
        return iges_fail(r, p->entity, iges_line(r, p, i), "parameter %d points to entity %d "
                           "(D %d), expected a %d", i, r->ent[target].type, 2 * target + 1, type);
    return SC_OK;
}

static int loop_of_142(reader *r, int e, curve_list *out)
{
    params p;
    int sptr, bptr = -1, status = iges_params(r, e, &p);
    if (status == SC_OK)
        status = iges_need(r, &p, 5);
    /* SPTR is not followed (the owner names the surface), but a used
     * entity is checked whole. */
    if (status == SC_OK)
        status = iges_pointer(r, &p, 2, &sptr);
    if (status == SC_OK)
        status = iges_pointer(r, &p, 3, &bptr);
    if (status)
        return SC_FAIL;
    if (bptr < 0)
        return LOOP_NO_PCURVE;
    return iges_trim_curves(r, bptr, iges_identity, 0, out, 0);
}

/* Appends the parameter-space curves of one boundary edge (141 or 508):
 * `count` pointers from parameter `first` on, `stride` apart, reversed as
 * a whole when the edge runs against the loop. */
static int edge_curves(reader *r, const params *p, int first, int count, int stride,
                       int reversed, curve_list *out)
{
    int start = out->n;
    for (int k = 0; k < count; k++) {
        int c;
        if (iges_pointer(r, p, first + k * stride, &c))
            return SC_FAIL;
        if (c < 0)
            return LOOP_NO_PCURVE;
        int status = iges_trim_curves(r, c, iges_identity, 0, out, 0);
        if (status)
            return status;
    }
    if (reversed)
        iges_reverse_chain(out, start);
    return SC_OK;
}

/* 141: TYPE, PREF, SPTR, N, then per model-space curve CRVPT, SENSE
 * (2 = reversed), K and K parameter-space curves. */
static int loop_of_141_params(reader *r, const params *p, curve_list *out)
{
    int sptr, n, at = 5, missing = 0;
    if (iges_need(r, p, 4) || iges_pointer(r, p, 3, &sptr) || iges_count(r, p, 4, 3, &n))
        return SC_FAIL;
    for (int i = 0; i < n; i++) {
        int sense, k;
        if (iges_need(r, p, at + 2) || iges_int(r, p, at + 1, &sense) ||
            iges_count(r, p, at + 2, 1, &k))
            return SC_FAIL;
        if (k == 0)
            missing = 1;
        else if (!missing) {
            int status = edge_curves(r, p, at + 3, k, 1, sense == 2, out);
            if (status)
                return status;
        }
        at += 3 + k;
    }
    return missing ? LOOP_NO_PCURVE : SC_OK;
}

/* 508: N, then per edge TYPE (0 edge, 1 vertex), EDGE, NDX, OF (1 = the
 * edge runs along the loop), K and K pairs (ISOP, CURV). A vertex "edge"
 * (a pole) without parameter-space curves adds nothing. */
static int loop_of_508_params(reader *r, const params *p, curve_list *out)
{
    int n, at = 2, missing = 0;
    if (iges_need(r, p, 1) || iges_count(r, p, 1, 5, &n))
        return SC_FAIL;
    for (int i = 0; i < n; i++) {
        int type, orient, k;
        if (iges_need(r, p, at + 4) || iges_int(r, p, at, &type) ||
            iges_int(r, p, at + 3, &orient) || iges_count(r, p, at + 4, 2, &k))
            return SC_FAIL;
        if (k == 0 && type == 0)
            missing = 1;
        else if (k > 0 && !missing) {
            int status = edge_curves(r, p, at + 6, k, 2, orient == 0, out);
            if (status)
                return status;
        }
        at += 5 + 2 * k;
    }
    return missing ? LOOP_NO_PCURVE : SC_OK;
}

static int loop_of(reader *r, int e, curve_list *out)
{
    if (r->ent[e].type == 142)
        return loop_of_142(r, e, out);
    params p;
    if (iges_params(r, e, &p))
        return SC_FAIL;
    int status = r->ent[e].type == 141 ? loop_of_141_params(r, &p, out)
                                       : loop_of_508_params(r, &p, out);
    return status;
}

/* Moves the curves of l into a new loop of the surface (l left empty);
 * SC_FAIL (l kept) when the loop array cannot grow. */
static int add_loop(reader *r, int e, sc_surface *s, int is_hole, curve_list *l)
{
    sc_loop *grown = sc_try_realloc(s->loops, (size_t)s->nloops + 1, sizeof(sc_loop));
    if (!grown)
        return iges_fail_oom(r, e, ((size_t)s->nloops + 1) * sizeof(sc_loop),
                             "the surface's loops");
    s->loops = grown;
    s->loops[s->nloops++] = (sc_loop){is_hole, l->n, l->items};
    memset(l, 0, sizeof *l);
    return SC_OK;
}

/* The domain rectangle as an outer loop: a surface whose outer boundary is
 * its domain but which has holes keeps its parity test simple. */
static int add_domain_loop(reader *r, int e, sc_surface *s)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    double corner[5][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}, {u0, v0}};
    curve_list l = {0};
    for (int i = 0; i < 4; i++) {
        sc_curve *c = iges_list_push(&l);
        if (!c || sc_curve_try_alloc(c, 2, 1, 2)) {
            iges_list_free(&l);
            return iges_fail_oom(r, e, sc_alloc_failed_bytes(), "the domain's loop");
        }
        c->knots[0] = c->knots[1] = 0;
        c->knots[2] = c->knots[3] = 1;
        for (int k = 0; k < 2; k++) {
            c->cp[3 * k + 0] = corner[i + k][0];
            c->cp[3 * k + 1] = corner[i + k][1];
            c->cp[3 * k + 2] = 1;
        }
    }
    if (add_loop(r, e, s, 0, &l)) {
        iges_list_free(&l);
        return SC_FAIL;
    }
    /* The outer loop goes first. */
    sc_loop outer = s->loops[s->nloops - 1];
    memmove(s->loops + 1, s->loops, sizeof(sc_loop) * (size_t)(s->nloops - 1));
    s->loops[0] = outer;
    return SC_OK;
}

static void curve_end(const sc_curve *c, int last, double p[2])
{
    const double *q = c->cp + 3 * (size_t)(last ? c->ncp - 1 : 0);
    p[0] = q[0] / q[2];
    p[1] = q[1] / q[2];
}

/* The widest gap between consecutive curves of a loop (the last and the
 * first included), relative to the surface's domain. */
static double largest_gap(const sc_surface *s, const curve_list *l)
{
    double u0, u1, v0, v1, worst = 0;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    for (int i = 0; i < l->n; i++) {
        double a[2], b[2];
        curve_end(&l->items[i], 1, a);
        curve_end(&l->items[(i + 1) % l->n], 0, b);
        worst = fmax(worst, hypot(a[0] - b[0], a[1] - b[1]));
    }
    return worst / fmax(u1 - u0, v1 - v0);
}

/* Builds the parameter-space loop whose entity is `e` (142, 141 or 508)
 * and attaches it to the surface (*added set), or says why it cannot be
 * (LOOP_NO_PCURVE, LOOP_UNSUPPORTED). */
static int attach_pcurves(reader *r, int e, int is_hole, sc_surface *s, int *added)
{
    curve_list l = {0};
    *added = 0;
    int status = loop_of(r, e, &l);
    if (status == SC_OK) {
        iges_orient_chain(&l);
        for (int i = 0; i < l.n; i++) {
            sc_error check;
            if (sc_curve_check(&l.items[i], &check)) {
                iges_list_free(&l);
                return iges_fail(r, e, 0, "trim curve %d: %s", i + 1, check.message);
            }
        }
        /* A parameter-space loop that does not close (Open CASCADE writes
         * such loops on periodic B-spline surfaces) would be dropped by
         * validation: the model-space curves, when there are any, are
         * projected instead. */
        if (l.n > 0 && largest_gap(s, &l) > 1e-3) {
            iges_list_free(&l);
            return LOOP_NO_PCURVE;
        }
        if (l.n > 0) {
            if (add_loop(r, e, s, is_hole, &l)) {
                iges_list_free(&l);
                return SC_FAIL;
            }
            *added = 1;
        }
    }
    iges_list_free(&l);
    return status;
}

/* Counts and reports (once per file and kind) a loop that could not be
 * built. */
static void report_loop(reader *r, int owner, int e, int is_hole, int status)
{
    const char *fate = is_hole ? "the hole is dropped" : "the surface is kept untrimmed";
    char type[32];
    if (status == LOOP_NO_PCURVE) {
        snprintf(type, sizeof type, "iges-%d", r->ent[e].type);
        sc_scene_skip(r->scene, type, "no-curve", 1);
        if (!r->warned_no_pcurve++)
            sc_log(SC_LOG_WARN, "%s:%d: entity %d (D %d) of surface D %d: a trim loop has "
                   "neither parameter-space curves nor model-space curves this reader can use; "
                   "%s (further cases are counted in `skipped`, not reported)", r->name,
                   r->ent[e].line, r->ent[e].type, 2 * e + 1, 2 * owner + 1, fate);
    } else if (status == LOOP_OFF_SURFACE) {
        snprintf(type, sizeof type, "iges-%d", r->ent[e].type);
        sc_scene_skip(r->scene, type, "off-surface", 1);
        if (!r->warned_off_surface++)
            sc_log(SC_LOG_WARN, "%s:%d: entity %d (D %d) of surface D %d: the model-space "
                   "curves of a trim loop do not lie on the surface (they stray more than "
                   "1e-3 of its size from it); %s (further cases are counted in "
                   "`skipped`, not reported)", r->name, r->ent[e].line, r->ent[e].type,
                   2 * e + 1, 2 * owner + 1, fate);
    } else {
        int u = r->unsupported_entity;
        snprintf(type, sizeof type, "iges-%d", r->ent[u].type);
        sc_scene_skip(r->scene, type, "unsupported-trim-curve", 1);
        if (!r->warned_unsupported++)
            sc_log(SC_LOG_WARN, "%s:%d: entity %d (D %d): trim curve of unsupported type %d; %s "
                   "(further cases are counted in `skipped`, not reported)", r->name,
                   r->ent[u].line, r->ent[u].type, 2 * u + 1, r->ent[u].type, fate);
    }
}

/* ------------------------------------------------------------------ */
/* Surfaces                                                             */
/* ------------------------------------------------------------------ */

/* Transformation, colour and name of a surface from its owner (the 144,
 * 143 or 510; the 128 itself for a free surface) and its 128, then into
 * the scene. */
static int finish_surface(reader *r, int owner, int base, sc_surface *s)
{
    double own[12], outer[12];
    if (iges_xform(r, base, own))
        return SC_FAIL;
    if (owner != base) {
        if (iges_xform(r, owner, outer))
            return SC_FAIL;
        iges_compose(outer, own, own);
    }
    /* inside subfigure instances: their placement last */
    iges_compose(r->instance, own, s->xform);
    float rgb[3];
    int has = iges_color(r, owner, rgb);
    if (has == 0 && owner != base)
        has = iges_color(r, base, rgb);
    if (has < 0)
        return SC_FAIL;
    if (has)
        memcpy(s->color, rgb, sizeof rgb);
    int named = r->ent[owner].label[0] ? owner : r->ent[base].label[0] ? base : -1;
    if (named < 0)
        snprintf(s->name, sizeof s->name, "iges%d", 2 * owner + 1);
    else if (r->ent[named].subscript)
        snprintf(s->name, sizeof s->name, "%s.%d", r->ent[named].label, r->ent[named].subscript);
    else
        snprintf(s->name, sizeof s->name, "%s", r->ent[named].label);
    sc_surface *dst = sc_scene_try_add_surface(r->scene);
    if (!dst)
        return iges_fail_oom(r, owner, ((size_t)r->scene->nsurfaces + 1) * sizeof(sc_surface),
                             "the scene's surfaces");
    float default_color[3];
    memcpy(default_color, dst->color, sizeof default_color);
    *dst = *s;
    if (!has) /* colour 0 in field 13: none assigned, so the scene's default */
        memcpy(dst->color, default_color, sizeof default_color);
    memset(s, 0, sizeof *s);
    return SC_OK;
}

/* The surface a trimmed surface stands on (its type is checked when it is
 * read). */
static int base_surface(reader *r, const params *p, int i, int *base)
{
    if (iges_pointer(r, p, i, base))
        return SC_FAIL;
    if (*base < 0)
        return iges_fail(r, p->entity, iges_line(r, p, i), "its surface pointer (parameter "
                           "%d) is null", i);
    return 1;
}

/* Relative to the surface's size: how far a projected loop may stray from
 * its 3D curves (a pixel of a whole-part view is about 1e-3), and how far
 * 3D curves may lie from their surface before the loop is refused (CAD
 * systems approximate intersection edges to about 1e-4). */
#define PROJECT_TOL 1e-6
#define PROJECT_OFF_LIMIT 1e-3

/* The diagonal of the control points' box, in object space. */
static double surface_size(const sc_surface *s)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < (size_t)s->nu * s->nv; k++)
        for (int d = 0; d < 3; d++) {
            double x = s->cp[4 * k + d] / s->cp[4 * k + 3];
            lo[d] = fmin(lo[d], x);
            hi[d] = fmax(hi[d], x);
        }
    return sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/* A loop given in model space into the surface's parameter space: exactly
 * onto a plane, projected onto anything else. */
static int attach_model(reader *r, const iges_surface *sf, sc_surface *s, int is_hole,
                        curve_list *l3)
{
    curve_list l = {0};
    double dev = 0;
    if (sf->need_bounds == IGES_BOUND_PLANE) {
        if (iges_plane_curves(sf, l3, &l)) {
            iges_list_free(&l);
            return iges_fail_oom(r, r->cur_owner, sc_alloc_failed_bytes(),
                                 "a trim loop mapped onto its plane");
        }
    } else {
        sc_curve *out;
        int nout;
        double size = surface_size(s);
        int status = sc_project_loop(s, l3->items, l3->n, PROJECT_TOL * size,
                                     PROJECT_OFF_LIMIT * size, &out, &nout, &dev);
        if (status == SC_FAIL)
            return iges_fail_oom(r, r->cur_owner, sc_alloc_failed_bytes(),
                                 "projecting a trim loop");
        if (status != SC_OK)
            return LOOP_OFF_SURFACE;
        l.items = out;
        l.n = l.cap = nout;
    }
    if (iges_charge_curves(r, r->cur_owner, &l, 0) || add_loop(r, r->cur_owner, s, is_hole, &l)) {
        iges_list_free(&l);
        return SC_FAIL;
    }
    r->scene->projected_loops++;
    r->scene->projection_dev = fmax(r->scene->projection_dev, dev);
    return SC_OK;
}

/* Loops of one trimmed surface: `loops` entities, the first of which is the
 * outer boundary when has_outer. Parameter-space curves are used on a 128
 * (whose parameters they are written in); model-space curves otherwise, and
 * where a 128's loop has none. Without a usable outer loop the domain is
 * the outer boundary. */
static int build_trimmed(reader *r, int owner, int base, const int *loops, int nloops,
                         int has_outer)
{
    /* Loop entities may be listed many times: each costs its curves. */
    if (sc_budget_charge(&r->budget, (size_t)nloops * sizeof(sc_loop), "trimmed surface",
                         r->name, r->ent[owner].line, r->err))
        return SC_FAIL;
    iges_surface sf;
    int kind = iges_read_surface(r, base, &sf);
    if (kind <= 0) {
        sc_surface_free(&sf.nurbs);
        if (kind < 0)
            return SC_FAIL;
        char type[32];
        snprintf(type, sizeof type, "iges-%d", r->ent[owner].type);
        sc_scene_skip(r->scene, type, "unsupported-surface", 1);
        return SC_OK;
    }
    double own[12], to_obj[12];
    if (iges_xform(r, base, own) || (iges_invert(own, to_obj) &&
                                     iges_fail(r, base, 0, "singular transformation matrix"))) {
        sc_surface_free(&sf.nurbs);
        return SC_FAIL;
    }
    r->cur_owner = owner;
    curve_list *model = sc_try_alloc((size_t)nloops + 1, sizeof(curve_list));
    if (!model) {
        sc_surface_free(&sf.nurbs);
        return iges_fail_oom(r, owner, ((size_t)nloops + 1) * sizeof(curve_list), "its loops");
    }
    int status = SC_OK, outer_added = 0, any_model = 0;
    sc_surface *s = &sf.nurbs;
    for (int i = 0; i < nloops && status == SC_OK; i++) {
        int is_hole = !(has_outer && i == 0), added = 0;
        int loop = sf.type == 128 ? attach_pcurves(r, loops[i], is_hole, s, &added)
                                  : LOOP_NO_PCURVE;
        if (loop == LOOP_NO_PCURVE) {
            loop = iges_loop_model(r, loops[i], to_obj, &model[i]);
            any_model |= loop == SC_OK;
            if (loop != SC_OK)
                iges_list_free(&model[i]);
        }
        if (loop == SC_FAIL)
            status = SC_FAIL;
        else if (loop != SC_OK)
            report_loop(r, owner, loops[i], is_hole, loop);
        outer_added |= added && !is_hole;
    }
    int bounded = status == SC_OK && sf.need_bounds && any_model
                      ? iges_bound_surface(&sf, model, nloops) : SC_OK;
    if (bounded == SC_FAIL) {
        status = iges_fail_oom(r, base, sc_alloc_failed_bytes(), "the surface");
    } else if (status == SC_OK && sf.need_bounds && (!any_model || bounded)) {
        /* an unbounded plane, cylinder or cone without usable loops */
        char type[32];
        snprintf(type, sizeof type, "iges-%d", sf.type);
        sc_scene_skip(r->scene, type, "unbounded", 1);
        if (!r->warned_unbounded++)
            sc_log(SC_LOG_WARN, "%s:%d: entity %d (D %d): an unbounded surface without trim "
                   "curves that bound it is not drawn (further cases are counted in "
                   "`skipped`, not reported)", r->name, r->ent[base].line, sf.type, 2 * base + 1);
        for (int i = 0; i < nloops; i++)
            iges_list_free(&model[i]);
        free(model);
        sc_surface_free(s);
        return SC_OK;
    }
    for (int i = 0; i < nloops && status == SC_OK; i++) {
        if (model[i].n == 0)
            continue;
        int is_hole = !(has_outer && i == 0);
        int loop = attach_model(r, &sf, s, is_hole, &model[i]);
        if (loop == SC_FAIL)
            status = SC_FAIL;
        else if (loop != SC_OK)
            report_loop(r, owner, loops[i], is_hole, loop);
        outer_added |= loop == SC_OK && !is_hole;
    }
    for (int i = 0; i < nloops; i++)
        iges_list_free(&model[i]);
    free(model);
    if (status == SC_OK && sf.type != 128)
        status = sc_budget_charge(&r->budget, sc_surface_bytes(s->deg_u, s->deg_v, s->nu, s->nv),
                                  "surface", r->name, r->ent[base].line, r->err);
    if (status == SC_OK) {
        if (!outer_added && s->nloops > 0)
            status = add_domain_loop(r, owner, s);
        if (status == SC_OK && sc_surface_unwrap_seams(s))
            status = iges_fail_oom(r, base, sc_alloc_failed_bytes(),
                                   "the surface extended across its seam");
        if (status == SC_OK)
            status = finish_surface(r, owner, base, s);
    }
    if (status)
        sc_surface_free(s);
    return status;
}

/* Loop entity pointers from parameters first.. (stride apart) checked to
 * be of `type`. */
static int loop_pointers(reader *r, const params *p, int first, int count, int type, int *out)
{
    for (int i = 0; i < count; i++) {
        if (iges_pointer(r, p, first + i, &out[i]))
            return SC_FAIL;
        if (out[i] < 0)
            return iges_fail(r, p->entity, iges_line(r, p, first + i), "loop pointer "
                               "(parameter %d) is null", first + i);
        if (expect_type(r, p, first + i, out[i], type))
            return SC_FAIL;
    }
    return SC_OK;
}

/* 144: PTS, N1 (0: the outer boundary is the domain's), N2, PTO, PTI(N2). */
static int convert_144(reader *r, const params *p)
{
    int base, n1, n2;
    if (iges_need(r, p, 4) || iges_int(r, p, 2, &n1) || iges_count(r, p, 3, 1, &n2))
        return SC_FAIL;
    int kind = base_surface(r, p, 1, &base), outer;
    if (kind <= 0)
        return kind;
    /* A null outer pointer means the domain boundary, whatever N1 says. */
    if (n1 != 0 && iges_pointer(r, p, 4, &outer))
        return SC_FAIL;
    if (n1 != 0 && outer < 0)
        n1 = 0;
    int *loops = sc_try_alloc((size_t)n2 + 1, sizeof(int)), n = 0;
    if (!loops)
        return iges_fail_oom(r, p->entity, ((size_t)n2 + 1) * sizeof(int), "its loops");
    int status = SC_OK;
    if (n1 != 0) {
        status = loop_pointers(r, p, 4, 1, 142, loops);
        n = 1;
    }
    if (status == SC_OK)
        status = loop_pointers(r, p, 5, n2, 142, loops + n);
    if (status == SC_OK)
        status = build_trimmed(r, p->entity, base, loops, n + n2, n1 != 0);
    free(loops);
    return status;
}

/* 143: TYPE, SPTR, N, BDPT(N) — the first boundary is the outer one. */
static int convert_143(reader *r, const params *p)
{
    int base, n;
    if (iges_need(r, p, 3) || iges_count(r, p, 3, 1, &n))
        return SC_FAIL;
    int kind = base_surface(r, p, 2, &base);
    if (kind <= 0)
        return kind;
    int *loops = sc_try_alloc((size_t)n + 1, sizeof(int));
    if (!loops)
        return iges_fail_oom(r, p->entity, ((size_t)n + 1) * sizeof(int), "its boundaries");
    int status = loop_pointers(r, p, 4, n, 141, loops);
    if (status == SC_OK)
        status = build_trimmed(r, p->entity, base, loops, n, 1);
    free(loops);
    return status;
}

/* 510: SURF, N, OF (1: the first loop is the outer one), LOOP(N). */
static int convert_510(reader *r, const params *p)
{
    int base, n, outer_first;
    if (iges_need(r, p, 3) || iges_count(r, p, 2, 1, &n) || iges_int(r, p, 3, &outer_first))
        return SC_FAIL;
    int kind = base_surface(r, p, 1, &base);
    if (kind <= 0)
        return kind;
    int *loops = sc_try_alloc((size_t)n + 1, sizeof(int));
    if (!loops)
        return iges_fail_oom(r, p->entity, ((size_t)n + 1) * sizeof(int), "its loops");
    int status = loop_pointers(r, p, 4, n, 508, loops);
    if (status == SC_OK)
        status = build_trimmed(r, p->entity, base, loops, n, outer_first == 1);
    free(loops);
    return status;
}

/* Which parameter of an entity points to the surface it uses: 128s
 * referenced this way are not surfaces of their own. */
static int surface_param(int type)
{
    switch (type) {
    case 142: return 2;
    case 144: return 1;
    case 143: return 2;
    case 141: return 3;
    case 510: return 1;
    case 140: return 5;
    default: return 0;
    }
}

/* Only finds which 128s are referenced, so a broken entity here is not an
 * error: whether it matters is known only when a surface uses it, and then
 * its conversion reports it. Until then it references nothing. */
static void mark_references(reader *r)
{
    sc_error *err = r->err;
    r->err = NULL;
    for (int e = 0; e < r->nent; e++) {
        int i = surface_param(r->ent[e].type);
        if (!i)
            continue;
        params p;
        int target = -1, status = iges_params(r, e, &p);
        if (status == SC_OK)
            status = iges_need(r, &p, i);
        if (status == SC_OK)
            status = iges_pointer(r, &p, i, &target);
        if (status == SC_OK && target >= 0)
            r->ent[target].referenced = 1;
    }
    r->err = err;
}

/* Surface entities: drawn on their own when nothing uses them. */
static int is_surface_type(int type)
{
    return type == 128 || type == 108 || type == 114 || type == 118 || type == 120 ||
           type == 122 || type == 140 || (type >= 190 && type <= 198 && type % 2 == 0);
}

static int is_known_type(int type)
{
    static const int known[] = {0,   100, 102, 104, 110, 116, 123, 124, 126, 141, 142,
                                143, 144, 186, 308, 314, 502, 504, 508, 510, 514};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (known[i] == type)
            return 1;
    return 0;
}

/* One entity that may make surfaces: a face (144, 143, 510) or a
 * surface nothing else uses. */
static int convert_entity(reader *r, int e)
{
    int type = r->ent[e].type;
    if (type == 144 || type == 143 || type == 510) {
        params p;
        int status = iges_params(r, e, &p);
        if (status == SC_OK)
            status = type == 144 ? convert_144(r, &p)
                     : type == 143 ? convert_143(r, &p) : convert_510(r, &p);
        return status;
    }
    if (is_surface_type(type) && !r->ent[e].referenced)
        return build_trimmed(r, e, e, NULL, 0, 0);
    return SC_OK;
}

/* 308 subfigure definition: DEPTH, NAME, N, DE(N). Its members are drawn
 * only through 408 instances. */
static int subfigure_members(reader *r, int e, params *p, int *n)
{
    if (iges_params(r, e, p) || iges_need(r, p, 3) || iges_count(r, p, 3, 1, n))
        return SC_FAIL;
    return SC_OK;
}

static void mark_subfigures(reader *r)
{
    sc_error *err = r->err;
    r->err = NULL; /* a broken 308 marks nothing; an instance of it reports it */
    for (int e = 0; e < r->nent; e++) {
        params p;
        int n, m;
        if (r->ent[e].type != 308 || subfigure_members(r, e, &p, &n))
            continue;
        for (int i = 0; i < n; i++)
            if (iges_pointer(r, &p, 4 + i, &m) == SC_OK && m >= 0)
                r->ent[m].in_subfigure = 1;
    }
    r->err = err;
}

/* 408 singular subfigure instance: DE (the 308), X, Y, Z, S: the
 * definition scaled by S, moved by (X, Y, Z), then placed by the 408's own
 * transformation, inside the placement of any instance it is part of. */
static int instantiate(reader *r, int e, int depth)
{
    entity *en = &r->ent[e];
    if (en->busy)
        return iges_fail(r, e, 0, "reference cycle: the subfigure instance contains itself");
    if (depth > MAX_NESTING)
        return iges_fail(r, e, 0, "subfigures nested more than %d deep", MAX_NESTING);
    params p, def;
    int sub, n;
    double v[4] = {0, 0, 0, 1}, own[12], outer[12];
    if (iges_params(r, e, &p) || iges_need(r, &p, 1) || iges_pointer(r, &p, 1, &sub))
        return SC_FAIL;
    for (int i = 0; i < 4 && i + 2 <= p.ntok - 1; i++)
        if (iges_real(r, &p, i + 2, &v[i]))
            return SC_FAIL;
    if (p.ntok - 1 < 5 || v[3] == 0)
        v[3] = 1;
    if (sub < 0 || r->ent[sub].type != 308)
        return iges_fail(r, e, iges_line(r, &p, 1), "parameter 1 does not point to a 308 "
                         "subfigure definition");
    if (subfigure_members(r, sub, &def, &n) || iges_xform(r, e, own))
        return SC_FAIL;
    double place[12] = {v[3], 0, 0, v[0], 0, v[3], 0, v[1], 0, 0, v[3], v[2]};
    memcpy(outer, r->instance, sizeof outer);
    iges_compose(own, place, own);
    iges_compose(outer, own, r->instance);
    en->busy = 1;
    int status = SC_OK;
    for (int i = 0; i < n && status == SC_OK; i++) {
        int m;
        status = iges_pointer(r, &def, 4 + i, &m);
        /* Instances of instances multiply: the members visited in all are
         * bounded, whatever they hold. */
        if (status == SC_OK && ++r->instance_visits > SC_MAX_LOOP_PIECES * 16)
            status = iges_fail(r, e, 0, "subfigure instances expand to more than %d entities "
                               "(docs/limits.md)", SC_MAX_LOOP_PIECES * 16);
        if (status == SC_OK && m >= 0)
            status = r->ent[m].type == 408 ? instantiate(r, m, depth + 1)
                                           : convert_entity(r, m);
    }
    en->busy = 0;
    memcpy(r->instance, outer, sizeof outer);
    return status;
}

static int convert_all(reader *r)
{
    mark_subfigures(r);
    memcpy(r->instance, iges_identity, sizeof r->instance);
    for (int e = 0; e < r->nent; e++) {
        int type = r->ent[e].type, status = SC_OK;
        if (r->ent[e].in_subfigure)
            continue;
        if (type == 408)
            status = instantiate(r, e, 0);
        else if (!is_known_type(type) && !is_surface_type(type)) {
            char name[32];
            snprintf(name, sizeof name, "iges-%d", type);
            sc_scene_skip(r->scene, name, "unsupported", 1);
        } else
            status = convert_entity(r, e);
        if (status)
            return SC_FAIL;
    }
    return SC_OK;
}

int sc_read_iges(const char *text, size_t size, const char *name, sc_scene *scene, sc_error *err)
{
    sc_scene_init(scene);
    if (sc_check_text(text, size, name, err))
        return SC_FAIL;
    reader r = {.name = name, .scene = scene, .err = err};
    int status;
    if (size > (size_t)1 << 30)
        status = iges_fail_at(&r, 0, "file of %zu bytes: larger than this reader accepts (1 GiB)", size);
    else
        status = iges_read_records(&r, text, size);
    if (status == SC_OK)
        status = iges_read_global(&r);
    if (status == SC_OK)
        status = iges_read_directory(&r);
    if (status == SC_OK) {
        mark_references(&r);
        status = convert_all(&r);
    }
    for (int i = 0; r.parsed && i < r.sec_count[SEC_P]; i++) {
        free(r.parsed[i].p.text);
        free(r.parsed[i].p.tok);
    }
    free(r.parsed);
    free(r.rec);
    free(r.ent);
    return sc_finish_read(status, name, scene, err);
}
