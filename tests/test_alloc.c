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
#include "iges_files.h"
#include "image.h"
#include "io.h"
#include "pack_file.h"
#include "step.h"
#include "splinecast.h"
#include "test.h"
#include "trim.h"
#include "trim_pack.h"

/* What a read may still leave to the aborting sc_alloc (docs/limits.md):
 * handles and records, a 2-point segment, the scratch of a curve of the
 * highest degree a file may have. */
enum { SMALL_FIXED_BYTES = 4096 };

/* One read of a real input; returns its status and checks that a failed
 * read leaves nothing behind (it frees what a successful one returns). */
typedef int (*read_once_fn)(const char *path, sc_error *err, int *left_empty);

/* Runs `read` failing the 1st, 2nd, ... try-allocation in turn (every
 * step-th when it makes more than max_runs tries). Returns
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
    size_t aborting = sc_alloc_aborting_max();
    long tries = sc_alloc_fail_at(0);
    if (aborting > SMALL_FIXED_BYTES) {
        fprintf(stderr, "  reading %s made an aborting allocation of %zu bytes\n", path,
                aborting);
        return -1;
    }
    if (tries < 1) {
        fprintf(stderr, "  reading %s made no checked allocation\n", path);
        return -1;
    }
    /* Every try, or for a large input `max_runs` of them spread evenly. */
    long step = tries > max_runs ? (tries + max_runs - 1) / max_runs : 1;
    int failed = 0;
    for (long n = 1; n <= tries; n += step) {
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
    fprintf(stderr, "  %s: %ld tries, %d failures reported; largest aborting allocation %zu "
            "bytes\n", path, tries, failed, aborting);
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
    /* A B-rep whose loops have only model-space edges (projected), and a
     * surface of degree 12: their 9,000 and 1,000 tries sampled. */
    static const char *const large[] = {"iges/occ22470.igs", "iges/OCC26138_Torus.igs"};
    for (size_t i = 0; i < sizeof large / sizeof *large; i++) {
        REQUIRE_DATA(large[i]);
        CHECK(drive_failures(test_data(large[i]), read_scene_once, 150) > 100);
    }
}

/* IGES entities that go through the analytic constructions, offset
 * fitting, projection and composite curves (the cases of
 * test_iges_analytic.c), each file read once per failing try. */
static const char cubic_126[] =
    "126,4,3,0,0,1,0,0.,0.,0.,0.,0.4,1.,1.,1.,1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,2.,0.,2.,-1.,1.,3.,"
    "0.,0.,4.,1.,-1.,0.,1.,0.,0.,0.;";

static int drive_iges(const char *name, const spec *e, int n)
{
    char *text = iges_make_iges(e, n);
    const char *path = test_write_tmp(name, text);
    free(text);
    return drive_failures(path, read_scene_once, 100000);
}

TEST(alloc_inject_iges_analytic)
{
    /* Free surfaces: sphere (196), torus (198), revolution (120), tabulated
     * cylinder (122) and ruled surface (118) of a cubic and a line. */
    spec free_surfaces[] = {
        {116, "116,1.,2.,3.,0;", 0, 0, NULL},                 /* D 1 */
        {123, "123,0.,0.,2.;", 0, 0, NULL},                   /* D 3 */
        {196, "196,1,1.5;", 0, 0, NULL},                      /* D 5 */
        {198, "198,1,3,3.,1.;", 0, 0, NULL},                  /* D 7 */
        {110, "110,0.,0.,0.,0.,0.,1.;", 0, 0, NULL},          /* D 9 */
        {110, "110,1.,0.,0.,2.,0.,1.;", 0, 0, NULL},          /* D 11 */
        {120, "120,9,11,0.,3.141592653589793;", 0, 0, NULL}, /* D 13 */
        {126, cubic_126, 0, 0, NULL},                         /* D 15 */
        {122, "122,15,1.,1.,5.;", 0, 0, NULL},                /* D 17 */
        {110, "110,0.,0.,0.,4.,0.,0.;", 0, 0, NULL},          /* D 19 */
        {118, "118,19,15,0,1;", 0, 0, NULL},                  /* D 21 */
    };
    CHECK(drive_iges("inject_free.igs", free_surfaces, 11) > 20);
    /* A 140 offset of a sphere: the fit's surfaces of up to 385 x 385
     * points. */
    spec offset[] = {
        {116, "116,0.,0.,0.,0;", 0, 0, NULL},     /* D 1 */
        {196, "196,1,2.;", 0, 0, NULL},           /* D 3 */
        {140, "140,0.,0.,1.,0.5,3;", 0, 0, NULL}, /* D 5 */
    };
    CHECK(drive_iges("inject_offset.igs", offset, 3) > 3);
    /* Trims of 104 conics: a whole ellipse, a parabola arc closed by a line
     * in a 102 composite, on planes (128). */
    spec conics[] = {
        {128, iges_plane_params(1), 0, 0, NULL},                                         /* D 1 */
        {124, "124,1.,0.,0.,0.5,0.,1.,0.,0.5,0.,0.,1.,0.;", 0, 0, NULL},                 /* D 3 */
        {104, "104,11.111111111111111,0.,25.,0.,0.,-1.,0.,0.3,0.,0.3,0.;", 3, 0, NULL},  /* D 5 */
        {142, "142,0,1,5,0,1;", 0, 0, NULL},                                             /* D 7 */
        {144, "144,1,1,0,7;", 0, 0, NULL},                                               /* D 9 */
        {128, iges_plane_params(1), 0, 0, NULL},                                         /* D 11 */
        {124, "124,1.,0.,0.,0.5,0.,1.,0.,0.2,0.,0.,1.,0.;", 0, 0, NULL},                 /* D 13 */
        {104, "104,1.,0.,0.,0.,-1.,0.,0.,-0.5,0.25,0.5,0.25;", 13, 0, NULL},             /* D 15 */
        {110, "110,1.,0.45,0.,0.,0.45,0.;", 0, 0, NULL},                                 /* D 17 */
        {102, "102,2,15,17;", 0, 0, NULL},                                               /* D 19 */
        {142, "142,0,11,19,0,1;", 0, 0, NULL},                                           /* D 21 */
        {144, "144,11,1,0,21;", 0, 0, NULL},                                             /* D 23 */
    };
    CHECK(drive_iges("inject_conics.igs", conics, 12) > 10);
}

TEST(alloc_inject_iges_projected)
{
    /* Loops given only in model space: projected onto a 192 cylinder
     * across its seam (510/508/504), mapped onto a 108 plane (144/142 with
     * a circle), and a 196 sphere bounded by its seam alone, whose loop
     * runs across the seam (the surface is extended by a period). */
    spec cylinder[] = {
        {116, "116,0.,0.,0.,0;", 0, 0, NULL},                                   /* D 1 */
        {123, "123,0.,0.,1.;", 0, 0, NULL},                                     /* D 3 */
        {192, "192,1,3,2.;", 0, 0, NULL},                                       /* D 5 */
        {100, "100,0.,0.,0.,2.,0.,2.,0.;", 0, 0, NULL},                         /* D 7 */
        {100, "100,3.,0.,0.,2.,0.,2.,0.;", 0, 0, NULL},                         /* D 9 */
        {110, "110,2.,0.,0.,2.,0.,3.;", 0, 0, NULL},                            /* D 11 */
        {504, "504,3,7,0,0,0,0,9,0,0,0,0,11,0,0,0,0;", 0, 0, NULL},             /* D 13 */
        {508, "508,4,0,13,1,1,0,0,13,3,1,0,0,13,2,0,0,0,13,3,0,0;", 0, 0, NULL}, /* D 15 */
        {510, "510,5,1,1,15;", 0, 0, NULL},                                     /* D 17 */
    };
    CHECK(drive_iges("inject_cylinder.igs", cylinder, 9) > 20);
    spec plane[] = {
        {108, "108,0.,0.,1.,1.,0,0.,0.,0.,0.;", 0, 0, NULL}, /* D 1 */
        {100, "100,1.,0.5,0.5,1.,0.5,1.,0.5;", 0, 0, NULL},   /* D 3 */
        {142, "142,0,1,0,3,2;", 0, 0, NULL},                  /* D 5 */
        {144, "144,1,1,0,5;", 0, 0, NULL},                    /* D 7 */
    };
    CHECK(drive_iges("inject_plane.igs", plane, 4) > 3);
    spec sphere[] = {
        {116, "116,0.,0.,0.,0;", 0, 0, NULL}, /* D 1 */
        {196, "196,1,2.;", 0, 0, NULL},       /* D 3 */
        {126, "126,4,2,1,0,0,0,0.,0.,0.,.5,.5,1.,1.,1.,"
              "1.,.7071067811865476,1.,.7071067811865476,1.,"
              "0.,0.,2.,2.,0.,2.,2.,0.,0.,2.,0.,-2.,0.,0.,-2.,0.,1.,0.,1.,0.;",
         0, 0, NULL},                                            /* D 5 */
        {504, "504,1,5,0,0,0,0;", 0, 0, NULL},                   /* D 7 */
        {508, "508,2,0,7,1,1,0,0,7,1,0,0;", 0, 0, NULL},         /* D 9 */
        {510, "510,3,1,1,9;", 0, 0, NULL},                       /* D 11 */
    };
    CHECK(drive_iges("inject_sphere.igs", sphere, 6) > 20);
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

TEST(alloc_inject_step)
{
    /* The whole STEP read: our pre-scan, then the surfaces the reader's
     * child process sends back, taken into the scene (the child's own
     * memory has its own limit: docs/step.md). Each read starts Open
     * CASCADE anew: 60 of its 480 tries, spread evenly. */
    REQUIRE_DATA("step/bug3883_xr2-ct-214_bolt.stp");
    CHECK(drive_failures(test_data("step/bug3883_xr2-ct-214_bolt.stp"), read_scene_once, 60) >
          50);
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

/* The trim blocks a renderer packs for the GPU from the same loops
 * (runtime/prepare/trim_pack.c). */
TEST(alloc_inject_trim_pack)
{
    sc_scene scene;
    sc_error err;
    CHECK_INT(sc_read_scene(test_root("examples/scenes/trim_nested.obj"), &scene, &err), SC_OK);
    int failed = 0;
    for (int i = 0; i < scene.nsurfaces; i++) {
        const sc_surface *s = &scene.surfaces[i];
        if (!s->nloops)
            continue;
        int degree = sc_surface_trim_degree(s);
        for (long n = 1;; n++) {
            sc_trim_block block;
            memset(&err, 0, sizeof err);
            sc_alloc_fail_at(n);
            int status = sc_trim_pack(s, degree, &block, &err);
            long made = sc_alloc_fail_at(0);
            if (made < n) {
                CHECK_INT(status, SC_OK);
                sc_trim_block_free(&block);
                break;
            }
            CHECK_INT(status, SC_FAIL);
            CHECK(block.texels == NULL);
            CHECK_CONTAINS(err.message, "out of memory: ");
            failed++;
        }
    }
    sc_scene_free(&scene);
    CHECK(failed > 5);
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
