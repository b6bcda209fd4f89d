/* small_hull.c — the incremental convex hull of small_hull.h: a tetrahedron of
 * extreme points, then each other point, farthest from the middle first;
 * a point outside some faces replaces those faces by a cone from their
 * horizon to it. Every decision that round-off could make inconsistent
 * (a flat start, a sliver face, a horizon that is not one loop, a face
 * turned inwards) refuses the set instead, and the result is checked
 * against every point before it is returned. */
#include "small_hull.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sc_base.h"

typedef struct face {
    int v[3];
    double n[3], d;      /* unit outward normal, n · x = d on the plane */
} face;

typedef struct hull {
    const double *p;
    face *faces;
    int count, cap;
    double inner[3];     /* a point inside: the start tetrahedron's centroid */
    double eps;          /* distances below this are "on the plane" */
} hull;

static const double *pt(const hull *h, int i) { return h->p + 3 * i; }

static double plane_distance(const face *f, const double *x)
{
    return f->n[0] * x[0] + f->n[1] * x[1] + f->n[2] * x[2] - f->d;
}

/* Appends the face (a, b, c), counter-clockwise seen from outside: 1;
 * -1 when it is a sliver, 0 when it faces the inside point (neither is
 * appended). */
static int add_face(hull *h, int a, int b, int c, double min_area2)
{
    const double *A = pt(h, a), *B = pt(h, b), *C = pt(h, c);
    double e1[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
    double e2[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > min_area2))
        return -1;
    face f = {.v = {a, b, c}};
    for (int k = 0; k < 3; k++)
        f.n[k] = n[k] / len;
    f.d = f.n[0] * A[0] + f.n[1] * A[1] + f.n[2] * A[2];
    if (!(plane_distance(&f, h->inner) < -h->eps))
        return 0;
    if (h->count == h->cap) {
        h->cap = h->cap ? 2 * h->cap : 64;
        h->faces = sc_realloc(h->faces, (size_t)h->cap, sizeof *h->faces);
    }
    h->faces[h->count++] = f;
    return 1;
}

/* The point farthest from the line a–b (or, with c >= 0, from the
 * plane a b c); its distance in *dist. */
static int farthest(const hull *h, int n, int a, int b, int c, double *dist)
{
    const double *A = pt(h, a), *B = pt(h, b);
    double e[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]}, nrm[3] = {0, 0, 0};
    double elen = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    if (c >= 0) {
        const double *C = pt(h, c);
        double f[3] = {C[0] - A[0], C[1] - A[1], C[2] - A[2]};
        nrm[0] = e[1] * f[2] - e[2] * f[1];
        nrm[1] = e[2] * f[0] - e[0] * f[2];
        nrm[2] = e[0] * f[1] - e[1] * f[0];
        double l = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        for (int k = 0; k < 3; k++)
            nrm[k] /= l;
    }
    int best = -1;
    *dist = -1;
    for (int i = 0; i < n; i++) {
        const double *X = pt(h, i);
        double x[3] = {X[0] - A[0], X[1] - A[1], X[2] - A[2]}, d;
        if (c >= 0) {
            d = fabs(x[0] * nrm[0] + x[1] * nrm[1] + x[2] * nrm[2]);
        } else {
            double cr[3] = {x[1] * e[2] - x[2] * e[1], x[2] * e[0] - x[0] * e[2],
                            x[0] * e[1] - x[1] * e[0]};
            d = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / elen;
        }
        if (d > *dist) {
            *dist = d;
            best = i;
        }
    }
    return best;
}

/* Adds point i: the faces it sees go, a cone from their horizon to it
 * comes. 0 when the horizon is not one loop or a new face is a sliver. */
static int add_point(hull *h, int i, int *seen, int *edges, int *next, int n,
                     double min_area2)
{
    const double *x = pt(h, i);
    int nseen = 0;
    for (int f = 0; f < h->count; f++)
        if (plane_distance(&h->faces[f], x) > h->eps)
            seen[nseen++] = f;
    if (!nseen)
        return 1;
    /* Horizon: edges of seen faces whose twin lies on an unseen face. */
    int nedges = 0;
    for (int s = 0; s < nseen; s++) {
        const face *f = &h->faces[seen[s]];
        for (int k = 0; k < 3; k++) {
            int a = f->v[k], b = f->v[(k + 1) % 3], twin_seen = 0;
            for (int t = 0; t < nseen && !twin_seen; t++) {
                const int *g = h->faces[seen[t]].v;
                twin_seen = (g[0] == b && g[1] == a) || (g[1] == b && g[2] == a) ||
                            (g[2] == b && g[0] == a);
            }
            if (!twin_seen) {
                if (nedges == n)
                    return 0;
                edges[2 * nedges] = a;
                edges[2 * nedges + 1] = b;
                nedges++;
            }
        }
    }
    /* One loop: every horizon vertex starts exactly one edge, and following
     * them from the first comes back after all of them. */
    for (int k = 0; k < n; k++)
        next[k] = -1;
    for (int e = 0; e < nedges; e++) {
        if (next[edges[2 * e]] >= 0)
            return 0;
        next[edges[2 * e]] = edges[2 * e + 1];
    }
    int v = edges[0], steps = 0;
    do {
        v = next[v];
        steps++;
    } while (v >= 0 && v != edges[0] && steps <= nedges);
    if (v != edges[0] || steps != nedges)
        return 0;
    /* The seen faces go (seen[] is increasing: the kept ones close up). */
    int kept = 0;
    for (int f = 0, s = 0; f < h->count; f++) {
        if (s < nseen && seen[s] == f)
            s++;
        else
            h->faces[kept++] = h->faces[f];
    }
    h->count = kept;
    for (int e = 0; e < nedges; e++)
        if (add_face(h, edges[2 * e], edges[2 * e + 1], i, min_area2) != 1)
            return 0;
    return 1;
}

int sc_small_hull(const double *coords, int n, double size, int **tris)
{
    if (n < 4 || !(size > 0))
        return -1;
    hull h = {.p = coords, .eps = 1e-11 * size};
    /* Faces narrower than this (twice their area) are slivers whose
     * normals round-off decides. */
    double min_area2 = 1e-14 * size * size;
    int i0 = 0;
    for (int i = 1; i < n; i++)
        if (coords[3 * i] < coords[3 * i0])
            i0 = i;
    double d1 = -1;
    int i1 = -1;
    for (int i = 0; i < n; i++) {
        const double *a = pt(&h, i0), *b = pt(&h, i);
        double d = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]));
        if (d > d1) {
            d1 = d;
            i1 = i;
        }
    }
    double d2, d3;
    int i2 = d1 > 1e-9 * size ? farthest(&h, n, i0, i1, -1, &d2) : -1;
    int i3 = i2 >= 0 && d2 > 1e-7 * size ? farthest(&h, n, i0, i1, i2, &d3) : -1;
    /* Nearly flat sets go to qhull, which bounds them as before (a thin
     * hull, or a slab when it finds none). */
    if (i3 < 0 || !(d3 > 1e-6 * size))
        return -1;
    const int start[4] = {i0, i1, i2, i3};
    for (int k = 0; k < 3; k++)
        h.inner[k] = 0.25 * (pt(&h, i0)[k] + pt(&h, i1)[k] + pt(&h, i2)[k] + pt(&h, i3)[k]);
    static const int tet[4][3] = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
    int ok = 1;
    for (int f = 0; f < 4 && ok; f++) {
        int a = start[tet[f][0]], b = start[tet[f][1]], c = start[tet[f][2]];
        /* Each face turned to look away from the centroid. */
        int r = add_face(&h, a, b, c, min_area2);
        ok = r == 1 || (r == 0 && add_face(&h, a, c, b, min_area2) == 1);
    }
    /* The other points, farthest from the middle first: the extreme ones
     * make the hull early, and the ones inside it are then skipped. */
    int *order = sc_alloc((size_t)n, sizeof(int));
    double *far = sc_alloc((size_t)n, sizeof(double));
    int m = 0;
    for (int i = 0; i < n; i++) {
        if (i == i0 || i == i1 || i == i2 || i == i3)
            continue;
        const double *x = pt(&h, i);
        double d = (x[0] - h.inner[0]) * (x[0] - h.inner[0]) +
                   (x[1] - h.inner[1]) * (x[1] - h.inner[1]) +
                   (x[2] - h.inner[2]) * (x[2] - h.inner[2]);
        int k = m++;
        for (; k > 0 && far[k - 1] < d; k--) {
            far[k] = far[k - 1];
            order[k] = order[k - 1];
        }
        far[k] = d;
        order[k] = i;
    }
    /* A hull of n points has at most 2n - 4 faces. */
    int *seen = sc_alloc((size_t)(2 * n), sizeof(int));
    int *edges = sc_alloc((size_t)(2 * n), sizeof(int));
    int *next = sc_alloc((size_t)n, sizeof(int));
    for (int k = 0; k < m && ok; k++)
        ok = add_point(&h, order[k], seen, edges, next, n, min_area2);
    free(seen);
    free(order);
    free(far);
    free(edges);
    free(next);
    int ntris = 0;
    int *t = NULL;
    if (ok) {
        t = sc_alloc((size_t)(3 * h.count), sizeof(int));
        for (int f = 0; f < h.count; f++)
            memcpy(t + 3 * ntris++, h.faces[f].v, sizeof h.faces[f].v);
        ok = sc_small_hull_bounds(coords, n, t, ntris, size);
    }
    free(h.faces);
    if (!ok) {
        free(t);
        return -1;
    }
    *tris = t;
    return ntris;
}

int sc_small_hull_bounds(const double *coords, int n, const int *tris, int ntris, double size)
{
    double volume = 0;
    for (int f = 0; f < ntris; f++) {
        const double *a = coords + 3 * tris[3 * f], *b = coords + 3 * tris[3 * f + 1],
                     *c = coords + 3 * tris[3 * f + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double nrm[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                         e1[0] * e2[1] - e1[1] * e2[0]};
        volume += a[0] * nrm[0] + a[1] * nrm[1] + a[2] * nrm[2];
        double slack = 1e-9 * size * sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        for (int k = 0; k < n; k++) {
            const double *q = coords + 3 * k;
            if (nrm[0] * (q[0] - a[0]) + nrm[1] * (q[1] - a[1]) + nrm[2] * (q[2] - a[2]) > slack)
                return 0;
        }
    }
    return volume > 0;
}
