/* stability.h — the stability suite (examples/scenes/stability/): finding
 * its folder, reading its table (README.md: one row per scene and camera),
 * asking the compiler which methods and starts it can build for a scene,
 * and measuring one renderer on one row against the CPU reference. Shared
 * by `splinecast bench --stability` (bench_stability.c) and
 * tests/test_stability.c, so that both run the same scenes the same way. */
#ifndef SC_STABILITY_H
#define SC_STABILITY_H

#include "splinecast.h"

/* One row of the table. */
typedef struct stab_row {
    char name[64];          /* scene=… in the bench's lines */
    char file[128];         /* relative to the suite's folder */
    char camera[192];       /* --camera text */
} stab_row;

typedef struct stab_suite {
    char dir[1024];
    stab_row *rows;
    int count;
} stab_suite;

/* The suite's folder: `given` when not NULL, else examples/scenes/stability
 * under the working directory or under the folders above the running
 * executable (build/splinecast → the checkout). Fails naming where it
 * looked. */
int stab_find_suite(const char *given, char *dir, size_t size, sc_error *err);
/* Reads dir/README.md's table; fails when it has no row. */
int stab_read_suite(const char *dir, stab_suite *out, sc_error *err);
void stab_free_suite(stab_suite *suite);
/* The row's scene (dir/file) and its view at width × height; cam->text
 * points into the row, which must outlive the camera's use. */
int stab_load_row(const stab_suite *suite, const stab_row *row, int width, int height,
                  sc_scene_id *scene, sc_camera_desc *cam, sc_error *err);

/* SC_OK when the compiler builds every key the scene needs with this
 * method and start; else SC_FAIL with its refusal in err (a method or
 * start not implemented, or one that refuses some key, named by it).
 * *keys_hash (when not NULL) identifies the set of keys: two starts a
 * method ignores give the same keys, hence the same programs and image. */
int stab_check_method(sc_scene_id scene, sc_method method, sc_start start,
                      unsigned long *keys_hash, sc_error *err);

typedef struct stab_result {
    sc_comparison cmp;      /* against the reference: holes, false_hits,
                               off, fail_pct, iters_mean, iters_max */
    double frame_ms;        /* median of the timed frames (0 without) */
    sc_frame_id frame;      /* the rendered frame, when asked to keep it */
} stab_result;

/* Makes a renderer of desc (programs from the context's cache), draws a
 * warm-up frame and `frames` timed ones (none: one frame, untimed), reads
 * the last back and compares it with `ref`. With keep_frame the frame is
 * left in out->frame for the caller to destroy. */
int stab_measure(sc_context_id ctx, sc_scene_id scene, const sc_renderer_desc *desc,
                 const sc_camera_desc *cam, sc_frame_id ref, int frames, int keep_frame,
                 stab_result *out, sc_error *err);

#endif
