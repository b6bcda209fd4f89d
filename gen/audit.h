/* audit.h — the shader audit in the style of Mesa's shader-db: one line per
 * generated shader stage,
 *
 *   KEY - FS: N inst, N spirv-inst, N vec4-regs (bound B), N tex, N bytes
 *
 * (IR instructions after optimisation, SPIR-V instructions from glslang,
 * peak live registers estimated from the optimised IR in vec4 units beside
 * the M + 2N bound of Pabst et al. section 4.2, texture fetches, GLSL
 * bytes), a parser for saved audits and a compare mode that prints what got
 * better and worse, with totals. The register rule is in docs/audit.md. */
#ifndef SCG_AUDIT_H
#define SCG_AUDIT_H

#include <stdio.h>

#include "glslang_check.h"
#include "ir.h"
#include "template.h"

/* The metrics of an audit line, in the order printed; lower is better. */
typedef enum scg_audit_metric {
    SCG_AUDIT_INST = 0,
    SCG_AUDIT_SPIRV_INST,
    SCG_AUDIT_VEC4_REGS,
    SCG_AUDIT_TEX,
    SCG_AUDIT_BYTES,
    SCG_AUDIT_METRIC_COUNT
} scg_audit_metric;

typedef struct scg_audit_line {
    char key[128];
    scg_stage stage;
    long value[SCG_AUDIT_METRIC_COUNT];
    int register_bound;    /* M + 2N (orders M >= N); 0 for vertex programs and
                              generic (loop) programs, whose degrees are not
                              known */
} scg_audit_line;

/* Peak registers live at once in the optimised program, in vec4 units.
 * Every value, variable and array element held in a temporary costs
 * ceil(components / 4); constants and uniforms cost nothing (they are
 * immediates or constant registers). A value is live from its definition to
 * its last use; a use inside a loop that the definition is outside of keeps
 * the value live to the loop's end. Operands whose last use is an
 * instruction are freed before its result is allocated. */
int scg_audit_register_estimate(const scg_program *prog);

/* FETCH instructions in the program (the unrolled program's texel reads). */
int scg_audit_fetch_count(const scg_program *prog);

/* Pabst et al. 4.2: evaluating a surface with its partial derivatives needs
 * M + 2N registers for orders M >= N (order = degree + 1). */
int scg_audit_register_bound(int degree_u, int degree_v);

/* Instructions of each op (index scg_op) in the program. */
void scg_audit_count_ops(const scg_program *prog, int counts[SCG_OP_COUNT]);

/* Fills an audit line for one emitted stage. `prog` is the optimised IR of
 * the fragment stage (NULL for the vertex stage, which has no IR: its inst
 * and vec4-regs are 0), `glslang` the validation result, `glsl` the text. */
void scg_audit_fill(scg_audit_line *line, const char *key, scg_stage stage,
                    const scg_program *prog, const scg_glslang_result *glslang,
                    const char *glsl);

/* The line as printed, without a newline. */
void scg_audit_format(const scg_audit_line *line, char *buf, size_t size);
/* "KEY - FS by kind: add 12, mul 30, …" (only kinds present), appended
 * to out without a newline; `audit -v` prints it indented. */
void scg_audit_format_kinds(const scg_program *prog, const char *key, scg_text *out);

/* Parses one printed line. Returns SC_OK, or SC_FAIL (err filled) for a
 * line that is not an audit line. */
int scg_audit_parse(const char *text, scg_audit_line *line, sc_error *err);

/* Parses a saved audit, `size` bytes of text that `name` names in
 * messages (the compiler opens no files: the caller reads it): audit
 * lines, skipping blank lines, lines starting with '#' and the indented
 * by-kind lines of -v. A malformed line fails with name:line. *lines is
 * malloc'd. */
int scg_audit_read(const char *name, const char *text, size_t size, scg_audit_line **lines,
                   int *count, sc_error *err);

/* Summary of a comparison, for callers and tests. */
typedef struct scg_audit_totals {
    long before[SCG_AUDIT_METRIC_COUNT], after[SCG_AUDIT_METRIC_COUNT];
    int helped[SCG_AUDIT_METRIC_COUNT], hurt[SCG_AUDIT_METRIC_COUNT];
    int common;            /* shaders in both audits (the totals cover these) */
    int added, removed;    /* shaders only in the new / only in the old audit */
} scg_audit_totals;

/* Prints, for each metric, every shader that got better or worse (old ->
 * new and the change in percent), then shaders that appeared or went away,
 * then one totals line per metric over the shaders both audits hold.
 * old_of_new (from scg_audit_pair) pairs the lines; NULL pairs equal keys. */
void scg_audit_compare(FILE *out, const scg_audit_line *old_lines, int old_count,
                       const scg_audit_line *new_lines, int new_count,
                       const int *old_of_new, scg_audit_totals *totals);

/* audit_match.c. The bits of the key fields a comma-separated list names
 * (shape, rational, eval, trim, method, start, iters, tol, ert, out). */
int scg_audit_match_fields(const char *list, unsigned *ignore, sc_error *err);
/* For each new line, the index of the old line of the same stage whose key
 * equals it with the `ignore` fields left out (-1: none). Names that are
 * not keys (vertex programs) pair whole. Fails when the pairing is not one
 * to one. */
int scg_audit_pair(const scg_audit_line *old_lines, int old_count,
                   const scg_audit_line *new_lines, int new_count, unsigned ignore,
                   int *old_of_new, sc_error *err);

#endif
