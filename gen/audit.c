/* audit.c — audit lines for generated shaders (audit.h): the register
 * estimate from the optimised IR, counts, the printed line, its parser, and
 * the compare mode that turns two saved audits into better / worse lists
 * and totals, so that a change that bloats a shader shows up as a diff. */
#include "audit.h"

#include <stdlib.h>
#include <string.h>

/* Field names as printed, by scg_audit_metric. */
static const char *const metric_names[SCG_AUDIT_METRIC_COUNT] = {
    "inst", "spirv-inst", "vec4-regs", "tex", "bytes",
};

int scg_audit_register_bound(int degree_u, int degree_v)
{
    int m = degree_u + 1, n = degree_v + 1;
    if (m < n) {
        int swap = m;
        m = n;
        n = swap;
    }
    return m + 2 * n;
}

/* vec4 registers one value or variable occupies while live. */
static int register_weight(const scg_inst *inst)
{
    if (inst->type == SCG_VOID || inst->op == SCG_OP_CONST || inst->op == SCG_OP_UNIFORM)
        return 0;
    int per_value = (scg_type_width(inst->type) + 3) / 4;
    if (inst->op == SCG_OP_VAR && inst->slot > 0)
        return per_value * inst->slot;
    return per_value;
}

int scg_audit_register_estimate(const scg_program *prog)
{
    int n = prog->count;
    if (n <= 1)
        return 0;
    /* loop_end[i]: for a LOOP at i, the index of its ENDLOOP. */
    int *loop_end = sc_alloc((size_t)n, sizeof *loop_end);
    int *open = sc_alloc((size_t)n, sizeof *open);
    int depth = 0;
    for (int i = 1; i < n; i++) {
        if (prog->insts[i].op == SCG_OP_LOOP)
            open[depth++] = i;
        else if (prog->insts[i].op == SCG_OP_ENDLOOP && depth > 0)
            loop_end[open[--depth]] = i;
    }
    /* last[v]: the point up to which v must be kept. `open` now holds the
     * loops enclosing the instruction being scanned, outermost first. */
    int *last = sc_alloc((size_t)n, sizeof *last);
    depth = 0;
    for (int i = 1; i < n; i++) {
        const scg_inst *inst = &prog->insts[i];
        for (int k = 0; k < 4; k++) {
            scg_value v = inst->arg[k];
            if (v <= 0 || v >= n)
                continue;
            int keep = i;
            for (int l = 0; l < depth; l++)
                if (open[l] >= v) {   /* the outermost loop v is outside of */
                    keep = loop_end[open[l]];
                    break;
                }
            if (keep > last[v])
                last[v] = keep;
        }
        if (inst->op == SCG_OP_LOOP)
            open[depth++] = i;
        else if (inst->op == SCG_OP_ENDLOOP && depth > 0)
            depth--;
    }
    /* Value v occupies its registers over [v, last[v] - 1], and at least at
     * v itself: operands dying at an instruction are free for its result. */
    long *delta = sc_alloc((size_t)n + 1, sizeof *delta);
    for (int v = 1; v < n; v++) {
        int w = register_weight(&prog->insts[v]);
        if (!w)
            continue;
        int until = last[v] - 1 > v ? last[v] - 1 : v;
        delta[v] += w;
        delta[until + 1] -= w;
    }
    long live = 0, peak = 0;
    for (int i = 1; i < n; i++) {
        live += delta[i];
        if (live > peak)
            peak = live;
    }
    free(delta);
    free(last);
    free(open);
    free(loop_end);
    return (int)peak;
}

int scg_audit_fetch_count(const scg_program *prog)
{
    int count = 0;
    for (int i = 1; i < prog->count; i++)
        count += prog->insts[i].op == SCG_OP_FETCH;
    return count;
}

void scg_audit_count_ops(const scg_program *prog, int counts[SCG_OP_COUNT])
{
    memset(counts, 0, sizeof(int) * SCG_OP_COUNT);
    for (int i = 1; i < prog->count; i++)
        counts[prog->insts[i].op]++;
}

void scg_audit_fill(scg_audit_line *line, const char *key, scg_stage stage,
                    const scg_program *prog, const scg_glslang_result *glslang,
                    const char *glsl)
{
    memset(line, 0, sizeof *line);
    snprintf(line->key, sizeof line->key, "%s", key);
    line->stage = stage;
    if (prog) {
        line->value[SCG_AUDIT_INST] = scg_program_size(prog);
        line->value[SCG_AUDIT_VEC4_REGS] = scg_audit_register_estimate(prog);
        line->value[SCG_AUDIT_TEX] = scg_audit_fetch_count(prog);
        /* Generic programs read their degrees at run time: no bound. */
        if (prog->key.eval != SCG_EVAL_LOOP)
            line->register_bound = scg_audit_register_bound(prog->key.deg_u, prog->key.deg_v);
    }
    line->value[SCG_AUDIT_SPIRV_INST] = glslang ? glslang->spirv_instructions : 0;
    line->value[SCG_AUDIT_BYTES] = (long)strlen(glsl);
}

void scg_audit_format(const scg_audit_line *line, char *buf, size_t size)
{
    const long *v = line->value;
    char bound[32] = "";
    if (line->register_bound > 0)
        snprintf(bound, sizeof bound, " (bound %d)", line->register_bound);
    snprintf(buf, size, "%s - %s: %ld inst, %ld spirv-inst, %ld vec4-regs%s, %ld tex, %ld bytes",
             line->key, scg_stage_audit_name(line->stage), v[SCG_AUDIT_INST],
             v[SCG_AUDIT_SPIRV_INST], v[SCG_AUDIT_VEC4_REGS], bound, v[SCG_AUDIT_TEX],
             v[SCG_AUDIT_BYTES]);
}

void scg_audit_format_kinds(const scg_program *prog, const char *key, scg_text *out)
{
    int counts[SCG_OP_COUNT];
    scg_audit_count_ops(prog, counts);
    scg_text_printf(out, "%s - FS by kind:", key);
    const char *sep = " ";
    for (int op = 0; op < SCG_OP_COUNT; op++)
        if (counts[op]) {
            scg_text_printf(out, "%s%s %d", sep, scg_op_name((scg_op)op), counts[op]);
            sep = ", ";
        }
}

int scg_audit_parse(const char *text, scg_audit_line *line, sc_error *err)
{
    memset(line, 0, sizeof *line);
    const char *dash = strstr(text, " - ");
    if (!dash || dash == text || (size_t)(dash - text) >= sizeof line->key)
        return sc_fail(err, NULL, 0, "not an audit line (want 'KEY - FS: ...')");
    memcpy(line->key, text, (size_t)(dash - text));
    const char *p = dash + 3;
    if (!strncmp(p, "FS: ", 4))
        line->stage = SCG_STAGE_FRAGMENT;
    else if (!strncmp(p, "VS: ", 4))
        line->stage = SCG_STAGE_VERTEX;
    else
        return sc_fail(err, NULL, 0, "audit line: stage is not FS or VS");
    p += 4;
    for (int m = 0; m < SCG_AUDIT_METRIC_COUNT; m++) {
        long value;
        int consumed = 0;
        char name[32];
        if (sscanf(p, "%ld %31[a-z0-9-]%n", &value, name, &consumed) != 2 ||
            strcmp(name, metric_names[m]))
            return sc_fail(err, NULL, 0, "audit line: field %d is not 'N %s'", m + 1,
                           metric_names[m]);
        line->value[m] = value;
        p += consumed;
        if (m == SCG_AUDIT_VEC4_REGS && !strncmp(p, " (bound ", 8)) {
            if (sscanf(p, " (bound %d)%n", &line->register_bound, &consumed) != 1)
                return sc_fail(err, NULL, 0, "audit line: malformed register bound");
            p += consumed;
        }
        if (m + 1 < SCG_AUDIT_METRIC_COUNT) {
            if (strncmp(p, ", ", 2))
                return sc_fail(err, NULL, 0, "audit line: ', ' expected after %s",
                               metric_names[m]);
            p += 2;
        }
    }
    while (*p == ' ' || *p == '\r' || *p == '\n')
        p++;
    if (*p)
        return sc_fail(err, NULL, 0, "audit line: unexpected text after the bytes field");
    return SC_OK;
}

static const scg_audit_line *find_line(const scg_audit_line *lines, int count,
                                       const scg_audit_line *like)
{
    for (int i = 0; i < count; i++)
        if (lines[i].stage == like->stage && !strcmp(lines[i].key, like->key))
            return &lines[i];
    return NULL;
}

int scg_audit_read(const char *name, const char *text, size_t size, scg_audit_line **lines,
                   int *count, sc_error *err)
{
    *lines = NULL;
    *count = 0;
    int cap = 0, line_no = 0, status = SC_OK;
    int *line_of = NULL;      /* input line of each audit line, for messages */
    char line_text[1024];
    size_t at = 0;
    while (at < size) {
        const char *start = text + at;
        const char *newline = memchr(start, '\n', size - at);
        size_t len = newline ? (size_t)(newline - start) : size - at;
        at += len + (newline != NULL);
        line_no++;
        if (len >= sizeof line_text)
            len = sizeof line_text - 1;
        memcpy(line_text, start, len);
        line_text[len] = 0;
        if (line_text[0] == '#' || line_text[0] == ' ' || line_text[0] == '\t' ||
            line_text[0] == 0 || line_text[0] == '\r')
            continue;
        if (*count == cap) {
            cap = cap ? 2 * cap : 64;
            *lines = sc_realloc(*lines, (size_t)cap, sizeof **lines);
            line_of = sc_realloc(line_of, (size_t)cap, sizeof *line_of);
        }
        scg_audit_line *line = &(*lines)[*count];
        if (scg_audit_parse(line_text, line, err) != SC_OK) {
            snprintf(err->file, sizeof err->file, "%s", name);
            err->line = line_no;
            status = SC_FAIL;
            break;
        }
        /* Compare mode pairs lines by key and stage: a repeated pair would
         * be counted twice in its totals. */
        const scg_audit_line *first = find_line(*lines, *count, line);
        if (first) {
            status = sc_fail(err, name, line_no, "%s %s already audited on line %d", line->key,
                             scg_stage_audit_name(line->stage), line_of[first - *lines]);
            break;
        }
        line_of[*count] = line_no;
        (*count)++;
    }
    free(line_of);
    if (status != SC_OK) {
        free(*lines);
        *lines = NULL;
        *count = 0;
    }
    return status;
}

static double percent_change(long before, long after)
{
    if (before == 0)
        return after == 0 ? 0.0 : 100.0;
    return 100.0 * (double)(after - before) / (double)before;
}

/* The old line paired with new line i. */
static const scg_audit_line *paired(const scg_audit_line *old_lines, int old_count,
                                    const scg_audit_line *new_lines, const int *old_of_new,
                                    int i)
{
    if (!old_of_new)
        return find_line(old_lines, old_count, &new_lines[i]);
    return old_of_new[i] >= 0 ? &old_lines[old_of_new[i]] : NULL;
}

static int is_paired(const scg_audit_line *old_lines, int old_count,
                     const scg_audit_line *new_lines, int new_count, const int *old_of_new,
                     int j)
{
    if (!old_of_new)
        return find_line(new_lines, new_count, &old_lines[j]) != NULL;
    for (int i = 0; i < new_count; i++)
        if (old_of_new[i] == j)
            return 1;
    (void)old_count;
    return 0;
}

void scg_audit_compare(FILE *out, const scg_audit_line *old_lines, int old_count,
                       const scg_audit_line *new_lines, int new_count,
                       const int *old_of_new, scg_audit_totals *totals)
{
    scg_audit_totals t;
    memset(&t, 0, sizeof t);
    for (int m = 0; m < SCG_AUDIT_METRIC_COUNT; m++) {
        for (int pass = 0; pass < 2; pass++) {   /* better first, then worse */
            for (int i = 0; i < new_count; i++) {
                const scg_audit_line *now = &new_lines[i];
                const scg_audit_line *was = paired(old_lines, old_count, new_lines, old_of_new, i);
                if (!was)
                    continue;
                long before = was->value[m], after = now->value[m];
                int better = after < before, worse = after > before;
                if ((pass == 0 && !better) || (pass == 1 && !worse))
                    continue;
                fprintf(out, "%s %s: %s %s %ld -> %ld (%+.2f%%)", better ? "better" : "worse",
                        metric_names[m], now->key, scg_stage_audit_name(now->stage), before,
                        after, percent_change(before, after));
                if (strcmp(was->key, now->key))
                    fprintf(out, " (was %s)", was->key);
                fputc('\n', out);
            }
        }
    }
    for (int i = 0; i < new_count; i++) {
        const scg_audit_line *now = &new_lines[i];
        const scg_audit_line *was = paired(old_lines, old_count, new_lines, old_of_new, i);
        if (!was) {
            t.added++;
            fprintf(out, "added: %s %s\n", now->key, scg_stage_audit_name(now->stage));
            continue;
        }
        t.common++;
        for (int m = 0; m < SCG_AUDIT_METRIC_COUNT; m++) {
            t.before[m] += was->value[m];
            t.after[m] += now->value[m];
            t.helped[m] += now->value[m] < was->value[m];
            t.hurt[m] += now->value[m] > was->value[m];
        }
    }
    for (int j = 0; j < old_count; j++)
        if (!is_paired(old_lines, old_count, new_lines, new_count, old_of_new, j)) {
            t.removed++;
            fprintf(out, "removed: %s %s\n", old_lines[j].key,
                    scg_stage_audit_name(old_lines[j].stage));
        }
    for (int m = 0; m < SCG_AUDIT_METRIC_COUNT; m++)
        fprintf(out, "total %s: %ld -> %ld (%+.2f%%); helped %d, hurt %d, of %d shaders in both\n",
                metric_names[m], t.before[m], t.after[m], percent_change(t.before[m], t.after[m]),
                t.helped[m], t.hurt[m], t.common);
    if (totals)
        *totals = t;
}
