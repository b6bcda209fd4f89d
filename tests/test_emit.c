/* test_emit.c — templates and the GLSL emitter: slot filling rules, the
 * printing of a small hand-built IR program whose GLSL is known line by
 * line, literals that read back as the same float, provenance headers,
 * failures that name what is missing, the golden files, and `splinecast
 * gen` (files, manifest, nothing written on failure). */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <unistd.h>

#include <stdlib.h>
#include <sys/stat.h>

#include "emit_glsl.h"
#include "template.h"

TEST(emit_template_fill_rules)
{
    const char *tpl = "a {{X}} b\n"
                      "    {{BLOCK}}\n"
                      "  {{EMPTY}}\n"
                      "end {{X}}\n";
    scg_slot slots[] = {{"X", "1"}, {"BLOCK", "p;\nq;\n\nr;\n"}, {"EMPTY", ""}};
    scg_text out = {0};
    sc_error err = {0};
    CHECK_INT(scg_template_fill(&out, "t", tpl, slots, 3, &err), SC_OK);
    /* Inline slots replaced in place; a slot alone on its line indents every
     * non-empty line of its text; an empty one removes its line. */
    CHECK_STR(scg_text_str(&out), "a 1 b\n    p;\n    q;\n\n    r;\nend 1\n");
    scg_text_free(&out);

    /* A slot the emitter does not fill, with its line. */
    CHECK_INT(scg_template_fill(&out, "t.frag", "x\ny {{MISSING}}\n", slots, 1, &err), SC_FAIL);
    CHECK_STR(err.file, "t.frag");
    CHECK_INT(err.line, 2);
    CHECK_CONTAINS(err.message, "{{MISSING}}");
    scg_text_free(&out);
    /* A slot given that the template lacks. */
    CHECK_INT(scg_template_fill(&out, "t.frag", "{{X}}\n", slots, 2, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "{{BLOCK}}");
    scg_text_free(&out);
    /* Malformed braces. */
    CHECK_INT(scg_template_fill(&out, "t.frag", "{{lower}}\n", slots, 0, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "malformed");
    scg_text_free(&out);
}

TEST(emit_templates_are_embedded)
{
    static const char *const names[] = {"raycast.frag", "hull.vert", "shade_headlight.glsl",
                                        "view_facing_normal.glsl", "view_shade.glsl",
                                        "view_aov.glsl", "view_iters.glsl", "view_uv.glsl"};
    sc_error err = {0};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        CHECK(scg_template_get(names[i], &err) != NULL);
    CHECK(scg_template_get("no-such-template", &err) == NULL);
    CHECK_CONTAINS(err.message, "no-such-template");
}

/* A ray-plane intersection written by hand in IR: the plane z = 0 in the
 * record's space, hit when 0 < t, (u, v) the hit's x and y, with one
 * variable, one branch and one fetch. Every GLSL line it must print is
 * known from the IR's definition. */
static scg_program *plane_program(unsigned outputs)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 1, 1);
    key.outputs = outputs;
    scg_program *p = scg_program_create(&key);
    scg_builder b;
    scg_builder_init(&b, p);
    /* One builder call per statement: C leaves the order in which function
     * arguments are evaluated open, and the value numbers depend on it. */
    scg_value origin = scg_input(&b, SCG_IN_RAY_ORIGIN);              /* 1 */
    scg_value dir = scg_input(&b, SCG_IN_RAY_DIR);                    /* 2 */
    scg_value origin_z = scg_comp(&b, origin, 2);                     /* 3 */
    scg_name(&b, "t");
    scg_value minus_z = scg_neg(&b, origin_z);                        /* 4 */
    scg_value dir_z = scg_comp(&b, dir, 2);                           /* 5 */
    scg_value t = scg_div(&b, minus_z, dir_z);                        /* 6 */
    scg_name(&b, "point");
    scg_value along = scg_mul(&b, dir, t);                            /* 7 */
    scg_value point = scg_add(&b, origin, along);                     /* 8 */
    scg_name(&b, "record");
    scg_value index = scg_input(&b, SCG_IN_RECORD);                   /* 9 */
    scg_value four = scg_const_i(&b, 4);                              /* 10 */
    scg_value texel = scg_mul(&b, index, four);                       /* 11 */
    scg_value record = scg_fetch(&b, SCG_TEX_RECORDS, texel);         /* 12 */
    scg_name(&b, "steps");
    scg_value steps = scg_var(&b, SCG_INT, 0, 0);                     /* 13 */
    scg_name(&b, "in_front");
    scg_value zero = scg_const_f(&b, 0.0f);                           /* 14 */
    scg_value in_front = scg_lt(&b, zero, t);                         /* 15 */
    scg_if(&b, in_front);                                             /* 16 */
    scg_value one = scg_const_i(&b, 1);                               /* 17 */
    scg_store(&b, steps, one);                                        /* 18 */
    scg_endif(&b);                                                    /* 19 */
    scg_name(&b, "clamped");
    scg_value tenth = scg_const_f(&b, 0.1f);                          /* 20 */
    scg_value clamped = scg_min(&b, tenth, point);                    /* 21 */
    scg_name(&b, "uv");
    scg_value clamped_x = scg_comp(&b, clamped, 0);                   /* 22 */
    scg_value point_y = scg_comp(&b, point, 1);                       /* 23 */
    scg_value uv = scg_vec2(&b, clamped_x, point_y);                  /* 24 */
    float up[3] = {0.0f, 0.0f, 1.0f};
    scg_output(&b, SCG_OUT_HIT, in_front);                            /* 25 */
    scg_output(&b, SCG_OUT_UV, uv);                                   /* 26 */
    scg_output(&b, SCG_OUT_T, t);                                     /* 27 */
    scg_output(&b, SCG_OUT_POINT, point);                             /* 28 */
    scg_value normal = scg_const_vec(&b, 3, up);                      /* 29 */
    scg_output(&b, SCG_OUT_NORMAL, normal);                           /* 30 */
    scg_name(&b, "iterations");
    scg_value taken = scg_load(&b, steps);                            /* 31 */
    scg_output(&b, SCG_OUT_ITERS, taken);                             /* 32 */
    scg_value id = scg_comp(&b, record, 3);                           /* 33 */
    scg_value surface = scg_f2i(&b, id);                              /* 34 */
    scg_output(&b, SCG_OUT_SURFACE, surface);                         /* 35 */
    return p;
}

TEST(emit_hand_built_program)
{
    scg_program *p = plane_program(SCG_OUTPUT_SHADE | SCG_OUTPUT_AOV);
    sc_error err = {0};
    CHECK_INT(scg_validate(p, &err), SC_OK);
    scg_text fn = {0};
    CHECK_INT(scg_emit_intersect_function(p, &fn, &err), SC_OK);
    const char *s = scg_text_str(&fn);
    CHECK_CONTAINS(s, "void sc_intersect(out bool hit, out vec2 uv, out float t, out vec3 point, "
                      "out vec3 normal, out int iters, out int surface)\n{\n");
    /* Values 3..: neg of a component, then the division, named hint_N. */
    CHECK_CONTAINS(s, "    float t_4 = -sc_ray_origin.z;\n"
                      "    float t_6 = t_4 / sc_ray_dir.z;\n"
                      "    vec3 point_7 = sc_ray_dir * t_6;\n"
                      "    vec3 point_8 = sc_ray_origin + point_7;\n");
    CHECK_CONTAINS(s, "    int record_11 = sc_record * 4;\n"
                      "    vec4 record_12 = texelFetch(sc_records, record_11);\n"
                      "    int steps_13 = 0;\n"
                      "    bool in_front_15 = 0.0 < t_6;\n\n"
                      "    if (in_front_15) {\n"
                      "        steps_13 = 1;\n"
                      "    }\n");
    /* GLSL has min(vec3, float) but not min(float, vec3): operands swap. */
    CHECK_CONTAINS(s, "    vec3 clamped_21 = min(point_8, 0.1);\n");
    CHECK_CONTAINS(s, "    vec2 uv_24 = vec2(clamped_21.x, point_8.y);\n");
    CHECK_CONTAINS(s, "    normal = vec3(0.0, 0.0, 1.0);\n");
    /* A load with no store after it is read as its variable. */
    CHECK_CONTAINS(s, "    iters = steps_13;\n");
    CHECK(!strstr(s, "iterations_31"));
    CHECK_CONTAINS(s, "    int iterations_34 = int(record_12.w);\n    surface = iterations_34;\n}\n");
    scg_text_free(&fn);

    scg_text frag = {0};
    CHECK_INT(scg_emit_fragment(p, &frag, &err), SC_OK);
    scg_glslang_result result = {0};
    int status = scg_glslang_check(SCG_STAGE_FRAGMENT, scg_text_str(&frag), "plane", &result,
                                   &err);
    if (status != SC_OK)
        TEST_FAIL_("%s", err.message);
    CHECK_INT(status, SC_OK);
    /* Only what the program reads is declared. */
    CHECK_CONTAINS(scg_text_str(&frag), "layout(binding = 2) uniform samplerBuffer sc_records;");
    CHECK(!strstr(scg_text_str(&frag), "sc_points"));
    CHECK(!strstr(scg_text_str(&frag), "sc_uv0"));
    CHECK(!strstr(scg_text_str(&frag), "sc_footprint"));
    scg_text_free(&frag);
    scg_program_free(p);
}

/* Vectors gathered from one value's components print as a swizzle; a
 * load is read as its variable unless the variable is stored before its
 * last use. */
TEST(emit_swizzles_and_loads_in_place)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 1, 1);
    scg_program *p = scg_program_create(&key);
    scg_builder b;
    scg_builder_init(&b, p);
    scg_value domain = scg_input(&b, SCG_IN_DOMAIN);                  /* 1 */
    scg_value u0 = scg_comp(&b, domain, 0);                           /* 2 */
    scg_value v0 = scg_comp(&b, domain, 2);                           /* 3 */
    scg_name(&b, "lo");
    scg_value lo = scg_vec2(&b, u0, v0);                              /* 4 */
    scg_name(&b, NULL);
    scg_value origin = scg_input(&b, SCG_IN_RAY_ORIGIN);              /* 5 */
    scg_name(&b, "count");
    scg_value count = scg_var(&b, SCG_INT, 0, 0);                     /* 6 */
    scg_name(&b, "before");
    scg_value before = scg_load(&b, count);                           /* 7 */
    scg_value one = scg_const_i(&b, 1);                               /* 8 */
    scg_value next = scg_add(&b, before, one);                        /* 9 */
    scg_store(&b, count, next);                                       /* 10 */
    scg_name(&b, "again");
    scg_value again = scg_load(&b, count);                            /* 11 */
    scg_store(&b, count, one);                                        /* 12 */
    scg_output(&b, SCG_OUT_ITERS, again);                             /* 13 */
    scg_output(&b, SCG_OUT_UV, lo);                                   /* 14 */
    scg_value ox = scg_comp(&b, origin, 0);                           /* 15 */
    scg_value oy = scg_comp(&b, origin, 1);                           /* 16 */
    scg_value oz = scg_comp(&b, origin, 2);                           /* 17 */
    scg_name(&b, "shuffled");
    scg_value shuffled = scg_vec3(&b, oz, oy, ox);                    /* 18 */
    scg_output(&b, SCG_OUT_POINT, shuffled);                          /* 19 */
    sc_error err = {0};
    CHECK_INT(scg_validate(p, &err), SC_OK);
    scg_text fn = {0};
    CHECK_INT(scg_emit_intersect_function(p, &fn, &err), SC_OK);
    const char *s = scg_text_str(&fn);
    CHECK_CONTAINS(s, "    vec2 lo_4 = sc_domain.xz;\n");
    CHECK_CONTAINS(s, "    int count_6 = 0;\n"
                      "    int before_9 = count_6 + 1;\n"
                      "    count_6 = before_9;\n"
                      "    int again_11 = count_6;\n"
                      "    count_6 = 1;\n"
                      "    iters = again_11;\n");
    CHECK_CONTAINS(s, "    vec3 shuffled_18 = sc_ray_origin.zyx;\n");
    scg_text_free(&fn);
    scg_program_free(p);
}

/* The literal the emitter prints for one float constant. */
static int literal_of(float x, char *buf, size_t size)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 1, 1);
    scg_program *p = scg_program_create(&key);
    scg_builder b;
    scg_builder_init(&b, p);
    scg_name(&b, "x");
    scg_value dir = scg_input(&b, SCG_IN_RAY_DIR);
    scg_value dir_x = scg_comp(&b, dir, 0);
    scg_value constant = scg_const_f(&b, x);
    scg_value sum = scg_add(&b, dir_x, constant);
    scg_output(&b, SCG_OUT_T, sum);
    scg_text fn = {0};
    int status = scg_emit_intersect_function(p, &fn, NULL);
    const char *at = strstr(scg_text_str(&fn), "sc_ray_dir.x + ");
    if (status == SC_OK && at) {
        at += strlen("sc_ray_dir.x + ");
        size_t len = strcspn(at, ";");
        snprintf(buf, size, "%.*s", (int)len, at);
    }
    scg_text_free(&fn);
    scg_program_free(p);
    return status == SC_OK && at ? 0 : -1;
}

TEST(emit_float_literals_read_back_exactly)
{
    char lit[64];
    CHECK_INT(literal_of(1.0f, lit, sizeof lit), 0);
    CHECK_STR(lit, "1.0");
    CHECK_INT(literal_of(0.1f, lit, sizeof lit), 0);
    CHECK_STR(lit, "0.1");
    CHECK_INT(literal_of(-2.5f, lit, sizeof lit), 0);
    CHECK_STR(lit, "(-2.5)");
    CHECK_INT(literal_of(1e20f, lit, sizeof lit), 0);
    CHECK_STR(lit, "1.0e+20");
    /* Shortest digits that give the same float back. */
    unsigned long long seed = 7;
    for (int i = 0; i < 200; i++) {
        float x = (float)((test_rand(&seed) - 0.5) * pow(10.0, 12.0 * test_rand(&seed) - 6.0));
        CHECK_INT(literal_of(x, lit, sizeof lit), 0);
        const char *digits = lit[0] == '(' ? lit + 1 : lit;
        CHECK(strtof(digits, NULL) == x);
        CHECK(strchr(digits, '.') != NULL);
    }
}

TEST(emit_provenance_header_and_determinism)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 3, 3);
    scg_generated a, b;
    sc_error err = {0};
    CHECK_INT(scg_generate(&key, &a, &err), SC_OK);
    CHECK_INT(scg_generate(&key, &b, &err), SC_OK);
    CHECK_STR(scg_text_str(&a.fragment), scg_text_str(&b.fragment));
    CHECK_STR(scg_text_str(&a.vertex), scg_text_str(&b.vertex));
    const char *frag = scg_text_str(&a.fragment);
    CHECK(!strncmp(frag, "// Generated by " SCG_GENERATOR_VERSION ".", 17 + strlen(SCG_GENERATOR_VERSION)));
    CHECK_CONTAINS(frag, "\n// key: bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade\n");
    CHECK_CONTAINS(frag, "\n#version 450 core\n");
    CHECK_CONTAINS(frag, "hull-cp-colour.vert");
    CHECK(!strncmp(scg_text_str(&a.vertex), "// Generated by ", 16));
    /* GLSL 4.50 core, nothing vendor-specific, no timestamps. */
    CHECK(!strstr(frag, "#extension"));
    CHECK(!strstr(frag, "20" "26") && !strstr(frag, "UTC"));
    scg_generated_free(&a);
    scg_generated_free(&b);
}

TEST(emit_missing_result_is_an_error)
{
    /* A program that computes no normal cannot be shaded. */
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 1, 1);
    scg_program *p = scg_program_create(&key);
    scg_builder b;
    scg_builder_init(&b, p);
    scg_value yes = scg_const_b(&b, true);
    scg_output(&b, SCG_OUT_HIT, yes);
    scg_value origin = scg_input(&b, SCG_IN_RAY_ORIGIN);
    scg_output(&b, SCG_OUT_POINT, origin);
    scg_text out = {0};
    sc_error err = {0};
    CHECK_INT(scg_emit_fragment(p, &out, &err), SC_FAIL);
    CHECK_CONTAINS(err.message, "'normal'");
    CHECK_STR(err.key, "bez1x1-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade");
    scg_text_free(&out);
    scg_program_free(p);
}

TEST(emit_vertex_programs_by_start_and_colour)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 2, 2);
    key.start = SC_START_MID;
    CHECK_STR(scg_vertex_program_name(&key), "hull-mid-colour");
    key.start = SC_START_CPMAP;
    key.outputs = SCG_OUTPUT_AOV;
    CHECK_STR(scg_vertex_program_name(&key), "hull-cp");
    scg_text vs = {0};
    sc_error err = {0};
    CHECK_INT(scg_emit_vertex(&key, &vs, &err), SC_OK);
    CHECK_CONTAINS(scg_text_str(&vs), "sc_uv0 = sc_hull_uv;");
    CHECK(!strstr(scg_text_str(&vs), "sc_base_colour"));
    CHECK_INT(scg_glslang_check(SCG_STAGE_VERTEX, scg_text_str(&vs), "hull-cp", NULL, &err), SC_OK);
    scg_text_free(&vs);
}

/* The golden files: every key of tests/golden/keys.txt generated again and
 * compared byte for byte, with a unified diff on mismatch. */
TEST(emit_golden_files)
{
    char cmd[2048], *out = NULL, *errors = NULL;
    snprintf(cmd, sizeof cmd,
             "(%s gen --key $(grep -v '^#' %s/tests/golden/keys.txt) -o %s/golden >/dev/null && "
             "diff -ru -x keys.txt %s/tests/golden %s/golden)",
             test_cli, test_root_dir, test_tmpdir(), test_root_dir, test_tmpdir());
    int status = test_run(cmd, &out, &errors);
    if (status != 0)
        fprintf(stderr, "%s%s  (re-bless after an intended change: make bless)\n",
                out ? out : "", errors ? errors : "");
    free(out);
    free(errors);
    CHECK_INT(status, 0);
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

TEST(emit_gen_command)
{
    char cmd[1024], path[1024], *out = NULL, *errors = NULL;
    snprintf(cmd, sizeof cmd, "%s gen --help", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "usage: splinecast gen");
    free(out);

    const char *bicubic = "bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade";
    const char *bilinear_aov = "bez1x1-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.aov";
    snprintf(cmd, sizeof cmd, "%s gen --key %s %s %s -o %s/gen/sub", test_cli, bicubic,
             bilinear_aov, bicubic, test_tmpdir());
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "keys 2 files 5\n");
    free(out);
    snprintf(path, sizeof path, "%s/gen/sub/manifest.tsv", test_tmpdir());
    FILE *f = fopen(path, "r");
    CHECK(f != NULL);
    char line[512];
    int rows = 0;
    CHECK(fgets(line, sizeof line, f) != NULL);
    CHECK_STR(line, "key\tstage\tfile\tbytes\n");
    while (fgets(line, sizeof line, f)) {
        char key[256], stage[16], file[256];
        long bytes;
        CHECK_INT(sscanf(line, "%255[^\t]\t%15[^\t]\t%255[^\t]\t%ld", key, stage, file, &bytes),
                  4);
        char full[1400];
        snprintf(full, sizeof full, "%s/gen/sub/%s", test_tmpdir(), file);
        CHECK_INT(file_size(full), bytes);
        rows++;
    }
    fclose(f);
    CHECK_INT(rows, 4);
    /* Each file on its own passes the command-line validator. */
    snprintf(cmd, sizeof cmd, "cd %s/gen/sub && glslangValidator %s.frag hull-mid.vert", test_tmpdir(),
             bilinear_aov);
    if (test_run("command -v glslangValidator", NULL, NULL) == 0)
        CHECK_INT(test_run(cmd, NULL, NULL), 0);

    /* A malformed key is bad usage; a key the compiler cannot build fails
     * with the key named and writes nothing. */
    snprintf(cmd, sizeof cmd, "%s gen --key bez3x3-nonsense -o %s/gen/bad", test_cli,
             test_tmpdir());
    CHECK_INT(test_run(cmd, NULL, &errors), 2);
    CHECK_CONTAINS(errors, "bez3x3-nonsense");
    free(errors);
    snprintf(cmd, sizeof cmd,
             "%s gen --key %s nurbs3x3-poly-dc-trim0-bclip-mid-it4-tol0.25-ert0-out.shade -o "
             "%s/gen/bad",
             test_cli, bicubic, test_tmpdir());
    CHECK_INT(test_run(cmd, &out, &errors), 1);
    CHECK_CONTAINS(errors, "bclip");
    CHECK_STR(out, "");
    snprintf(path, sizeof path, "%s/gen/bad", test_tmpdir());
    CHECK_INT(file_size(path), -1);
    free(out);
    free(errors);
    snprintf(cmd, sizeof cmd, "%s gen --key %s", test_cli, bicubic);
    CHECK_INT(test_run(cmd, NULL, NULL), 2);
}

/* A surface no GPU program can draw (degree 17 in u: the scene model takes
 * it, the programs stop at 16) is refused by `gen --scene`, as by
 * `render`, naming it; nothing is written. */
TEST(emit_gen_scene_refuses_undrawable_surface)
{
    char obj[4096] = "cstype bezier\ndeg 17 1\n";
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 18; i++)
            snprintf(obj + strlen(obj), sizeof obj - strlen(obj), "v %d %d 0\n", i, j);
    snprintf(obj + strlen(obj), sizeof obj - strlen(obj), "surf 0 1 0 1");
    for (int k = 1; k <= 36; k++)
        snprintf(obj + strlen(obj), sizeof obj - strlen(obj), " %d", k);
    snprintf(obj + strlen(obj), sizeof obj - strlen(obj), "\nparm u 0 1\nparm v 0 1\nend\n");
    const char *path = test_write_tmp("deg17.obj", obj);
    char cmd[1024], *err_text = NULL;
    snprintf(cmd, sizeof cmd, "%s gen --scene %s -o %s/gen/deg17", test_cli, path, test_tmpdir());
    CHECK_INT(test_run(cmd, NULL, &err_text), 1);
    CHECK_CONTAINS(err_text, "deg17.obj");
    CHECK_CONTAINS(err_text, "degree 17");
    free(err_text);
    char manifest[1024];
    snprintf(manifest, sizeof manifest, "%s/gen/deg17/manifest.tsv", test_tmpdir());
    CHECK(access(manifest, F_OK) != 0);
}

/* `make shaders` at build time: every example scene's keys generate and
 * validate (the scenes of examples/scenes, as the Makefile lists them). */
TEST(emit_gen_every_example_scene)
{
    char cmd[2048], *out = NULL, *err_text = NULL;
    snprintf(cmd, sizeof cmd,
             "cd %s && for s in examples/scenes/*.obj examples/scenes/*.bpt; do "
             "%s gen --scene $s -o %s/gen/all/$(basename $s) > /dev/null || echo \"FAILED $s\"; "
             "echo \"done $s\"; done",
             test_root_dir, test_cli, test_tmpdir());
    CHECK_INT(test_run(cmd, &out, &err_text), 0);
    int scenes = 0;
    for (const char *p = out; (p = strstr(p, "done ")) != NULL; p++)
        scenes++;
    CHECK(scenes >= 15);
    CHECK(strstr(out, "FAILED") == NULL);
    if (strstr(out, "FAILED"))
        fprintf(stderr, "%s%s", out, err_text ? err_text : "");
    free(out);
    free(err_text);
}

TEST(emit_gen_scene_keys)
{
    char cmd[1024], *out = NULL;
    snprintf(cmd, sizeof cmd, "%s gen --scene teapot --iters 1,4 -o %s/gen/teapot", test_cli,
             test_tmpdir());
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    /* The teapot is 32 bicubic polynomial patches: one key per count, each
     * without the AOVs (what a renderer draws with), and both as the
     * renderer's candidate lists draw them (ert5, started on the control
     * net: start mid). */
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-cp-it1-tol0.05-ert1-out.shade.aov.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-cp-it4-tol0.05-ert1-out.shade.aov.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-cp-it1-tol0.05-ert1-out.shade.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-cp-it4-tol0.05-ert1-out.shade.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-mid-it1-tol0.05-ert5-out.shade.aov.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-mid-it4-tol0.05-ert5-out.shade.aov.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-mid-it1-tol0.05-ert5-out.shade.frag");
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-mid-it4-tol0.05-ert5-out.shade.frag");
    CHECK_CONTAINS(out, "list-tiles.vert");
    CHECK_CONTAINS(out, "keys 8 files 11\n");
    free(out);
}
