/* gl_peak.h — the vec4 multiply-add rate of a fragment program on the
 * current context (sc_measure_peak, `bench --peak`). */
#ifndef SC_GL_PEAK_H
#define SC_GL_PEAK_H

#include "gl_loader.h"

typedef struct sc_gl_peak {
    int width, height, chains, length, frames;   /* all given, > 0 */
    double flops, gpu_ms, wall_ms;               /* gpu_ms -1: no timer query */
} sc_gl_peak;

/* Fills flops, gpu_ms and wall_ms of p. */
int sc_gl_measure_peak(const sc_gl *gl, sc_gl_peak *p, sc_error *err);

#endif
