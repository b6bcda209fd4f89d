/* view_legend.h — what makes a debug view readable on its own: one
 * background for every view (the shaded view's sRGB 0.2 grey), and a
 * legend strip along the bottom that says what the colours mean. */
#ifndef SC_VIEW_LEGEND_H
#define SC_VIEW_LEGEND_H

#include "aov.h"
#include "image.h"
#include "splinecast_options.h"

/* The grey every view shows where nothing was hit (sRGB, 0..255). */
enum { SC_VIEW_BACKGROUND = 51 };

/* Paints the pixels the AOVs mark as misses in the background grey (all
 * views but shade, whose programs clear to it, and hull, which draws the
 * proxies there), then draws the legend of `view` into the bottom rows of
 * an RGBA image at least 96x64 (smaller images keep every pixel for the
 * view). max_iters scales the iteration view. */
void sc_view_finish(sc_show view, const sc_aov *aov, int max_iters, sc_image *img);

/* The reflection-line view: the view direction mirrored in each pixel's
 * normal looks up black and white stripes at infinity (view_reflect.c).
 * img is RGBA of the AOVs' size. */
void sc_view_reflect(const sc_aov *aov, sc_image *img);

#endif
