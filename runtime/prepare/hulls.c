/* hulls.c — sub-patches and their convex hulls (hulls.h). Hulls are built
 * from the world-space Bézier patches of each surface
 * (sc_surface_world_patches), the same ones the renderer packs into GPU
 * records; a Bézier patch is split further by de Casteljau (bezier.h),
 * which is knot insertion to full multiplicity. A build's hulls come from
 * libqhull's reentrant API with triangulated output ("Qt"). A surface
 * update first keeps a piece's old triangles where they still bound its
 * moved control points, then tries the incremental hull of small_hull.h,
 * and leaves to qhull only the sets that refuses (flat or nearly flat
 * pieces): qhull's set-up costs tens of microseconds a piece, the other
 * two a few. Builds keep qhull, so that a renderer made from a scene draws
 * exactly what it drew before: the small hull is the same convex body,
 * but triangulates coplanar faces its own way, and the "view" and "cp"
 * starts interpolate over the triangles. */
#include "hulls.h"

#include <libqhull_r/qhull_ra.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bezier.h"
#include "nurbs.h"
#include "small_hull.h"

enum { DEFAULT_DIVISIONS = 2, DEFAULT_MAX_DEPTH = 8 };

/* A piece of a Bézier patch being refined: homogeneous points as in
 * sc_bezier_patch, and its rectangle in the patch's [0, 1]². */
typedef struct piece {
    int deg_u, deg_v;
    double *cp;
    double local[4];
} piece;

/* Growing output plus what the hull builder needs while it runs. */
typedef struct builder {
    sc_hulls *out;
    int cap_sub, cap_vert, cap_idx;
    FILE *qhull_log;             /* qhull's messages, kept out of stderr;
                                    opened when qhull first runs */
    const sc_surface *surface;
    int surface_index, patch_index;
    const sc_bezier_patch *patch;
    double tolerance;            /* absolute, world units */
    int max_depth;
    /* An update: the surface's hulls before it (prev's sub-patches
     * [prev_next, prev_end)), whose triangles its pieces may keep. */
    const sc_hulls *prev;
    int prev_next, prev_end;
} builder;

/* ---- Bézier pieces ---- */

static size_t piece_points(const piece *p)
{
    return (size_t)(p->deg_u + 1) * (size_t)(p->deg_v + 1);
}

/* Splits p along dir (0: u, 1: v) at the fraction f of its rectangle into
 * lo and hi (their cp arrays are allocated): de Casteljau at f, i.e. knot
 * insertion to full multiplicity. */
static void split_at(const piece *p, int dir, double f, piece *lo, piece *hi)
{
    *lo = *hi = *p;
    lo->cp = sc_alloc(piece_points(p) * 4, sizeof(double));
    hi->cp = sc_alloc(piece_points(p) * 4, sizeof(double));
    double cut = p->local[2 * dir] + f * (p->local[2 * dir + 1] - p->local[2 * dir]);
    lo->local[2 * dir + 1] = cut;
    hi->local[2 * dir] = cut;
    sc_bezier_grid_split(p->cp, p->deg_u, p->deg_v, dir, f, lo->cp, hi->cp);
}

/* Euclidean point (i, j) of a piece (world space, as its patch). */
static void piece_point(const piece *p, int i, int j, double out[3])
{
    const double *h = p->cp + 4 * (j * (p->deg_u + 1) + i);
    for (int c = 0; c < 3; c++)
        out[c] = h[c] / h[3];
}

static double dist3(const double a[3], const double b[3])
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* How far the control mesh is from flat, per direction: the largest
 * distance of a control point from the bilinear patch through the four
 * corners, and which direction holds more of it (the larger deviation of
 * the lines along u from their chords, against those along v). */
static double piece_flatness(const builder *b, const piece *p, int *split_dir)
{
    int du = p->deg_u, dv = p->deg_v, row = du + 1;
    /* The Euclidean points once (a surface update refines every piece of
     * a surface again, so this runs for every piece of every frame). */
    double *e = sc_alloc(piece_points(p) * 3, sizeof(double));
    for (int j = 0; j <= dv; j++)
        for (int i = 0; i <= du; i++)
            piece_point(p, i, j, e + 3 * (j * row + i));
#define E(i, j) (e + 3 * ((j) * row + (i)))
    const double *c00 = E(0, 0), *c10 = E(du, 0), *c01 = E(0, dv), *c11 = E(du, dv);
    double bilinear = 0, along_u = 0, along_v = 0;
    for (int j = 0; j <= dv; j++)
        for (int i = 0; i <= du; i++) {
            double s = (double)i / du, t = (double)j / dv, q[3];
            const double *x = E(i, j);
            for (int c = 0; c < 3; c++)
                q[c] = (1 - t) * ((1 - s) * c00[c] + s * c10[c]) +
                       t * ((1 - s) * c01[c] + s * c11[c]);
            bilinear = fmax(bilinear, dist3(x, q));
            /* chords of the row j (along u) and of the column i (along v) */
            const double *r0 = E(0, j), *r1 = E(du, j), *k0 = E(i, 0), *k1 = E(i, dv);
            double on_row[3], on_col[3];
            for (int c = 0; c < 3; c++) {
                on_row[c] = (1 - s) * r0[c] + s * r1[c];
                on_col[c] = (1 - t) * k0[c] + t * k1[c];
            }
            along_u = fmax(along_u, dist3(x, on_row));
            along_v = fmax(along_v, dist3(x, on_col));
        }
#undef E
    free(e);
    *split_dir = along_u >= along_v ? 0 : 1;
    return bilinear;
}

/* ---- output ---- */

static sc_subpatch *add_subpatch(builder *b)
{
    sc_hulls *h = b->out;
    if (h->count == b->cap_sub) {
        b->cap_sub = b->cap_sub ? 2 * b->cap_sub : 64;
        h->subpatches = sc_realloc(h->subpatches, (size_t)b->cap_sub, sizeof *h->subpatches);
    }
    sc_subpatch *s = &h->subpatches[h->count++];
    memset(s, 0, sizeof *s);
    return s;
}

static void reserve(builder *b, int vertices, int indices)
{
    sc_hulls *h = b->out;
    while (h->nvertices + vertices > b->cap_vert) {
        b->cap_vert = b->cap_vert ? 2 * b->cap_vert : 1024;
        h->vertices = sc_realloc(h->vertices, (size_t)b->cap_vert, sizeof *h->vertices);
    }
    while (h->nindices + indices > b->cap_idx) {
        b->cap_idx = b->cap_idx ? 2 * b->cap_idx : 4096;
        h->indices = sc_realloc(h->indices, (size_t)b->cap_idx, sizeof *h->indices);
    }
}

/* Runs qhull on n points; on success stores the hull's triangles (3 input
 * point numbers each, counter-clockwise seen from outside) in *tris and
 * returns their count; -1 when qhull finds no 3D hull. */
static int qhull_triangles(builder *b, double *coords, int n, int **tris)
{
    qhT qh_storage;
    qhT *qh = &qh_storage;
    qh_zero(qh, b->qhull_log);
    char options[] = "qhull Qt";
    int exitcode = qh_new_qhull(qh, 3, n, coords, False, options, NULL, b->qhull_log);
    int count = -1;
    if (!exitcode) {
        count = 0;
        int cap = 0;
        facetT *facet;
        FORALLfacets {
            int ids[3], k = 0;
            double *pts[3];
            vertexT *vertex, **vertexp;
            FOREACHvertex_(facet->vertices) {
                if (k < 3) {
                    pts[k] = vertex->point;
                    ids[k] = qh_pointid(qh, vertex->point);
                }
                k++;
            }
            if (k != 3)
                continue;  /* "Qt" makes every facet a triangle */
            double e1[3], e2[3], nrm[3];
            for (int c = 0; c < 3; c++) {
                e1[c] = pts[1][c] - pts[0][c];
                e2[c] = pts[2][c] - pts[0][c];
            }
            nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
            nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
            nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
            /* qhull's facet normals point outwards; its vertex order does not
             * follow them. */
            if (nrm[0] * facet->normal[0] + nrm[1] * facet->normal[1] +
                    nrm[2] * facet->normal[2] < 0) {
                int t = ids[1];
                ids[1] = ids[2];
                ids[2] = t;
            }
            if (3 * (count + 1) > cap) {
                cap = cap ? 2 * cap : 96;
                *tris = sc_realloc(*tris, (size_t)cap, sizeof(int));
            }
            memcpy(*tris + 3 * count, ids, sizeof ids);
            count++;
        }
    }
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    return count;
}

/* The input points of a piece's hull, n control points relative to its
 * middle: each once, or (copies 6) each pushed 1e-5 of the piece's size
 * along each axis both ways, a thin slab around flat or collinear points,
 * which have no 3D hull. */
static double *input_points(const double *world, int n, int copies, double size)
{
    double *coords = sc_alloc((size_t)n * (size_t)copies * 3, sizeof(double));
    double eps = 1e-5 * size;
    for (int k = 0; k < n; k++)
        for (int c = 0; c < copies; c++) {
            double *q = coords + 3 * (copies * k + c);
            memcpy(q, world + 3 * k, 3 * sizeof(double));
            if (copies > 1)
                q[c / 2] += c % 2 ? eps : -eps;
        }
    return coords;
}

/* In an update, the hull the piece had before: the next of the surface's
 * old sub-patches from the same Bézier patch with the same rectangle (the
 * refinement visits pieces in the same order each time, so a forward
 * search from the last one found meets them in turn). */
static const sc_subpatch *previous_piece(builder *b, const piece *p)
{
    for (int k = b->prev_next; b->prev && k < b->prev_end; k++) {
        const sc_subpatch *s = &b->prev->subpatches[k];
        if (s->patch > b->patch_index)
            break;
        if (s->patch == b->patch_index && s->copies > 0 &&
            !memcmp(s->local, p->local, sizeof s->local)) {
            b->prev_next = k + 1;
            return s;
        }
    }
    return NULL;
}

/* The triangles of the old hull `before`, in the numbers of its input
 * points, when they still bound the n moved ones (coords):
 * sc_small_hull_bounds. Returns their count, or -1. */
static int kept_triangles(const sc_hulls *prev, const sc_subpatch *before, const double *coords,
                          int n, double size, int **tris)
{
    int ntris = before->index_count / 3;
    int *t = sc_alloc((size_t)(3 * ntris > 0 ? 3 * ntris : 1), sizeof(int));
    int ok = ntris > 0;
    for (int i = 0; i < 3 * ntris && ok; i++) {
        t[i] = prev->vertices[prev->indices[before->first_index + i]].source;
        ok = t[i] >= 0 && t[i] < n;
    }
    if (!ok || !sc_small_hull_bounds(coords, n, t, ntris, size)) {
        free(t);
        return -1;
    }
    *tris = t;
    return ntris;
}

/* The hull of one piece, appended as a sub-patch. */
static int emit_hull(builder *b, const piece *p, sc_error *err)
{
    int np = (int)piece_points(p);
    double *world = sc_alloc((size_t)np * 3, sizeof(double));
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int j = 0; j <= p->deg_v; j++)
        for (int i = 0; i <= p->deg_u; i++) {
            double *x = world + 3 * (j * (p->deg_u + 1) + i);
            piece_point(p, i, j, x);
            for (int c = 0; c < 3; c++) {
                lo[c] = fmin(lo[c], x[c]);
                hi[c] = fmax(hi[c], x[c]);
            }
        }
    double size = dist3(lo, hi);
    if (!(size > 0)) {  /* collapsed to one point: nothing to draw */
        free(world);
        return SC_OK;
    }
    /* qhull works relative to the piece's middle: its round-off
     * tolerances scale with the coordinates, so far from the origin it would
     * merge facets by amounts that depend on where the model sits. */
    double mid[3];
    for (int c = 0; c < 3; c++)
        mid[c] = 0.5 * (lo[c] + hi[c]);
    for (int k = 0; k < np; k++)
        for (int c = 0; c < 3; c++)
            world[3 * k + c] -= mid[c];
    int *tris = NULL, ntris = -1, copies = 1;
    double *coords = NULL;
    const sc_subpatch *before = previous_piece(b, p);
    if (before) {
        copies = before->copies;
        coords = input_points(world, np, copies, size);
        ntris = kept_triangles(b->prev, before, coords, np * copies, size, &tris);
        b->out->kept_pieces += ntris >= 0;
    }
    if (ntris < 0) {
        free(coords);
        copies = 1;
        coords = input_points(world, np, 1, size);
        if (b->prev && np >= 4)
            ntris = sc_small_hull(coords, np, size, &tris);
    }
    if (ntris < 0 && !b->qhull_log && !(b->qhull_log = fopen("/dev/null", "w"))) {
        free(world);
        free(coords);
        return sc_fail(err, NULL, 0, "cannot open /dev/null for qhull's messages");
    }
    if (ntris < 0) {
        b->out->qhull_pieces++;
        ntris = np >= 4 ? qhull_triangles(b, coords, np, &tris) : -1;
    }
    if (ntris < 0) {
        /* Flat or collinear control points (a planar patch) have no 3D hull:
         * bound them by a thin slab. */
        copies = 6;
        free(coords);
        coords = input_points(world, np, 6, size);
        ntris = qhull_triangles(b, coords, np * 6, &tris);
    }
    free(world);
    if (ntris < 0) {
        free(coords);
        free(tris);
        return sc_fail(err, NULL, 0,
                       "surface %d (%s): qhull found no hull for a sub-patch of patch %d",
                       b->surface_index, b->surface->name, b->patch_index);
    }
    int nin = np * copies;
    reserve(b, nin, 3 * ntris);
    sc_hulls *h = b->out;
    sc_subpatch *s = add_subpatch(b);
    s->surface = b->surface_index;
    s->patch = b->patch_index;
    memcpy(s->local, p->local, sizeof s->local);
    const sc_bezier_patch *bp = b->patch;
    s->domain[0] = bp->u0 + (bp->u1 - bp->u0) * p->local[0];
    s->domain[1] = bp->u0 + (bp->u1 - bp->u0) * p->local[1];
    s->domain[2] = bp->v0 + (bp->v1 - bp->v0) * p->local[2];
    s->domain[3] = bp->v0 + (bp->v1 - bp->v0) * p->local[3];
    s->first_vertex = h->nvertices;
    s->first_index = h->nindices;
    s->copies = copies;
    for (int c = 0; c < 3; c++) {
        s->lo[c] = INFINITY;
        s->hi[c] = -INFINITY;
    }
    /* Hull vertices are the input points the triangles use, once each; an
     * input point carries the parameters of the control point it came from. */
    int *vertex_of = sc_alloc((size_t)nin, sizeof(int));
    for (int k = 0; k < nin; k++)
        vertex_of[k] = -1;
    for (int t = 0; t < 3 * ntris; t++) {
        int k = tris[t];
        if (vertex_of[k] < 0) {
            int cp_index = k / copies;
            int i = cp_index % (p->deg_u + 1), j = cp_index / (p->deg_u + 1);
            sc_hull_vertex *v = &h->vertices[h->nvertices];
            v->source = k;
            for (int c = 0; c < 3; c++)
                v->pos[c] = coords[3 * k + c] + mid[c];
            v->uv[0] = p->local[0] + (p->local[1] - p->local[0]) * i / p->deg_u;
            v->uv[1] = p->local[2] + (p->local[3] - p->local[2]) * j / p->deg_v;
            for (int c = 0; c < 3; c++) {
                s->lo[c] = fmin(s->lo[c], v->pos[c]);
                s->hi[c] = fmax(s->hi[c], v->pos[c]);
            }
            vertex_of[k] = h->nvertices++;
        }
        h->indices[h->nindices++] = (uint32_t)vertex_of[k];
    }
    s->vertex_count = h->nvertices - s->first_vertex;
    s->index_count = h->nindices - s->first_index;
    free(vertex_of);
    free(tris);
    free(coords);
    return SC_OK;
}

/* Adaptive refinement: split along the less flat direction until the mesh
 * is flat within the tolerance or the depth is used up. Takes ownership of
 * p->cp. */
static int refine(builder *b, piece *p, int depth, sc_error *err)
{
    int dir;
    double flatness = piece_flatness(b, p, &dir);
    int status;
    if (flatness <= b->tolerance || depth >= b->max_depth) {
        status = emit_hull(b, p, err);
    } else {
        piece lo, hi;
        split_at(p, dir, 0.5, &lo, &hi);
        status = refine(b, &lo, depth + 1, err);
        if (status == SC_OK)
            status = refine(b, &hi, depth + 1, err);
        else
            free(hi.cp);
    }
    free(p->cp);
    p->cp = NULL;
    return status;
}

/* The k-th of n equal parts along dir, cut off the front of *rest, which
 * holds parts k..n-1 and is left holding k+1..n-1 (the last part is rest
 * itself). */
static piece cut_off(piece *rest, int dir, int k, int n)
{
    piece part = *rest;
    if (k < n - 1) {
        piece next;
        split_at(rest, dir, 1.0 / (n - k), &part, &next);
        free(rest->cp);
        *rest = next;
    } else {
        rest->cp = NULL;
    }
    return part;
}

/* Uniform refinement: n × n pieces of equal parameter size, cut off strip
 * by strip at 1/n, 1/(n-1), … of what is left. */
static int uniform(builder *b, const piece *whole, int n, sc_error *err)
{
    piece rest_u = *whole;
    rest_u.cp = sc_alloc(piece_points(whole) * 4, sizeof(double));
    memcpy(rest_u.cp, whole->cp, piece_points(whole) * 4 * sizeof(double));
    int status = SC_OK;
    for (int a = 0; a < n && status == SC_OK; a++) {
        piece strip = cut_off(&rest_u, 0, a, n);
        for (int c = 0; c < n && status == SC_OK; c++) {
            piece cell = cut_off(&strip, 1, c, n);
            status = emit_hull(b, &cell, err);
            free(cell.cp);
        }
        free(strip.cp);
    }
    free(rest_u.cp);
    return status;
}

/* A builder appending to out with the options of out->desc and out->tolerance. */
static void builder_open(builder *b, sc_hulls *out)
{
    *b = (builder){.out = out, .tolerance = out->tolerance, .max_depth = out->desc.max_depth};
}

static void builder_close(builder *b)
{
    if (b->qhull_log)
        fclose(b->qhull_log);
}

/* Appends the hulls of surface si, built from its world-space patches,
 * and says where they went. */
static int build_surface(builder *b, const sc_scene *scene, int si, const sc_patch_list *list,
                         sc_hull_range *range, sc_error *err)
{
    sc_hulls *h = b->out;
    b->surface = &scene->surfaces[si];
    b->surface_index = si;
    b->tolerance = h->surface_tolerance ? h->surface_tolerance[si] : h->tolerance;
    range->first_subpatch = h->count;
    range->first_vertex = h->nvertices;
    range->first_index = h->nindices;
    int status = SC_OK;
    for (int pi = 0; pi < list->count && status == SC_OK; pi++) {
        const sc_bezier_patch *bp = &list->patches[pi];
        b->patch = bp;
        b->patch_index = pi;
        piece p = {.deg_u = bp->deg_u, .deg_v = bp->deg_v, .local = {0, 1, 0, 1}};
        if (h->desc.mode == SC_SPLIT_UNIFORM) {
            p.cp = bp->cp; /* uniform() copies what it cuts */
            status = uniform(b, &p, h->desc.divisions, err);
        } else {
            p.cp = sc_alloc(piece_points(&p) * 4, sizeof(double));
            memcpy(p.cp, bp->cp, piece_points(&p) * 4 * sizeof(double));
            status = refine(b, &p, 0, err);
        }
    }
    range->subpatch_count = h->count - range->first_subpatch;
    range->vertex_count = h->nvertices - range->first_vertex;
    range->index_count = h->nindices - range->first_index;
    range->patch_count = list->count;
    h->npatches += list->count;
    return status;
}

int sc_hulls_build_from(const sc_scene *scene, const sc_patch_list *patches,
                        const sc_hull_desc *desc, sc_hulls *hulls, sc_error *err)
{
    static const sc_hull_desc defaults = {0};
    if (!desc)
        desc = &defaults;
    memset(hulls, 0, sizeof *hulls);
    hulls->desc = *desc;
    if (!(hulls->desc.tolerance > 0))
        hulls->desc.tolerance = SC_HULL_DEFAULT_TOLERANCE;
    if (hulls->desc.max_depth <= 0)
        hulls->desc.max_depth = DEFAULT_MAX_DEPTH;
    if (hulls->desc.divisions <= 0)
        hulls->desc.divisions = DEFAULT_DIVISIONS;
    double lo[3], hi[3];
    double diag = sc_scene_bounds(scene, lo, hi) ? dist3(lo, hi) : 0;
    hulls->tolerance = hulls->desc.tolerance * diag;
    if (desc->surface_tolerance) {
        hulls->surface_tolerance = sc_alloc((size_t)(scene->nsurfaces ? scene->nsurfaces : 1),
                                            sizeof(double));
        for (int si = 0; si < scene->nsurfaces; si++)
            hulls->surface_tolerance[si] = desc->surface_tolerance[si] * diag;
        hulls->desc.surface_tolerance = NULL; /* the caller's array need not outlive us */
    }
    builder b;
    builder_open(&b, hulls);
    hulls->nsurfaces = scene->nsurfaces;
    hulls->surfaces = sc_alloc((size_t)(scene->nsurfaces ? scene->nsurfaces : 1),
                               sizeof *hulls->surfaces);
    int status = SC_OK;
    for (int si = 0; si < scene->nsurfaces && status == SC_OK; si++)
        status = build_surface(&b, scene, si, &patches[si], &hulls->surfaces[si], err);
    builder_close(&b);
    if (status != SC_OK)
        sc_hulls_free(hulls);
    return status;
}

int sc_hulls_build(const sc_scene *scene, const sc_hull_desc *desc, sc_hulls *hulls,
                   sc_error *err)
{
    int n = scene->nsurfaces;
    sc_patch_list *patches = sc_alloc((size_t)(n ? n : 1), sizeof *patches);
    for (int s = 0; s < n; s++)
        sc_surface_world_patches(&scene->surfaces[s], s, &patches[s]);
    int status = sc_hulls_build_from(scene, patches, desc, hulls, err);
    for (int s = 0; s < n; s++)
        sc_patch_list_free(&patches[s]);
    free(patches);
    return status;
}

/* Turns `old` elements of size `size` at `first` of an array of *count
 * into room for `fresh` ones, moving those after them. */
static void *splice(void *array, int *count, int first, int old, int fresh, size_t size)
{
    int total = *count - old + fresh, rest = *count - first - old;
    char *a = array;
    if (fresh > old)
        a = sc_realloc(a, (size_t)total, size);
    if (rest > 0)
        memmove(a + (size_t)(first + fresh) * size, a + (size_t)(first + old) * size,
                (size_t)rest * size);
    *count = total;
    return a;
}

int sc_hulls_update_surface_from(sc_hulls *hulls, const sc_scene *scene, int surface,
                                 const sc_patch_list *patches, int *moved, sc_error *err)
{
    if (surface < 0 || surface >= hulls->nsurfaces || scene->nsurfaces != hulls->nsurfaces)
        return sc_fail(err, NULL, 0, "surface %d is not in the scene the hulls were built for",
                       surface);
    sc_hulls one = {.desc = hulls->desc,
                    .tolerance = hulls->surface_tolerance ? hulls->surface_tolerance[surface]
                                                          : hulls->tolerance};
    builder b;
    builder_open(&b, &one);
    b.prev = hulls;
    b.prev_next = hulls->surfaces[surface].first_subpatch;
    b.prev_end = b.prev_next + hulls->surfaces[surface].subpatch_count;
    sc_hull_range fresh;
    int status = build_surface(&b, scene, surface, patches, &fresh, err);
    builder_close(&b);
    if (status != SC_OK) {
        sc_hulls_free(&one);
        return SC_FAIL;
    }
    sc_hull_range *old = &hulls->surfaces[surface];
    int dsub = one.count - old->subpatch_count;
    int dvert = one.nvertices - old->vertex_count;
    int didx = one.nindices - old->index_count;
    *moved = dsub || dvert || didx;
    if (*moved) {
        hulls->subpatches = splice(hulls->subpatches, &hulls->count, old->first_subpatch,
                                   old->subpatch_count, one.count, sizeof *hulls->subpatches);
        hulls->vertices = splice(hulls->vertices, &hulls->nvertices, old->first_vertex,
                                 old->vertex_count, one.nvertices, sizeof *hulls->vertices);
        hulls->indices = splice(hulls->indices, &hulls->nindices, old->first_index,
                                old->index_count, one.nindices, sizeof *hulls->indices);
        for (int k = old->first_subpatch + one.count; k < hulls->count; k++) {
            hulls->subpatches[k].first_vertex += dvert;
            hulls->subpatches[k].first_index += didx;
        }
        for (int i = old->first_index + one.nindices; i < hulls->nindices; i++)
            hulls->indices[i] = (uint32_t)((int)hulls->indices[i] + dvert);
        for (int s = surface + 1; s < hulls->nsurfaces; s++) {
            hulls->surfaces[s].first_subpatch += dsub;
            hulls->surfaces[s].first_vertex += dvert;
            hulls->surfaces[s].first_index += didx;
        }
    }
    for (int k = 0; k < one.count; k++) {
        sc_subpatch *s = &hulls->subpatches[old->first_subpatch + k];
        *s = one.subpatches[k];
        s->first_vertex += old->first_vertex;
        s->first_index += old->first_index;
    }
    if (one.nvertices)
        memcpy(hulls->vertices + old->first_vertex, one.vertices,
               (size_t)one.nvertices * sizeof *one.vertices);
    for (int i = 0; i < one.nindices; i++)
        hulls->indices[old->first_index + i] = one.indices[i] + (uint32_t)old->first_vertex;
    hulls->npatches += one.npatches - old->patch_count;
    hulls->qhull_pieces += one.qhull_pieces;
    hulls->kept_pieces += one.kept_pieces;
    old->subpatch_count = one.count;
    old->vertex_count = one.nvertices;
    old->index_count = one.nindices;
    old->patch_count = one.npatches;
    sc_hulls_free(&one);
    return SC_OK;
}

int sc_hulls_update_surface(sc_hulls *hulls, const sc_scene *scene, int surface, int *moved,
                            sc_error *err)
{
    if (surface < 0 || surface >= scene->nsurfaces)
        return sc_fail(err, NULL, 0, "surface %d is not in the scene the hulls were built for",
                       surface);
    sc_patch_list patches;
    sc_surface_world_patches(&scene->surfaces[surface], surface, &patches);
    int status = sc_hulls_update_surface_from(hulls, scene, surface, &patches, moved, err);
    sc_patch_list_free(&patches);
    return status;
}

void sc_hulls_free(sc_hulls *hulls)
{
    free(hulls->subpatches);
    free(hulls->vertices);
    free(hulls->indices);
    free(hulls->surfaces);
    free(hulls->surface_tolerance);
    memset(hulls, 0, sizeof *hulls);
}

int sc_hull_contains(const sc_hulls *hulls, int index, const double p[3])
{
    const sc_subpatch *s = &hulls->subpatches[index];
    for (int c = 0; c < 3; c++)
        if (p[c] < s->lo[c] || p[c] > s->hi[c])
            return 0;
    /* Inside a convex hull = behind the plane of every outward triangle. */
    for (int t = 0; t < s->index_count; t += 3) {
        const uint32_t *tri = hulls->indices + s->first_index + t;
        const double *a = hulls->vertices[tri[0]].pos, *b = hulls->vertices[tri[1]].pos,
                     *c = hulls->vertices[tri[2]].pos;
        double e1[3], e2[3], d[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = b[k] - a[k];
            e2[k] = c[k] - a[k];
            d[k] = p[k] - a[k];
        }
        double n0 = e1[1] * e2[2] - e1[2] * e2[1], n1 = e1[2] * e2[0] - e1[0] * e2[2],
               n2 = e1[0] * e2[1] - e1[1] * e2[0];
        if (n0 * d[0] + n1 * d[1] + n2 * d[2] > 0)
            return 0;
    }
    return 1;
}
