/* programs.c — the program cache (programs.h): keys are looked up by their
 * canonical text; a miss runs gen's whole pipeline (scg_generate: build,
 * optimise, emit, glslang) and then the driver's compiler. */
#include "programs.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "emit_glsl.h"
#include "gl_binary_cache.h"
#include "glslang_check.h"
#include "programs_dir.h"

typedef struct entry {
    char key_text[SCG_KEY_MAX];
    scg_key key;
    GLuint program;
    double gen_ms, gl_ms;
} entry;

typedef struct vertex_shader {
    char name[64];
    GLuint shader;
} vertex_shader;

struct sc_program_cache {
    const sc_gl *gl;
    int count, cap;
    entry *entries;
    int nvertex, cap_vertex;
    vertex_shader *vertex;
    /* Where programs come from besides the compiler (sc_program_cache_set_sources). */
    sc_programs_dir *dir;
    int generate_missing;
    sc_binary_cache *binary;
};

sc_program_cache *sc_program_cache_create(const sc_gl *gl)
{
    sc_program_cache *cache = sc_alloc(1, sizeof *cache);
    cache->gl = gl;
    return cache;
}

void sc_program_cache_destroy(sc_program_cache *cache)
{
    if (!cache)
        return;
    for (int i = 0; i < cache->count; i++)
        cache->gl->DeleteProgram(cache->entries[i].program);
    for (int i = 0; i < cache->nvertex; i++)
        cache->gl->DeleteShader(cache->vertex[i].shader);
    free(cache->entries);
    free(cache->vertex);
    sc_programs_dir_close(cache->dir);
    sc_binary_cache_close(cache->binary);
    free(cache);
}

int sc_program_cache_set_sources(sc_program_cache *cache, const char *glsl_dir,
                                 int generate_missing, const char *binary_dir, sc_error *err)
{
    if (glsl_dir && sc_programs_dir_open(glsl_dir, &cache->dir, err) != SC_OK)
        return SC_FAIL;
    cache->generate_missing = generate_missing;
    if (binary_dir)
        cache->binary = sc_binary_cache_open(cache->gl, binary_dir);
    return SC_OK;
}

/* Compiles one stage; on failure err gets the driver's log, the line it
 * names and the key. */
static GLuint compile(const sc_gl *gl, GLenum stage, const char *source, const char *key,
                      sc_error *err)
{
    GLuint shader = gl->CreateShader(stage);
    gl->ShaderSource(shader, 1, &source, NULL);
    gl->CompileShader(shader);
    GLint ok = 0;
    gl->GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetShaderInfoLog(shader, sizeof log, NULL, log);
        gl->DeleteShader(shader);
        scg_fail_shader_log(err, key,
                            stage == GL_VERTEX_SHADER ? "the driver rejected vert"
                                                      : "the driver rejected frag",
                            log, source);
        return 0;
    }
    return shader;
}

static GLuint vertex_shader_for(sc_program_cache *cache, const char *name, const char *source,
                                const char *key, sc_error *err)
{
    for (int i = 0; i < cache->nvertex; i++)
        if (!strcmp(cache->vertex[i].name, name))
            return cache->vertex[i].shader;
    GLuint shader = compile(cache->gl, GL_VERTEX_SHADER, source, key, err);
    if (!shader)
        return 0;
    if (cache->nvertex == cache->cap_vertex) {
        cache->cap_vertex = cache->cap_vertex ? 2 * cache->cap_vertex : 4;
        cache->vertex = sc_realloc(cache->vertex, (size_t)cache->cap_vertex, sizeof *cache->vertex);
    }
    vertex_shader *v = &cache->vertex[cache->nvertex++];
    snprintf(v->name, sizeof v->name, "%s", name);
    v->shader = shader;
    return shader;
}

/* The cached program of the key's canonical text, or 0. */
static uint32_t find(const sc_program_cache *cache, const char *text)
{
    for (int i = 0; i < cache->count; i++)
        if (!strcmp(cache->entries[i].key_text, text))
            return (uint32_t)i + 1;
    return 0;
}

static int add_entry(sc_program_cache *cache, const scg_key *key, const char *text,
                     GLuint program, double gen_ms, double gl_ms, int from_binary,
                     sc_program *out);

/* Compiles, links and caches; gen_ms is what generating took. */
static int from_glsl(sc_program_cache *cache, const scg_key *key, const char *text,
                     const char *vertex_name, const char *vertex, const char *fragment,
                     double gen_ms, sc_program *out, sc_error *err)
{
    const sc_gl *gl = cache->gl;
    double t1 = sc_now();
    uint64_t source_hash = cache->binary ? sc_binary_cache_source_hash(vertex, fragment) : 0;
    GLuint program = sc_binary_cache_load(cache->binary, text, source_hash);
    if (program)
        return add_entry(cache, key, text, program, gen_ms, 1e3 * (sc_now() - t1), 1, out);
    GLuint vs = vertex_shader_for(cache, vertex_name, vertex, text, err);
    GLuint fs = vs ? compile(gl, GL_FRAGMENT_SHADER, fragment, text, err) : 0;
    if (!fs)
        return SC_FAIL;
    program = gl->CreateProgram();
    sc_binary_cache_prepare(cache->binary, program);
    gl->AttachShader(program, vs);
    gl->AttachShader(program, fs);
    gl->LinkProgram(program);
    gl->DetachShader(program, vs);
    gl->DetachShader(program, fs);
    gl->DeleteShader(fs);
    GLint ok = 0;
    gl->GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetProgramInfoLog(program, sizeof log, NULL, log);
        gl->DeleteProgram(program);
        /* Link logs seldom name a line; when one does, it is the
         * fragment program's (the vertex programs are shared and linked
         * with every key). */
        return scg_fail_shader_log(err, text, "the driver could not link frag", log, fragment);
    }
    double t2 = sc_now();
    sc_binary_cache_store(cache->binary, text, source_hash, program);
    return add_entry(cache, key, text, program, gen_ms, 1e3 * (t2 - t1), 0, out);
}

/* Caches a linked program; from_binary: loaded from the binary cache. */
static int add_entry(sc_program_cache *cache, const scg_key *key, const char *text,
                     GLuint program, double gen_ms, double gl_ms, int from_binary,
                     sc_program *out)
{
    if (cache->count == cache->cap) {
        cache->cap = cache->cap ? 2 * cache->cap : 8;
        cache->entries = sc_realloc(cache->entries, (size_t)cache->cap, sizeof *cache->entries);
    }
    entry *e = &cache->entries[cache->count++];
    snprintf(e->key_text, sizeof e->key_text, "%s", text);
    e->key = *key;
    e->program = program;
    e->gen_ms = gen_ms;
    e->gl_ms = gl_ms;
    if (from_binary)
        sc_log(SC_LOG_INFO, "program %s: loaded from the binary cache in %.0f ms", text, gl_ms);
    else
        sc_log(SC_LOG_INFO, "program %s: %s in %.0f ms, compiled in %.0f ms", text,
               gen_ms > 0 ? "generated" : "read", e->gen_ms, e->gl_ms);
    out->id = (uint32_t)cache->count;
    return SC_OK;
}

int sc_program_cache_offers(const sc_program_cache *cache, const scg_key *key)
{
    if (!cache->dir || cache->generate_missing)
        return 1;
    char text[SCG_KEY_MAX];
    scg_key_format(key, text, sizeof text);
    return find(cache, text) != 0 || sc_programs_dir_has(cache->dir, text);
}

int sc_program_for_key(sc_program_cache *cache, const scg_key *key, sc_program *out,
                       sc_error *err)
{
    char text[SCG_KEY_MAX];
    scg_key_format(key, text, sizeof text);
    if ((out->id = find(cache, text)) != 0)
        return SC_OK;
    double t0 = sc_now();
    if (cache->dir && (!cache->generate_missing || sc_programs_dir_has(cache->dir, text))) {
        /* Built at build time: read, not generated (no compiler, no glslang). */
        char vertex_name[64], *vertex, *fragment;
        if (sc_programs_dir_load(cache->dir, text, vertex_name, &vertex, &fragment, err) != SC_OK)
            return SC_FAIL;
        int status = from_glsl(cache, key, text, vertex_name, vertex, fragment, 0, out, err);
        free(vertex);
        free(fragment);
        return status;
    }
    scg_generated gen;
    if (scg_generate(key, &gen, err) != SC_OK)
        return SC_FAIL;
    int status = from_glsl(cache, key, text, gen.vertex_name, scg_text_str(&gen.vertex),
                           scg_text_str(&gen.fragment), 1e3 * (sc_now() - t0), out, err);
    scg_generated_free(&gen);
    return status;
}

int sc_program_from_glsl(sc_program_cache *cache, const scg_key *key, const char *vertex_name,
                         const char *vertex, const char *fragment, sc_program *out,
                         sc_error *err)
{
    char text[SCG_KEY_MAX];
    scg_key_format(key, text, sizeof text);
    if ((out->id = find(cache, text)) != 0)
        return SC_OK;
    return from_glsl(cache, key, text, vertex_name, vertex, fragment, 0, out, err);
}

static const entry *lookup(const sc_program_cache *cache, sc_program program)
{
    if (program.id == 0 || program.id > (uint32_t)cache->count)
        return NULL;
    return &cache->entries[program.id - 1];
}

GLuint sc_program_gl_name(const sc_program_cache *cache, sc_program program)
{
    const entry *e = lookup(cache, program);
    return e ? e->program : 0;
}

const scg_key *sc_program_key(const sc_program_cache *cache, sc_program program)
{
    const entry *e = lookup(cache, program);
    return e ? &e->key : NULL;
}

int sc_program_count(const sc_program_cache *cache) { return cache->count; }

void sc_program_times(const sc_program_cache *cache, sc_program program, double *gen_ms,
                      double *gl_ms)
{
    const entry *e = lookup(cache, program);
    *gen_ms = e ? e->gen_ms : 0;
    *gl_ms = e ? e->gl_ms : 0;
}
