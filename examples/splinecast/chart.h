/* chart.h — `splinecast bench SCENE --chart DIR` (bench_chart.c): every
 * way of drawing the scene this build knows — the ray caster under every
 * method, start, iteration cap and hull subdivision, GLU's tessellator and
 * the tessellation shaders at a ladder of tolerances — timed and compared
 * with the CPU reference in three views, written to DIR/points.csv and
 * drawn by gnuplot into DIR/chart.png and DIR/chart.svg. */
#ifndef SC_CHART_H
#define SC_CHART_H

#include "splinecast.h"

/* The CSV's header line: the columns, in order. */
#define CHART_COLUMNS                                                                     \
    "scene,view,config,frame_ms,image_ms,fail_pct,pos_p99_px,normal_mean_deg,"            \
    "normal_p99_deg,gpu_bytes,triangles,compile_ms"

/* Zero means default. */
typedef struct chart_desc {
    const char *scene;       /* a scene file, or "teapot" (the default) */
    const char *dir;         /* required: made when missing */
    const char *camera;      /* the whole view (default: framing the scene) */
    int width, height;       /* 1024 × 1024 */
    int frames;              /* timed frames per row (3) */
    const char *configs;     /* comma list of config names or families
                                ("glu", "newton-mid", …); NULL: all */
    const char *views;       /* comma list of whole, closeup8, deforming */
    sc_backend backend;
} chart_desc;

/* Runs the sweep; returns the process exit status. */
int chart_run(const chart_desc *desc);
/* The command line's `bench --chart DIR …`. */
int bench_chart(int argc, char **argv);

#endif
