/* test_gl_faults.c — GL faults end in errors, not crashes: a driver that
 * rejects a program (GLSL broken on purpose, through the cache's own compile
 * and link path) names the key and the GLSL line; a scene over the GPU
 * memory budget is refused before anything is uploaded, with the message a
 * real GL_OUT_OF_MEMORY gives; no EGL falls back to OSMesa and a driver
 * capped below 4.5 names the version it has; and a frame is the same bits
 * every time for the same input and thread count. */
#include "gl_context_util.h"
#include "test.h"

#include <stdlib.h>

#include "emit_glsl.h"
#include "gl_context.h"
#include "io.h"
#include "programs.h"
#include "scene_keys.h"
#include "splinecast.h"

/* `text` with `line` inserted before the line that holds its last '}' (the
 * end of main); *at is the inserted line's number, counted from 1. */
static char *insert_before_end(const char *text, const char *line, int *at)
{
    const char *end = strrchr(text, '}');
    while (end > text && end[-1] != '\n')
        end--;
    *at = 1;
    for (const char *p = text; p < end; p++)
        *at += *p == '\n';
    size_t head = (size_t)(end - text), n = strlen(line);
    char *out = malloc(strlen(text) + n + 1);
    memcpy(out, text, head);
    memcpy(out + head, line, n);
    strcpy(out + head + n, end);
    return out;
}

/* The teapot's key, generated; a broken fragment program given to the
 * cache's driver path fails naming the key, the GLSL line and the line's
 * text; a program that compiles but does not link names the key and the
 * linker's message; the cache stays usable. */
TEST(gl_fault_program_rejected)
{
    TEST_NEED_GL_CONTEXT(ctx);
    sc_scene scene;
    sc_error err = {0};
    CHECK_INT(sc_load_default_scene(&scene, &err), SC_OK);
    scg_key key;
    sc_surface_key(&scene.surfaces[0], NULL, &key);
    sc_scene_free(&scene);
    char key_text[SCG_KEY_MAX];
    scg_key_format(&key, key_text, sizeof key_text);
    scg_generated gen;
    CHECK_INT(scg_generate(&key, &gen, &err), SC_OK);

    sc_program_cache *cache = sc_program_cache_create(sc_gl_context_gl(ctx));
    int line;
    char *broken = insert_before_end(scg_text_str(&gen.fragment),
                                     "    sc_no_such_name = 1.0;\n", &line);
    sc_program program;
    int status = sc_program_from_glsl(cache, &key, gen.vertex_name, scg_text_str(&gen.vertex),
                                      broken, &program, &err);
    free(broken);
    char expect[64], text[1024];
    snprintf(expect, sizeof expect, "the driver rejected frag line %d: ", line);
    CHECK_INT(status, SC_FAIL);
    CHECK_INT(program.id, 0);
    CHECK_STR(err.key, key_text);
    CHECK_INT(err.line, line);
    CHECK_CONTAINS(err.message, expect);
    CHECK_CONTAINS(err.message, "| sc_no_such_name = 1.0;");
    CHECK_CONTAINS(sc_error_text(&err, text, sizeof text), key_text);
    CHECK_INT(sc_program_count(cache), 0);

    char *unlinked = insert_before_end(scg_text_str(&gen.fragment),
                                       "    gl_FragDepth = sc_never_defined(0.5);\n", &line);
    /* Declared, so it compiles; never defined, so it cannot link. */
    const char *decl = "float sc_never_defined(float x);\n";
    char *main_at = strstr(unlinked, "void main");
    CHECK(main_at != NULL);
    size_t head = (size_t)(main_at - unlinked);
    char *with_decl = malloc(strlen(unlinked) + strlen(decl) + 1);
    memcpy(with_decl, unlinked, head);
    strcpy(with_decl + head, decl);
    strcat(with_decl, main_at);
    free(unlinked);
    memset(&err, 0, sizeof err);
    status = sc_program_from_glsl(cache, &key, gen.vertex_name, scg_text_str(&gen.vertex),
                                  with_decl, &program, &err);
    free(with_decl);
    CHECK_INT(status, SC_FAIL);
    CHECK_STR(err.key, key_text);
    CHECK_CONTAINS(err.message, "the driver could not link frag");
    CHECK_CONTAINS(err.message, "sc_never_defined");
    CHECK_INT(sc_program_count(cache), 0);

    /* The generated program itself still compiles in the same cache. */
    CHECK_INT(sc_program_for_key(cache, &key, &program, &err), SC_OK);
    CHECK_INT(sc_program_count(cache), 1);
    scg_generated_free(&gen);
    sc_program_cache_destroy(cache);
}

/* A scene over the GPU memory budget: refused before anything is sent,
 * naming the bytes it needs, the renderer left unmade and the context
 * clean; at exactly its size, and with no budget, it is made and draws the
 * same frame as a renderer that never met a budget. */
TEST(gl_fault_memory_budget)
{
    sc_error err = {0};
    sc_context_id ctx;
    sc_scene_id teapot;
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    CHECK_INT(sc_make_scene(NULL, &teapot, &err), SC_OK);
    sc_renderer_id free_r, r;
    CHECK_INT(sc_make_renderer(ctx, teapot, NULL, &free_r, &err), SC_OK);
    sc_renderer_info info;
    CHECK_INT(sc_query_renderer_info(free_r, &info, &err), SC_OK);
    CHECK(info.gpu_bytes > 1000);

    sc_renderer_desc desc = {.gpu_memory_budget = info.gpu_bytes - 1};
    r.id = 7;
    CHECK_INT(sc_make_renderer(ctx, teapot, &desc, &r, &err), SC_FAIL);
    CHECK_INT(r.id, 0);
    char expect[160];
    snprintf(expect, sizeof expect,
             "out of GPU memory: the scene needs %zu bytes of GPU data "
             "(the GPU memory budget is %zu bytes)", info.gpu_bytes, info.gpu_bytes - 1);
    CHECK_STR(err.message, expect);   /* the words of gl_fault_out_of_memory's */
    desc.gpu_memory_budget = info.gpu_bytes;
    CHECK_INT(sc_make_renderer(ctx, teapot, &desc, &r, &err), SC_OK);
    sc_camera_desc cam = {.width = 48, .height = 40};
    sc_frame_id a, b;
    CHECK_INT(sc_render(free_r, &cam, &a, &err), SC_OK);
    CHECK_INT(sc_render(r, &cam, &b, &err), SC_OK);
    sc_frame_info fa, fb;
    CHECK_INT(sc_query_frame_info(a, &fa, &err), SC_OK);
    CHECK_INT(sc_query_frame_info(b, &fb, &err), SC_OK);
    CHECK(memcmp(fa.rgba, fb.rgba, 4 * 48 * 40) == 0);
    CHECK(memcmp(fa.t, fb.t, sizeof(float) * 48 * 40) == 0);
    sc_shutdown();
}

/* A real GL_OUT_OF_MEMORY (Mesa refuses a buffer over 4 GiB without
 * allocating it) read by the check every upload goes through: the scene's
 * size in the message, the error queue drained. */
TEST(gl_fault_out_of_memory)
{
    TEST_NEED_GL_CONTEXT(ctx);
    const sc_gl *gl = sc_gl_context_gl(ctx);
    GLuint buffer;
    gl->CreateBuffers(1, &buffer);
    gl->NamedBufferStorage(buffer, (GLsizeiptr)1 << 33, NULL, 0);
    sc_error err = {0};
    int status = sc_gl_check_upload(gl, "uploading the patch data", 123456, &err);
    GLenum after = gl->GetError();
    gl->DeleteBuffers(1, &buffer);
    if (status == SC_OK)
        SKIP("this driver gave an 8 GiB buffer: no GL_OUT_OF_MEMORY to test");
    CHECK_STR(err.message, "out of GPU memory: the scene needs 123456 bytes of GPU data "
                           "(GL_OUT_OF_MEMORY after uploading the patch data)");
    CHECK_INT(after, GL_NO_ERROR);
}

/* 1 when the file exists. */
static int exists(const char *dir, const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return access(path, F_OK) == 0;
}

/* A driver capped below 4.5 (Mesa's MESA_GL_VERSION_OVERRIDE, in a child
 * `splinecast render`): the error names the version required and the one
 * found, for each backend tried, and nothing is written. */
TEST(gl_fault_version_below_45)
{
    char cmd[2048], *out = NULL, *err_text = NULL;
    const char *dir = test_tmpdir();
    snprintf(cmd, sizeof cmd,
             "MESA_GL_VERSION_OVERRIDE=3.3 %s render teapot -o %s/capped.png --size 8x8", test_cli,
             dir);
    CHECK_INT(test_run(cmd, &out, &err_text), 1);
    CHECK_CONTAINS(err_text, "EGL: OpenGL 4.5 core is required, the driver offers 3.3 (\"3.3");
    CHECK_CONTAINS(err_text,
                   "; OSMesa: OpenGL 4.5 core is required, the driver offers 3.3 (\"3.3");
    CHECK(!exists(dir, "capped.png") && !exists(dir, "capped.aov"));
    free(out);
    free(err_text);

    /* No core profile at all (3.0): the version of any context the driver
     * makes. */
    snprintf(cmd, sizeof cmd,
             "MESA_GL_VERSION_OVERRIDE=3.0 %s render teapot -o %s/capped.png --size 8x8 "
             "--backend osmesa", test_cli, dir);
    CHECK_INT(test_run(cmd, &out, &err_text), 1);
    CHECK_CONTAINS(err_text, "OSMesa: OpenGL 4.5 core is required, the driver offers 3.0 (\"3.0");
    CHECK(!exists(dir, "capped.png"));
    free(out);
    free(err_text);
}

/* No EGL (libglvnd finds no vendor library): EGL asked for, OSMesa draws
 * after a warning that says what EGL lacks (not "EGL_SUCCESS"). Under
 * AddressSanitizer the leak check is off for this child: what the failed
 * EGL start leaves behind is Mesa's, in libraries unloaded by then, whose
 * names a suppression can no longer match. */
TEST(gl_fault_no_egl_falls_back)
{
    char cmd[2048], *out = NULL, *err_text = NULL;
    const char *dir = test_tmpdir();
    snprintf(cmd, sizeof cmd,
             "ASAN_OPTIONS=detect_leaks=0:abort_on_error=0 "
             "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent %s render teapot -o %s/novendor.png "
             "--size 8x8 --frames 1 --backend egl", test_cli, dir);
    CHECK_INT(test_run(cmd, &out, &err_text), 0);
    CHECK_CONTAINS(err_text, "warning: EGL: ");
    CHECK_CONTAINS(err_text, "; falling back to OSMesa");
    CHECK(strstr(err_text, "EGL_SUCCESS") == NULL);
    CHECK_CONTAINS(err_text, "render: osmesa");
    CHECK_CONTAINS(out, "stats programs=1 ");
    /* The AOV file only when asked for (--aov). */
    CHECK(exists(dir, "novendor.png") && !exists(dir, "novendor.aov"));
    free(out);
    free(err_text);
}

/* 1 when the two files hold the same bytes. */
static int same_bytes(const char *dir, const char *a, const char *b)
{
    char pa[1024], pb[1024];
    snprintf(pa, sizeof pa, "%s/%s", dir, a);
    snprintf(pb, sizeof pb, "%s/%s", dir, b);
    char *da = NULL, *db = NULL;
    size_t na = 0, nb = 0;
    sc_error err = {0};
    int same = sc_read_file(pa, &da, &na, &err) == SC_OK &&
               sc_read_file(pb, &db, &nb, &err) == SC_OK && na == nb && na > 0 &&
               memcmp(da, db, na) == 0;
    if (!same)
        fprintf(stderr, "  %s and %s differ (%zu and %zu bytes) %s\n", a, b, na, nb,
                err.message);
    free(da);
    free(db);
    return same;
}

/* The same input and thread count (LP_NUM_THREADS, fixed by `make test`)
 * give the same bits: two runs of `splinecast render teapot` write the
 * same PNG and AOV bytes, and two frames of one renderer the same image
 * and AOVs, iterations included. */
TEST(gl_fault_same_bits)
{
    char cmd[2048];
    const char *dir = test_tmpdir();
    for (int run = 0; run < 2; run++) {
        snprintf(cmd, sizeof cmd, "%s render teapot -o %s/same%d.png --size 96x80 --frames 1 "
                 "--aov %s/same%d.aov", test_cli, dir, run, dir, run);
        CHECK_INT(test_run(cmd, NULL, NULL), 0);
    }
    CHECK(same_bytes(dir, "same0.png", "same1.png"));
    CHECK(same_bytes(dir, "same0.aov", "same1.aov"));

    sc_error err = {0};
    sc_context_id ctx;
    sc_scene_id teapot;
    sc_renderer_id r;
    if (sc_make_context(NULL, &ctx, &err) != SC_OK) {
        sc_shutdown();
        SKIP("no GL context: %s", err.message);
    }
    CHECK_INT(sc_make_scene(NULL, &teapot, &err), SC_OK);
    CHECK_INT(sc_make_renderer(ctx, teapot, NULL, &r, &err), SC_OK);
    sc_camera_desc cam = {.width = 96, .height = 80};
    sc_frame_id frames[2];
    sc_frame_info f[2];
    for (int i = 0; i < 2; i++) {
        CHECK_INT(sc_render(r, &cam, &frames[i], &err), SC_OK);
        CHECK_INT(sc_query_frame_info(frames[i], &f[i], &err), SC_OK);
    }
    size_t n = 96 * 80;
    CHECK(memcmp(f[0].rgba, f[1].rgba, 4 * n) == 0);
    CHECK(memcmp(f[0].surface, f[1].surface, n * sizeof(int32_t)) == 0);
    CHECK(memcmp(f[0].uv, f[1].uv, 2 * n * sizeof(float)) == 0);
    CHECK(memcmp(f[0].t, f[1].t, n * sizeof(float)) == 0);
    CHECK(memcmp(f[0].point, f[1].point, 3 * n * sizeof(float)) == 0);
    CHECK(memcmp(f[0].normal, f[1].normal, 3 * n * sizeof(float)) == 0);
    CHECK(memcmp(f[0].iters, f[1].iters, n * sizeof(float)) == 0);
    long hits = 0;
    for (size_t p = 0; p < n; p++)
        hits += f[0].surface[p] >= 0;
    CHECK(hits > (long)n / 10);
    sc_shutdown();
}
