/* test_ref_files.c — the files the reference writes and reads (AOV, PNG),
 * round trip, and the `ref` / `diff` commands end to end. */
#include "test.h"

#include <stdlib.h>
#include <sys/stat.h>

#include "image.h"
#include "imgdiff.h"

/* ------------------------------------------------------- AOV, PNG -- */

TEST(ref_aov_round_trip)
{
    sc_camera cam = {.eye = {0.1, 0.2, 0.3}, .target = {1.0 / 3.0, 0, 0}, .fovy_deg = 29.9, .width = 7, .height = 5};
    sc_aov a, b;
    sc_aov_alloc(&a, &cam, 1);
    unsigned long long state = 42;
    for (int px = 0; px < 35; px++) {
        a.surface[px] = test_rand(&state) < 0.3 ? -1 : (int32_t)(test_rand(&state) * 1000);
        a.t[px] = (float)test_rand(&state);
        a.iters[px] = (float)(int)(test_rand(&state) * 20);
        for (int k = 0; k < 2; k++)
            a.uv[2 * px + k] = (float)test_rand(&state);
        for (int k = 0; k < 3; k++) {
            a.point[3 * px + k] = (float)(test_rand(&state) - 0.5);
            a.normal[3 * px + k] = (float)(test_rand(&state) - 0.5);
        }
    }
    char path[512], err_buf[600];
    snprintf(path, sizeof path, "%s/rt.aov", test_tmpdir());
    sc_error err;
    CHECK_INT(sc_aov_write(path, &a, &err), SC_OK);
    CHECK_INT(sc_aov_read(path, &b, &err), SC_OK);
    CHECK_INT(b.width, 7);
    CHECK_INT(b.height, 5);
    CHECK_INT(b.has_iters, 1);
    CHECK(!memcmp(a.surface, b.surface, 35 * sizeof(int32_t)));
    CHECK(!memcmp(a.uv, b.uv, 70 * sizeof(float)));
    CHECK(!memcmp(a.t, b.t, 35 * sizeof(float)));
    CHECK(!memcmp(a.point, b.point, 105 * sizeof(float)));
    CHECK(!memcmp(a.normal, b.normal, 105 * sizeof(float)));
    CHECK(!memcmp(a.iters, b.iters, 35 * sizeof(float)));
    CHECK(!memcmp(a.camera.eye, b.camera.eye, sizeof a.camera.eye));
    CHECK(!memcmp(a.camera.target, b.camera.target, sizeof a.camera.target));
    sc_aov_free(&b);
    /* A cut-off file is refused, naming the file. */
    FILE *f = fopen(path, "r+b");
    CHECK(f);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fclose(f);
    CHECK_INT(truncate(path, size - 4), 0);
    CHECK_INT(sc_aov_read(path, &b, &err), SC_FAIL);
    CHECK_CONTAINS(sc_error_text(&err, err_buf, sizeof err_buf), "rt.aov");
    CHECK_CONTAINS(err.message, "truncated");
    const char *bad = test_write_tmp("not_an.aov", "P6 3 3 255\n");
    CHECK_INT(sc_aov_read(bad, &b, &err), SC_FAIL);
    CHECK_INT(err.line, 1);
    sc_aov_free(&a);
}

TEST(ref_png_round_trip)
{
    for (int channels = 3; channels <= 4; channels++) {
        sc_image img, back;
        sc_image_alloc(&img, 13, 6, channels);
        unsigned long long state = 7;
        for (int i = 0; i < 13 * 6 * channels; i++)
            img.pixels[i] = (unsigned char)(test_rand(&state) * 256);
        char path[512];
        snprintf(path, sizeof path, "%s/rt%d.png", test_tmpdir(), channels);
        sc_error err;
        CHECK_INT(sc_png_write(path, &img, &err), SC_OK);
        CHECK_INT(sc_png_read(path, &back, &err), SC_OK);
        CHECK_INT(back.width, 13);
        CHECK_INT(back.height, 6);
        CHECK_INT(back.channels, channels);
        CHECK(!memcmp(img.pixels, back.pixels, (size_t)(13 * 6 * channels)));
        sc_image_free(&img);
        sc_image_free(&back);
    }
    sc_image img;
    sc_error err;
    CHECK_INT(sc_png_read(test_write_tmp("notpng.png", "hello"), &img, &err), SC_FAIL);
}

/* ------------------------------------------------------- commands -- */

TEST(ref_cli_ref_and_diff)
{
    char *out = NULL, *errs = NULL, cmd[2048];
    const char *dir = test_tmpdir();
    snprintf(cmd, sizeof cmd, "%s ref --help", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "out.aov");
    free(out);
    snprintf(cmd, sizeof cmd, "%s diff --help", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "accuracy");
    free(out);

    snprintf(cmd, sizeof cmd, "%s ref teapot -o %s/a.png --size 40x30 --stats", test_cli, dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "ref image=");
    CHECK_CONTAINS(out, "size=40x30");
    CHECK_CONTAINS(out, "stats rays=1200 ");
    CHECK_CONTAINS(out, "rays_per_s=");
    free(out);
    sc_image img;
    sc_error err;
    char path[600];
    snprintf(path, sizeof path, "%s/a.png", dir);
    CHECK_INT(sc_png_read(path, &img, &err), SC_OK);
    CHECK_INT(img.width, 40);
    CHECK_INT(img.height, 30);
    sc_image_free(&img);

    /* Same view moved by a hair: refused. */
    snprintf(cmd, sizeof cmd,
             "(%s ref teapot -o %s/b.png --size 40x30 --camera 6,-12,9,0.26,0,1.5,30 && "
             "%s ref teapot -o %s/c.png --size 40x30 --camera 6,-12,9,0.26,0,1.5001,30 && "
             "%s ref teapot -o %s/e.png --size 30x40 --camera 6,-12,9,0.26,0,1.5,30)",
             test_cli, dir, test_cli, dir, test_cli, dir);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    snprintf(cmd, sizeof cmd, "%s diff %s/b.aov %s/b.png", test_cli, dir, dir);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "accuracy coverage_pct=0 fail_pct=0 ");
    free(out);
    snprintf(cmd, sizeof cmd, "%s diff %s/b.aov %s/c.aov", test_cli, dir, dir);
    CHECK(test_run(cmd, &out, &errs) != 0);
    CHECK_STR(out, "");
    CHECK_CONTAINS(errs, "camera");
    free(out);
    free(errs);
    snprintf(cmd, sizeof cmd, "%s diff %s/e.aov %s/b.aov", test_cli, dir, dir);
    CHECK(test_run(cmd, NULL, &errs) != 0);
    CHECK_CONTAINS(errs, "size");
    free(errs);
    /* A missing file: the system's reason. */
    snprintf(cmd, sizeof cmd, "%s diff %s/b.aov %s/missing.aov", test_cli, dir, dir);
    CHECK(test_run(cmd, &out, &errs) != 0);
    CHECK_STR(out, "");
    CHECK_CONTAINS(errs, "missing.aov: cannot open: No such file or directory");
    free(out);
    free(errs);

    /* Bad input: a message naming the file, and no output written. */
    const char *bad = test_write_tmp("bad.bpt", "1\n3 3\n0 0 0\n");
    snprintf(cmd, sizeof cmd, "%s ref %s -o %s/bad.png --size 8x8", test_cli, bad, dir);
    CHECK(test_run(cmd, NULL, &errs) != 0);
    CHECK_CONTAINS(errs, "bad.bpt");
    free(errs);
    snprintf(path, sizeof path, "%s/bad.aov", dir);
    struct stat st;
    CHECK(stat(path, &st) != 0);
    snprintf(cmd, sizeof cmd, "%s ref teapot -o %s/d.png --size 0x8", test_cli, dir);
    CHECK_INT(test_run(cmd, NULL, NULL), 2);
}
