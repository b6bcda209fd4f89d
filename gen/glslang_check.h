/* glslang_check.h — validation of generated GLSL through glslang's C
 * interface, in process: parse and link one stage as OpenGL 4.50 core, make
 * SPIR-V for OpenGL and count its instructions (the audit's spirv-inst).
 * A rejected program fails with the key, glslang's message and the offending
 * GLSL line, so a build log alone tells what went wrong. */
#ifndef SCG_GLSLANG_CHECK_H
#define SCG_GLSLANG_CHECK_H

#include <stddef.h>

#include "sc_base.h"

typedef enum scg_stage {
    SCG_STAGE_VERTEX = 0,
    SCG_STAGE_FRAGMENT
} scg_stage;

/* "vert" / "frag": file extensions, and the stage names in the manifest. */
const char *scg_stage_extension(scg_stage stage);
/* "VS" / "FS": the stage names in audit lines. */
const char *scg_stage_audit_name(scg_stage stage);

typedef struct scg_glslang_result {
    int spirv_instructions;  /* instructions after the 5-word header */
    size_t spirv_words;      /* whole module, header included */
} scg_glslang_result;

/* Parses and links one stage as OpenGL 4.50 core; when `result` is not NULL
 * also translates it to SPIR-V for OpenGL and counts the instructions
 * (translation costs about half as much again as the parse, so callers that
 * only validate pass NULL). glslang is initialised on the first call of the
 * process (thread-safe). `key` names the program in messages (may be NULL).
 * On failure err->message is "STAGE line N: glslang's message | the GLSL
 * line", err->key the key and err->line the GLSL line (0 when glslang names
 * none), so sc_error_text gives "key KEY: frag line N: ...". */
int scg_glslang_check(scg_stage stage, const char *glsl, const char *key,
                      scg_glslang_result *result, sc_error *err);

/* Both stages parsed once each and linked into one program, which also
 * catches interfaces that do not match (a varying declared differently in
 * the two). SPIR-V counts per stage as above for non-NULL results. */
int scg_glslang_check_program(const char *vertex_glsl, const char *fragment_glsl,
                              const char *key, scg_glslang_result *vertex_result,
                              scg_glslang_result *fragment_result, sc_error *err);

/* Fails with the first error of a compiler's log (glslang's or a GL
 * driver's: glslang, Mesa and NVIDIA spellings of the line): err->message
 * "WHAT line N: message | the GLSL line of glsl" (or "WHAT: message" when
 * the log names no line), err->key the key, err->line N. */
int scg_fail_shader_log(sc_error *err, const char *key, const char *what, const char *log,
                        const char *glsl);

/* Instructions in a SPIR-V word stream: after the 5-word header, each
 * instruction's first word holds its word count in the high 16 bits.
 * Returns -1 for a malformed stream (bad magic, zero or overlong count). */
int scg_spirv_count_instructions(const unsigned int *words, size_t nwords);

#endif
