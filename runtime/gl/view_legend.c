/* view_legend.c — the debug views' background and legend (view_legend.h).
 * The legend is drawn on the CPU after read-back with a 3×5 pixel font:
 * the programs stay free of layout, and every view gets the same strip. */
#include "view_legend.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* 3×5 glyphs, one row per 3-bit number (bit 2 the left column). */
static const struct {
    char c;
    unsigned char rows[5];
} glyphs[] = {
    {'0', {7, 5, 5, 5, 7}}, {'1', {2, 6, 2, 2, 7}}, {'2', {7, 1, 7, 4, 7}},
    {'3', {7, 1, 3, 1, 7}}, {'4', {5, 5, 7, 1, 1}}, {'5', {7, 4, 7, 1, 7}},
    {'6', {7, 4, 7, 5, 7}}, {'7', {7, 1, 1, 2, 2}}, {'8', {7, 5, 7, 5, 7}},
    {'9', {7, 5, 7, 1, 7}}, {'.', {0, 0, 0, 0, 2}}, {'+', {0, 2, 7, 2, 0}},
    {'-', {0, 0, 7, 0, 0}}, {'=', {0, 7, 0, 7, 0}}, {'A', {2, 5, 7, 5, 5}},
    {'C', {7, 4, 4, 4, 7}}, {'D', {6, 5, 5, 5, 6}}, {'E', {7, 4, 6, 4, 7}},
    {'F', {7, 4, 6, 4, 4}}, {'H', {5, 5, 7, 5, 5}}, {'I', {7, 2, 2, 2, 7}},
    {'L', {4, 4, 4, 4, 7}}, {'M', {5, 7, 7, 5, 5}}, {'N', {6, 5, 5, 5, 5}},
    {'O', {7, 5, 5, 5, 7}}, {'P', {7, 5, 7, 4, 4}}, {'R', {6, 5, 6, 5, 5}},
    {'S', {7, 4, 7, 1, 7}}, {'T', {7, 2, 2, 2, 2}}, {'U', {5, 5, 5, 5, 7}},
    {'V', {5, 5, 5, 5, 2}}, {'W', {5, 5, 7, 7, 5}}, {'X', {5, 5, 2, 5, 5}},
    {'Y', {5, 5, 2, 2, 2}}, {'Z', {7, 1, 2, 4, 7}}, {'(', {1, 2, 2, 2, 1}},
    {')', {4, 2, 2, 2, 4}}, {',', {0, 0, 0, 2, 4}}, {'/', {1, 1, 2, 4, 4}},
    {':', {0, 2, 0, 2, 0}},
};

enum { STRIP = 14, BAR_W = 64, BAR_H = 5 };

static void put(sc_image *img, int x, int y, const unsigned char rgb[3])
{
    if (x < 0 || y < 0 || x >= img->width || y >= img->height)
        return;
    unsigned char *p = img->pixels + ((size_t)y * (size_t)img->width + (size_t)x) * 4;
    memcpy(p, rgb, 3);
    p[3] = 255;
}

/* Writes text at (x, y) (top left); returns the x after it. */
static int text(sc_image *img, int x, int y, const char *s)
{
    static const unsigned char white[3] = {230, 230, 230};
    for (; *s; s++, x += 4)
        for (size_t g = 0; g < sizeof glyphs / sizeof glyphs[0]; g++)
            if (glyphs[g].c == *s)
                for (int r = 0; r < 5; r++)
                    for (int c = 0; c < 3; c++)
                        if (glyphs[g].rows[r] & (4 >> c))
                            put(img, x + c, y + r, white);
    return x;
}

typedef void (*ramp_fn)(double s, unsigned char rgb[3]);

static void ramp_iters(double s, unsigned char rgb[3])
{
    rgb[0] = (unsigned char)lround(255 * s);
    rgb[1] = 0;
    rgb[2] = (unsigned char)lround(255 * (1 - s));
}
static void ramp_u(double s, unsigned char rgb[3])
{
    rgb[0] = (unsigned char)lround(255 * s);
    rgb[1] = rgb[2] = 0;
}
static void ramp_v(double s, unsigned char rgb[3])
{
    rgb[1] = (unsigned char)lround(255 * s);
    rgb[0] = rgb[2] = 0;
}
static void ramp_depth(double s, unsigned char rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = (unsigned char)lround(255 * (1 - 0.8 * s));
}

/* "LO [bar] HI" from x; returns the x after it. */
static int bar(sc_image *img, int x, int y, const char *lo, const char *hi, ramp_fn ramp)
{
    x = text(img, x, y, lo) + 2;
    for (int i = 0; i < BAR_W; i++) {
        unsigned char rgb[3];
        ramp(i / (double)(BAR_W - 1), rgb);
        for (int j = 0; j < BAR_H; j++)
            put(img, x + i, y + j, rgb);
    }
    return text(img, x + BAR_W + 3, y, hi) + 6;
}

static void swatch(sc_image *img, int x, int y, const unsigned char rgb[3])
{
    for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++)
            put(img, x + i, y + j, rgb);
}

void sc_view_finish(sc_show view, const sc_aov *aov, int max_iters, sc_image *img)
{
    if (view == SC_SHOW_SHADE || img->channels != 4)
        return;
    int n = img->width * img->height;
    if (view != SC_SHOW_HULL)
        for (int p = 0; p < n; p++)
            if (aov->surface[p] < 0) {
                unsigned char *px = img->pixels + 4 * p;
                px[0] = px[1] = px[2] = SC_VIEW_BACKGROUND;
                px[3] = 255;
            }
    if (img->width < 96 || img->height < 64)
        return;
    /* A darker strip, so the legend reads over anything. */
    for (int y = img->height - STRIP; y < img->height; y++)
        for (int x = 0; x < img->width; x++) {
            unsigned char *px = img->pixels + ((size_t)y * (size_t)img->width + (size_t)x) * 4;
            px[0] = px[1] = px[2] = 20;
            px[3] = 255;
        }
    int x = 3, y = img->height - STRIP + 5;
    char lo[32], hi[32];
    switch (view) {
    case SC_SHOW_ITERS:
        x = text(img, x, y, "ITERS") + 4;
        snprintf(hi, sizeof hi, "%d", max_iters > 1 ? max_iters : 1);
        bar(img, x, y, "1", hi, ramp_iters);
        break;
    case SC_SHOW_UV:
        x = text(img, x, y, "U") + 2;
        x = bar(img, x, y, "0", "1", ramp_u);
        x = text(img, x, y, "V") + 2;
        bar(img, x, y, "0", "1", ramp_v);
        break;
    case SC_SHOW_DEPTH: {
        double t_lo = INFINITY, t_hi = -INFINITY;
        for (int p = 0; p < n; p++)
            if (aov->surface[p] >= 0) {
                t_lo = fmin(t_lo, aov->t[p]);
                t_hi = fmax(t_hi, aov->t[p]);
            }
        if (!(t_hi >= t_lo))
            t_lo = t_hi = 0;
        snprintf(lo, sizeof lo, "%.4g", t_lo);
        snprintf(hi, sizeof hi, "%.4g", t_hi);
        x = text(img, x, y, "DISTANCE") + 4;
        bar(img, x, y, lo, hi, ramp_depth);
        break;
    }
    case SC_SHOW_NORMAL: {
        static const unsigned char px[3] = {255, 128, 128}, py[3] = {128, 255, 128},
                                   pz[3] = {128, 128, 255};
        x = text(img, x, y, "NORMAL (N+1)/2:") + 4;
        swatch(img, x, y, px);
        x = text(img, x + 7, y, "+X") + 4;
        swatch(img, x, y, py);
        x = text(img, x + 7, y, "+Y") + 4;
        swatch(img, x, y, pz);
        text(img, x + 7, y, "+Z");
        break;
    }
    case SC_SHOW_REFLECT:
        text(img, x, y, "REFLECTION LINES");
        break;
    default:
        text(img, x, y, view == SC_SHOW_HULL ? "HULLS: BRIGHT = HIT, DIM = MISS" : "");
        break;
    }
}
