/* iges_faces.c — the model-space (3D) side of IGES trim loops: the curves
 * of a 142's CPTR, of a 141's model-space curves, of the 504 edges a 508
 * loop uses, in the order and direction of the loop and in the surface's
 * object space, ready to be projected into its parameter space
 * (sc_project_loop) or mapped onto a plane. */
#include "iges_local.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int iges_invert(const double m[12], double out[12])
{
    double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
           i = m[10];
    double det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    if (!(fabs(det) > 1e-300))
        return SC_FAIL;
    double inv[9] = {(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det,
                     (f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det,
                     (d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det};
    for (int r = 0; r < 3; r++) {
        for (int k = 0; k < 3; k++)
            out[4 * r + k] = inv[3 * r + k];
        out[4 * r + 3] = -(inv[3 * r] * m[3] + inv[3 * r + 1] * m[7] + inv[3 * r + 2] * m[11]);
    }
    return SC_OK;
}

static double end_distance(const sc_curve *a, int ia, const sc_curve *b, int ib)
{
    const double *p = a->cp + 4 * ia, *q = b->cp + 4 * ib;
    double s = 0;
    for (int d = 0; d < 3; d++)
        s += (p[d] / p[3] - q[d] / q[3]) * (p[d] / p[3] - q[d] / q[3]);
    return sqrt(s);
}

/* As iges_orient_chain, in 3D: members written against the chain turned. */
static void orient_chain3(curve_list *l)
{
    if (l->n < 2)
        return;
    sc_curve *c = l->items;
    int last0 = c[0].ncp - 1, last1 = c[1].ncp - 1;
    double fwd = fmin(end_distance(&c[0], last0, &c[1], 0), end_distance(&c[0], last0, &c[1], last1));
    double rev = fmin(end_distance(&c[0], 0, &c[1], 0), end_distance(&c[0], 0, &c[1], last1));
    if (rev < fwd)
        sc_curve_reverse(&c[0]);
    for (int i = 1; i < l->n; i++) {
        int prev_end = c[i - 1].ncp - 1;
        if (end_distance(&c[i - 1], prev_end, &c[i], c[i].ncp - 1) <
            end_distance(&c[i - 1], prev_end, &c[i], 0))
            sc_curve_reverse(&c[i]);
    }
}

/* The model-space curve entity c, reversed or not, appended in object
 * space. Curves of zero length (degenerate edges at a pole) are left out:
 * the projection joins their ends in (u, v). */
static int add_model_curve(reader *r, int c, const double to_obj[12], int reversed,
                           curve_list *out)
{
    int first = out->n;
    int status = iges_trim_curves(r, c, to_obj, reversed, out, 0);
    if (status)
        return status;
    int kept = first;
    for (int i = first; i < out->n; i++) {
        sc_curve *k = &out->items[i];
        double size = 0;
        for (int j = 1; j < k->ncp; j++)
            size = fmax(size, end_distance(k, 0, k, j));
        if (size > 0)
            out->items[kept++] = *k;
        else
            sc_curve_free(k);
    }
    out->n = kept;
    return SC_OK;
}

/* 504 edge list entry `ndx` (1-based): its model-space curve. */
static int edge_curve(reader *r, int list, int ndx, int *curve)
{
    params p;
    int n;
    if (iges_params(r, list, &p) || iges_need(r, &p, 1) || iges_count(r, &p, 1, 5, &n))
        return SC_FAIL;
    if (ndx < 1 || ndx > n)
        return iges_fail(r, list, 0, "edge index %d outside its %d edges", ndx, n);
    if (iges_pointer(r, &p, 2 + 5 * (ndx - 1), curve))
        return SC_FAIL;
    if (*curve < 0)
        return iges_fail(r, list, 0, "edge %d has no curve", ndx);
    return SC_OK;
}

int iges_loop_model(reader *r, int e, const double to_obj[12], curve_list *out)
{
    params p;
    if (iges_params(r, e, &p))
        return SC_FAIL;
    int status = SC_OK;
    out->dim = 3;
    switch (r->ent[e].type) {
    case 142: {
        int cptr;
        if (iges_need(r, &p, 4) || iges_pointer(r, &p, 4, &cptr))
            return SC_FAIL;
        if (cptr < 0)
            return LOOP_NO_PCURVE;
        status = add_model_curve(r, cptr, to_obj, 0, out);
        break;
    }
    case 141: {
        int n, at = 5;
        if (iges_need(r, &p, 4) || iges_count(r, &p, 4, 3, &n))
            return SC_FAIL;
        for (int i = 0; i < n && status == SC_OK; i++) {
            int crv, sense, k;
            if (iges_need(r, &p, at + 2) || iges_pointer(r, &p, at, &crv) ||
                iges_int(r, &p, at + 1, &sense) || iges_count(r, &p, at + 2, 1, &k))
                return SC_FAIL;
            if (crv < 0)
                return LOOP_NO_PCURVE;
            status = add_model_curve(r, crv, to_obj, sense == 2, out);
            at += 3 + k;
        }
        break;
    }
    case 508: {
        int n, at = 2;
        if (iges_need(r, &p, 1) || iges_count(r, &p, 1, 5, &n))
            return SC_FAIL;
        for (int i = 0; i < n && status == SC_OK; i++) {
            int type, list, ndx, orient, k, crv;
            if (iges_need(r, &p, at + 4) || iges_int(r, &p, at, &type) ||
                iges_pointer(r, &p, at + 1, &list) || iges_int(r, &p, at + 2, &ndx) ||
                iges_int(r, &p, at + 3, &orient) || iges_count(r, &p, at + 4, 2, &k))
                return SC_FAIL;
            at += 5 + 2 * k;
            if (type != 0)
                continue; /* a vertex: a pole, joined in (u, v) */
            if (list < 0 || r->ent[list].type != 504)
                return iges_fail(r, e, iges_line(r, &p, at + 1), "edge %d: not a 504 edge "
                                 "list", i + 1);
            status = edge_curve(r, list, ndx, &crv);
            if (status == SC_OK)
                status = add_model_curve(r, crv, to_obj, orient == 0, out);
        }
        break;
    }
    default:
        return LOOP_NO_PCURVE;
    }
    if (status == SC_OK && out->n == 0)
        return LOOP_NO_PCURVE;
    if (status == SC_OK)
        orient_chain3(out);
    return status;
}
