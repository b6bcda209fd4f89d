/* refcast.c — the CPU reference ray caster (refcast.h).
 *
 * Per ray, each Bézier patch the BVH lets through is moved into a frame
 * aligned with the ray: two unit vectors e1, e2 across the ray and the ray
 * direction d, origin at the eye. Then (e1·P, e2·P) is the position of a
 * point relative to the ray, and d·P its distance along it. That frame is
 * orthonormal, so this is Dammertz–Keller's object-space subdivision with
 * the box axes turned to the ray: the ray meets a box exactly when both
 * cross coordinates of the box straddle zero — sign tests, no division, no
 * slab rounding — and d·P bounds the distance. The transform is linear in
 * homogeneous coordinates, so rational patches are moved and subdivided as
 * (w·x, w·y, w·z, w) and projected only to take boxes (the convex hull
 * property holds for positive weights).
 *
 * A node is split at 0.5 (exact in floating point, so neighbouring boxes
 * always touch) along the direction whose corner-to-corner extent is
 * larger; the other direction is tried when that split does not shrink the
 * box. When neither split gives a child whose box has a smaller L1 diagonal
 * than the node's, the node is a leaf: its parameter centre is a candidate
 * hit at the box's mid distance. Nearest children go first and subtrees
 * beyond the best hit so far are cut, so a leaf trimmed away just lets the
 * search continue to the next candidate. */
#define _POSIX_C_SOURCE 200809L
#include "refcast.h"
#include "tri_trace.h"

#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bezier.h"
#include "io.h"
#include "nurbs.h"

enum {
    MAX_PATCH_DEGREE = 63,
    /* Each level halves one parameter interval: about 2 × 53 levels reach
     * double precision; deeper nodes are leaves whatever their size. */
    MAX_DEPTH = 240,
    BVH_LEAF_SIZE = 2,
    BVH_STACK = 128,
    /* A ray lying in a planar piece of surface meets every box along it;
     * nearest-first order and the distance cut normally end that at once,
     * but a run of trimmed-away leaves could go on for very long. A ray
     * that spends this many splits keeps the best hit found so far and is
     * counted in the statistics. */
    RAY_SPLIT_BUDGET = 1 << 21,
    /* Sub-patches are classified against the trim loops as a whole down
     * to this depth; below it only leaves are tested. */
    TRIM_CULL_DEPTH = 24,
};

/* Relative size of a box (to the largest coordinate of the patch in the
 * ray frame) at which subdivision stops: 2^12 ulps. */
#define NOISE_FLOOR 0x1p-40

/* Bumped whenever the reference would render a different image, so that
 * cached reference AOVs are not reused across such a change. */
#define REFCAST_VERSION "refcast-1"

typedef struct ref_patch {
    int surface;
    int deg_u, deg_v;
    int rational;
    double u0, u1, v0, v1;    /* in the surface's domain */
    double *cp;               /* world space, homogeneous, u fastest */
    double lo[3], hi[3];      /* world box of the control points, padded */
} ref_patch;

typedef struct bvh_node {
    double lo[3], hi[3];
    int left, right;          /* children, for an inner node */
    int first, count;         /* patches order[first .. first+count), for a leaf */
} bvh_node;

struct sc_refcast {
    const sc_scene *scene;
    int npatches;
    ref_patch *patches;
    int *order;               /* patch indices in BVH leaf order */
    int nnodes;
    bvh_node *nodes;
    sc_trim **trims;          /* per surface, NULL when untrimmed */
    int max_points;           /* largest (deg_u+1)(deg_v+1) */
    sc_tri_tracer *terrain;   /* a terrain scene's patches (tri_trace.h)
                                 instead of the surfaces' */
};

/* ---------------------------------------------------------------- BVH -- */

typedef struct sort_key {
    double key;
    int index;
} sort_key;

static int compare_keys(const void *pa, const void *pb)
{
    const sort_key *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return a->index - b->index; /* deterministic order for equal centres */
}

/* Top-down median split on the longest axis of the patch centres; returns
 * the node's index. */
static int bvh_build(sc_refcast *rc, int first, int count, sort_key *scratch)
{
    int index = rc->nnodes++;
    bvh_node *node = &rc->nodes[index];
    double clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 3; k++) {
        node->lo[k] = INFINITY;
        node->hi[k] = -INFINITY;
    }
    for (int i = first; i < first + count; i++) {
        const ref_patch *p = &rc->patches[rc->order[i]];
        for (int k = 0; k < 3; k++) {
            double c = 0.5 * (p->lo[k] + p->hi[k]);
            node->lo[k] = fmin(node->lo[k], p->lo[k]);
            node->hi[k] = fmax(node->hi[k], p->hi[k]);
            clo[k] = fmin(clo[k], c);
            chi[k] = fmax(chi[k], c);
        }
    }
    node->first = first;
    node->count = count;
    node->left = node->right = -1;
    if (count <= BVH_LEAF_SIZE)
        return index;
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (chi[k] - clo[k] > chi[axis] - clo[axis])
            axis = k;
    for (int i = 0; i < count; i++) {
        const ref_patch *p = &rc->patches[rc->order[first + i]];
        scratch[i].key = 0.5 * (p->lo[axis] + p->hi[axis]);
        scratch[i].index = rc->order[first + i];
    }
    qsort(scratch, (size_t)count, sizeof *scratch, compare_keys);
    for (int i = 0; i < count; i++)
        rc->order[first + i] = scratch[i].index;
    int half = count / 2;
    int left = bvh_build(rc, first, half, scratch);
    int right = bvh_build(rc, first + half, count - half, scratch);
    rc->nodes[index].left = left;
    rc->nodes[index].right = right;
    rc->nodes[index].count = 0;
    return index;
}

/* --------------------------------------------------------- preparation -- */

int sc_refcast_patch_count(const sc_refcast *rc) { return rc->npatches; }

void sc_refcast_free(sc_refcast *rc)
{
    if (!rc)
        return;
    for (int i = 0; i < rc->npatches; i++)
        free(rc->patches[i].cp);
    free(rc->patches);
    free(rc->order);
    free(rc->nodes);
    if (rc->trims)
        for (int s = 0; s < rc->scene->nsurfaces; s++)
            sc_trim_free(rc->trims[s]);
    free(rc->trims);
    if (rc->terrain)
        sc_tri_tracer_free(rc->terrain);
    free(rc->terrain);
    free(rc);
}

int sc_refcast_prepare(const sc_scene *scene, sc_refcast **out, sc_error *err)
{
    *out = NULL;
    sc_refcast *rc = sc_alloc(1, sizeof *rc);
    rc->scene = scene;
    rc->trims = sc_alloc((size_t)scene->nsurfaces + 1, sizeof(sc_trim *));
    if (scene->terrain) {
        /* Surface 0 only stands for the terrain (terrain_scene.h). */
        rc->terrain = sc_alloc(1, sizeof *rc->terrain);
        sc_tri_tracer_init(rc->terrain, scene->terrain);
        *out = rc;
        return SC_OK;
    }
    int cap = 0;
    double scene_lo[3] = {INFINITY, INFINITY, INFINITY}, scene_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    /* Messages name the scene's file when it came from one. */
    const char *file = scene->source[0] ? scene->source : NULL;
    for (int s = 0; s < scene->nsurfaces; s++) {
        const sc_surface *surf = &scene->surfaces[s];
        if (surf->deg_u > MAX_PATCH_DEGREE || surf->deg_v > MAX_PATCH_DEGREE) {
            sc_refcast_free(rc);
            return sc_fail(err, file, 0, "surface %d ('%s'): degree %dx%d is above the reference's limit %d",
                           s, surf->name, surf->deg_u, surf->deg_v, MAX_PATCH_DEGREE);
        }
        if (sc_trim_prepare(surf, &rc->trims[s], err) != SC_OK) {
            sc_refcast_free(rc);
            if (err && file && !err->file[0])
                snprintf(err->file, sizeof err->file, "%s", file);
            return SC_FAIL;
        }
        sc_bezier_patch *bez = NULL;
        int nbez = 0;
        sc_surface_to_bezier(surf, &bez, &nbez);
        for (int b = 0; b < nbez; b++) {
            if (rc->npatches == cap) {
                cap = cap ? 2 * cap : 64;
                rc->patches = sc_realloc(rc->patches, (size_t)cap, sizeof(ref_patch));
            }
            ref_patch *p = &rc->patches[rc->npatches++];
            memset(p, 0, sizeof *p);
            p->surface = s;
            p->deg_u = bez[b].deg_u;
            p->deg_v = bez[b].deg_v;
            p->rational = surf->rational;
            p->u0 = bez[b].u0;
            p->u1 = bez[b].u1;
            p->v0 = bez[b].v0;
            p->v1 = bez[b].v1;
            int npts = (p->deg_u + 1) * (p->deg_v + 1);
            if (npts > rc->max_points)
                rc->max_points = npts;
            p->cp = sc_alloc((size_t)npts * 4, sizeof(double));
            const double *x = surf->xform;
            for (int k = 0; k < 3; k++) {
                p->lo[k] = INFINITY;
                p->hi[k] = -INFINITY;
            }
            for (int i = 0; i < npts; i++) {
                const double *h = &bez[b].cp[4 * i];
                double *o = &p->cp[4 * i];
                /* The affine map on homogeneous points: A·(w·x) + b·w. */
                for (int k = 0; k < 3; k++) {
                    o[k] = x[4 * k] * h[0] + x[4 * k + 1] * h[1] + x[4 * k + 2] * h[2] + x[4 * k + 3] * h[3];
                    p->lo[k] = fmin(p->lo[k], o[k] / h[3]);
                    p->hi[k] = fmax(p->hi[k], o[k] / h[3]);
                }
                o[3] = h[3];
            }
            for (int k = 0; k < 3; k++) {
                scene_lo[k] = fmin(scene_lo[k], p->lo[k]);
                scene_hi[k] = fmax(scene_hi[k], p->hi[k]);
            }
            sc_bezier_patch_free(&bez[b]);
        }
        free(bez);
    }
    /* World boxes only steer the BVH; the exact test is the patch's own in
     * the ray frame. Padding keeps slab rounding from dropping a patch. */
    double extent = 0.0;
    for (int k = 0; k < 3; k++)
        if (rc->npatches)
            extent = fmax(extent, fmax(fabs(scene_lo[k]), fabs(scene_hi[k])));
    double pad = 1e-9 * (extent + 1.0);
    for (int i = 0; i < rc->npatches; i++)
        for (int k = 0; k < 3; k++) {
            rc->patches[i].lo[k] -= pad;
            rc->patches[i].hi[k] += pad;
        }
    rc->order = sc_alloc((size_t)rc->npatches + 1, sizeof(int));
    for (int i = 0; i < rc->npatches; i++)
        rc->order[i] = i;
    rc->nodes = sc_alloc(2 * (size_t)rc->npatches + 1, sizeof(bvh_node));
    if (rc->npatches) {
        sort_key *scratch = sc_alloc((size_t)rc->npatches, sizeof(sort_key));
        bvh_build(rc, 0, rc->npatches, scratch);
        free(scratch);
    }
    *out = rc;
    return SC_OK;
}

/* ------------------------------------------------- patch subdivision -- */

/* A sub-patch on the subdivision stack: its parameter box within the
 * Bézier patch ([0, 1]²), its box in the ray frame and the L1 length of
 * that box's diagonal. Its control points live in a parallel array. */
typedef struct sub_node {
    double s0, s1, t0, t1;
    double lo[3], hi[3];
    double size;
    int depth;
    int kept;                 /* 1: the whole parameter box survives trimming */
} sub_node;

/* Per-thread work space, sized for the scene's largest patch. */
typedef struct ray_work {
    int stride;               /* doubles per sub-patch: 4 × max_points */
    double *cp;               /* (MAX_DEPTH + 2) sub-patches */
    sub_node *nodes;
    double *split_a, *split_b;
    double *projected;        /* 3 per control point */
} ray_work;

static void work_init(ray_work *w, const sc_refcast *rc)
{
    w->stride = 4 * (rc->max_points ? rc->max_points : 1);
    w->cp = malloc(sizeof(double) * (size_t)w->stride * (MAX_DEPTH + 2));
    w->nodes = malloc(sizeof(sub_node) * (MAX_DEPTH + 2));
    w->split_a = malloc(sizeof(double) * (size_t)w->stride);
    w->split_b = malloc(sizeof(double) * (size_t)w->stride);
    w->projected = malloc(sizeof(double) * (size_t)w->stride);
    if (!w->cp || !w->nodes || !w->split_a || !w->split_b || !w->projected) {
        fprintf(stderr, "splinecast: out of memory for the reference's work space\n");
        abort();
    }
}

static void work_free(ray_work *w)
{
    free(w->cp);
    free(w->nodes);
    free(w->split_a);
    free(w->split_b);
    free(w->projected);
}

/* The ray: origin, unit direction and the two unit vectors across it. */
typedef struct ray_frame {
    double origin[3];
    double axis[3][3];        /* e1, e2, d */
    double offset[3];         /* axis[k] · origin */
} ray_frame;

static void make_frame(const double origin[3], const double dir[3], ray_frame *f)
{
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double d[3] = {dir[0] / len, dir[1] / len, dir[2] / len};
    /* e1: across the ray, built from the axis the ray is least aligned with. */
    int k = fabs(d[0]) <= fabs(d[1]) && fabs(d[0]) <= fabs(d[2]) ? 0 : fabs(d[1]) <= fabs(d[2]) ? 1 : 2;
    double a[3] = {0, 0, 0};
    a[k] = 1.0;
    double e1[3] = {d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2], d[0] * a[1] - d[1] * a[0]};
    double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int i = 0; i < 3; i++)
        e1[i] /= l1;
    double e2[3] = {d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2], d[0] * e1[1] - d[1] * e1[0]};
    memcpy(f->origin, origin, sizeof f->origin);
    memcpy(f->axis[0], e1, sizeof e1);
    memcpy(f->axis[1], e2, sizeof e2);
    memcpy(f->axis[2], d, sizeof d);
    for (int i = 0; i < 3; i++)
        f->offset[i] = f->axis[i][0] * origin[0] + f->axis[i][1] * origin[1] + f->axis[i][2] * origin[2];
}

/* Box of the (projected) control points in the ray frame; returns the L1
 * length of its diagonal. Plain comparisons rather than fmin/fmax: this is
 * the innermost loop, and the values are never NaN. */
static double sub_box(const double *cp, int npts, int rational, double lo[3], double hi[3])
{
    double lx = INFINITY, ly = INFINITY, lz = INFINITY, hx = -INFINITY, hy = -INFINITY, hz = -INFINITY;
    for (int i = 0; i < npts; i++) {
        const double *h = &cp[4 * i];
        double x = h[0], y = h[1], z = h[2];
        if (rational) {
            double inv = 1.0 / h[3];
            x *= inv;
            y *= inv;
            z *= inv;
        }
        lx = x < lx ? x : lx;
        hx = x > hx ? x : hx;
        ly = y < ly ? y : ly;
        hy = y > hy ? y : hy;
        lz = z < lz ? z : lz;
        hz = z > hz ? z : hz;
    }
    lo[0] = lx, lo[1] = ly, lo[2] = lz;
    hi[0] = hx, hi[1] = hy, hi[2] = hz;
    return (hx - lx) + (hy - ly) + (hz - lz);
}

/* Lengths of the control polygon along u and along v, summed over all
 * lines (max norm per leg, projected points). Corners alone would not do:
 * a patch closed in one direction (a full circle in one Bézier span) has
 * coinciding corners there, and would then be split the other way only. */
static void polygon_lengths(const double *cp, int nu, int nv, int rational, double *projected,
                            double *len_u, double *len_v)
{
    int npts = nu * nv;
    for (int i = 0; i < npts; i++) {
        double inv = rational ? 1.0 / cp[4 * i + 3] : 1.0;
        for (int k = 0; k < 3; k++)
            projected[3 * i + k] = cp[4 * i + k] * inv;
    }
    double lu = 0.0, lv = 0.0;
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            const double *p = &projected[3 * (j * nu + i)];
            double du = 0.0, dv = 0.0;
            for (int k = 0; k < 3; k++) {
                if (i + 1 < nu) {
                    double d = fabs(p[3 + k] - p[k]);
                    du = d > du ? d : du;
                }
                if (j + 1 < nv) {
                    double d = fabs(p[3 * nu + k] - p[k]);
                    dv = d > dv ? d : dv;
                }
            }
            lu += du;
            lv += dv;
        }
    *len_u = lu;
    *len_v = lv;
}

/* The best candidate along one ray. */
typedef struct ray_best {
    double t;
    int surface;
    double u, v;
    long subdivisions;
    int over_budget;
} ray_best;

static int box_meets_ray(const double lo[3], const double hi[3], double t_max)
{
    return lo[0] <= 0.0 && hi[0] >= 0.0 && lo[1] <= 0.0 && hi[1] >= 0.0 && hi[2] >= 0.0 &&
           lo[2] <= t_max;
}

static void intersect_patch(const sc_refcast *rc, const ref_patch *p, const ray_frame *f,
                            ray_work *w, ray_best *best)
{
    int nu = p->deg_u + 1, nv = p->deg_v + 1, npts = nu * nv;
    size_t bytes = sizeof(double) * 4 * (size_t)npts;
    double *root = w->cp;
    for (int i = 0; i < npts; i++) {
        const double *h = &p->cp[4 * i];
        for (int k = 0; k < 3; k++)
            root[4 * i + k] = f->axis[k][0] * h[0] + f->axis[k][1] * h[1] + f->axis[k][2] * h[2] -
                              f->offset[k] * h[3];
        root[4 * i + 3] = h[3];
    }
    sub_node *top = &w->nodes[0];
    top->s0 = top->t0 = 0.0;
    top->s1 = top->t1 = 1.0;
    top->depth = 0;
    top->kept = rc->trims[p->surface] == NULL;
    top->size = sub_box(root, npts, p->rational, top->lo, top->hi);
    if (!box_meets_ray(top->lo, top->hi, best->t))
        return;
    /* Below this L1 size a box is rounding noise of the de Casteljau
     * steps (about degree × ulp of the coordinates): its size may still
     * wobble down by an ulp, and near a trimmed-away leaf both children of
     * every such node would be searched, so stop here (~1e-12 relative). */
    double magnitude = 0.0;
    for (int k = 0; k < 3; k++)
        magnitude = fmax(magnitude, fmax(fabs(top->lo[k]), fabs(top->hi[k])));
    double noise_floor = magnitude * NOISE_FLOOR;
    int sp = 1;
    while (sp > 0) {
        if (best->subdivisions > RAY_SPLIT_BUDGET) {
            best->over_budget = 1;
            return;
        }
        sub_node node = w->nodes[sp - 1];
        double *cp = w->cp + (size_t)(sp - 1) * (size_t)w->stride;
        if (node.lo[2] > best->t) {
            sp--;
            continue;
        }
        if (!node.kept && node.depth <= TRIM_CULL_DEPTH) {
            /* Whole sub-patches trimmed away are dropped, wholly kept ones
             * need no more tests. */
            double du = p->u1 - p->u0, dv = p->v1 - p->v0;
            int state = sc_trim_classify_rect(rc->trims[p->surface], p->u0 + node.s0 * du,
                                              p->u0 + node.s1 * du, p->v0 + node.t0 * dv,
                                              p->v0 + node.t1 * dv);
            if (state == 0) {
                sp--;
                continue;
            }
            w->nodes[sp - 1].kept = node.kept = state == 1;
        }
        /* Prefer the direction whose control polygon is longer. */
        double len_u, len_v;
        polygon_lengths(cp, nu, nv, p->rational, w->projected, &len_u, &len_v);
        int first_dir = len_u >= len_v ? 0 : 1, dir = -1;
        double lo_a[3], hi_a[3], lo_b[3], hi_b[3], size_a = 0, size_b = 0;
        int splittable = node.depth < MAX_DEPTH && node.size > noise_floor;
        for (int attempt = 0; attempt < 2 && splittable; attempt++) {
            int d = attempt ? 1 - first_dir : first_dir;
            double a = d ? node.t0 : node.s0, b = d ? node.t1 : node.s1, mid = 0.5 * (a + b);
            if (!(mid > a && mid < b))
                continue;
            sc_bezier_grid_split(cp, nu - 1, nv - 1, d, 0.5, w->split_a, w->split_b);
            best->subdivisions++;
            size_a = sub_box(w->split_a, npts, p->rational, lo_a, hi_a);
            size_b = sub_box(w->split_b, npts, p->rational, lo_b, hi_b);
            if (size_a < node.size || size_b < node.size) {
                dir = d;
                break;
            }
        }
        sp--;
        if (dir < 0) {
            /* A leaf: the box no longer shrinks. */
            double t = 0.5 * (node.lo[2] + node.hi[2]);
            if (!(t > 0.0 && t < best->t))
                continue;
            double s = 0.5 * (node.s0 + node.s1), tt = 0.5 * (node.t0 + node.t1);
            double u = p->u0 + s * (p->u1 - p->u0), v = p->v0 + tt * (p->v1 - p->v0);
            if (!node.kept && !sc_trim_inside(rc->trims[p->surface], u, v))
                continue;
            best->t = t;
            best->surface = p->surface;
            best->u = u;
            best->v = v;
            continue;
        }
        sub_node child_a = node, child_b = node;
        child_a.depth = child_b.depth = node.depth + 1;
        if (dir == 0) {
            child_a.s1 = child_b.s0 = 0.5 * (node.s0 + node.s1);
        } else {
            child_a.t1 = child_b.t0 = 0.5 * (node.t0 + node.t1);
        }
        memcpy(child_a.lo, lo_a, sizeof lo_a);
        memcpy(child_a.hi, hi_a, sizeof hi_a);
        memcpy(child_b.lo, lo_b, sizeof lo_b);
        memcpy(child_b.hi, hi_b, sizeof hi_b);
        child_a.size = size_a;
        child_b.size = size_b;
        int hit_a = box_meets_ray(lo_a, hi_a, best->t), hit_b = box_meets_ray(lo_b, hi_b, best->t);
        /* Farther child first, so the nearer one is processed next. */
        int a_first = lo_a[2] > lo_b[2];
        for (int k = 0; k < 2; k++) {
            int take_a = (k == 0) == a_first;
            if (!(take_a ? hit_a : hit_b))
                continue;
            w->nodes[sp] = take_a ? child_a : child_b;
            memcpy(w->cp + (size_t)sp * (size_t)w->stride, take_a ? w->split_a : w->split_b, bytes);
            sp++;
        }
    }
}

/* ------------------------------------------------------------- rays -- */

/* A terrain's nearest hit: exact in double precision (tri_trace.c); its
 * (u, v) is the domain point, its surface 0. */
static void trace_terrain(const sc_refcast *rc, const double origin[3], const double dir[3],
                          sc_ref_hit *hit)
{
    memset(hit, 0, sizeof *hit);
    hit->surface = -1;
    double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double unit[3] = {dir[0] / len, dir[1] / len, dir[2] / len};
    sc_tri_hit h;
    if (sc_tri_tracer_trace(rc->terrain, origin, unit, 0.0, &h) != SC_OK)
        return;
    hit->surface = 0;
    hit->u = h.point[0];
    hit->v = h.point[1];
    hit->t = h.t;
    double facing = h.normal[0] * unit[0] + h.normal[1] * unit[1] + h.normal[2] * unit[2];
    for (int k = 0; k < 3; k++) {
        hit->point[k] = h.point[k];
        hit->normal[k] = facing > 0 ? -h.normal[k] : h.normal[k];
    }
}

static void trace(const sc_refcast *rc, const double origin[3], const double dir[3], ray_work *w,
                  sc_ref_hit *hit)
{
    if (rc->terrain) {
        trace_terrain(rc, origin, dir, hit);
        return;
    }
    ray_frame f;
    make_frame(origin, dir, &f);
    ray_best best = {.t = INFINITY, .surface = -1};
    const double *d = f.axis[2];
    double inv[3];
    for (int k = 0; k < 3; k++)
        inv[k] = d[k] != 0.0 ? 1.0 / d[k] : copysign(1e300, d[k]);
    /* BVH walk, nearest child first, cut by the best distance so far. */
    int stack[BVH_STACK];
    double entry[BVH_STACK];
    int sp = 0;
    if (rc->nnodes) {
        stack[sp] = 0;
        entry[sp++] = 0.0;
    }
    while (sp > 0) {
        sp--;
        if (entry[sp] > best.t)
            continue;
        const bvh_node *node = &rc->nodes[stack[sp]];
        if (node->count) {
            for (int i = node->first; i < node->first + node->count; i++)
                intersect_patch(rc, &rc->patches[rc->order[i]], &f, w, &best);
            continue;
        }
        double t_child[2];
        int hit_child[2], child[2] = {node->left, node->right};
        for (int c = 0; c < 2; c++) {
            const bvh_node *n = &rc->nodes[child[c]];
            double tmin = 0.0, tmax = best.t;
            for (int k = 0; k < 3; k++) {
                double t0 = (n->lo[k] - origin[k]) * inv[k], t1 = (n->hi[k] - origin[k]) * inv[k];
                double near_k = t0 < t1 ? t0 : t1, far_k = t0 < t1 ? t1 : t0;
                tmin = near_k > tmin ? near_k : tmin;
                tmax = far_k < tmax ? far_k : tmax;
            }
            hit_child[c] = tmin <= tmax;
            t_child[c] = tmin;
        }
        int near = t_child[1] < t_child[0] ? 1 : 0;
        for (int k = 0; k < 2; k++) {
            int c = k == 0 ? 1 - near : near;
            if (hit_child[c] && sp < BVH_STACK) {
                stack[sp] = child[c];
                entry[sp++] = t_child[c];
            }
        }
    }

    memset(hit, 0, sizeof *hit);
    hit->surface = best.surface;
    hit->subdivisions = best.subdivisions;
    hit->over_budget = best.over_budget;
    if (best.surface < 0)
        return;
    const sc_surface *s = &rc->scene->surfaces[best.surface];
    hit->u = best.u;
    hit->v = best.v;
    hit->t = best.t;
    sc_surface_eval_world(s, best.u, best.v, hit->point, NULL, NULL);
    double n_obj[3] = {0, 0, 1};
    sc_surface_normal(s, best.u, best.v, n_obj);
    sc_xform_normal(s->xform, n_obj, hit->normal);
    if (hit->normal[0] * d[0] + hit->normal[1] * d[1] + hit->normal[2] * d[2] > 0.0)
        for (int k = 0; k < 3; k++)
            hit->normal[k] = -hit->normal[k];
}

void sc_refcast_trace(const sc_refcast *rc, const double origin[3], const double dir[3],
                      sc_ref_hit *hit)
{
    ray_work w;
    work_init(&w, rc);
    trace(rc, origin, dir, &w, hit);
    work_free(&w);
}

/* ------------------------------------------------------------ images -- */

typedef struct render_job {
    const sc_refcast *rc;
    const sc_camera *cam;
    sc_aov *aov;
    atomic_int next_row;
    pthread_mutex_t lock;     /* guards rows_done, the progress calls and totals */
    int rows_done, last_tenth;
    const sc_refcast_options *opt;
    long hits, subdivisions, over_budget;
} render_job;

static void *render_rows(void *arg)
{
    render_job *job = arg;
    const sc_camera *cam = job->cam;
    sc_aov *aov = job->aov;
    ray_work w;
    work_init(&w, job->rc);
    long hits = 0, subdivisions = 0, over_budget = 0;
    for (;;) {
        int j = atomic_fetch_add(&job->next_row, 1);
        if (j >= cam->height)
            break;
        for (int i = 0; i < cam->width; i++) {
            double dir[3];
            sc_camera_ray(cam, i + 0.5, j + 0.5, dir);
            sc_ref_hit hit;
            trace(job->rc, cam->eye, dir, &w, &hit);
            subdivisions += hit.subdivisions;
            over_budget += hit.over_budget;
            size_t px = (size_t)j * (size_t)cam->width + (size_t)i;
            aov->surface[px] = hit.surface;
            if (hit.surface < 0)
                continue;
            hits++;
            aov->uv[2 * px] = (float)hit.u;
            aov->uv[2 * px + 1] = (float)hit.v;
            aov->t[px] = (float)hit.t;
            for (int k = 0; k < 3; k++) {
                aov->point[3 * px + k] = (float)hit.point[k];
                aov->normal[3 * px + k] = (float)hit.normal[k];
            }
        }
        pthread_mutex_lock(&job->lock);
        job->rows_done++;
        int tenth = job->rows_done * 10 / cam->height;
        if (job->opt && job->opt->progress && tenth > job->last_tenth) {
            job->last_tenth = tenth;
            job->opt->progress((double)job->rows_done / cam->height, job->opt->progress_user);
        }
        pthread_mutex_unlock(&job->lock);
    }
    pthread_mutex_lock(&job->lock);
    job->hits += hits;
    job->subdivisions += subdivisions;
    job->over_budget += over_budget;
    pthread_mutex_unlock(&job->lock);
    work_free(&w);
    return NULL;
}

int sc_refcast_render(const sc_refcast *rc, const sc_camera *cam, const sc_refcast_options *opt,
                      sc_aov *aov, sc_refcast_stats *stats, sc_error *err)
{
    if (cam->width <= 0 || cam->height <= 0)
        return sc_fail(err, NULL, 0, "image size %dx%d is empty", cam->width, cam->height);
    int threads = opt && opt->threads > 0 ? opt->threads : (int)sysconf(_SC_NPROCESSORS_ONLN);
    if (threads < 1)
        threads = 1;
    if (threads > 256)
        threads = 256;
    if (threads > cam->height)
        threads = cam->height;
    sc_aov_alloc(aov, cam, 0);
    render_job job = {.rc = rc, .cam = cam, .aov = aov, .opt = opt};
    atomic_init(&job.next_row, 0);
    pthread_mutex_init(&job.lock, NULL);
    double t0 = sc_now();
    pthread_t ids[256];
    int started = 0;
    for (; started < threads - 1; started++)
        if (pthread_create(&ids[started], NULL, render_rows, &job) != 0)
            break; /* fewer threads: the rows are shared out dynamically anyway */
    render_rows(&job);
    for (int k = 0; k < started; k++)
        pthread_join(ids[k], NULL);
    pthread_mutex_destroy(&job.lock);
    if (stats) {
        stats->seconds = sc_now() - t0;
        stats->rays = (long)cam->width * cam->height;
        stats->hits = job.hits;
        stats->subdivisions = job.subdivisions;
        stats->over_budget = job.over_budget;
        stats->threads = started + 1;
    }
    return SC_OK;
}

/* ------------------------------------------------------------- cache -- */

static uint64_t fnv1a(uint64_t h, const void *data, size_t size)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < size; i++) {
        h ^= p[i];
        h *= 1099511628211ULL;
    }
    return h;
}

int sc_refcast_cached(const char *scene_path, const sc_camera *cam, const char *cache_dir,
                      sc_aov *aov, sc_error *err)
{
    uint64_t h = fnv1a(14695981039346656037ULL, REFCAST_VERSION, sizeof REFCAST_VERSION);
    if (!strcmp(scene_path, "teapot")) {
        const sc_embedded_file *file = sc_embedded_find(sc_embedded_scenes, "teapot32.bpt");
        if (file)
            h = fnv1a(h, file->data, file->size);
    } else {
        char *data;
        size_t size;
        if (sc_read_file(scene_path, &data, &size, err) != SC_OK)
            return SC_FAIL;
        h = fnv1a(h, data, size);
        free(data);
    }
    char cam_text[512], path[1024];
    sc_camera_format(cam, cam_text, sizeof cam_text);
    h = fnv1a(h, cam_text, strlen(cam_text));
    int size[2] = {cam->width, cam->height};
    h = fnv1a(h, size, sizeof size);
    snprintf(path, sizeof path, "%s/ref-%016llx.aov", cache_dir, (unsigned long long)h);

    sc_error ignored;
    if (sc_aov_read(path, aov, &ignored) == SC_OK) {
        if (aov->width == cam->width && aov->height == cam->height &&
            !memcmp(aov->camera.eye, cam->eye, sizeof cam->eye) &&
            !memcmp(aov->camera.target, cam->target, sizeof cam->target) &&
            aov->camera.fovy_deg == cam->fovy_deg)
            return SC_OK;
        sc_aov_free(aov);
    }
    sc_scene scene;
    sc_scene_init(&scene);
    if (sc_read_scene(scene_path, &scene, err) != SC_OK)
        return SC_FAIL;
    sc_refcast *rc;
    int status = sc_refcast_prepare(&scene, &rc, err);
    if (status == SC_OK) {
        status = sc_refcast_render(rc, cam, NULL, aov, NULL, err);
        sc_refcast_free(rc);
    }
    sc_scene_free(&scene);
    if (status != SC_OK)
        return SC_FAIL;
    mkdir(cache_dir, 0777); /* may exist already; the write below reports real trouble */
    if (sc_aov_write(path, aov, err) != SC_OK) {
        sc_aov_free(aov);
        return SC_FAIL;
    }
    return SC_OK;
}
