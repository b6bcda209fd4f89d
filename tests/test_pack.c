/* test_pack.c — build time to run time (docs/api.md, docs/pack-format.md):
 * a scene packed without GL and drawn from the pack gives the image of a
 * renderer made from the scene; damaged packs fail with what is wrong;
 * programs come from a `splinecast gen` folder by its manifest (a missing
 * or changed key fails naming it, or is generated when asked) and from a
 * binary cache on a second start; examples/packed_gl.c, built against an
 * installed copy, draws a pack with generated programs. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>
#include <string.h>

#include "embed_util.h"
#include "io.h"
#include "pack_file.h"
#include "splinecast.h"

/* Counts the library's program messages by kind. */
typedef struct program_log {
    int generated, read, from_binary;
    int lists_read;            /* read programs of candidate lists (ert5) */
} program_log;

static void count_programs(sc_log_level level, const char *message, void *user)
{
    (void)level;
    program_log *log = user;
    log->generated += strstr(message, ": generated in ") != NULL;
    log->read += strstr(message, ": read in ") != NULL;
    log->lists_read += strstr(message, ": read in ") && strstr(message, "-ert5-");
    log->from_binary += strstr(message, ": loaded from the binary cache") != NULL;
}

static void tmp_path(char *buf, size_t size, const char *name)
{
    snprintf(buf, size, "%s/%s", test_tmpdir(), name);
}

static int run_cli(const char *args, char **out, char **errs)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' %.3000s", test_cli, args);
    return test_run(cmd, out, errs);
}

/* The trimmed example scene packed and drawn: the same image, pixel for
 * pixel and AOV for AOV, as a renderer made from the scene itself. */
TEST(pack_renderer_draws_the_scene_s_image)
{
    const char *scene_path = test_root("examples/scenes/trim_nine.obj");
    char pack[1024];
    tmp_path(pack, sizeof pack, "nine.pack");
    sc_error err = {0};
    sc_scene_id scene;
    sc_context_id ctx;
    CHECK_INT(sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err), SC_OK);
    CHECK_INT(sc_save_pack(scene, NULL, pack, &err), SC_OK);
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    /* A packed renderer draws every hull as a hull (it keeps no sub-patch
     * domains on the CPU for candidate lists): the direct one too, for
     * the same pixels. */
    sc_renderer_id direct, packed;
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.list_below_px = SC_LISTS_OFF},
                               &direct, &err),
              SC_OK);
    CHECK_INT(sc_make_renderer(ctx, (sc_scene_id){0}, &(sc_renderer_desc){.pack = pack}, &packed,
                               &err),
              SC_OK);
    /* The same keys, hulls and bytes. */
    sc_renderer_info a, b;
    CHECK_INT(sc_query_renderer_info(direct, &a, &err), SC_OK);
    CHECK_INT(sc_query_renderer_info(packed, &b, &err), SC_OK);
    CHECK_INT(b.hulls, a.hulls);
    CHECK_INT(b.triangles, a.triangles);
    CHECK_INT((long)b.gpu_bytes, (long)a.gpu_bytes);
    CHECK_INT(b.programs, a.programs);
    for (int c = 0; c < 3; c++) {
        CHECK_NEAR(b.lo[c], a.lo[c], 0);
        CHECK_NEAR(b.hi[c], a.hi[c], 0);
    }
    sc_key ka[8], kb[8];
    int na = 0, nb = 0;
    CHECK_INT(sc_query_renderer_keys(direct, ka, 8, &na, &err), SC_OK);
    CHECK_INT(sc_query_renderer_keys(packed, kb, 8, &nb, &err), SC_OK);
    CHECK_INT(nb, na);
    for (int k = 0; k < na && k < nb && k < 8; k++)
        CHECK_STR(kb[k].text, ka[k].text);
    /* The default view frames the same box. */
    sc_camera_desc view = {.width = 96, .height = 96};
    sc_frame_id fa, fb;
    CHECK_INT(sc_render(direct, &view, &fa, &err), SC_OK);
    CHECK_INT(sc_render(packed, &view, &fb, &err), SC_OK);
    sc_frame_info ia, ib;
    CHECK_INT(sc_query_frame_info(fa, &ia, &err), SC_OK);
    CHECK_INT(sc_query_frame_info(fb, &ib, &err), SC_OK);
    CHECK_STR(ib.camera, ia.camera);
    long hits = 0, differ = 0;
    for (int p = 0; p < 96 * 96; p++) {
        hits += ia.surface[p] >= 0;
        differ += ia.surface[p] != ib.surface[p] || ia.t[p] != ib.t[p] ||
                  memcmp(ia.rgba + 4 * p, ib.rgba + 4 * p, 4) != 0;
    }
    CHECK(hits > 96 * 96 / 10);
    CHECK_INT(differ, 0);
    /* What the pack decided cannot be asked again. */
    sc_renderer_id bad;
    CHECK_INT(sc_make_renderer(ctx, (sc_scene_id){0},
                               &(sc_renderer_desc){.pack = pack, .max_iters = 3}, &bad, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.message, "max_iters is fixed by the pack");
    CHECK_INT(sc_make_renderer(ctx, (sc_scene_id){0},
                               &(sc_renderer_desc){.pack = pack, .eval = SC_EVAL_DC}, &bad, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.message, "eval is fixed by the pack");
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.pack = pack}, &bad, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.message, "zero handle");
    sc_shutdown();
}

/* Damaged packs: each fails with the file's name and what is wrong, and
 * nothing is drawn. */
TEST(pack_damaged_files_refused)
{
    char pack[1024], broken[1024];
    tmp_path(pack, sizeof pack, "teapot.pack");
    tmp_path(broken, sizeof broken, "broken.pack");
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    CHECK_INT(sc_save_pack(scene, NULL, pack, &err), SC_OK);
    char *data;
    size_t size;
    CHECK_INT(sc_read_file(pack, &data, &size, &err), SC_OK);
    sc_pack k;
    CHECK_INT(sc_pack_parse((unsigned char *)data, size, "t.pack", &k, &err), SC_OK);
    CHECK_INT(k.nsurfaces, 32);
    CHECK(k.nhulls >= 32);
    sc_pack_free(&k);

    struct {
        const char *what;
        size_t at;          /* byte changed (or new size when truncating) */
        int truncate;
        const char *message;
    } cases[] = {
        {"magic", 0, 0, "not a splinecast pack"},
        {"version", 8, 0, "pack version 2; this library reads version 1"},
        {"a byte of data", 0, 0, "checksum mismatch"},
        {"truncation", 1000, 1, "truncated: the header says"},
        {"truncation inside the header", 20, 1, "truncated"},
    };
    cases[2].at = size - 40;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        unsigned char *copy = malloc(size);
        memcpy(copy, data, size);
        size_t n = size;
        if (cases[c].truncate)
            n = cases[c].at;
        else if (c == 1)
            copy[8] = 2;
        else
            copy[cases[c].at] ^= 0x5a;
        FILE *f = fopen(broken, "wb");
        fwrite(copy, 1, n, f);
        fclose(f);
        free(copy);
        memset(&err, 0, sizeof err);
        CHECK_INT(sc_pack_read(broken, &k, &err), SC_FAIL);
        CHECK_STR(err.file, broken);
        CHECK_CONTAINS(err.message, cases[c].message);
    }
    free(data);
    /* Through the API and the command line. */
    sc_context_id ctx;
    if (sc_make_context(NULL, &ctx, &err) == SC_OK) {
        sc_renderer_id r;
        CHECK_INT(sc_make_renderer(ctx, (sc_scene_id){0}, &(sc_renderer_desc){.pack = broken},
                                   &r, &err),
                  SC_FAIL);
        CHECK_CONTAINS(err.message, "truncated");
    }
    char args[2048], *out = NULL, *errs = NULL;
    snprintf(args, sizeof args, "pack teapot -o '%s/cli.pack' --iters 0", test_tmpdir());
    CHECK_INT(run_cli(args, NULL, &errs), 2);
    CHECK_CONTAINS(errs, "--iters takes 1 to");
    free(errs);
    snprintf(args, sizeof args, "pack teapot -o '%s/cli.pack'", test_tmpdir());
    CHECK_INT(run_cli(args, &out, NULL), 0);
    CHECK_CONTAINS(out, "cli.pack bytes=");
    free(out);
    sc_shutdown();
}

/* The pixels of a 128 x 128 frame of the teapot that hit it. */
static long frame_hits(sc_renderer_id r)
{
    sc_error err = {0};
    sc_frame_id frame;
    sc_frame_info info;
    if (sc_render(r, &(sc_camera_desc){.width = 128, .height = 128}, &frame, &err) != SC_OK ||
        sc_query_frame_info(frame, &info, &err) != SC_OK) {
        fprintf(stderr, "  frame: %s\n", err.message);
        return -1;
    }
    long hits = 0;
    for (int p = 0; p < 128 * 128; p++)
        hits += info.surface[p] >= 0;
    return hits;
}

/* Programs from a gen folder: read, not generated, those of candidate
 * lists included; a folder without them draws those hulls as hulls; a key
 * the manifest lacks, and a file changed since, fail naming the key;
 * generate_missing generates what is missing. */
TEST(pack_programs_from_gen_folder)
{
    char dir[1024], args[2048];
    tmp_path(dir, sizeof dir, "gen-teapot");
    snprintf(args, sizeof args, "gen --scene teapot -o '%s'", dir);
    CHECK_INT(run_cli(args, NULL, NULL), 0);
    sc_error err = {0};
    sc_scene_id scene;
    CHECK_INT(sc_make_scene(NULL, &scene, &err), SC_OK);
    program_log log = {0};
    sc_set_logger(count_programs, &log);
    sc_set_log_level(SC_LOG_INFO);
    sc_context_id ctx;
    if (sc_make_context(&(sc_context_desc){.programs_dir = dir}, &ctx, &err) != SC_OK) {
        sc_set_logger(NULL, NULL);
        sc_set_log_level(SC_LOG_WARN);
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    sc_renderer_id r;
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &r, &err), SC_OK);
    CHECK_INT(log.generated, 0);
    CHECK_INT(log.read, 1);
    /* A frame whose small hulls the default lists: gen --scene wrote their
     * list programs too. */
    long hits = frame_hits(r);
    CHECK(hits > 128 * 128 / 20);
    CHECK_INT(log.generated, 0);
    CHECK(log.lists_read > 0);
    /* A folder of the scene's keys alone: those hulls are drawn as hulls,
     * with what the folder has, and cover the same pixels. */
    sc_key keys[2];
    int n = 0;
    CHECK_INT(sc_query_scene_keys(scene, NULL, &keys[0], 1, &n, &err), SC_OK);
    CHECK_INT(sc_query_scene_keys(scene, &(sc_keys_desc){.outputs = SC_OUTPUT_SHADE}, &keys[1], 1,
                                  &n, &err),
              SC_OK);
    char keys_dir[1024];
    tmp_path(keys_dir, sizeof keys_dir, "gen-teapot-keys");
    snprintf(args, sizeof args, "gen --key %s %s -o '%s'", keys[0].text, keys[1].text, keys_dir);
    CHECK_INT(run_cli(args, NULL, NULL), 0);
    sc_context_id keys_ctx;
    CHECK_INT(sc_make_context(&(sc_context_desc){.programs_dir = keys_dir}, &keys_ctx, &err),
              SC_OK);
    sc_renderer_id keys_r;
    CHECK_INT(sc_make_renderer(keys_ctx, scene, NULL, &keys_r, &err), SC_OK);
    int lists_read = log.lists_read;
    CHECK_INT(frame_hits(keys_r), hits);
    CHECK_INT(log.generated, 0);
    CHECK_INT(log.lists_read, lists_read);
    sc_destroy_context(keys_ctx);
    /* Another key: not in the folder. */
    sc_renderer_id other;
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.max_iters = 3}, &other, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.key, "-it3-");
    CHECK_CONTAINS(err.message, "not in ");
    CHECK_CONTAINS(err.message, "manifest.tsv");
    sc_destroy_context(ctx);
    /* ... generated when asked. */
    CHECK_INT(sc_make_context(&(sc_context_desc){.programs_dir = dir, .generate_missing = 1},
                              &ctx, &err),
              SC_OK);
    CHECK_INT(sc_make_renderer(ctx, scene, &(sc_renderer_desc){.max_iters = 3}, &other, &err),
              SC_OK);
    CHECK_INT(log.generated, 1);
    sc_destroy_context(ctx);
    /* A fragment program changed after gen wrote it: the one a renderer
     * draws with, which writes no AOVs. */
    char path[1400];
    snprintf(path, sizeof path, "%s/%s.frag", dir, keys[1].text);
    FILE *f = fopen(path, "a");
    CHECK(f != NULL);
    fputs("// edited\n", f);
    fclose(f);
    CHECK_INT(sc_make_context(&(sc_context_desc){.programs_dir = dir}, &ctx, &err), SC_OK);
    CHECK_INT(sc_make_renderer(ctx, scene, NULL, &r, &err), SC_FAIL);
    CHECK_STR(err.key, keys[1].text);
    CHECK_CONTAINS(err.message, "where the manifest says");
    sc_destroy_context(ctx);
    /* A folder without a manifest. */
    CHECK_INT(sc_make_context(&(sc_context_desc){.programs_dir = test_tmpdir()}, &ctx, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.file, "manifest.tsv");
    sc_set_logger(NULL, NULL);
    sc_set_log_level(SC_LOG_WARN);
    sc_shutdown();
}

/* Linked programs kept on disk: a second context loads the binary instead
 * of compiling, when the driver has binary formats; without them nothing
 * is written and the program is compiled. */
TEST(pack_binary_cache_second_start)
{
    char cache[1024];
    tmp_path(cache, sizeof cache, "binary-cache");
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", cache);
    CHECK_INT(test_run(cmd, NULL, NULL), 0);
    program_log log = {0};
    sc_set_logger(count_programs, &log);
    sc_set_log_level(SC_LOG_INFO);
    sc_error err = {0};
    sc_context_id ctx;
    const char *key = "bez2x2-poly-dc-trim0-newton-cp-it4-tol0.05-ert0-out.shade";
    if (sc_make_context(&(sc_context_desc){.binary_cache_dir = cache}, &ctx, &err) != SC_OK) {
        sc_set_logger(NULL, NULL);
        sc_set_log_level(SC_LOG_WARN);
        SKIP("no GL context: %s", err.message);
    }
    sc_program_id p;
    CHECK_INT(sc_make_program(ctx, key, &p, &err), SC_OK);
    CHECK_INT(log.generated, 1);
    CHECK_INT(log.from_binary, 0);
    sc_destroy_context(ctx);
    /* KEY.DRIVER.bin, the key in its canonical text. */
    snprintf(cmd, sizeof cmd, "(ls '%s' 2>/dev/null | grep -c '^bez2x2-.*-it4-.*\\.[0-9a-f]\\{16\\}\\.bin$')",
             cache);
    char *out = NULL;
    test_run(cmd, &out, NULL);
    int files = out ? atoi(out) : 0;
    free(out);
    CHECK_INT(sc_make_context(&(sc_context_desc){.binary_cache_dir = cache}, &ctx, &err), SC_OK);
    CHECK_INT(sc_make_program(ctx, key, &p, &err), SC_OK);
    /* The GLSL is generated again (it keys the binary); the driver's
     * compiler is not run when a binary was kept. */
    CHECK_INT(log.generated + log.from_binary, 2);
    CHECK_INT(log.from_binary, files);
    sc_program_info info;
    CHECK_INT(sc_query_program_info(p, &info, &err), SC_OK);
    CHECK(info.gl_program != 0);
    sc_set_logger(NULL, NULL);
    sc_set_log_level(SC_LOG_WARN);
    sc_shutdown();
}

/* examples/packed_gl.c against an installed copy: a pack and a gen folder
 * drawn in the program's own GL; the second start loads what the first
 * kept, and draws the same pixels. */
TEST(pack_example_against_installed_copy)
{
    char exe[1024], dir[1024], pack[1024], cache[1024], image[1024], args[8192];
    if (test_build_example("packed_gl", exe, sizeof exe) != 0)
        return;
    tmp_path(dir, sizeof dir, "gen-nine");
    tmp_path(pack, sizeof pack, "example-nine.pack");
    tmp_path(cache, sizeof cache, "example-cache");
    tmp_path(image, sizeof image, "packed.ppm");
    const char *scene = test_root("examples/scenes/trim_nine.obj");
    snprintf(args, sizeof args, "gen --scene '%s' -o '%s'", scene, dir);
    CHECK_INT(run_cli(args, NULL, NULL), 0);
    snprintf(args, sizeof args, "pack '%s' -o '%s'", scene, pack);
    CHECK_INT(run_cli(args, NULL, NULL), 0);
    snprintf(args, sizeof args, "rm -rf '%s' && '%s' '%s' '%s' '%s' '%s' 96 96", cache, exe, pack,
             dir, cache, image);
    char *out[2] = {NULL, NULL}, *errs = NULL;
    int status = test_run(args, &out[0], &errs);
    if (status != 0 && errs && strstr(errs, "context"))
        SKIP("no GL context: %s", errs);
    if (status != 0)
        fprintf(stderr, "  %s\n%s", args, errs ? errs : "");
    free(errs);
    CHECK_INT(status, 0);
    snprintf(args, sizeof args, "'%s' '%s' '%s' '%s' '%s' 96 96", exe, pack, dir, cache, image);
    CHECK_INT(test_run(args, &out[1], NULL), 0);
    for (int i = 0; i < 2; i++) {
        CHECK(out[i] && strstr(out[i], "first_frame_ms="));
        CHECK(out[i] && strstr(out[i], "wrote "));
    }
    const char *c0 = out[0] ? strstr(out[0], "covered=") : NULL;
    const char *c1 = out[1] ? strstr(out[1], "covered=") : NULL;
    CHECK(c0 && c1 && atol(c0 + 8) > 96 * 96 / 20);
    if (c0 && c1)
        CHECK_INT(atol(c1 + 8), atol(c0 + 8));
    free(out[0]);
    free(out[1]);
    /* A gen folder of other keys: the example fails naming the key. */
    char other[1024];
    tmp_path(other, sizeof other, "gen-other");
    snprintf(args, sizeof args, "gen --scene teapot -o '%s'", other);
    CHECK_INT(run_cli(args, NULL, NULL), 0);
    snprintf(args, sizeof args, "'%s' '%s' '%s' - '%s' 96 96", exe, pack, other, image);
    errs = NULL;
    CHECK_INT(test_run(args, NULL, &errs), 1);
    CHECK_CONTAINS(errs, "key ");
    CHECK_CONTAINS(errs, "-fast");
    CHECK_CONTAINS(errs, "manifest.tsv");
    free(errs);
}
