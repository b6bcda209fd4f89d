/* step_scan.c — our own check of a STEP file's exchange structure (ISO
 * 10303-21) before a library parses it: the library's parser reports
 * errors without a usable position and is not built to meet hostile
 * input, so every file is first read once here, in bounded work and
 * memory, and refused with "file:line: what is wrong" when its structure
 * is broken. The scan also maps instance ids to lines, for messages about
 * faces, and counts the faces. */
#include "step.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct scanner {
    const char *s;
    size_t n, i;
    int line;
    const char *name;
    sc_error *err;
    /* instances and references of the DATA sections */
    int ninst, capinst;
    int *inst_id, *inst_line;
    int nref, capref;
    int *ref_id, *ref_line;
    int faces;
} scanner;

static int fail(scanner *sc, int line, const char *what)
{
    return sc_fail(sc->err, sc->name, line, "%s", what);
}

/* Skips white space and comments; fails on an unclosed comment or a
 * control character outside strings. */
static int skip_space(scanner *sc)
{
    while (sc->i < sc->n) {
        unsigned char c = (unsigned char)sc->s[sc->i];
        if (c == '\n') {
            sc->line++;
            sc->i++;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            sc->i++;
        } else if (c == '/' && sc->i + 1 < sc->n && sc->s[sc->i + 1] == '*') {
            int start = sc->line;
            sc->i += 2;
            while (sc->i + 1 < sc->n && !(sc->s[sc->i] == '*' && sc->s[sc->i + 1] == '/')) {
                if (sc->s[sc->i] == '\n')
                    sc->line++;
                else if (sc->s[sc->i] == 0)
                    return fail(sc, sc->line, "NUL byte: this is not a text file");
                sc->i++;
            }
            if (sc->i + 1 >= sc->n)
                return fail(sc, start, "comment `/*` is never closed");
            sc->i += 2;
        } else if (c < 0x20 || c == 0x7F) {
            return sc_fail(sc->err, sc->name, sc->line,
                           c ? "control character 0x%02x: this is not a text file"
                             : "NUL byte: this is not a text file", c);
        } else {
            return SC_OK;
        }
    }
    return SC_OK;
}

static int is_word(char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
           c == '_' || c == '-';
}

/* The keyword at the cursor (letters, digits, '_', '-'), or an empty one. */
static size_t word_at(const scanner *sc)
{
    size_t k = sc->i;
    while (k < sc->n && is_word(sc->s[k]))
        k++;
    return k - sc->i;
}

static int expect_char(scanner *sc, char c, const char *what)
{
    if (skip_space(sc))
        return SC_FAIL;
    if (sc->i >= sc->n || sc->s[sc->i] != c)
        return fail(sc, sc->line, what);
    sc->i++;
    return SC_OK;
}

static int keyword_is(const scanner *sc, size_t len, const char *kw)
{
    return len == strlen(kw) && !strncmp(sc->s + sc->i, kw, len);
}

/* Fails when memory runs out (both arrays still valid). */
static int push(int **a, int **b, int *n, int *cap, int x, int y)
{
    if (*n == *cap) {
        int grow = *cap ? 2 * *cap : 256;
        int *ga = sc_try_realloc(*a, (size_t)grow, sizeof **a);
        if (ga)
            *a = ga;
        int *gb = ga ? sc_try_realloc(*b, (size_t)grow, sizeof **b) : NULL;
        if (!gb)
            return SC_FAIL;
        *b = gb;
        *cap = grow;
    }
    (*a)[*n] = x;
    (*b)[*n] = y;
    (*n)++;
    return SC_OK;
}

/* An instance name `#digits`, as a positive int. */
static int read_id(scanner *sc, int *id)
{
    size_t k = sc->i + 1;
    long long v = 0;
    if (k >= sc->n || sc->s[k] < '0' || sc->s[k] > '9')
        return fail(sc, sc->line, "`#` must be followed by an instance number");
    while (k < sc->n && sc->s[k] >= '0' && sc->s[k] <= '9') {
        v = v * 10 + (sc->s[k] - '0');
        if (v > INT32_MAX)
            return fail(sc, sc->line, "instance number too large");
        k++;
    }
    if (v == 0)
        return fail(sc, sc->line, "instance number 0 (numbers start at 1)");
    sc->i = k;
    *id = (int)v;
    return SC_OK;
}

/* The parameters of one record, from just after its '(' to just after the
 * matching ')': strings, enumerations, binaries, numbers, references,
 * nested lists and typed parameters. `data` says whether references are
 * collected (the DATA section) or refused (the header). */
static int scan_params(scanner *sc, int start_line, int data)
{
    int depth = 1;
    /* after a whole parameter only `,` or `)` may follow; `after_open`:
     * just after a `(`, where `)` closes an empty list */
    int need_sep = 0, after_open = 1;
    while (depth > 0) {
        if (skip_space(sc))
            return SC_FAIL;
        if (sc->i >= sc->n)
            return fail(sc, start_line, "record is never closed: `)` or `;` missing before the "
                        "end of the file");
        char c = sc->s[sc->i];
        if (c == ')') {
            if (!need_sep && !after_open)
                return fail(sc, sc->line, "missing parameter before `)`");
            depth--;
            sc->i++;
            need_sep = 1, after_open = 0;
            continue;
        }
        if (c == ',') {
            if (!need_sep)
                return fail(sc, sc->line, "missing parameter before `,`");
            sc->i++;
            need_sep = 0, after_open = 0;
            continue;
        }
        if (c == ';')
            return fail(sc, start_line, "record is not closed: `;` before its last `)`");
        if (need_sep)
            return fail(sc, sc->line, "expected `,` or `)` after a parameter");
        after_open = 0;
        need_sep = 1;
        if (c == '(') {
            if (++depth > SC_STEP_MAX_NESTING)
                return sc_fail(sc->err, sc->name, sc->line, "parameters nested more than %d deep",
                               SC_STEP_MAX_NESTING);
            sc->i++;
            need_sep = 0, after_open = 1;
        } else if (c == '\'') {
            int sline = sc->line;
            sc->i++;
            for (;;) {
                if (sc->i >= sc->n)
                    return fail(sc, sline, "string is never closed (a `'` is missing)");
                char d = sc->s[sc->i++];
                if (d == '\n')
                    sc->line++;
                else if (d == 0)
                    return fail(sc, sc->line, "NUL byte: this is not a text file");
                else if (d == '\'') {
                    if (sc->i < sc->n && sc->s[sc->i] == '\'')
                        sc->i++;
                    else
                        break;
                }
            }
        } else if (c == '"') {
            sc->i++;
            while (sc->i < sc->n && ((sc->s[sc->i] >= '0' && sc->s[sc->i] <= '9') ||
                                     (sc->s[sc->i] >= 'A' && sc->s[sc->i] <= 'F')))
                sc->i++;
            if (sc->i >= sc->n || sc->s[sc->i] != '"')
                return fail(sc, sc->line, "binary value is not closed by `\"` (hex digits only)");
            sc->i++;
        } else if (c == '.' && sc->i + 1 < sc->n && !(sc->s[sc->i + 1] >= '0' &&
                                                     sc->s[sc->i + 1] <= '9')) {
            /* an enumeration .NAME. */
            size_t k = sc->i + 1;
            while (k < sc->n && is_word(sc->s[k]))
                k++;
            if (k >= sc->n || sc->s[k] != '.' || k == sc->i + 1)
                return fail(sc, sc->line, "enumeration value is not closed by `.`");
            sc->i = k + 1;
        } else if (c == '#') {
            int id;
            if (!data)
                return fail(sc, sc->line, "instance reference in the header section");
            if (read_id(sc, &id))
                return SC_FAIL;
            if (push(&sc->ref_id, &sc->ref_line, &sc->nref, &sc->capref, id, sc->line))
                return sc_fail_oom(sc->err, sc->name, sc->line, (size_t)sc->capref * 2,
                                   2 * sizeof(int), "instance references");
        } else if (c == '$' || c == '*') {
            sc->i++;
        } else if (is_word(c) || c == '+' || c == '.' || c == '!') {
            /* a number, or the keyword of a typed parameter KEYWORD(...) */
            int letter = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '!';
            sc->i++;
            while (sc->i < sc->n && (is_word(sc->s[sc->i]) || sc->s[sc->i] == '.' ||
                                     sc->s[sc->i] == '+'))
                sc->i++;
            if (letter) {
                if (skip_space(sc))
                    return SC_FAIL;
                if (sc->i >= sc->n || sc->s[sc->i] != '(')
                    return fail(sc, sc->line, "expected `(` after a typed parameter's name");
                need_sep = 0;
            }
        } else {
            return sc_fail(sc->err, sc->name, sc->line, "unexpected character `%c` in a record",
                           c);
        }
    }
    return SC_OK;
}

/* A simple record KEYWORD(params) at the cursor; sets *face when the
 * keyword names a face. */
static int scan_simple_record(scanner *sc, int data, int *face)
{
    if (skip_space(sc))
        return SC_FAIL;
    size_t len = word_at(sc);
    if (sc->i < sc->n && sc->s[sc->i] == '!') {
        /* a user-defined entity, !NAME */
        size_t k = sc->i + 1;
        while (k < sc->n && is_word(sc->s[k]))
            k++;
        len = k - sc->i;
    }
    char c0 = sc->i < sc->n ? sc->s[sc->i] : 0;
    if (len == 0 || !((c0 >= 'A' && c0 <= 'Z') || (c0 >= 'a' && c0 <= 'z') || c0 == '!'))
        return fail(sc, sc->line, "expected an entity name");
    if (face && (keyword_is(sc, len, "ADVANCED_FACE") || keyword_is(sc, len, "FACE_SURFACE")))
        *face = 1;
    sc->i += len;
    int line = sc->line;
    if (expect_char(sc, '(', "expected `(` after the entity name"))
        return SC_FAIL;
    return scan_params(sc, line, data);
}

/* One instance `#id = record;` (simple or complex) of a DATA section. */
static int scan_instance(scanner *sc)
{
    int line = sc->line, id, face = 0;
    if (read_id(sc, &id))
        return SC_FAIL;
    if (expect_char(sc, '=', "expected `=` after the instance number"))
        return SC_FAIL;
    if (skip_space(sc))
        return SC_FAIL;
    if (sc->i < sc->n && sc->s[sc->i] == '(') {
        /* complex instance: ( A(...) B(...) ... ) */
        sc->i++;
        int parts = 0;
        for (;;) {
            if (skip_space(sc))
                return SC_FAIL;
            if (sc->i >= sc->n)
                return fail(sc, line, "complex instance is never closed");
            if (sc->s[sc->i] == ')') {
                sc->i++;
                break;
            }
            if (scan_simple_record(sc, 1, &face))
                return SC_FAIL;
            parts++;
        }
        if (parts == 0)
            return fail(sc, line, "complex instance with no records");
    } else if (scan_simple_record(sc, 1, &face)) {
        return SC_FAIL;
    }
    if (expect_char(sc, ';', "expected `;` at the end of the instance"))
        return SC_FAIL;
    if (push(&sc->inst_id, &sc->inst_line, &sc->ninst, &sc->capinst, id, line))
        return sc_fail_oom(sc->err, sc->name, line, (size_t)sc->capinst * 2, 2 * sizeof(int),
                           "instances");
    sc->faces += face;
    return SC_OK;
}

/* The keyword KW followed by `;`. */
static int expect_keyword(scanner *sc, const char *kw, const char *what)
{
    if (skip_space(sc))
        return SC_FAIL;
    size_t len = word_at(sc);
    if (!keyword_is(sc, len, kw))
        return fail(sc, sc->line, what);
    sc->i += len;
    return expect_char(sc, ';', what);
}

static void sort_pairs(int *a, int *b, int n)
{
    /* heap sort on a, carrying b: bounded time for any input */
    for (int start = n / 2 - 1, end = n;; ) {
        int root;
        if (start >= 0) {
            root = start--;
        } else {
            if (--end <= 0)
                break;
            int t = a[0]; a[0] = a[end]; a[end] = t;
            t = b[0]; b[0] = b[end]; b[end] = t;
            root = 0;
        }
        for (;;) {
            int child = 2 * root + 1;
            if (child >= end)
                break;
            if (child + 1 < end && a[child + 1] > a[child])
                child++;
            if (a[root] >= a[child])
                break;
            int t = a[root]; a[root] = a[child]; a[child] = t;
            t = b[root]; b[root] = b[child]; b[child] = t;
            root = child;
        }
    }
}

static int find_id(const int *ids, int n, int id)
{
    int lo = 0, hi = n - 1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        if (ids[mid] == id)
            return mid;
        if (ids[mid] < id)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

static int scan_file(scanner *sc)
{
    if (expect_keyword(sc, "ISO-10303-21", "not a STEP file: it must begin with `ISO-10303-21;`"))
        return SC_FAIL;
    if (expect_keyword(sc, "HEADER", "expected `HEADER;` after `ISO-10303-21;`"))
        return SC_FAIL;
    for (;;) {
        if (skip_space(sc))
            return SC_FAIL;
        if (sc->i >= sc->n)
            return fail(sc, sc->line, "the header section is never closed by `ENDSEC;`");
        if (keyword_is(sc, word_at(sc), "ENDSEC"))
            break;
        if (scan_simple_record(sc, 0, NULL) ||
            expect_char(sc, ';', "expected `;` after a header entity"))
            return SC_FAIL;
    }
    if (expect_keyword(sc, "ENDSEC", "expected `ENDSEC;`"))
        return SC_FAIL;
    int sections = 0;
    for (;;) {
        if (skip_space(sc))
            return SC_FAIL;
        if (sc->i >= sc->n)
            return fail(sc, sc->line, "the file ends without `END-ISO-10303-21;`");
        size_t len = word_at(sc);
        if (keyword_is(sc, len, "END-ISO-10303-21")) {
            sc->i += len;
            if (expect_char(sc, ';', "expected `;` after `END-ISO-10303-21`"))
                return SC_FAIL;
            break;
        }
        if (!keyword_is(sc, len, "DATA"))
            return sc_fail(sc->err, sc->name, sc->line, "expected `DATA;` or `END-ISO-10303-21;`, "
                           "not `%.*s`", (int)(len ? (len < 40 ? len : 40) : 1), sc->s + sc->i);
        sc->i += len;
        if (skip_space(sc))
            return SC_FAIL;
        if (sc->i < sc->n && sc->s[sc->i] == '(') {
            /* DATA ('name', ('schema')); of edition 3 */
            int line = sc->line;
            sc->i++;
            if (scan_params(sc, line, 0))
                return SC_FAIL;
        }
        if (expect_char(sc, ';', "expected `;` after `DATA`"))
            return SC_FAIL;
        sections++;
        for (;;) {
            if (skip_space(sc))
                return SC_FAIL;
            if (sc->i >= sc->n)
                return fail(sc, sc->line, "the DATA section is never closed by `ENDSEC;`");
            if (sc->s[sc->i] != '#')
                break;
            if (scan_instance(sc))
                return SC_FAIL;
        }
        if (expect_keyword(sc, "ENDSEC", "expected an instance `#N = ...;` or `ENDSEC;`"))
            return SC_FAIL;
    }
    if (sections == 0)
        return fail(sc, sc->line, "the file has no DATA section");
    /* Anything after the end must be blank. */
    if (skip_space(sc))
        return SC_FAIL;
    if (sc->i < sc->n)
        return fail(sc, sc->line, "text after `END-ISO-10303-21;`");
    return SC_OK;
}

int sc_step_scan_text(const char *text, size_t size, const char *name, sc_step_scan *scan,
                      sc_error *err)
{
    memset(scan, 0, sizeof *scan);
    scanner sc = {.s = text, .n = size, .line = 1, .name = name, .err = err};
    int status = scan_file(&sc);
    if (status == SC_OK) {
        sort_pairs(sc.inst_id, sc.inst_line, sc.ninst);
        for (int k = 1; k < sc.ninst && status == SC_OK; k++)
            if (sc.inst_id[k] == sc.inst_id[k - 1]) {
                int a = sc.inst_line[k], b = sc.inst_line[k - 1];
                status = sc_fail(err, name, a > b ? a : b, "instance #%d is defined twice "
                                 "(also on line %d)", sc.inst_id[k], a > b ? b : a);
            }
        for (int k = 0; k < sc.nref && status == SC_OK; k++)
            if (find_id(sc.inst_id, sc.ninst, sc.ref_id[k]) < 0)
                status = sc_fail(err, name, sc.ref_line[k], "reference to #%d, which the file "
                                 "does not define", sc.ref_id[k]);
    }
    free(sc.ref_id);
    free(sc.ref_line);
    if (status != SC_OK) {
        free(sc.inst_id);
        free(sc.inst_line);
        return SC_FAIL;
    }
    scan->ninstances = sc.ninst;
    scan->ids = sc.inst_id;
    scan->lines = sc.inst_line;
    scan->faces = sc.faces;
    return SC_OK;
}

void sc_step_scan_free(sc_step_scan *scan)
{
    free(scan->ids);
    free(scan->lines);
    memset(scan, 0, sizeof *scan);
}

int sc_step_line_of(const sc_step_scan *scan, int id)
{
    int k = find_id(scan->ids, scan->ninstances, id);
    return k < 0 ? 0 : scan->lines[k];
}
