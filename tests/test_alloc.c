/* test_alloc.c — memory that is not there, on the read paths (issue 18):
 * every allocation whose size comes from a file goes through sc_try_alloc,
 * and its failure is a "file:line: out of memory: N bytes for WHAT" error
 * that leaves the scene (or image, grid, pack) empty. Two ways in:
 *
 * - failure injection: sc_alloc_fail_at(n) makes the nth try fail; each
 *   reader is run on a real input once for every n until a run makes
 *   fewer than n tries, so that every failure path of that input is taken
 *   (under `make asan` LeakSanitizer then reports any leak they leave);
 * - the command line under a real memory limit (`ulimit -v`), on a large
 *   legitimate file (tests/big_scene.sh), which must end with the error
 *   and exit status 1, not an abort. */
#include <stdlib.h>

#include "aov.h"
#include "heights.h"
#include "image.h"
#include "io.h"
#include "pack_file.h"
#include "step.h"
#include "splinecast.h"
#include "test.h"
#include "trim.h"

/* One read of a real input; returns its status and checks that a failed
 * read leaves nothing behind (it frees what a successful one returns). */
typedef int (*read_once_fn)(const char *path, sc_error *err, int *left_empty);

/* Runs `read` failing the 1st, 2nd, ... try-allocation in turn. Returns
 * the number of runs that failed (each with an out-of-memory error that
 * names `path`), or -1 after printing what went wrong. */
static int drive_failures(const char *path, read_once_fn read, int max_runs)
{
    sc_error err;
    int empty = 1;
    sc_alloc_fail_at(0);
    memset(&err, 0, sizeof err);
    sc_set_logger(test_gather_warnings, &(test_warnings){0});
    int first = read(path, &err, &empty);
    sc_set_logger(NULL, NULL);
    if (first != SC_OK) {
        char text[1200];
        fprintf(stderr, "  %s does not read: %s\n", path, sc_error_text(&err, text, sizeof text));
        return -1;
    }
    long tries = sc_alloc_fail_at(0);
    if (tries < 1) {
        fprintf(stderr, "  reading %s made no checked allocation\n", path);
        return -1;
    }
    int failed = 0;
    for (long n = 1; n <= tries && n <= max_runs; n++) {
        memset(&err, 0, sizeof err);
        empty = 1;
        sc_alloc_fail_at(n);
        /* Warnings (a dropped material library) are expected here. */
        sc_set_logger(test_gather_warnings, &(test_warnings){0});
        int status = read(path, &err, &empty);
        sc_set_logger(NULL, NULL);
        long made = sc_alloc_fail_at(0);
        if (made < n)
            break; /* this input makes fewer tries when the earlier ones succeed */
        if (status == SC_OK)
            continue; /* a failure the reader may survive (a material library) */
        char text[1200];
        sc_error_text(&err, text, sizeof text);
        if (!strstr(text, "out of memory") || !strstr(text, path) || !empty) {
            fprintf(stderr, "  failing try %ld of %s: \"%s\"%s\n", n, path, text,
                    empty ? "" : " (and the result is not empty)");
            return -1;
        }
        failed++;
    }
    return failed;
}

static int read_scene_once(const char *path, sc_error *err, int *left_empty)
{
    sc_scene scene;
    int status = sc_read_scene(path, &scene, err);
    *left_empty = scene.nsurfaces == 0 && !scene.surfaces && !scene.skipped;
    sc_scene_free(&scene);
    return status;
}

static int read_aov_once(const char *path, sc_error *err, int *left_empty)
{
    sc_aov aov;
    int status = sc_aov_read(path, &aov, err);
    if (status != SC_OK)
        *left_empty = !aov.surface && !aov.uv && !aov.t && !aov.point && !aov.normal;
    else
        sc_aov_free(&aov);
    return status;
}

static int read_png_once(const char *path, sc_error *err, int *left_empty)
{
    sc_image img;
    memset(&img, 0, sizeof img);
    int status = sc_png_read(path, &img, err);
    if (status != SC_OK)
        *left_empty = !img.pixels;
    sc_image_free(&img);
    return status;
}

static int read_heights_once(const char *path, sc_error *err, int *left_empty)
{
    sc_heights h;
    int status = sc_heights_read(path, 1, 1, &h, err);
    if (status != SC_OK)
        *left_empty = !h.z;
    sc_heights_free(&h);
    return status;
}

static int read_pack_once(const char *path, sc_error *err, int *left_empty)
{
    sc_pack k;
    int status = sc_pack_read(path, &k, err);
    if (status != SC_OK)
        *left_empty = !k.keys && !k.points && !k.hulls && !k.indices;
    sc_pack_free(&k);
    return status;
}

TEST(alloc_inject_bpt)
{
    CHECK(drive_failures(TEST_TEAPOT32, read_scene_once, 100000) > 32);
}

TEST(alloc_inject_obj)
{
    /* Trims, holes, gaps closed by validation, a material library. */
    static const char *const files[] = {"trim_nested.obj", "trimmed_hole.obj", "mixed.obj",
                                        "trim_touch.obj"};
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        char rel[128];
        snprintf(rel, sizeof rel, "examples/scenes/%s", files[i]);
        CHECK(drive_failures(test_root(rel), read_scene_once, 100000) > 0);
    }
}

TEST(alloc_inject_iges)
{
    /* Real parts: trimmed surfaces (144), B-spline surfaces and curves. */
    static const char *const files[] = {"iges/OCC131-2.igs", "iges/bug24012_face.igs"};
    for (size_t i = 0; i < sizeof files / sizeof *files; i++) {
        REQUIRE_DATA(files[i]);
        CHECK(drive_failures(test_data(files[i]), read_scene_once, 100000) > 0);
    }
}

static int scan_step_once(const char *path, sc_error *err, int *left_empty)
{
    char *text;
    size_t size;
    if (sc_read_file_max(path, (size_t)1 << 30, 1, &text, &size, err))
        return SC_FAIL;
    sc_step_scan scan;
    int status = sc_step_scan_text(text, size, path, &scan, err);
    free(text);
    if (status != SC_OK)
        *left_empty = !scan.ids && !scan.lines;
    else
        sc_step_scan_free(&scan);
    return status;
}

TEST(alloc_inject_step_scan)
{
    /* Our pre-scan of a STEP file (the library's transfer runs in a child
     * process, whose memory is its own limit: docs/step.md). */
    REQUIRE_DATA("step/bug3883_xr2-ct-214_bolt.stp");
    CHECK(drive_failures(test_data("step/bug3883_xr2-ct-214_bolt.stp"), scan_step_once, 1000) > 0);
}

TEST(alloc_inject_images)
{
    /* An AOV file and a PNG as the renderer writes them. */
    sc_camera cam;
    memset(&cam, 0, sizeof cam);
    cam.width = 7;
    cam.height = 5;
    cam.fovy_deg = 40;
    cam.eye[0] = 3;
    sc_aov aov;
    sc_aov_alloc(&aov, &cam, 1);
    for (int i = 0; i < 35; i++)
        aov.t[i] = (float)i;
    sc_error err;
    char aov_path[1024];
    snprintf(aov_path, sizeof aov_path, "%s/inject.aov", test_tmpdir());
    int status = sc_aov_write(aov_path, &aov, &err);
    sc_aov_free(&aov);
    CHECK_INT(status, SC_OK);
    CHECK(drive_failures(aov_path, read_aov_once, 1000) > 0);

    sc_image img;
    sc_image_alloc(&img, 9, 4, 4);
    for (int i = 0; i < 9 * 4 * 4; i++)
        img.pixels[i] = (unsigned char)(7 * i);
    char png_path[1024];
    snprintf(png_path, sizeof png_path, "%s/inject.png", test_tmpdir());
    status = sc_png_write(png_path, &img, &err);
    sc_image_free(&img);
    CHECK_INT(status, SC_OK);
    CHECK(drive_failures(png_path, read_png_once, 1000) > 0);
}

TEST(alloc_inject_heights)
{
    CHECK(drive_failures(test_root("examples/scenes/hills33.pgm"), read_heights_once, 1000) > 0);
    /* A CSV grows its array as the values arrive: 3,000 values. */
    size_t cap = 64 * 1024, n = 0;
    char *csv = malloc(cap);
    for (int r = 0; r < 60; r++)
        for (int c = 0; c < 50; c++)
            n += (size_t)snprintf(csv + n, cap - n, "%d%s", (r * 7 + c * 3) % 11,
                                  c == 49 ? "\n" : ",");
    const char *path = test_write_tmp("inject.csv", csv);
    free(csv);
    CHECK(drive_failures(path, read_heights_once, 1000) > 2);
}

TEST(alloc_inject_pack)
{
    /* The teapot's pack as `splinecast pack` writes it. */
    char path[1024], cmd[2048];
    snprintf(path, sizeof path, "%s/inject.pack", test_tmpdir());
    snprintf(cmd, sizeof cmd, "%s pack teapot -o %s", test_cli, path);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    CHECK(drive_failures(path, read_pack_once, 1000) > 0);
}

/* The trim pieces a renderer and the reference prepare from a scene's
 * loops (runtime/model/trim.c): their failure is an error, no leak. */
TEST(alloc_inject_trim)
{
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_scene(test_root("examples/scenes/trim_nested.obj"), &scene, &err), SC_OK);
    int failed = 0;
    for (int i = 0; i < scene.nsurfaces; i++) {
        if (!scene.surfaces[i].nloops)
            continue;
        for (long n = 1;; n++) {
            sc_trim *trim = NULL;
            memset(&err, 0, sizeof err);
            sc_alloc_fail_at(n);
            int status = sc_trim_prepare(&scene.surfaces[i], &trim, &err);
            long made = sc_alloc_fail_at(0);
            sc_trim_free(trim);
            if (made < n) {
                CHECK_INT(status, SC_OK);
                break;
            }
            CHECK_INT(status, SC_FAIL);
            CHECK(trim == NULL);
            CHECK_CONTAINS(err.message, "out of memory: ");
            failed++;
        }
    }
    sc_scene_free(&scene);
    CHECK(failed > 2);
}

/* Through the API: a scene from text (the OBJ reader) and a terrain from a
 * height file; every failure is an sc_error naming the input, and no
 * scene handle. */
static const char *api_text;
static int make_scene_once(const char *path, sc_error *err, int *left_empty)
{
    sc_scene_desc desc = {0};
    if (api_text) {
        desc.text = api_text;
        desc.size = strlen(api_text);
        desc.name = path;
    } else {
        desc.heights = path;
    }
    sc_scene_id id = {0};
    int status = sc_make_scene(&desc, &id, err);
    *left_empty = id.id == 0;
    sc_destroy_scene(id);
    return status;
}

TEST(alloc_inject_api)
{
    char *text = test_read_file(test_root("examples/scenes/trim_nested.obj"));
    CHECK(text);
    api_text = text;
    int failed = drive_failures("trim_nested.obj", make_scene_once, 100000);
    api_text = NULL;
    free(text);
    CHECK(failed > 0);
    CHECK(drive_failures(test_root("examples/scenes/hills33.pgm"), make_scene_once, 1000) > 0);
}

/* The command line: SC_ALLOC_FAIL=N fails the Nth try of the process. */
TEST(alloc_cli_inject)
{
    char cmd[2048], *err = NULL;
    snprintf(cmd, sizeof cmd, "SC_ALLOC_FAIL=40 %s info %s", test_cli,
             test_root("examples/scenes/trim_nested.obj"));
    int status = test_run(cmd, NULL, &err);
    CHECK_INT(status, 1);
    CHECK_CONTAINS(err, "trim_nested.obj");
    CHECK_CONTAINS(err, "out of memory: ");
    free(err);
}

/* The command line under a real memory limit, on a legitimate file larger
 * than the limit allows. The limit is found from the process's own needs
 * (shared libraries, GL and Open CASCADE make its baseline differ from one
 * machine to the next): the smallest of a series of limits under which
 * `info teapot` works, plus 16 MiB, which 20,000 patches (5.5 MB of OBJ,
 * about 60 MB read) do not fit in. AddressSanitizer reserves terabytes of
 * address space, so the test is for the plain build. */
TEST(alloc_cli_memory_limit)
{
#if defined(__SANITIZE_ADDRESS__)
    SKIP("a limit on address space does not work under AddressSanitizer");
#else
    char cmd[2048];
    int base = 0;
    for (int mib = 64; mib <= 2048 && !base; mib += 16) {
        snprintf(cmd, sizeof cmd, "ulimit -v %d && %s info teapot", mib * 1024, test_cli);
        if (test_run(cmd, NULL, NULL) == 0)
            base = mib;
    }
    CHECK(base > 0);
    char big[1024];
    snprintf(big, sizeof big, "%s/alloc_big.obj", test_tmpdir());
    snprintf(cmd, sizeof cmd, "sh %s %s 20000", test_root("tests/big_scene.sh"), big);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    /* Without a limit it reads. */
    char *out = NULL, *err = NULL;
    snprintf(cmd, sizeof cmd, "%s info %s", test_cli, big);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "surfaces 20000\n");
    free(out);
    snprintf(cmd, sizeof cmd, "ulimit -v %d && %s info %s", (base + 16) * 1024, test_cli, big);
    int status = test_run(cmd, NULL, &err);
    fprintf(stderr, "  limit %d MiB: %s", base + 16, err ? err : "(no message)\n");
    CHECK_INT(status, 1);
    CHECK_CONTAINS(err, "alloc_big.obj:");
    CHECK_CONTAINS(err, ": out of memory: ");
    free(err);
    unlink(big);
#endif
}
