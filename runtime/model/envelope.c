/* envelope.c — the per-file geometry budget of envelope.h: readers charge what
 * they are about to allocate, so that a file expanding without bound fails
 * at the point of the file that asks for too much. */
#include "envelope.h"

size_t sc_curve_bytes(int dim, int degree, int ncp)
{
    size_t n = ncp > 0 ? (size_t)ncp : 0;
    return sizeof(sc_curve) + sizeof(double) * (n + (size_t)(degree > 0 ? degree : 0) + 1) +
           sizeof(double) * n * (size_t)(dim + 1);
}

size_t sc_surface_bytes(int deg_u, int deg_v, int nu, int nv)
{
    size_t u = nu > 0 ? (size_t)nu : 0, v = nv > 0 ? (size_t)nv : 0;
    return sizeof(sc_surface) + sizeof(double) * (u + v + (size_t)deg_u + (size_t)deg_v + 2) +
           sizeof(double) * 4 * u * v;
}

int sc_budget_charge(sc_budget *b, size_t bytes, const char *what, const char *name, int line,
                     sc_error *err)
{
    size_t limit = b->limit ? b->limit : SC_GEOMETRY_BUDGET;
    if (bytes > limit - b->used)
        return sc_fail(err, name, line, "%s: the file expands to more than %zu MiB of geometry "
                       "(the limit per file; docs/limits.md)", what, limit >> 20);
    b->used += bytes;
    return SC_OK;
}
