/* aov.h — per-pixel render outputs ("arbitrary output variables"): what
 * every renderer (the CPU reference and the GPU path) writes and `diff`
 * compares. The file keeps size and camera, so a comparison needs nothing
 * else. Format: docs/aov-format.md. */
#ifndef SC_AOV_H
#define SC_AOV_H

#include <stddef.h>
#include <stdint.h>

#include "camera.h"

typedef struct sc_aov {
    int width, height;
    sc_camera camera;     /* camera.width/height equal width/height */
    int has_iters;        /* iters is filled (GPU iterative methods) */
    /* Per pixel, row 0 at the top, index j * width + i: */
    int32_t *surface;     /* surface id, -1 for a miss */
    float *uv;            /* 2 per pixel: (u, v) in the surface's domain */
    float *t;             /* distance from the eye along the unit ray */
    float *point;         /* 3 per pixel: world-space hit point */
    float *normal;        /* 3 per pixel: unit world normal facing the viewer */
    float *iters;         /* iteration count, NULL unless has_iters */
} sc_aov;

/* Allocates all channels for cam->width × cam->height, every pixel a miss. */
void sc_aov_alloc(sc_aov *aov, const sc_camera *cam, int has_iters);
void sc_aov_free(sc_aov *aov);
/* Written to a temporary file and renamed: nothing half-written on failure. */
int sc_aov_write(const char *path, const sc_aov *aov, sc_error *err);
/* Checks the data's size against the header before allocating anything;
 * every failure (out of memory included) is an error, not an abort. */
int sc_aov_read(const char *path, sc_aov *aov, sc_error *err);
/* The same from memory; `name` is used in messages. */
int sc_aov_read_mem(const void *data, size_t size, const char *name, sc_aov *aov, sc_error *err);

#endif
