/* test_audit.c — the shader audit: the register estimate on small IR
 * programs whose peak is counted by hand, the M + 2N bound, the audit line
 * and its parser, the compare mode's lists and totals, and `splinecast
 * audit` end to end. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>

#include "audit.h"

static scg_program *new_program(scg_builder *b)
{
    scg_key key;
    scg_key_default(&key, SCG_PATCH_BEZIER, 1, 1);
    scg_program *p = scg_program_create(&key);
    scg_builder_init(b, p);
    return p;
}

TEST(audit_registers_of_a_chain_and_a_fan)
{
    scg_builder b;
    /* A chain: each value dies where the next is made, so one register. */
    scg_program *chain = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_RAY_DIR);
    scg_value a = scg_mul(&b, x, x);
    scg_value c = scg_add(&b, a, a);
    scg_value d = scg_dot(&b, c, c);
    scg_output(&b, SCG_OUT_T, d);
    CHECK_INT(scg_audit_register_estimate(chain), 1);
    scg_program_free(chain);

    /* A fan: five products of one input, all alive until they are summed.
     * Constants cost nothing; vec4 and float both cost one register. */
    for (int wide = 0; wide < 2; wide++) {
        scg_program *fan = new_program(&b);
        scg_value in = scg_input(&b, wide ? SCG_IN_DOMAIN : SCG_IN_T_LIMIT);
        scg_value v[5];
        for (int i = 0; i < 5; i++) {
            scg_value k = scg_const_f(&b, (float)(i + 2));
            v[i] = scg_mul(&b, in, k);
        }
        scg_value sum = v[0];
        for (int i = 1; i < 5; i++)
            sum = scg_add(&b, sum, v[i]);
        if (wide)
            sum = scg_comp(&b, sum, 0);
        scg_output(&b, SCG_OUT_T, sum);
        sc_error err = {0};
        CHECK_INT(scg_validate(fan, &err), SC_OK);
        /* At the fifth product the input dies and v0 … v4 are alive. */
        CHECK_INT(scg_audit_register_estimate(fan), 5);
        scg_program_free(fan);
    }
}

/* x = input; [loop 2 times:] a = x·x; b = x + x; c = a·b; [endloop] */
static scg_program *loop_program(int with_loop)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value x = scg_input(&b, SCG_IN_RAY_DIR);
    if (with_loop) {
        scg_value two = scg_const_i(&b, 2);
        scg_loop(&b, two);
    }
    scg_value a = scg_mul(&b, x, x);
    scg_value s = scg_add(&b, x, x);
    scg_value c = scg_mul(&b, a, s);
    (void)c;
    if (with_loop)
        scg_endloop(&b);
    return p;
}

TEST(audit_registers_across_a_loop)
{
    /* Straight-line: x dies at b = x + x, so at most a and b (2). In the
     * loop, x is needed by the next iteration: x, a and b (3). */
    scg_program *flat = loop_program(0), *looped = loop_program(1);
    sc_error err = {0};
    CHECK_INT(scg_validate(looped, &err), SC_OK);
    CHECK_INT(scg_audit_register_estimate(flat), 2);
    CHECK_INT(scg_audit_register_estimate(looped), 3);
    scg_program_free(flat);
    scg_program_free(looped);
}

TEST(audit_registers_of_an_array_and_fetches)
{
    scg_builder b;
    scg_program *p = new_program(&b);
    scg_value points = scg_var(&b, SCG_VEC4, 16, 0);
    scg_value domain = scg_input(&b, SCG_IN_DOMAIN);
    scg_value zero = scg_const_i(&b, 0);
    scg_store_at(&b, points, zero, domain);
    scg_value record = scg_input(&b, SCG_IN_RECORD);
    scg_value texel = scg_fetch(&b, SCG_TEX_POINTS, record);
    scg_value again = scg_fetch(&b, SCG_TEX_RECORDS, record);
    scg_value both = scg_add(&b, texel, again);
    scg_store_at(&b, points, zero, both);
    sc_error err = {0};
    CHECK_INT(scg_validate(p, &err), SC_OK);
    /* The 16 elements of the array, and beside them at most two values:
     * the record index and the first texel while the second is fetched the
     * index dies, so texel, second texel; then their sum alone. */
    CHECK_INT(scg_audit_register_estimate(p), 16 + 2);
    CHECK_INT(scg_audit_fetch_count(p), 2);
    int counts[SCG_OP_COUNT];
    scg_audit_count_ops(p, counts);
    CHECK_INT(counts[SCG_OP_FETCH], 2);
    CHECK_INT(counts[SCG_OP_STORE], 2);
    CHECK_INT(counts[SCG_OP_INPUT], 2);
    scg_program_free(p);
}

TEST(audit_register_bound_of_the_paper)
{
    /* Pabst et al. 4.2: M + 2N registers for orders M >= N. */
    CHECK_INT(scg_audit_register_bound(3, 3), 4 + 2 * 4);
    CHECK_INT(scg_audit_register_bound(3, 1), 4 + 2 * 2);
    CHECK_INT(scg_audit_register_bound(1, 3), 4 + 2 * 2);
    CHECK_INT(scg_audit_register_bound(7, 7), 8 + 2 * 8);
    /* The paper's limit M + 2N <= 19 admits 6x6 (7 + 14 = 21 does not). */
    CHECK(scg_audit_register_bound(5, 5) <= 19);
    CHECK(scg_audit_register_bound(6, 6) > 19);
}

TEST(audit_line_format_and_parse)
{
    scg_audit_line line = {0}, back;
    snprintf(line.key, sizeof line.key, "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade");
    line.stage = SCG_STAGE_FRAGMENT;
    long values[] = {1055, 5952, 69, 18, 35850};
    memcpy(line.value, values, sizeof values);
    line.register_bound = 12;
    char text[512];
    scg_audit_format(&line, text, sizeof text);
    CHECK_STR(text, "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade - FS: 1055 inst, "
                    "5952 spirv-inst, 69 vec4-regs (bound 12), 18 tex, 35850 bytes");
    sc_error err = {0};
    CHECK_INT(scg_audit_parse(text, &back, &err), SC_OK);
    CHECK_STR(back.key, line.key);
    CHECK_INT(back.stage, SCG_STAGE_FRAGMENT);
    for (int m = 0; m < SCG_AUDIT_METRIC_COUNT; m++)
        CHECK_INT(back.value[m], line.value[m]);
    CHECK_INT(back.register_bound, 12);
    CHECK_INT(scg_audit_parse("hull-mid - VS: 0 inst, 150 spirv-inst, 0 vec4-regs, 0 tex, "
                              "1748 bytes\n", &back, &err), SC_OK);
    CHECK_INT(back.stage, SCG_STAGE_VERTEX);
    CHECK_INT(back.register_bound, 0);
    CHECK_INT(back.value[SCG_AUDIT_BYTES], 1748);

    static const char *const bad[] = {
        "no dash here",
        "k - GS: 1 inst, 2 spirv-inst, 3 vec4-regs, 4 tex, 5 bytes",
        "k - FS: 1 inst, 2 spirv-inst, 3 vec4-regs, 4 tex",
        "k - FS: 1 inst, 2 spirv, 3 vec4-regs, 4 tex, 5 bytes",
        "k - FS: 1 inst, 2 spirv-inst, 3 vec4-regs, 4 tex, 5 bytes and more",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK_INT(scg_audit_parse(bad[i], &back, &err), SC_FAIL);
}

static scg_audit_line make_line(const char *key, scg_stage stage, long inst, long bytes)
{
    scg_audit_line line = {0};
    snprintf(line.key, sizeof line.key, "%s", key);
    line.stage = stage;
    line.value[SCG_AUDIT_INST] = inst;
    line.value[SCG_AUDIT_SPIRV_INST] = 2 * inst;
    line.value[SCG_AUDIT_VEC4_REGS] = 10;
    line.value[SCG_AUDIT_TEX] = 16;
    line.value[SCG_AUDIT_BYTES] = bytes;
    return line;
}

TEST(audit_compare_lists_and_totals)
{
    scg_audit_line old_lines[] = {
        make_line("a", SCG_STAGE_FRAGMENT, 100, 1000),
        make_line("b", SCG_STAGE_FRAGMENT, 200, 2000),
        make_line("v", SCG_STAGE_VERTEX, 0, 500),
    };
    scg_audit_line new_lines[] = {
        make_line("a", SCG_STAGE_FRAGMENT, 90, 1000),
        make_line("b", SCG_STAGE_FRAGMENT, 200, 2500),
        make_line("d", SCG_STAGE_FRAGMENT, 50, 700),
    };
    scg_audit_totals totals;
    FILE *out = tmpfile();
    CHECK(out != NULL);
    scg_audit_compare(out, old_lines, 3, new_lines, 3, NULL, &totals);
    CHECK_INT(totals.common, 2);
    CHECK_INT(totals.added, 1);
    CHECK_INT(totals.removed, 1);
    CHECK_INT(totals.before[SCG_AUDIT_INST], 300);
    CHECK_INT(totals.after[SCG_AUDIT_INST], 290);
    CHECK_INT(totals.helped[SCG_AUDIT_INST], 1);
    CHECK_INT(totals.hurt[SCG_AUDIT_INST], 0);
    CHECK_INT(totals.helped[SCG_AUDIT_SPIRV_INST], 1);
    CHECK_INT(totals.hurt[SCG_AUDIT_BYTES], 1);
    CHECK_INT(totals.before[SCG_AUDIT_BYTES], 3000);
    CHECK_INT(totals.after[SCG_AUDIT_BYTES], 3500);
    CHECK_INT(totals.helped[SCG_AUDIT_TEX] + totals.hurt[SCG_AUDIT_TEX], 0);
    char text[4096];
    rewind(out);
    size_t n = fread(text, 1, sizeof text - 1, out);
    text[n] = 0;
    fclose(out);
    CHECK_CONTAINS(text, "better inst: a FS 100 -> 90 (-10.00%)\n");
    CHECK_CONTAINS(text, "worse bytes: b FS 2000 -> 2500 (+25.00%)\n");
    CHECK_CONTAINS(text, "added: d FS\n");
    CHECK_CONTAINS(text, "removed: v VS\n");
    CHECK_CONTAINS(text, "total inst: 300 -> 290 (-3.33%); helped 1, hurt 0, of 2 shaders in both\n");
    CHECK_CONTAINS(text, "total bytes: 3000 -> 3500 (+16.67%); helped 0, hurt 1, of 2 shaders in both\n");
}

TEST(audit_command)
{
    char cmd[1024], *out = NULL, *errors = NULL;
    snprintf(cmd, sizeof cmd, "%s audit --help", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "usage: splinecast audit");
    free(out);

    const char *bicubic = "bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade";
    const char *septic = "bez7x7-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade";
    snprintf(cmd, sizeof cmd, "%s audit -v --key %s %s", test_cli, bicubic, septic);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "\n  bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert0-out.shade - FS by kind: ");
    char path[512];
    snprintf(path, sizeof path, "%s", test_write_tmp("old.audit", out));
    scg_audit_line *lines;
    int count;
    sc_error err = {0};
    CHECK_INT(scg_audit_read(path, out, strlen(out), &lines, &count, &err), SC_OK);
    free(out);
    /* Two fragment programs and their one shared vertex program; the -v
     * lines are skipped by the reader. */
    CHECK_INT(count, 3);
    CHECK_STR(lines[0].key, bicubic);
    CHECK_INT(lines[0].register_bound, 12);
    CHECK_INT(lines[1].stage, SCG_STAGE_VERTEX);
    CHECK_STR(lines[1].key, "hull-cp-colour");
    CHECK_STR(lines[2].key, septic);
    CHECK_INT(lines[2].register_bound, 24);
    /* The unrolled 7x7 program reads 64 control points, the 3x3 one 16;
     * everything else they fetch is the same. */
    CHECK_INT(lines[2].value[SCG_AUDIT_TEX] - lines[0].value[SCG_AUDIT_TEX], 64 - 16);
    CHECK(lines[2].value[SCG_AUDIT_INST] > lines[0].value[SCG_AUDIT_INST]);
    CHECK(lines[0].value[SCG_AUDIT_SPIRV_INST] > lines[0].value[SCG_AUDIT_INST]);
    CHECK(lines[0].value[SCG_AUDIT_VEC4_REGS] > 0);
    free(lines);

    /* Compare against a copy where the bicubic line is smaller. */
    snprintf(cmd, sizeof cmd,
             "(sed 's/^%s - FS: [0-9]* inst/%s - FS: 1 inst/' %s/old.audit > %s/new.audit && "
             "%s audit --compare %s/old.audit %s/new.audit)",
             bicubic, bicubic, test_tmpdir(), test_tmpdir(), test_cli, test_tmpdir(), test_tmpdir());
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "better inst: bez3x3-poly");
    CHECK_CONTAINS(out, "helped 1, hurt 0, of 3 shaders in both");
    free(out);

    /* A malformed saved audit is refused with its file and line. */
    const char *bad = test_write_tmp("bad.audit", "# comment\nnot an audit line\n");
    snprintf(cmd, sizeof cmd, "%s audit --compare %s %s", test_cli, bad, bad);
    CHECK_INT(test_run(cmd, NULL, &errors), 1);
    CHECK_CONTAINS(errors, "bad.audit:2:");
    free(errors);
    snprintf(cmd, sizeof cmd, "%s audit --compare %s", test_cli, bad);
    CHECK_INT(test_run(cmd, NULL, NULL), 2);

    /* A saved audit that names a shader twice would count it twice in the
     * totals: a file and itself concatenated is refused at the repeat, the
     * fourth of its six lines. */
    snprintf(cmd, sizeof cmd,
             "(cat %s/old.audit %s/old.audit | grep -v '^ ' > %s/twice.audit && "
             "%s audit --compare %s/old.audit %s/twice.audit)",
             test_tmpdir(), test_tmpdir(), test_tmpdir(), test_cli, test_tmpdir(), test_tmpdir());
    CHECK_INT(test_run(cmd, NULL, &errors), 1);
    CHECK_CONTAINS(errors, "twice.audit:4: ");
    CHECK_CONTAINS(errors, "already audited on line 1");
    free(errors);
}

TEST(audit_scene)
{
    char cmd[512], *out = NULL;
    snprintf(cmd, sizeof cmd, "%s audit --scene teapot", test_cli);
    CHECK_INT(test_run(cmd, &out, NULL), 0);
    CHECK_CONTAINS(out, "bez3x3-poly-pow-trim0-hybrid-cp-it6-tol0.05-ert1-out.shade.aov - FS: ");
    CHECK_CONTAINS(out, "hull-cp-colour - VS: 0 inst, ");
    int lines = 0;
    for (const char *p = out; *p; p++)
        lines += *p == '\n';
    CHECK_INT(lines, 2);
    free(out);
}
