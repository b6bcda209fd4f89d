/* cmd_audit.c — `splinecast audit`: one shader-db style line per generated
 * shader (sc_generate_glsl's audits, docs/audit.md), so that a change that bloats a shader shows up as a
 * diff of two saved audits (--compare). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast audit KEYS [-v]\n"
    "       splinecast audit --compare OLD NEW [--match FIELDS]\n"
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
    "  --match FIELDS     with --compare: pair shaders whose keys agree once the\n"
    "                     key fields FIELDS are left out (comma-separated: shape,\n"
    "                     rational, eval, trim, method, start, iters, tol, ert,\n"
    "                     out), to compare across an option change, e.g.\n"
    "                     --match method,start,iters\n"
    "\n";

/* The whole file, NUL-terminated; NULL after printing why not. */
static char *read_file(const char *path, size_t *size)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "%s: cannot open the audit file\n", path);
        return NULL;
    }
    char *text = NULL;
    size_t len = 0, cap = 0, got;
    do {
        if (len + 4096 > cap) {
            cap = 2 * cap + 4096;
            char *grown = realloc(text, cap + 1);
            if (!grown) {
                fclose(f);
                free(text);
                fprintf(stderr, "%s: out of memory reading the audit file\n", path);
                return NULL;
            }
            text = grown;
        }
        got = fread(text + len, 1, cap - len, f);
        len += got;
    } while (got > 0);
    int failed = ferror(f);
    fclose(f);
    if (failed) {
        free(text);
        fprintf(stderr, "%s: cannot read the audit file\n", path);
        return NULL;
    }
    text[len] = 0;
    *size = len;
    return text;
}

static int compare(const char *old_path, const char *new_path, const char *match)
{
    sc_audit_text before = {.name = old_path}, after = {.name = new_path};
    char *old_text = read_file(old_path, &before.size);
    char *new_text = old_text ? read_file(new_path, &after.size) : NULL;
    int status = 1;
    if (new_text) {
        before.text = old_text;
        after.text = new_text;
        sc_error err = {0};
        status = sc_compare_audits_matching(&before, &after, match, stdout, &err) == SC_OK
                     ? 0
                     : cli_report(&err);
    }
    free(old_text);
    free(new_text);
    return status;
}
int cmd_audit(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        fputs(gen_keys_usage, stdout);
        return 0;
    }
    if (argc >= 2 && !strcmp(argv[1], "--compare")) {
        const char *match = NULL;
        if (argc == 6 && !strcmp(argv[4], "--match"))
            match = argv[5];
        else if (argc != 4)
            return cli_usage_error("audit", "--compare wants OLD NEW [--match FIELDS] and "
                                   "nothing else");
        return compare(argv[2], argv[3], match);
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
    char (*vertex_seen)[64] = calloc(set.count > 0 ? (size_t)set.count : 1, sizeof *vertex_seen);
    for (int k = 0; k < set.count; k++) {
        sc_glsl glsl;
        sc_error err = {0};
        if (sc_generate_glsl(&(sc_glsl_desc){.key = set.keys[k].text, .audit = 1}, &glsl, &err) !=
            SC_OK) {
            cli_report(&err);
            failures++;
            continue;
        }
        printf("%s\n", glsl.fragment_audit.line);
        if (verbose)
            printf("  %s\n", glsl.ir_kinds);
        int seen = 0;
        for (int v = 0; v < nvertex; v++)
            seen |= !strcmp(vertex_seen[v], glsl.vertex_name);
        if (!seen) {
            snprintf(vertex_seen[nvertex++], sizeof vertex_seen[0], "%s", glsl.vertex_name);
            printf("%s\n", glsl.vertex_audit.line);
        }
        sc_free_glsl(&glsl);
    }
    free(vertex_seen);
    free(set.keys);
    if (failures)
        fprintf(stderr, "splinecast audit: %d keys failed\n", failures);
    return failures ? 1 : 0;
}
