/* test_gl_faults.c — GL faults end in errors, not crashes: a driver that
 * rejects a program (GLSL broken on purpose, through the cache's own compile
 * and link path) names the key and the GLSL line; a scene over the GPU
 * memory budget is refused before anything is uploaded, with the message a
 * real GL_OUT_OF_MEMORY gives; no EGL falls back to OSMesa and a driver
 * capped below 4.5 names the version it has; and a frame is the same bits
 * every time for the same input and thread count. */
#include "test.h"

#include <stdlib.h>

#include "emit_glsl.h"
#include "gl_context.h"
#include "io.h"
#include "programs.h"
#include "scene_keys.h"

static sc_gl_context *fault_context(const char **why)
{
    static sc_gl_context *ctx;
    static sc_error err;
    static int tried;
    if (!tried) {
        tried = 1;
        sc_gl_context_desc desc = {0};
        sc_gl_context_create(&desc, &ctx, &err);
    }
    *why = err.message;
    if (ctx && sc_gl_context_make_current(ctx, &err) != SC_OK)
        return NULL;
    return ctx;
}

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
    const char *why;
    sc_gl_context *ctx = fault_context(&why);
    if (!ctx)
        SKIP("no GL context: %s", why);
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
