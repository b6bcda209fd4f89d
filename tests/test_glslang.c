/* test_glslang.c — validation through glslang's C interface: acceptance,
 * SPIR-V instruction counts (against glslangValidator and spirv-dis, a
 * different path through the same compiler), rejection messages with key
 * and line, interface mismatches between stages, and the whole key family
 * generated and validated in process. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "emit_glsl.h"
#include "glslang_check.h"

static const char small_fragment[] =
    "#version 450 core\n"
    "layout(location = 0) uniform mat4 m;\n"
    "layout(location = 0) in vec3 p;\n"
    "layout(location = 0) out vec4 c;\n"
    "void main() { c = m * vec4(p, 1.0); }\n";

TEST(glslang_spirv_count_of_word_stream)
{
    /* Header (magic, version, generator, bound, schema), then OpCapability
     * Shader (2 words), OpMemoryModel (3 words), OpNop (1 word). */
    unsigned words[] = {0x07230203u, 0x00010000u, 0, 8, 0,
                        (2u << 16) | 17u, 1,
                        (3u << 16) | 14u, 0, 1,
                        (1u << 16) | 0u};
    CHECK_INT(scg_spirv_count_instructions(words, 11), 3);
    CHECK_INT(scg_spirv_count_instructions(words, 5), 0);
    /* A word count running past the end, a zero count, a wrong magic. */
    CHECK_INT(scg_spirv_count_instructions(words, 9), -1);
    unsigned zero[] = {0x07230203u, 0x00010000u, 0, 8, 0, 0u};
    CHECK_INT(scg_spirv_count_instructions(zero, 6), -1);
    words[0] = 0x12345678u;
    CHECK_INT(scg_spirv_count_instructions(words, 11), -1);
}

TEST(glslang_spirv_count_matches_glslangvalidator)
{
    scg_glslang_result result = {0};
    sc_error err = {0};
    CHECK_INT(scg_glslang_check(SCG_STAGE_FRAGMENT, small_fragment, "small", &result, &err),
              SC_OK);
    CHECK(result.spirv_words > 5);
    /* The same source through the command-line compiler, disassembled:
     * one line per instruction once comments are dropped. */
    const char *src = test_write_tmp("small.frag", small_fragment);
    char cmd[1024], *out = NULL;
    snprintf(cmd, sizeof cmd,
             "(glslangValidator --client opengl100 -G -o %s/small.spv %s >/dev/null && "
             "spirv-dis --no-header %s/small.spv | grep -vc '^ *;')",
             test_tmpdir(), src, test_tmpdir());
    if (test_run("command -v glslangValidator spirv-dis", NULL, NULL) != 0)
        SKIP("glslangValidator or spirv-dis not installed");
    char *errors = NULL;
    int status = test_run(cmd, &out, &errors);
    if (status != 0)
        fprintf(stderr, "  %s\n  %s%s", cmd, out ? out : "", errors ? errors : "");
    CHECK_INT(status, 0);
    CHECK_INT(result.spirv_instructions, atoi(out));
    free(out);
    free(errors);
}

TEST(glslang_rejection_names_key_line_and_code)
{
    const char *bad = "#version 450 core\n"
                      "layout(location = 0) out vec4 c;\n"
                      "void main()\n"
                      "{\n"
                      "    c = vec4(undeclared_thing);\n"
                      "}\n";
    sc_error err = {0};
    CHECK_INT(scg_glslang_check(SCG_STAGE_FRAGMENT, bad, "the-key", NULL, &err), SC_FAIL);
    CHECK_STR(err.key, "the-key");
    CHECK_INT(err.line, 5);
    CHECK_CONTAINS(err.message, "frag line 5");
    CHECK_CONTAINS(err.message, "undeclared_thing");
    CHECK_CONTAINS(err.message, "| c = vec4(undeclared_thing);");
    char text[1024];
    CHECK_CONTAINS(sc_error_text(&err, text, sizeof text), "key the-key: frag line 5");
}

TEST(glslang_vertex_stage_and_missing_main)
{
    const char *vs = "#version 450 core\n"
                     "layout(location = 0) in vec3 pos;\n"
                     "void main() { gl_Position = vec4(pos, 1.0); }\n";
    scg_glslang_result result = {0};
    sc_error err = {0};
    CHECK_INT(scg_glslang_check(SCG_STAGE_VERTEX, vs, "vs", &result, &err), SC_OK);
    CHECK(result.spirv_instructions > 10);
    /* The same text is not a fragment program (gl_Position is vertex-only). */
    CHECK_INT(scg_glslang_check(SCG_STAGE_FRAGMENT, vs, "vs", NULL, &err), SC_FAIL);
    CHECK_INT(scg_glslang_check(SCG_STAGE_FRAGMENT, "#version 450 core\n", "empty", NULL, &err),
              SC_FAIL);
    CHECK_CONTAINS(err.message, "link");
}

TEST(glslang_program_link_catches_interface_mismatch)
{
    const char *vs = "#version 450 core\n"
                     "layout(location = 0) in vec3 pos;\n"
                     "layout(location = 1) out vec3 ray;\n"
                     "void main() { ray = pos; gl_Position = vec4(pos, 1.0); }\n";
    const char *fs_ok = "#version 450 core\n"
                        "layout(location = 1) in vec3 ray;\n"
                        "layout(location = 0) out vec4 c;\n"
                        "void main() { c = vec4(ray, 1.0); }\n";
    const char *fs_bad = "#version 450 core\n"
                         "layout(location = 1) in vec2 ray;\n"
                         "layout(location = 0) out vec4 c;\n"
                         "void main() { c = vec4(ray, 0.0, 1.0); }\n";
    scg_glslang_result vr = {0}, fr = {0};
    sc_error err = {0};
    CHECK_INT(scg_glslang_check_program(vs, fs_ok, "pair", &vr, &fr, &err), SC_OK);
    CHECK(vr.spirv_instructions > 0 && fr.spirv_instructions > 0);
    CHECK_INT(scg_glslang_check_program(vs, fs_bad, "pair", NULL, NULL, &err), SC_FAIL);
    CHECK_STR(err.key, "pair");
}

/* Generates and validates keys[i] for i ≡ worker (mod workers); returns the
 * number of failures, printing each. */
static int validate_share(const scg_key *keys, int count, int worker, int workers)
{
    int failures = 0;
    for (int i = worker; i < count; i += workers) {
        scg_generated gen;
        sc_error err = {0};
        if (scg_generate(&keys[i], &gen, &err) != SC_OK) {
            char text[1024];
            fprintf(stderr, "  %s\n", sc_error_text(&err, text, sizeof text));
            failures++;
            continue;
        }
        scg_generated_free(&gen);
    }
    return failures;
}

/* Two processes share the family: glslang's parse is the cost, and the
 * machines have two cores. */
static int validate_in_two_processes(const scg_key *keys, int count)
{
    fflush(NULL);
    pid_t child = fork();
    if (child == 0)
        _exit(validate_share(keys, count, 1, 2) ? 1 : 0);
    int failures = validate_share(keys, count, 0, child > 0 ? 2 : 1);
    if (child > 0) {
        int status = 0;
        if (waitpid(child, &status, 0) != child || !WIFEXITED(status) || WEXITSTATUS(status))
            failures++;
    }
    return failures;
}

TEST(glslang_family_degrees_1_to_7_rational_iterations)
{
    static const int iterations[] = {1, 4, 16};
    scg_key *keys = sc_alloc(7 * 7 * 2 * 3, sizeof *keys);
    int count = 0;
    for (int du = 1; du <= 7; du++)
        for (int dv = 1; dv <= 7; dv++)
            for (int rational = 0; rational < 2; rational++)
                for (int it = 0; it < 3; it++) {
                    scg_key *k = &keys[count++];
                    scg_key_default(k, SCG_PATCH_BEZIER, du, dv);
                    k->rational = rational;
                    k->max_iters = iterations[it];
                }
    CHECK_INT(count, 294);
    int failures = validate_in_two_processes(keys, count);
    free(keys);
    CHECK_INT(failures, 0);
}

TEST(glslang_family_high_degrees)
{
    static const int degrees[][2] = {{8, 8}, {12, 12}, {12, 3}, {8, 1}};
    scg_key keys[8];
    int count = 0;
    for (int d = 0; d < 4; d++)
        for (int rational = 0; rational < 2; rational++) {
            scg_key_default(&keys[count], SCG_PATCH_BEZIER, degrees[d][0], degrees[d][1]);
            keys[count++].rational = rational;
        }
    CHECK_INT(validate_in_two_processes(keys, count), 0);
}

TEST(glslang_other_key_options_validate)
{
    /* Every output, start, early-ray-termination mode, evaluation form and
     * method the compiler builds, on one degree pair. */
    static const char *const texts[] = {
        "bez3x3-poly-dc-trim0-newton-cp-it4-tol0.25-ert2-out.shade.aov.iters.uv",
        "bez2x4-rat-bern-trim0-newton-mid-it8-tol1-ert1-out.aov",
        "nurbs3x3-rat-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade.aov",
        "bezdyn-rat-loop-trim0-newton-mid-it4-tol0.25-ert0-out.shade",
        "nurbsdyn-poly-loop-trim0-newton-cp-it4-tol0.25-ert0-out.iters",
        "bez3x3-poly-dc-trim0-broyden-mid-it6-tol0.05-ert1-out.shade.aov",
        "nurbsdyn-rat-loop-fast2i16-broyden-cp-it6-tol0.05-ert2-out.shade",
        "bez3x3-rat-dc-fast3i16-subdiv-mid-it24-tol0.05-ert2-out.shade.aov",
        "bez2x4-poly-bern-trim0-subdiv-mid-it8-tol1-ert0-out.iters",
        "bez3x3-poly-dc-fast2i16-hybrid-cp-it6-tol0.05-ert1-out.shade.aov",
        "bez4x2-rat-bern-trim0-hybrid-mid-it4-tol0.25-ert2-out.shade",
        "nurbs3x2-rat-dc-fast3i16-hybrid-cp-it6-tol0.05-ert1-out.shade.aov",
        "nurbsdyn-poly-loop-trim0-hybrid-mid-it5-tol0.25-ert0-out.iters",
        "bez3x3-rat-dc-fast3i16-bclip-mid-it32-tol0.05-ert2-out.shade.aov",
        "bez2x4-poly-bern-trim0-bclip-mid-it8-tol1-ert1-out.iters",
    };
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++) {
        scg_key key;
        sc_error err = {0};
        char text[1024];
        if (scg_key_parse(texts[i], &key, &err) != SC_OK) {
            TEST_FAIL_("%s: %s", texts[i], err.message);
            return;
        }
        scg_generated gen;
        if (scg_generate_counted(&key, &gen, &err) != SC_OK) {
            TEST_FAIL_("%s", sc_error_text(&err, text, sizeof text));
            return;
        }
        CHECK(gen.fragment_check.spirv_instructions > 0);
        CHECK(gen.vertex_check.spirv_instructions > 0);
        scg_generated_free(&gen);
    }
}
