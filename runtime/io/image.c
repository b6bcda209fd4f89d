/* image.c — 8-bit RGB(A) images and their PNG files (image.h), through
 * libpng. Writing goes to a temporary file in the target's folder that is
 * renamed at the end, so a failed write never leaves a partial PNG. */
#include "image.h"

#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "envelope.h"

void sc_image_alloc(sc_image *img, int width, int height, int channels)
{
    img->width = width;
    img->height = height;
    img->channels = channels;
    img->pixels = sc_alloc((size_t)width * (size_t)height, (size_t)channels);
}

void sc_image_free(sc_image *img)
{
    free(img->pixels);
    memset(img, 0, sizeof *img);
}

/* Encodes img into an open file; libpng reports errors by longjmp. */
static int write_png_stream(FILE *f, const sc_image *img)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_write_struct(&png, &info);
        return SC_FAIL;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return SC_FAIL;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, 8,
                 img->channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    size_t stride = (size_t)img->width * (size_t)img->channels;
    for (int y = 0; y < img->height; y++)
        png_write_row(png, img->pixels + (size_t)y * stride);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return SC_OK;
}

int sc_png_write(const char *path, const sc_image *img, sc_error *err)
{
    if (img->width <= 0 || img->height <= 0 || (img->channels != 3 && img->channels != 4))
        return sc_fail(err, path, 0, "cannot write a %dx%d image with %d channels", img->width,
                       img->height, img->channels);
    sc_out_file out;
    if (sc_out_open(&out, path, err))
        return SC_FAIL;
    if (write_png_stream(out.f, img) != SC_OK) {
        sc_out_abandon(&out);
        return sc_fail(err, path, 0, "writing the PNG failed (disk full?)");
    }
    return sc_out_commit(&out, err);
}

int sc_png_read(const char *path, sc_image *img, sc_error *err)
{
    memset(img, 0, sizeof *img);
    FILE *f = fopen(path, "rb");
    if (!f)
        return sc_fail(err, path, 0, "cannot open");
    unsigned char sig[8];
    if (fread(sig, 1, 8, f) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
        fclose(f);
        return sc_fail(err, path, 0, "not a PNG file");
    }
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        return sc_fail(err, path, 0, "libpng could not start");
    }
    /* volatile: modified between setjmp and a possible longjmp. */
    unsigned char *volatile pixels = NULL;
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        free(pixels);
        return sc_fail(err, path, 0, "corrupt or truncated PNG");
    }
    png_init_io(png, f);
    png_set_sig_bytes(png, 8);
    png_read_info(png, info);
    int color = png_get_color_type(png, info);
    /* Bring every PNG to 8-bit RGB or RGBA. */
    png_set_strip_16(png);
    png_set_packing(png);
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY || color == PNG_COLOR_TYPE_GRAY_ALPHA)
        png_set_gray_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    png_read_update_info(png, info);
    int width = (int)png_get_image_width(png, info);
    int height = (int)png_get_image_height(png, info);
    int channels = png_get_channels(png, info);
    if (channels != 3 && channels != 4)
        png_error(png, "unsupported channel count");
    /* The size comes from a 33-byte header: checked, and memory that is not
     * there is an error, not an abort. */
    if ((long long)width * height > SC_MAX_IMAGE_PIXELS ||
        !(pixels = sc_try_alloc((size_t)width * (size_t)height, (size_t)channels))) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(f);
        if ((long long)width * height > SC_MAX_IMAGE_PIXELS)
            return sc_fail(err, path, 0, "image of %d x %d pixels: more than the limit "
                           "(docs/limits.md)", width, height);
        return sc_fail_oom(err, path, 0, (size_t)width * (size_t)height, (size_t)channels,
                           "the pixels");
    }
    size_t stride = (size_t)width * (size_t)channels;
    for (int y = 0; y < height; y++)
        png_read_row(png, pixels + (size_t)y * stride, NULL);
    png_read_end(png, NULL);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    img->width = width;
    img->height = height;
    img->channels = channels;
    img->pixels = pixels;
    return SC_OK;
}
