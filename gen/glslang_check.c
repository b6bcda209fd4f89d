/* glslang_check.c — in-process validation of generated GLSL with glslang's
 * C interface (glslang_check.h). A separate glslangValidator process costs
 * about 0.1 s per file; in process the cost is the parse itself, which is
 * what lets the tests validate whole key families. */
#define _POSIX_C_SOURCE 200809L
#include "glslang_check.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>

/* No automatic location or binding mapping: the emitted programs declare
 * every location and binding (SPIR-V for OpenGL needs them), and glslang's
 * mapping would decorate plain uniforms with a descriptor set, which OpenGL
 * has not; without it the SPIR-V is what `glslangValidator -G` makes. */

enum { SPIRV_MAGIC = 0x07230203u, SPIRV_HEADER_WORDS = 5 };

const char *scg_stage_extension(scg_stage stage)
{
    return stage == SCG_STAGE_VERTEX ? "vert" : "frag";
}

const char *scg_stage_audit_name(scg_stage stage)
{
    return stage == SCG_STAGE_VERTEX ? "VS" : "FS";
}

static pthread_once_t glslang_once = PTHREAD_ONCE_INIT;

/* Finalising at exit returns glslang's global pools, which would otherwise
 * show up as leaks under the sanitizer. */
static void glslang_finalize_at_exit(void) { glslang_finalize_process(); }

static void glslang_init(void)
{
    glslang_initialize_process();
    atexit(glslang_finalize_at_exit);
}

static glslang_stage_t glslang_stage_of(scg_stage stage)
{
    return stage == SCG_STAGE_VERTEX ? GLSLANG_STAGE_VERTEX : GLSLANG_STAGE_FRAGMENT;
}

static glslang_input_t input_for(scg_stage stage, const char *glsl)
{
    glslang_input_t in = {
        .language = GLSLANG_SOURCE_GLSL,
        .stage = glslang_stage_of(stage),
        .client = GLSLANG_CLIENT_OPENGL,
        .client_version = GLSLANG_TARGET_OPENGL_450,
        .target_language = GLSLANG_TARGET_SPV,
        .target_language_version = GLSLANG_TARGET_SPV_1_0,
        .code = glsl,
        .default_version = 450,
        .default_profile = GLSLANG_CORE_PROFILE,
        .force_default_version_and_profile = 0,
        .forward_compatible = 0,
        .messages = GLSLANG_MSG_DEFAULT_BIT | GLSLANG_MSG_SPV_RULES_BIT,
        .resource = glslang_default_resource(),
    };
    return in;
}

/* Copies line `line` (1-based) of text into buf, without leading blanks. */
static void source_line(const char *text, int line, char *buf, size_t size)
{
    buf[0] = 0;
    for (int n = 1; n < line && text; n++) {
        text = strchr(text, '\n');
        if (text)
            text++;
    }
    if (!text || !*text)
        return;
    while (*text == ' ' || *text == '\t')
        text++;
    size_t len = strcspn(text, "\n");
    if (len >= size)
        len = size - 1;
    memcpy(buf, text, len);
    buf[len] = 0;
}

/* Logs name a line as "ERROR: 0:LINE: message" (glslang, AMD),
 * "0:LINE(COL): error: message" (Mesa) or "0(LINE) : error C…: message"
 * (NVIDIA). The first line that reports an error is the one to show (a
 * warning may come before it); later errors usually follow from it. */
static int first_error(const char *log, int *line, char *msg, size_t size)
{
    *line = 0;
    const char *e = NULL;
    for (const char *l = log; l && *l && !e; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        char text[512];
        snprintf(text, sizeof text, "%.*s", (int)strcspn(l, "\n"), l);
        if (strstr(text, "ERROR") || strstr(text, "error"))
            e = l;
    }
    if (!e) {
        snprintf(msg, size, "%s", log && *log ? log : "rejected without a message");
        msg[strcspn(msg, "\n")] = 0;
        return 0;
    }
    if (!strncmp(e, "ERROR: ", 7))
        e += 7;
    int string_no = 0, consumed = 0;
    if (sscanf(e, "%d:%d%n", &string_no, line, &consumed) == 2 &&
        (e[consumed] == ':' || e[consumed] == '(')) {
        e += consumed;
        if (*e == '(')
            e += strcspn(e, ")\n") + (e[strcspn(e, ")\n")] == ')');
    } else if (sscanf(e, "%d(%d)%n", &string_no, line, &consumed) == 2 && consumed > 0) {
        e += consumed;
    } else {
        *line = 0;
    }
    while (*e == ' ' || *e == ':')
        e++;
    size_t len = strcspn(e, "\n");
    if (len >= size)
        len = size - 1;
    memcpy(msg, e, len);
    msg[len] = 0;
    return *line;
}

int scg_fail_shader_log(sc_error *err, const char *key, const char *what, const char *log,
                        const char *glsl)
{
    char msg[300], code[160];
    int line = 0;
    first_error(log, &line, msg, sizeof msg);
    code[0] = 0;
    if (line > 0 && glsl)
        source_line(glsl, line, code, sizeof code);
    if (line > 0)
        sc_fail_key(err, key, "%s line %d: %s | %s", what, line, msg, code);
    else
        sc_fail_key(err, key, "%s: %s", what, msg);
    if (err)
        err->line = line;
    return SC_FAIL;
}

int scg_spirv_count_instructions(const unsigned int *words, size_t nwords)
{
    if (nwords < SPIRV_HEADER_WORDS || words[0] != SPIRV_MAGIC)
        return -1;
    int count = 0;
    for (size_t at = SPIRV_HEADER_WORDS; at < nwords; count++) {
        size_t wc = words[at] >> 16;
        if (wc == 0 || wc > nwords - at)
            return -1;
        at += wc;
    }
    return count;
}

/* Parses one stage into a new shader object, or fails with its log. */
static glslang_shader_t *parse_stage(scg_stage stage, const char *glsl, const char *key,
                                     sc_error *err)
{
    glslang_input_t in = input_for(stage, glsl);
    glslang_shader_t *shader = glslang_shader_create(&in);
    if (!shader) {
        sc_fail_key(err, key, "glslang could not create a shader");
        return NULL;
    }
    if (!glslang_shader_preprocess(shader, &in) || !glslang_shader_parse(shader, &in)) {
        scg_fail_shader_log(err, key, scg_stage_extension(stage),
                            glslang_shader_get_info_log(shader), glsl);
        glslang_shader_delete(shader);
        return NULL;
    }
    return shader;
}

/* Translates the linked program's `stage` to SPIR-V and counts it. glslang
 * appends each translation of one program to the same buffer, so the
 * module of this stage starts where the previous one ended. */
static int count_spirv(glslang_program_t *program, scg_stage stage, const char *key,
                       size_t *consumed, scg_glslang_result *result, sc_error *err)
{
    glslang_spv_options_t spv = {.disable_optimizer = true, .validate = false};
    glslang_program_SPIRV_generate_with_options(program, glslang_stage_of(stage), &spv);
    const char *spv_messages = glslang_program_SPIRV_get_messages(program);
    size_t nwords = glslang_program_SPIRV_get_size(program);
    const unsigned int *words = glslang_program_SPIRV_get_ptr(program);
    size_t start = *consumed < nwords && words[*consumed] == SPIRV_MAGIC ? *consumed : 0;
    int count = scg_spirv_count_instructions(words + start, nwords - start);
    if (count < 0) {
        return sc_fail_key(err, key, "%s: no valid SPIR-V%s%s", scg_stage_extension(stage),
                           spv_messages ? ": " : "", spv_messages ? spv_messages : "");
    }
    *consumed = nwords;
    result->spirv_instructions = count;
    result->spirv_words = nwords - start;
    return SC_OK;
}

/* Links the given shaders (NULL entries skipped) and counts SPIR-V for the
 * stages whose result pointer is not NULL. */
static int link_and_count(glslang_shader_t *vertex, glslang_shader_t *fragment, const char *key,
                          scg_glslang_result *vertex_result,
                          scg_glslang_result *fragment_result, sc_error *err)
{
    int status = SC_OK;
    glslang_program_t *program = glslang_program_create();
    if (vertex)
        glslang_program_add_shader(program, vertex);
    if (fragment)
        glslang_program_add_shader(program, fragment);
    int messages = GLSLANG_MSG_DEFAULT_BIT | GLSLANG_MSG_SPV_RULES_BIT;
    if (!glslang_program_link(program, messages))
        status = scg_fail_shader_log(err, key, "link", glslang_program_get_info_log(program),
                                     NULL);
    size_t consumed = 0;
    if (status == SC_OK && vertex && vertex_result)
        status = count_spirv(program, SCG_STAGE_VERTEX, key, &consumed, vertex_result, err);
    if (status == SC_OK && fragment && fragment_result)
        status = count_spirv(program, SCG_STAGE_FRAGMENT, key, &consumed, fragment_result, err);
    glslang_program_delete(program);
    return status;
}

int scg_glslang_check(scg_stage stage, const char *glsl, const char *key,
                      scg_glslang_result *result, sc_error *err)
{
    pthread_once(&glslang_once, glslang_init);
    glslang_shader_t *shader = parse_stage(stage, glsl, key, err);
    if (!shader)
        return SC_FAIL;
    int status = stage == SCG_STAGE_VERTEX
                     ? link_and_count(shader, NULL, key, result, NULL, err)
                     : link_and_count(NULL, shader, key, NULL, result, err);
    glslang_shader_delete(shader);
    return status;
}

int scg_glslang_check_program(const char *vertex_glsl, const char *fragment_glsl,
                              const char *key, scg_glslang_result *vertex_result,
                              scg_glslang_result *fragment_result, sc_error *err)
{
    pthread_once(&glslang_once, glslang_init);
    glslang_shader_t *vs = parse_stage(SCG_STAGE_VERTEX, vertex_glsl, key, err);
    if (!vs)
        return SC_FAIL;
    glslang_shader_t *fs = parse_stage(SCG_STAGE_FRAGMENT, fragment_glsl, key, err);
    if (!fs) {
        glslang_shader_delete(vs);
        return SC_FAIL;
    }
    int status = link_and_count(vs, fs, key, vertex_result, fragment_result, err);
    glslang_shader_delete(fs);
    glslang_shader_delete(vs);
    return status;
}
