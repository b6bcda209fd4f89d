/* view_options.h — the options every command that renders a view shares
 * (`ref`, `render`, `pick`): --size, --camera, --up, --view-from, the
 * image name given with -o and the scene it draws. One parser and one set
 * of messages, so that the commands word the same mistake the same way. */
#ifndef SC_CLI_VIEW_OPTIONS_H
#define SC_CLI_VIEW_OPTIONS_H

#include "splinecast.h"

typedef struct cli_view {
    int width, height;      /* 512x512 unless --size */
    const char *camera;     /* --camera text, or NULL */
    double up[3];           /* --up, zero when not given */
    double from[3];         /* --view-from, zero when not given */
} cli_view;

/* Help lines of the options above, for the commands' usage texts. */
extern const char cli_view_usage[];

void cli_view_init(cli_view *view);
/* When argv[*i] is a view option, takes it and its value (advancing *i)
 * and returns 1; returns 0 for any other argument, and 2 after printing
 * a usage error for a bad value. */
int cli_view_option(const char *cmd, int argc, char **argv, int *i, cli_view *view);
/* The camera the options give (valid while view lives); returns 0, or 2
 * after printing a usage error (a --camera that does not parse, --view-from
 * with --camera). */
int cli_view_camera(const char *cmd, const cli_view *view, sc_camera_desc *out);
/* An image name must end in .png (any case): returns 0, or 2 after
 * printing a usage error. */
int cli_check_png_name(const char *cmd, const char *path);
/* Reads a scene to draw: returns 0, or 1 after printing the reader's error
 * or, for a scene without a single surface, "SCENE: nothing to draw". */
int cli_open_drawable_scene(const char *cmd, const char *path, sc_scene_id *out);

#endif
