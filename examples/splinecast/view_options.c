/* view_options.c — the shared view options (view_options.h). */
#include "view_options.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "commands.h"

/* The largest side a frame may have: the GL renderbuffer limit of the
 * drivers the project runs on, and the reference's image limit. */
enum { MAX_SIDE = 16384 };

const char cli_view_usage[] =
    "  --size WxH             image size, W and H from 1 to 16384 (default 512x512)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOVY[,UX,UY,UZ]   eye, target, vertical field of\n"
    "                         view in degrees, optionally the up vector\n"
    "                         (default: framing the scene)\n"
    "  --up X,Y,Z             the up vector (default +z, or +y for a view along z);\n"
    "                         the default framing looks from above along it\n"
    "  --view-from +x|-x|+y|-y|+z|-z   the default framing, seen from that side\n";

void cli_view_init(cli_view *view)
{
    memset(view, 0, sizeof *view);
    view->width = view->height = 512;
}

static int parse_size(const char *text, int *w, int *h)
{
    char *end;
    errno = 0;
    long a = strtol(text, &end, 10);
    if (end == text || (*end != 'x' && *end != 'X'))
        return 0;
    const char *second = end + 1;
    long b = strtol(second, &end, 10);
    if (end == second || *end || errno || a < 1 || b < 1 || a > MAX_SIDE || b > MAX_SIDE)
        return 0;
    *w = (int)a;
    *h = (int)b;
    return 1;
}

static int parse_vector(const char *text, double v[3])
{
    const char *p = text;
    for (int k = 0; k < 3; k++) {
        char *end;
        errno = 0;
        v[k] = strtod(p, &end);
        if (end == p || errno || !isfinite(v[k]))
            return 0;
        p = end;
        if (k < 2 && *p++ != ',')
            return 0;
    }
    return *p == 0 && (v[0] != 0 || v[1] != 0 || v[2] != 0);
}

static int parse_side(const char *text, double v[3])
{
    if (strlen(text) != 2 || (text[0] != '+' && text[0] != '-') || text[1] < 'x' ||
        text[1] > 'z')
        return 0;
    memset(v, 0, 3 * sizeof *v);
    v[text[1] - 'x'] = text[0] == '+' ? 1.0 : -1.0;
    return 1;
}

int cli_view_option(const char *cmd, int argc, char **argv, int *i, cli_view *view)
{
    const char *a = argv[*i];
    int is_view = !strcmp(a, "--size") || !strcmp(a, "--camera") || !strcmp(a, "--up") ||
                  !strcmp(a, "--view-from");
    if (!is_view)
        return 0;
    if (*i + 1 >= argc)
        return cli_usage_error(cmd, "%s needs a value", a);
    const char *value = argv[++*i];
    if (!strcmp(a, "--size")) {
        if (!parse_size(value, &view->width, &view->height))
            return cli_usage_error(cmd, "--size takes WxH with W and H from 1 to %d "
                                   "(e.g. 512x512), not '%s'", MAX_SIDE, value);
    } else if (!strcmp(a, "--camera")) {
        view->camera = value;
    } else if (!strcmp(a, "--up")) {
        if (!parse_vector(value, view->up))
            return cli_usage_error(cmd, "--up takes a non-zero vector X,Y,Z (e.g. 0,1,0), "
                                   "not '%s'", value);
    } else if (!parse_side(value, view->from)) {
        return cli_usage_error(cmd, "--view-from takes +x, -x, +y, -y, +z or -z, not '%s'",
                               value);
    }
    return 1;
}

int cli_view_camera(const char *cmd, const cli_view *view, sc_camera_desc *out)
{
    memset(out, 0, sizeof *out);
    out->width = view->width;
    out->height = view->height;
    out->text = view->camera;
    memcpy(out->up, view->up, sizeof out->up);
    memcpy(out->from, view->from, sizeof out->from);
    if (view->camera && (view->from[0] || view->from[1] || view->from[2]))
        return cli_usage_error(cmd, "--view-from chooses the default framing's side; it "
                               "cannot go with --camera");
    sc_error err = {0};
    if (sc_check_camera(out, &err) != SC_OK)
        return cli_usage_error(cmd, "--camera: %s", err.message);
    return 0;
}

int cli_check_png_name(const char *cmd, const char *path)
{
    size_t n = strlen(path);
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    if (n < 4 || strcasecmp(path + n - 4, ".png") || strlen(base) <= 4)
        return cli_usage_error(cmd, "the image is written as PNG: its name must end in .png, "
                               "not '%s'", path);
    return 0;
}

int cli_open_drawable_scene(const char *cmd, const char *path, sc_scene_id *out)
{
    sc_error err = {0};
    sc_scene_info info;
    if (sc_make_scene(&(sc_scene_desc){.path = path}, out, &err) != SC_OK)
        return cli_report(&err);
    if (sc_query_scene_info(*out, &info, &err) != SC_OK) {
        sc_destroy_scene(*out);
        return cli_report(&err);
    }
    if (info.surfaces == 0) {
        sc_destroy_scene(*out);
        fprintf(stderr, "%s: nothing to draw: the scene has no surfaces (`splinecast info %s` "
                "lists what the reader skipped); no image written\n", path, path);
        return 1;
    }
    return 0;
}
