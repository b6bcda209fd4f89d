/* camera.c — the shared pinhole camera (camera.h): parsing and printing the
 * --camera syntax, the default view that frames a scene, primary rays, the
 * pixel footprint and the matching OpenGL matrices. Every renderer derives
 * its rays from here, so that a CPU reference and a GPU image of the same
 * camera agree pixel for pixel. */
#include "camera.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double pi = 3.14159265358979323846;

/* The view direction of the default camera: a 3/4 view from the front
 * left, somewhat above, with +z up. */
static const double default_direction[3] = {1.0, -2.0, 1.2};
static const double default_fovy_deg = 30.0;

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    double r[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                   a[0] * b[1] - a[1] * b[0]};
    memcpy(out, r, sizeof r);
}

static void normalize3(double v[3])
{
    double len = sqrt(dot3(v, v));
    if (len > 0) {
        v[0] /= len;
        v[1] /= len;
        v[2] /= len;
    }
}

int sc_camera_parse(const char *text, sc_camera *cam, sc_error *err)
{
    double values[10];
    const char *p = text;
    int n = 7;
    for (int k = 0; k < n; k++) {
        char *end;
        errno = 0;
        values[k] = strtod(p, &end);
        if (end == p || errno == ERANGE || !isfinite(values[k]))
            return sc_fail(err, NULL, 0,
                           "camera '%s': value %d is not a finite number "
                           "(expected EX,EY,EZ,TX,TY,TZ,FOVY[,UX,UY,UZ])", text, k + 1);
        p = end;
        while (*p == ' ')
            p++;
        if (k == 6 && *p == ',')
            n = 10; /* an up vector follows */
        if (k < n - 1) {
            if (*p != ',')
                return sc_fail(err, NULL, 0,
                               "camera '%s': expected 7 comma-separated numbers "
                               "EX,EY,EZ,TX,TY,TZ,FOVY, or 10 with UX,UY,UZ", text);
            p++;
        }
    }
    if (*p != '\0')
        return sc_fail(err, NULL, 0, "camera '%s': unexpected text after the %d numbers",
                       text, n);
    if (!(values[6] > 0.0 && values[6] < 180.0))
        return sc_fail(err, NULL, 0, "camera '%s': field of view %g is not in (0, 180) degrees",
                       text, values[6]);
    if (values[0] == values[3] && values[1] == values[4] && values[2] == values[5])
        return sc_fail(err, NULL, 0, "camera '%s': eye and target are the same point", text);
    if (n == 10 && values[7] == 0 && values[8] == 0 && values[9] == 0)
        return sc_fail(err, NULL, 0, "camera '%s': the up vector is zero", text);
    memcpy(cam->eye, values, 3 * sizeof(double));
    memcpy(cam->target, values + 3, 3 * sizeof(double));
    cam->fovy_deg = values[6];
    if (n == 10)
        memcpy(cam->up, values + 7, 3 * sizeof(double));
    return SC_OK;
}

static int has_up(const sc_camera *cam)
{
    return cam->up[0] != 0 || cam->up[1] != 0 || cam->up[2] != 0;
}

void sc_camera_format(const sc_camera *cam, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", cam->eye[0],
                     cam->eye[1], cam->eye[2], cam->target[0], cam->target[1], cam->target[2],
                     cam->fovy_deg);
    if (has_up(cam) && n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, ",%.17g,%.17g,%.17g", cam->up[0], cam->up[1],
                 cam->up[2]);
}

/* The default direction {1, -2, 1.2} is given for +z up; for another up it
 * is turned so that its third component runs along that up (and x stays
 * x where it can), so that a y-up model is seen from the front, above. */
static void default_direction_for(const sc_camera *cam, double dir[3])
{
    double e3[3] = {0, 0, 1}, e1[3] = {1, 0, 0}, e2[3];
    if (has_up(cam)) {
        memcpy(e3, cam->up, sizeof e3);
        normalize3(e3);
        double ref[3] = {1, 0, 0};
        if (fabs(e3[0]) > 0.9)
            ref[0] = 0, ref[1] = 1;
        double d = dot3(ref, e3);
        for (int k = 0; k < 3; k++)
            e1[k] = ref[k] - d * e3[k];
        normalize3(e1);
    }
    cross3(e3, e1, e2);
    for (int k = 0; k < 3; k++)
        dir[k] = default_direction[0] * e1[k] + default_direction[1] * e2[k] +
                 default_direction[2] * e3[k];
}

void sc_camera_default(const sc_scene *scene, sc_camera *cam)
{
    memset(cam->up, 0, sizeof cam->up);
    double lo[3], hi[3];
    int any = scene && sc_scene_view_bounds(scene, lo, hi);
    sc_camera_default_box(any ? lo : NULL, any ? hi : NULL, NULL, cam);
}

void sc_camera_default_box(const double box_lo[3], const double box_hi[3], const double from[3],
                           sc_camera *cam)
{
    double lo[3] = {-1.0, -1.0, -1.0}, hi[3] = {1.0, 1.0, 1.0};
    double dir[3];
    if (from && (from[0] != 0 || from[1] != 0 || from[2] != 0))
        memcpy(dir, from, sizeof dir);
    else
        default_direction_for(cam, dir);
    normalize3(dir);
    cam->fovy_deg = default_fovy_deg;
    /* Nothing to frame: the unit cube around the origin. */
    if (box_lo && box_hi) {
        memcpy(lo, box_lo, sizeof lo);
        memcpy(hi, box_hi, sizeof hi);
    }
    double radius = 0.0;
    for (int k = 0; k < 3; k++) {
        cam->target[k] = 0.5 * (lo[k] + hi[k]);
        radius += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    radius = 0.5 * sqrt(radius);
    if (!(radius > 0.0))
        radius = 1.0;
    /* The bounding sphere touches the top and bottom of the view. */
    double distance = radius / sin(0.5 * default_fovy_deg * pi / 180.0);
    for (int k = 0; k < 3; k++)
        cam->eye[k] = cam->target[k] + distance * dir[k];
}

void sc_camera_frame(const sc_camera *cam, double forward[3], double right[3], double up[3])
{
    double f[3] = {cam->target[0] - cam->eye[0], cam->target[1] - cam->eye[1],
                   cam->target[2] - cam->eye[2]};
    normalize3(f);
    /* The camera's up; by default (or when the view runs along it) +z up,
     * unless the view is (nearly) along z: then +y. */
    double world_up[3] = {0.0, 0.0, 1.0};
    double given[3] = {cam->up[0], cam->up[1], cam->up[2]};
    normalize3(given);
    if (has_up(cam) && fabs(dot3(f, given)) < 1.0 - 1e-9)
        memcpy(world_up, given, sizeof world_up);
    else if (fabs(f[2]) > 1.0 - 1e-9)
        world_up[1] = 1.0, world_up[2] = 0.0;
    double r[3], u[3];
    cross3(f, world_up, r);
    normalize3(r);
    cross3(r, f, u);
    normalize3(u);
    memcpy(forward, f, sizeof f);
    memcpy(right, r, sizeof r);
    memcpy(up, u, sizeof u);
}

void sc_camera_ray(const sc_camera *cam, double x, double y, double dir[3])
{
    double f[3], r[3], u[3];
    sc_camera_frame(cam, f, r, u);
    double half_h = tan(0.5 * cam->fovy_deg * pi / 180.0);
    double aspect = (double)cam->width / (double)cam->height;
    double sx = (2.0 * x / cam->width - 1.0) * half_h * aspect;
    double sy = (1.0 - 2.0 * y / cam->height) * half_h;
    for (int k = 0; k < 3; k++)
        dir[k] = f[k] + sx * r[k] + sy * u[k];
    normalize3(dir);
}

double sc_camera_footprint(const sc_camera *cam, double t)
{
    return t * 2.0 * tan(0.5 * cam->fovy_deg * pi / 180.0) / cam->height;
}

void sc_camera_gl_matrices(const sc_camera *cam, double znear, double zfar, float view[16],
                           float proj[16])
{
    double f[3], r[3], u[3];
    sc_camera_frame(cam, f, r, u);
    /* View: rows right, up, -forward; translation moves the eye to 0. */
    double m[16] = {0};
    for (int k = 0; k < 3; k++) {
        m[k * 4 + 0] = r[k];
        m[k * 4 + 1] = u[k];
        m[k * 4 + 2] = -f[k];
    }
    m[12] = -dot3(r, cam->eye);
    m[13] = -dot3(u, cam->eye);
    m[14] = dot3(f, cam->eye);
    m[15] = 1.0;
    for (int k = 0; k < 16; k++)
        view[k] = (float)m[k];

    double cot = 1.0 / tan(0.5 * cam->fovy_deg * pi / 180.0);
    double aspect = (double)cam->width / (double)cam->height;
    double p[16] = {0};
    p[0] = cot / aspect;
    p[5] = cot;
    p[10] = (zfar + znear) / (znear - zfar);
    p[11] = -1.0;
    p[14] = 2.0 * zfar * znear / (znear - zfar);
    for (int k = 0; k < 16; k++)
        proj[k] = (float)p[k];
}
