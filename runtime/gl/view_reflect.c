/* view_reflect.c — reflection lines (seed 004, Figs. 15–17): the view
 * direction mirrored in the exact normal of the AOVs looks up an
 * environment of parallel light stripes at infinity. A line of the image
 * follows a constant angle of the mirrored ray, so it depends on the
 * normal: where the surface is only C0 the lines break, where it is C1
 * they kink, and they bend smoothly only where it is C2. Drawn from the
 * AOVs like the normal view, so every surface kind gets it. */
#include <math.h>

#include "view_legend.h"

/* Stripes per half turn of the mirrored ray around the stripe axis. */
enum { STRIPES = 14 };

void sc_view_reflect(const sc_aov *aov, sc_image *img)
{
    /* Stripes parallel to a horizontal axis at 30 degrees to x: neither
     * family of grid lines (x, y) nor the diagonals of a type-1 mesh runs
     * along them, so no patch edge hides its kinks. b and c span the
     * plane normal to that axis. */
    const double b[3] = {-0.5, 0.8660254037844386, 0}, c[3] = {0, 0, 1};
    int n = aov->width * aov->height;
    for (int p = 0; p < n; p++) {
        unsigned char *px = img->pixels + 4 * p;
        px[3] = 255;
        if (aov->surface[p] < 0) {
            px[0] = px[1] = px[2] = 0;
            continue;
        }
        const float *q = aov->point + 3 * p, *nv = aov->normal + 3 * p;
        double d[3], dn = 0, len = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = q[k] - aov->camera.eye[k];
            len += d[k] * d[k];
        }
        len = sqrt(len);
        for (int k = 0; k < 3; k++)
            dn += (d[k] /= len > 0 ? len : 1) * nv[k];
        double r[3];
        for (int k = 0; k < 3; k++)
            r[k] = d[k] - 2 * dn * nv[k];
        /* Angle of the mirrored ray around the axis, in (-pi, pi]. */
        double rb = r[0] * b[0] + r[1] * b[1] + r[2] * b[2];
        double rc = r[0] * c[0] + r[1] * c[1] + r[2] * c[2];
        double phase = atan2(rb, rc) * STRIPES / M_PI;
        /* Sharp black and white stripes, their edges softened over about a
         * pixel's change of phase so they do not alias. */
        double s = cos(M_PI * phase);
        double x = fmin(fmax(0.5 + 2.5 * s, 0), 1);
        unsigned char v = (unsigned char)lround(30 + 215 * x);
        px[0] = px[1] = px[2] = v;
    }
}
