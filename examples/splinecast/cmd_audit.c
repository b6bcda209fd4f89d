/* cmd_audit.c — `splinecast audit`: one shader-db style line per generated
 * shader (gen/audit.h), so that a change that bloats a shader shows up as a
 * diff of two saved audits (--compare). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "audit.h"
#include "commands.h"
#include "emit_glsl.h"

static const char usage[] =
    "usage: splinecast audit KEYS [-v]\n"
    "       splinecast audit --compare OLD NEW\n"
    "\n"
    "Generates and validates every key and prints one line per shader:\n"
    "  KEY - FS: N inst, N spirv-inst, N vec4-regs (bound B), N tex, N bytes\n"
    "  NAME - VS: ...                (once per distinct vertex program)\n"
    "inst: IR instructions after optimisation; spirv-inst: SPIR-V instructions\n"
    "from glslang; vec4-regs: peak live registers estimated from the optimised\n"
    "IR in vec4 units (docs/audit.md), beside the M + 2N bound of Pabst et al.\n"
    "section 4.2 for orders M >= N; tex: texel fetches; bytes: GLSL size.\n"
    "The vertex programs have no IR: their inst and vec4-regs are 0.\n"
    "  -v                 add an indented line of IR instructions by kind\n"
    "  --compare OLD NEW  read two saved audits and print what got better and\n"
    "                     worse per metric, shaders added and removed, and\n"
    "                     totals over the shaders both hold\n"
    "\n";

static int compare(const char *old_path, const char *new_path)
{
    scg_audit_line *old_lines, *new_lines;
    int old_count, new_count;
    sc_error err = {0};
    if (scg_audit_read(old_path, &old_lines, &old_count, &err) != SC_OK)
        return cli_report(&err);
    if (scg_audit_read(new_path, &new_lines, &new_count, &err) != SC_OK) {
        free(old_lines);
        return cli_report(&err);
    }
    scg_audit_compare(stdout, old_lines, old_count, new_lines, new_count, NULL);
    free(old_lines);
    free(new_lines);
    return 0;
}

int cmd_audit(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        fputs(gen_keys_usage, stdout);
        return 0;
    }
    if (argc >= 2 && !strcmp(argv[1], "--compare")) {
        if (argc != 4)
            return cli_usage_error("audit", "--compare wants OLD NEW and nothing else");
        return compare(argv[2], argv[3]);
    }
    gen_keys set;
    int first_other;
    int status = gen_parse_keys("audit", argc, argv, &set, &first_other);
    if (status)
        return status;
    int verbose = 0;
    for (int i = 1; i < first_other && status == 0; i++) {
        if (!strcmp(argv[i], "-v"))
            verbose = 1;
        else
            status = cli_usage_error("audit", "unknown option '%s'", argv[i]);
    }
    if (status) {
        free(set.keys);
        return status;
    }

    int failures = 0, nvertex = 0;
    char (*vertex_seen)[64] = sc_alloc((size_t)set.count, sizeof *vertex_seen);
    for (int k = 0; k < set.count; k++) {
        scg_generated gen;
        sc_error err = {0};
        if (scg_generate_counted(&set.keys[k], &gen, &err) != SC_OK) {
            cli_report(&err);
            failures++;
            continue;
        }
        scg_audit_line line;
        char text[512];
        scg_audit_fill(&line, gen.key, SCG_STAGE_FRAGMENT, gen.program, &gen.fragment_check,
                       scg_text_str(&gen.fragment));
        scg_audit_format(&line, text, sizeof text);
        printf("%s\n", text);
        if (verbose)
            scg_audit_format_kinds(gen.program, gen.key, stdout);
        int seen = 0;
        for (int v = 0; v < nvertex; v++)
            seen |= !strcmp(vertex_seen[v], gen.vertex_name);
        if (!seen) {
            snprintf(vertex_seen[nvertex++], sizeof vertex_seen[0], "%s", gen.vertex_name);
            scg_audit_fill(&line, gen.vertex_name, SCG_STAGE_VERTEX, NULL, &gen.vertex_check,
                           scg_text_str(&gen.vertex));
            scg_audit_format(&line, text, sizeof text);
            printf("%s\n", text);
        }
        scg_generated_free(&gen);
    }
    free(vertex_seen);
    free(set.keys);
    if (failures)
        fprintf(stderr, "splinecast audit: %d keys failed\n", failures);
    return failures ? 1 : 0;
}
