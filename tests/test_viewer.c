/* test_viewer.c — examples/viewer under Xvfb: a scripted camera (orbit,
 * zoom, pan), a view switched by key, a click that picks, and a screenshot
 * of the window that must show exactly the image `splinecast render` makes
 * offscreen of the same view. */
#include <stdlib.h>

#include "test.h"

#include "image.h"

TEST(viewer_screenshot_matches_render)
{
    if (access("/usr/bin/xvfb-run", X_OK) != 0)
        SKIP("xvfb-run not installed (make deps)");
    const char *dir = test_tmpdir();
    char viewer[1024], cmd[4096], shot[1024], ref[1024];
    snprintf(viewer, sizeof viewer, "%.*sviewer", (int)(strrchr(test_cli, '/') ?
             strrchr(test_cli, '/') - test_cli + 1 : 0), test_cli);
    snprintf(shot, sizeof shot, "%s/viewer_shot.png", dir);
    snprintf(ref, sizeof ref, "%s/viewer_ref.png", dir);
    char script_text[1400];
    snprintf(script_text, sizeof script_text,
             "orbit 35 -12\nzoom 0.85\npan 0.04 -0.03\nkey v\nkey v\nclick 80 60\n"
             "screenshot %s\n", shot);
    const char *script = test_write_tmp("viewer_script.txt", script_text);
    snprintf(cmd, sizeof cmd, "xvfb-run -a -s '-screen 0 640x480x24' %s teapot --size 160x120 "
             "--script %s", viewer, script);
    char *out = NULL, *err = NULL;
    int status = test_run(cmd, &out, &err);
    if (status != 0 && err && (strstr(err, "no window system") || strstr(err, "OSMesa"))) {
        free(out);
        free(err);
        SKIP("no window system or GL under Xvfb");
    }
    if (status != 0)
        fprintf(stderr, "  %s\n", err ? err : "");
    CHECK_INT(status, 0);
    /* The last frame's camera and view, as the viewer prints them. */
    const char *last = NULL;
    for (const char *p = strstr(out, "viewer frame="); p; p = strstr(p + 1, "viewer frame="))
        last = p;
    CHECK(last != NULL);
    char camera[400], view[16];
    CHECK(sscanf(strstr(last, "camera="), "camera=%399s", camera) == 1);
    CHECK(sscanf(strstr(last, "view="), "view=%15s", view) == 1);
    CHECK_STR(view, "uv");      /* shade -> iters -> uv */
    CHECK_CONTAINS(out, "pick surface=");
    CHECK_CONTAINS(out, "viewer screenshot=");
    free(out);
    free(err);

    snprintf(cmd, sizeof cmd, "%s render teapot -o %s --size 160x120 --frames 1 --view uv "
             "--camera %s", test_cli, ref, camera);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    sc_image a = {0}, b = {0};
    sc_error e = {0};
    CHECK_INT(sc_png_read(shot, &a, &e), SC_OK);
    CHECK_INT(sc_png_read(ref, &b, &e), SC_OK);
    CHECK_INT(a.width, b.width);
    CHECK_INT(a.height, b.height);
    long differ = 0, covered = 0;
    for (int p = 0; p < a.width * a.height; p++) {
        const unsigned char *x = a.pixels + p * a.channels, *y = b.pixels + p * b.channels;
        int d = 0;
        for (int c = 0; c < 3; c++)
            d |= abs(x[c] - y[c]) > 1;
        differ += d;
        covered += !(y[0] == 51 && y[1] == 51 && y[2] == 51);
    }
    fprintf(stderr, "  %ld of %d pixels differ, %ld not background\n", differ, a.width * a.height,
            covered);
    CHECK(covered > a.width * a.height / 10);
    CHECK_INT(differ, 0);
    sc_image_free(&a);
    sc_image_free(&b);
}
