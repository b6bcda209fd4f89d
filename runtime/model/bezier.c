/* bezier.c — de Casteljau subdivision (bezier.h). One triangle scheme for
 * curves, polynomial coefficients and patch rows, so that every consumer
 * computes a split with the same operations in the same order: the trim
 * pieces of the reference and of the GPU, and the hulls and the patches
 * they bound, agree to the bit. */
#include "bezier.h"

#include <stdlib.h>
#include <string.h>

#include "nurbs_local.h"

/* Doubles held on the stack before the triangle allocates: degree 63 with
 * 4 doubles per point, the highest patch degree the reference takes, so
 * its subdivision never allocates. */
enum { STACK_DOUBLES = 4 * 64 };

void sc_bezier_split(const double *cp, int degree, int dim, int stride, double t,
                     double *left, double *right)
{
    double stack[STACK_DOUBLES];
    size_t need = (size_t)(degree + 1) * (size_t)dim;
    double *work = scratch(stack, STACK_DOUBLES, need);
    for (int i = 0; i <= degree; i++)
        memcpy(work + (size_t)i * (size_t)dim, cp + (size_t)i * (size_t)stride,
               sizeof(double) * (size_t)dim);
    /* After round r, work[0] is point r of the left half and work[degree-r]
     * point degree-r of the right half. */
    for (int r = 0; r <= degree; r++) {
        if (r > 0)
            for (int i = 0; i <= degree - r; i++)
                for (int c = 0; c < dim; c++)
                    work[i * dim + c] = (1.0 - t) * work[i * dim + c] + t * work[(i + 1) * dim + c];
        if (left)
            memcpy(left + (size_t)r * (size_t)stride, work, sizeof(double) * (size_t)dim);
        if (right)
            memcpy(right + (size_t)(degree - r) * (size_t)stride, work + (degree - r) * dim,
                   sizeof(double) * (size_t)dim);
    }
    scratch_release(work, stack);
}

void sc_bezier_point(const double *cp, int degree, int dim, int stride, double t, double *out)
{
    double stack[STACK_DOUBLES];
    size_t need = (size_t)(degree + 1) * (size_t)dim;
    double *left = scratch(stack, STACK_DOUBLES, need);
    sc_bezier_split(cp, degree, dim, dim, t, left, NULL);
    memcpy(out, left + (size_t)degree * (size_t)dim, sizeof(double) * (size_t)dim);
    scratch_release(left, stack);
}

void sc_bezier_grid_split(const double *cp, int deg_u, int deg_v, int dir, double t,
                          double *lo, double *hi)
{
    int nu = deg_u + 1, nv = deg_v + 1;
    int lines = dir == 0 ? nv : nu;
    int step = dir == 0 ? 4 : 4 * nu;      /* between points of a line */
    int line_step = dir == 0 ? 4 * nu : 4; /* between lines */
    for (int l = 0; l < lines; l++) {
        size_t off = (size_t)l * (size_t)line_step;
        sc_bezier_split(cp + off, dir == 0 ? deg_u : deg_v, 4, step, t, lo ? lo + off : NULL,
                        hi ? hi + off : NULL);
    }
}
