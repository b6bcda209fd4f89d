/* nurbs_local.h — small helpers shared by the files of the NURBS core
 * (nurbs.c, nurbs_ops.c, bezier.c, trim.c); not part of its API. */
#ifndef SC_NURBS_LOCAL_H
#define SC_NURBS_LOCAL_H

#include <stdlib.h>

#include "sc_base.h"

/* Degrees up to which evaluation and the operations work in stack buffers. */
enum { MAX_STACK_DEGREE = 32, STACK_ORDER = MAX_STACK_DEGREE + 1 };

/* Scratch memory: a stack array when it is large enough, else the heap, so
 * that the common low degrees never allocate. */
static inline double *scratch(double *stack_buf, size_t stack_len, size_t need)
{
    return need <= stack_len ? stack_buf : sc_alloc(need, sizeof(double));
}

static inline void scratch_release(double *buf, const double *stack_buf)
{
    if (buf != stack_buf)
        free(buf);
}

/* C(n, k) in double, exact while it fits in 53 bits. */
static inline double binomial(int n, int k)
{
    double b = 1.0;
    for (int i = 1; i <= k; i++)
        b = b * (n - k + i) / i;
    return b;
}

#endif
