/* tri_prisms.c — GPU records, prisms and Manhattan sets of a terrain
 * (tri_prisms.h). */
#include "tri_prisms.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void sc_tri_patch_list(const sc_tri_mesh *m, sc_patch_list *out)
{
    int n = m->degree;
    out->count = m->count;
    out->patches = sc_alloc((size_t)(m->count ? m->count : 1), sizeof *out->patches);
    for (int p = 0; p < m->count; p++) {
        sc_bezier_patch *bp = &out->patches[p];
        double tri[6];
        sc_tri_mesh_domain(m, p, tri);
        *bp = (sc_bezier_patch){.surface = 0, .deg_u = n, .deg_v = n, .u0 = 0, .u1 = 1,
                                .v0 = 0, .v1 = 1};
        bp->cp = sc_alloc((size_t)m->ncoef * 4, sizeof(double));
        for (int i = n; i >= 0; i--)
            for (int j = n - i; j >= 0; j--) {
                int k = n - i - j, at = sc_tri_index(n, i, j);
                double *pt = bp->cp + 4 * at;
                pt[0] = (i * tri[0] + j * tri[2] + k * tri[4]) / n;
                pt[1] = (i * tri[1] + j * tri[3] + k * tri[5]) / n;
                pt[2] = m->coef[(size_t)p * (size_t)m->ncoef + (size_t)at];
                pt[3] = 1;
            }
    }
}

void sc_tri_prisms(const sc_tri_mesh *m, sc_hulls *out)
{
    /* Bottom triangle counter-clockwise seen from below, top seen from
     * above, and two outward triangles per side (vertices 0–2 bottom,
     * 3–5 top, the domain triangle counter-clockwise seen from above). */
    static const uint32_t faces[24] = {0, 2, 1, 3, 4, 5, 0, 1, 4, 0, 4, 3,
                                       1, 2, 5, 1, 5, 4, 2, 0, 3, 2, 3, 5};
    memset(out, 0, sizeof *out);
    out->count = m->count;
    out->subpatches = sc_alloc((size_t)(m->count ? m->count : 1), sizeof *out->subpatches);
    out->nvertices = 6 * m->count;
    out->vertices = sc_alloc((size_t)(out->nvertices ? out->nvertices : 1),
                             sizeof *out->vertices);
    out->nindices = 24 * m->count;
    out->indices = sc_alloc((size_t)(out->nindices ? out->nindices : 1), sizeof(uint32_t));
    out->npatches = m->count;
    out->nsurfaces = 1;
    out->surfaces = sc_alloc(1, sizeof *out->surfaces);
    out->surfaces[0] = (sc_hull_range){0, m->count, 0, out->nvertices, 0, out->nindices,
                                       m->count};
    for (int p = 0; p < m->count; p++) {
        double tri[6], lo = INFINITY, hi = -INFINITY;
        sc_tri_mesh_domain(m, p, tri);
        for (int k = 0; k < m->ncoef; k++) {
            double z = m->coef[(size_t)p * (size_t)m->ncoef + (size_t)k];
            lo = fmin(lo, z);
            hi = fmax(hi, z);
        }
        /* A flat patch still gets a slab, so that its faces rasterise. */
        double pad = 1e-4 * fmax(hi - lo, fmax(m->hx, m->hy));
        lo -= pad;
        hi += pad;
        sc_subpatch *s = &out->subpatches[p];
        *s = (sc_subpatch){.surface = 0, .patch = p, .local = {0, 1, 0, 1},
                           .domain = {0, 1, 0, 1}, .first_vertex = 6 * p, .vertex_count = 6,
                           .first_index = 24 * p, .index_count = 24};
        s->lo[2] = lo;
        s->hi[2] = hi;
        s->lo[0] = fmin(tri[0], fmin(tri[2], tri[4]));
        s->hi[0] = fmax(tri[0], fmax(tri[2], tri[4]));
        s->lo[1] = fmin(tri[1], fmin(tri[3], tri[5]));
        s->hi[1] = fmax(tri[1], fmax(tri[3], tri[5]));
        for (int v = 0; v < 6; v++) {
            sc_hull_vertex *hv = &out->vertices[6 * p + v];
            *hv = (sc_hull_vertex){.pos = {tri[2 * (v % 3)], tri[2 * (v % 3) + 1],
                                           v < 3 ? lo : hi}};
        }
        for (int k = 0; k < 24; k++)
            out->indices[24 * p + k] = (uint32_t)(6 * p) + faces[k];
    }
}

int sc_tri_manhattan(const sc_tri_mesh *m, int patch, const double eye[3])
{
    int ei = (int)floor((eye[0] - m->x0) / m->hx), ej = (int)floor((eye[1] - m->y0) / m->hy);
    ei = ei < 0 ? 0 : ei >= m->nx ? m->nx - 1 : ei;
    ej = ej < 0 ? 0 : ej >= m->ny ? m->ny - 1 : ej;
    int q = patch / 2, i = q % m->nx, j = q / m->nx;
    return abs(i - ei) + abs(j - ej);
}

void sc_tri_key(const sc_tri_mesh *m, const scg_key *like, scg_key *out)
{
    scg_key_default(out, SCG_PATCH_TRIANGLE, m->degree, m->degree);
    out->start = SC_START_SECURE;
    out->max_iters = like->max_iters;
    out->tol_milli = like->tol_milli;
    out->ert = like->ert;
    out->outputs = like->outputs;
}
