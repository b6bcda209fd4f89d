/* nurbs_util.h — builders and distances shared by the NURBS core's tests
 * (nurbs_util.c). */
#ifndef SC_TEST_NURBS_UTIL_H
#define SC_TEST_NURBS_UTIL_H

#include "nurbs.h"

#define R2 0.70710678118654752440 /* √2 / 2 */

void make_curve(sc_curve *c, int dim, int degree, int ncp, const double *knots,
                const double *cp, const double *w);
void random_knots(unsigned long long *rng, int degree, int ncp, double *knots);
void random_curve(unsigned long long *rng, int dim, int degree, int ncp, sc_curve *c);
void random_surface(unsigned long long *rng, int deg_u, int deg_v, int nu, int nv,
                    sc_surface *s);
void make_sphere(sc_surface *s);
double dist3(const double *a, const double *b);
double len3(const double *a);
double curve_distance(const sc_curve *x, const sc_curve *y, double a, double b,
                      unsigned long long *rng);
double surface_distance(const sc_surface *x, const sc_surface *y, double u0, double u1,
                        double v0, double v1, unsigned long long *rng);

#endif
