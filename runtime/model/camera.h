/* camera.h — the one view description every rendering command shares
 * (BRIEF "Views are shared"): a pinhole camera given as eye, target and
 * vertical field of view, +z up unless the view is along z (then +y), pixel
 * (i, j) centred at (i + 0.5, j + 0.5), row 0 at the top. */
#ifndef SC_CAMERA_H
#define SC_CAMERA_H

#include "scene.h"

typedef struct sc_camera {
    double eye[3];
    double target[3];
    double fovy_deg;      /* vertical field of view in degrees, (0, 180) */
    int width, height;    /* image size in pixels */
    double up[3];         /* the up vector; all zero: +z, or +y when the view
                             is along z. When the view runs along it, the
                             zero rule is used instead */
} sc_camera;

/* Parses "EX,EY,EZ,TX,TY,TZ,FOVY" or "…,FOVY,UX,UY,UZ" (with an up
 * vector) into cam (size untouched; up untouched by the 7-number form). */
int sc_camera_parse(const char *text, sc_camera *cam, sc_error *err);
/* Writes the same syntax with %.17g, so it parses back exactly: 7 numbers,
 * or 10 when cam->up is set. */
void sc_camera_format(const sc_camera *cam, char *buf, size_t size);
/* A view that frames the scene's bounding box (size untouched, up the
 * default): a 3/4 view from the front left, somewhat above. */
void sc_camera_default(const sc_scene *scene, sc_camera *cam);
/* The same framing of the box [lo, hi] (sc_scene_view_bounds; NULL: the
 * unit cube around the origin, as for an empty scene) for cam->up (set it
 * first: "above" is along it), seen from direction `from` (towards the eye
 * from the target, any length; NULL or zero: the 3/4 view). */
void sc_camera_default_box(const double lo[3], const double hi[3], const double from[3],
                           sc_camera *cam);

/* The box the default view frames (view_bounds.c): control points of
 * untrimmed surfaces, the kept region of trimmed ones. 0 for an empty
 * scene. */
int sc_scene_view_bounds(const sc_scene *scene, double lo[3], double hi[3]);

/* Orthonormal camera frame: forward (towards the target), right, up. */
void sc_camera_frame(const sc_camera *cam, double forward[3], double right[3],
                     double up[3]);
/* Ray through the image point (x, y) in pixels (pixel centres at +0.5, y
 * down from the top row): origin = eye, dir normalised. */
void sc_camera_ray(const sc_camera *cam, double x, double y, double dir[3]);
/* Size of one pixel at distance t along a ray: t · 2 tan(fovy/2) / height. */
double sc_camera_footprint(const sc_camera *cam, double t);
/* Column-major OpenGL view and projection matrices for the same view. */
void sc_camera_gl_matrices(const sc_camera *cam, double znear, double zfar,
                           float view[16], float proj[16]);

#endif
