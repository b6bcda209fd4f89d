/* newton.h — Newton's method for the intersection skeleton (newton.c). */
#ifndef SCG_NEWTON_H
#define SCG_NEWTON_H

#include "intersect.h"

/* The whole method: variables from uv0, then the key's maximum iterations
 * of scg_newton_step. */
void scg_method_newton(scg_isect *c, scg_value uv0, scg_value behind);

/* One Newton step from uv_var (a step function for scg_isect_repeat):
 * updates uv, iters and done, and converged_var when the caller set one. */
void scg_newton_step(scg_isect *c, void *user);

#endif
