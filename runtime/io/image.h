/* image.h — 8-bit RGB(A) images and PNG files (libpng). */
#ifndef SC_IMAGE_H
#define SC_IMAGE_H

#include "sc_base.h"

typedef struct sc_image {
    int width, height;
    int channels;             /* 3 (RGB) or 4 (RGBA) */
    unsigned char *pixels;    /* row 0 at the top */
} sc_image;

void sc_image_alloc(sc_image *img, int width, int height, int channels);
void sc_image_free(sc_image *img);
/* Written to a temporary file and renamed: nothing half-written on failure. */
int sc_png_write(const char *path, const sc_image *img, sc_error *err);
int sc_png_read(const char *path, sc_image *img, sc_error *err);

#endif
