/* key.c — variant keys: canonical text form, parsing (lenient about
 * spelling first, then strict: a key that is not in canonical form is
 * refused with the canonical spelling), and the check that the compiler can
 * build a key. Grammar in key.h and docs/variant-key.md. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "key.h"

static const char *const kind_names[] = {"bez", "nurbs", "tri"};
static const char *const eval_names[] = {"dc", "bern", "loop", "pow"};
/* Indexed by the options' enums; their DEFAULT values have no spelling,
 * since a key holds the value chosen. */
static const char *const trim_names[] = {[SC_TRIM_FAST] = "fast", [SC_TRIM_CLIP] = "clip",
                                         [SC_TRIM_LEFT] = "left", [SC_TRIM_NONE] = "trim"};
static const char *const method_names[] = {
    [SC_METHOD_NEWTON] = "newton", [SC_METHOD_BROYDEN] = "broyden", [SC_METHOD_BCLIP] = "bclip",
    [SC_METHOD_SUBDIV] = "subdiv", [SC_METHOD_HYBRID] = "hybrid"};
static const char *const start_names[] = {[SC_START_MID] = "mid", [SC_START_CPMAP] = "cp",
                                          [SC_START_VIEW] = "view",
                                          [SC_START_SECURE] = "secure"};
static const char *const output_names[] = {"shade", "aov", "iters", "uv", "hull"};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

void scg_key_for_lists(scg_key *key)
{
    key->ert = SCG_ERT_LISTS;
    key->start = SC_START_MID;
}

void scg_key_default(scg_key *key, scg_patch_kind kind, int deg_u, int deg_v)
{
    memset(key, 0, sizeof *key);
    key->kind = kind;
    key->deg_u = deg_u;
    key->deg_v = deg_v;
    key->eval = SCG_EVAL_DC;
    key->method = SC_METHOD_NEWTON;
    key->trim = SC_TRIM_NONE;
    key->start = SCG_DEFAULT_START;
    key->max_iters = SCG_DEFAULT_ITERS;
    key->tol_milli = SCG_DEFAULT_TOL_MILLI;
    key->ert = SCG_ERT_NONE;
    key->outputs = SCG_OUTPUT_SHADE;
}

float scg_key_tolerance(const scg_key *key) { return (float)key->tol_milli / 1000.0f; }

bool scg_key_equal(const scg_key *a, const scg_key *b)
{
    return a->kind == b->kind && a->deg_u == b->deg_u && a->deg_v == b->deg_v &&
           a->rational == b->rational && a->eval == b->eval && a->trim == b->trim &&
           a->trim_degree == b->trim_degree && a->trim_iters == b->trim_iters &&
           a->method == b->method &&
           a->start == b->start && a->max_iters == b->max_iters &&
           a->tol_milli == b->tol_milli && a->ert == b->ert && a->outputs == b->outputs;
}

/* Out-of-range enum values are printed as "?" so that a corrupt key never
 * indexes past a table; such a key fails to parse back. */
#define NAME(table, v) \
    ((int)(v) >= 0 && (int)(v) < COUNT(table) && table[v] ? table[v] : "?")

const char *scg_key_format(const scg_key *key, char *buf, size_t size)
{
    char degrees[32], trim[32], tol[32], outs[64] = "out";
    if (key->eval == SCG_EVAL_LOOP)
        snprintf(degrees, sizeof degrees, "dyn");
    else if (key->kind == SCG_PATCH_TRIANGLE)   /* one total degree: tri4 */
        snprintf(degrees, sizeof degrees, "%d", key->deg_u);
    else
        snprintf(degrees, sizeof degrees, "%dx%d", key->deg_u, key->deg_v);
    if (key->trim == SC_TRIM_NONE)
        snprintf(trim, sizeof trim, "trim0");
    else
        snprintf(trim, sizeof trim, "%s%di%d", NAME(trim_names, key->trim), key->trim_degree,
                 key->trim_iters);
    /* Milli-units written as a decimal without trailing zeros: exact both
     * ways, and one spelling per value. */
    int whole = key->tol_milli / 1000, frac = key->tol_milli % 1000;
    if (frac == 0)
        snprintf(tol, sizeof tol, "%d", whole);
    else {
        char digits[8];
        snprintf(digits, sizeof digits, "%03d", frac);
        for (int n = 2; n > 0 && digits[n] == '0'; n--)
            digits[n] = 0;
        snprintf(tol, sizeof tol, "%d.%s", whole, digits);
    }
    for (int i = 0; i < COUNT(output_names); i++)
        if (key->outputs & (1u << i)) {
            strcat(outs, ".");
            strcat(outs, output_names[i]);
        }
    snprintf(buf, size, "%s%s-%s-%s-%s-%s-%s-it%d-tol%s-ert%d-%s", NAME(kind_names, key->kind),
             degrees, key->rational ? "rat" : "poly", NAME(eval_names, key->eval), trim,
             NAME(method_names, key->method), NAME(start_names, key->start), key->max_iters,
             tol, (int)key->ert, outs);
    return buf;
}

/* Reads a decimal integer (leading zeros allowed here; the canonical check
 * rejects them later). Advances *s. */
static bool read_int(const char **s, int *out)
{
    const char *p = *s;
    long v = 0;
    if (!isdigit((unsigned char)*p))
        return false;
    while (isdigit((unsigned char)*p)) {
        v = v * 10 + (*p - '0');
        if (v > 1000000)
            return false;
        p++;
    }
    *s = p;
    *out = (int)v;
    return true;
}

/* Index of the table entry that `field` starts with (longest match), with
 * *rest pointing after it. */
static int match_prefix(const char *field, const char *const *table, int n, const char **rest)
{
    int best = -1;
    size_t best_len = 0;
    for (int i = 0; i < n; i++) {
        if (!table[i])
            continue;
        size_t len = strlen(table[i]);
        if (strncmp(field, table[i], len) == 0 && len > best_len) {
            best = i;
            best_len = len;
        }
    }
    if (best >= 0)
        *rest = field + best_len;
    return best;
}

static int match_exact(const char *field, const char *const *table, int n)
{
    for (int i = 0; i < n; i++)
        if (table[i] && strcmp(field, table[i]) == 0)
            return i;
    return -1;
}

static const char *const field_names[] = {
    "patch kind and degrees", "rational", "evaluation form", "trim configuration",
    "method", "initial values", "maximum iterations", "tolerance",
    "early ray termination", "outputs"};
enum { KEY_FIELDS = 10 };

static int field_error(sc_error *err, const char *text, int field, const char *value,
                       const char *expected)
{
    return sc_fail_key(err, text, "variant key '%s': %s field '%s': expected %s", text,
                       field_names[field], value, expected);
}

static int parse_tolerance(const char *s, int *milli)
{
    int whole = 0, frac = 0, digits = 0;
    if (!read_int(&s, &whole) || whole > 1000)
        return -1;
    if (*s == '.') {
        s++;
        if (!isdigit((unsigned char)*s))
            return -1;
        while (isdigit((unsigned char)*s)) {
            if (digits == 3) {
                if (*s != '0')
                    return -1;
            } else {
                frac = frac * 10 + (*s - '0');
                digits++;
            }
            s++;
        }
    }
    if (*s)
        return -1;
    while (digits < 3) {
        frac *= 10;
        digits++;
    }
    *milli = whole * 1000 + frac;
    return *milli >= 1 && *milli <= 1000 * 1000 ? 0 : -1;
}

int scg_key_parse(const char *text, scg_key *key, sc_error *err)
{
    char fields[KEY_FIELDS][64];
    int nfields = 0;
    const char *p = text;
    if (!text || !*text)
        return field_error(err, text ? text : "", 0, "", "a key such as "
                           "bez3x3-poly-dc-trim0-newton-mid-it4-tol0.25-ert0-out.shade");
    for (const char *c = text; *c; c++)
        if (!(islower((unsigned char)*c) || isdigit((unsigned char)*c) || *c == '.' ||
              *c == '-' || *c == '_'))
            return sc_fail_key(err, text, "variant key '%s': character '%c' outside [a-z0-9._-]",
                               text, *c);
    while (nfields < KEY_FIELDS + 1) {
        const char *dash = strchr(p, '-');
        size_t len = dash ? (size_t)(dash - p) : strlen(p);
        if (nfields == KEY_FIELDS || len >= sizeof fields[0])
            return sc_fail_key(err, text, "variant key '%s': %s", text,
                               nfields == KEY_FIELDS ? "too many fields (expected 10 joined by '-')"
                                                     : "field too long");
        memcpy(fields[nfields], p, len);
        fields[nfields][len] = 0;
        nfields++;
        if (!dash)
            break;
        p = dash + 1;
    }
    if (nfields != KEY_FIELDS)
        return sc_fail_key(err, text,
                           "variant key '%s': %d fields, expected 10: kind+degrees, poly|rat, "
                           "dc|bern|loop, trim, method, start, itN, tolT, ertE, out.LIST",
                           text, nfields);

    scg_key k;
    memset(&k, 0, sizeof k);
    const char *rest;
    int kind = match_prefix(fields[0], kind_names, COUNT(kind_names), &rest);
    if (kind < 0)
        return field_error(err, text, 0, fields[0], "bez, nurbs or tri then UxV or dyn");
    k.kind = (scg_patch_kind)kind;
    bool dyn = strcmp(rest, "dyn") == 0;
    if (k.kind == SCG_PATCH_TRIANGLE && !dyn) {
        if (!read_int(&rest, &k.deg_u) || *rest)
            return field_error(err, text, 0, fields[0], "tri then one total degree, e.g. tri4");
        if (k.deg_u < 1 || k.deg_u > SCG_MAX_TRI_DEGREE)
            return field_error(err, text, 0, fields[0], "a triangle degree from 1 to 4");
        k.deg_v = k.deg_u;
    } else if (!dyn) {
        if (!read_int(&rest, &k.deg_u) || *rest++ != 'x' || !read_int(&rest, &k.deg_v) ||
            *rest)
            return field_error(err, text, 0, fields[0], "a kind then degrees UxV or dyn");
        if (k.deg_u < 1 || k.deg_v < 1 || k.deg_u > SCG_MAX_DEGREE || k.deg_v > SCG_MAX_DEGREE)
            return field_error(err, text, 0, fields[0], "degrees from 1 to 16");
    }
    if (strcmp(fields[1], "poly") == 0)
        k.rational = false;
    else if (strcmp(fields[1], "rat") == 0)
        k.rational = true;
    else
        return field_error(err, text, 1, fields[1], "poly or rat");
    int eval = match_exact(fields[2], eval_names, COUNT(eval_names));
    if (eval < 0)
        return field_error(err, text, 2, fields[2], "dc, bern, pow or loop");
    k.eval = (scg_eval_form)eval;
    if (dyn != (k.eval == SCG_EVAL_LOOP))
        return field_error(err, text, 2, fields[2],
                           "loop together with degrees dyn (the generic program), "
                           "dc, bern or pow with degrees UxV");
    if (strcmp(fields[3], "trim0") == 0)
        k.trim = SC_TRIM_NONE;
    else {
        int trim = match_prefix(fields[3], trim_names, COUNT(trim_names), &rest);
        if (trim < 0 || trim == SC_TRIM_NONE || !read_int(&rest, &k.trim_degree) || *rest++ != 'i' ||
            !read_int(&rest, &k.trim_iters) || *rest || k.trim_degree < 1 ||
            k.trim_degree > SCG_MAX_DEGREE || k.trim_iters < 1 ||
            k.trim_iters > SCG_MAX_TRIM_ITERS)
            return field_error(err, text, 3, fields[3],
                               "trim0, or clipNiC, leftNiC or fastNiC with N the trim degree "
                               "1 to 16 and C the clipping iteration cap 1 to 64");
        k.trim = (sc_trim_method)trim;
    }
    int method = match_exact(fields[4], method_names, COUNT(method_names));
    if (method < 0)
        return field_error(err, text, 4, fields[4], "newton, broyden, bclip, subdiv or hybrid");
    k.method = (sc_method)method;
    int start = match_exact(fields[5], start_names, COUNT(start_names));
    if (start < 0)
        return field_error(err, text, 5, fields[5], "mid, cp, view or secure");
    k.start = (sc_start)start;
    rest = fields[6];
    if (strncmp(rest, "it", 2) != 0 || (rest += 2, !read_int(&rest, &k.max_iters)) || *rest ||
        k.max_iters < 1 || k.max_iters > SCG_MAX_ITERS)
        return field_error(err, text, 6, fields[6], "itN with N from 1 to 64");
    if (strncmp(fields[7], "tol", 3) != 0 || parse_tolerance(fields[7] + 3, &k.tol_milli) != 0)
        return field_error(err, text, 7, fields[7],
                           "tolT with T in pixel footprints, 0.001 to 1000, at most 3 decimals");
    rest = fields[8];
    int ert = -1;
    if (strncmp(rest, "ert", 3) != 0 || (rest += 3, !read_int(&rest, &ert)) || *rest || ert > 5)
        return field_error(err, text, 8, fields[8], "ert0, ert1, ert2, ert3, ert4 or ert5");
    k.ert = (scg_ert)ert;
    if (strncmp(fields[9], "out.", 4) != 0)
        return field_error(err, text, 9, fields[9], "out. followed by shade, aov, iters, uv, hull");
    for (const char *o = fields[9] + 3; *o == '.';) {
        o++;
        size_t len = strcspn(o, ".");
        int bit = -1;
        for (int i = 0; i < COUNT(output_names); i++)
            if (strlen(output_names[i]) == len && strncmp(o, output_names[i], len) == 0)
                bit = i;
        if (bit < 0)
            return field_error(err, text, 9, fields[9],
                               "out. followed by shade, aov, iters, uv, hull joined by '.'");
        k.outputs |= 1u << bit;
        o += len;
    }

    /* One spelling per key: compare with the canonical text field by field. */
    char canon[SCG_KEY_MAX];
    scg_key_format(&k, canon, sizeof canon);
    if (strcmp(canon, text) != 0) {
        const char *c = canon;
        for (int f = 0; f < KEY_FIELDS; f++) {
            size_t len = strcspn(c, "-");
            if (strlen(fields[f]) != len || strncmp(fields[f], c, len) != 0)
                return sc_fail_key(err, text,
                                   "variant key '%s': %s field '%s' is not canonical: write "
                                   "'%.*s' (the whole key: %s)",
                                   text, field_names[f], fields[f], (int)len, c, canon);
            c += len + (c[len] == '-');
        }
    }
    *key = k;
    return SC_OK;
}

int scg_key_check(const scg_key *key, sc_error *err)
{
    char text[SCG_KEY_MAX];
    scg_key parsed;
    /* A key assembled in C (not parsed) may hold values no text can name. */
    if (scg_key_parse(scg_key_format(key, text, sizeof text), &parsed, err) != SC_OK)
        return SC_FAIL;
    const char *missing = NULL;
    bool tri = key->kind == SCG_PATCH_TRIANGLE;
    /* The triangular program (tri_newton.c) is one method on one form:
     * Newton from the secure starts on the quartic along the ray. */
    if (tri && (key->eval != SCG_EVAL_DC || key->rational || key->trim != SC_TRIM_NONE ||
                key->method != SC_METHOD_NEWTON || key->start != SC_START_SECURE))
        return sc_fail_key(err, text, "key %s: triangular patches (tri) are drawn with "
                           "poly-dc-trim0-newton-secure only", text);
    if (!tri && key->start == SC_START_SECURE)
        return sc_fail_key(err, text, "key %s: the secure starts (secure) are for "
                           "triangular patches (tri) only", text);
    if (key->eval == SCG_EVAL_POWER && (key->deg_u > SC_MAX_POW_DEGREE ||
                                        key->deg_v > SC_MAX_POW_DEGREE))
        return sc_fail_key(err, text, "key %s: the power form (pow) goes up to degree %d: its "
                           "rounding error grows about as 2^degree (dc has no such limit)",
                           text, SC_MAX_POW_DEGREE);
    if (key->kind == SCG_PATCH_NURBS && key->eval == SCG_EVAL_POWER)
        return sc_fail_key(err, text, "key %s: the power form (pow) is for Bézier keys "
                           "(bez…): a NURBS key evaluates the span it finds by de Boor", text);
    if (key->kind == SCG_PATCH_NURBS && key->eval == SCG_EVAL_BASIS)
        missing = "the basis form for NURBS (nurbs…-bern) is";
    bool subdivides = key->method == SC_METHOD_SUBDIV || key->method == SC_METHOD_BCLIP;
    if (!missing && subdivides && (key->kind != SCG_PATCH_BEZIER || key->eval == SCG_EVAL_LOOP))
        return sc_fail_key(err, text,
                           "%s cuts the record's Bézier points into pieces, so it needs an "
                           "unrolled Bézier key (bez…, dc, bern or pow)",
                           method_names[key->method]);
    if (!missing && subdivides && key->start != SC_START_MID)
        return sc_fail_key(err, text,
                           "%s starts from the whole sub-patch and takes no start value: "
                           "write 'mid' for the start field",
                           method_names[key->method]);
    if (key->ert == SCG_ERT_PEEL && (key->outputs & SCG_OUTPUT_HULLVIEW))
        return sc_fail_key(err, text,
                           "key %s: ert4 (depth peeling) writes no depth, and the hull view "
                           "(out.hull) writes the hull face's depth where rays miss",
                           text);
    if (key->ert == SCG_ERT_LISTS && tri)
        return sc_fail_key(err, text, "key %s: ert5 (candidate lists) is for tensor patches; a "
                           "terrain's prisms are drawn in Manhattan sets", text);
    if (key->ert == SCG_ERT_LISTS && key->start != SC_START_MID)
        return sc_fail_key(err, text, "key %s: ert5 (candidate lists) draws no hull to "
                           "interpolate a start over: write 'mid' for the start field", text);
    if (key->ert == SCG_ERT_LISTS && (key->outputs & SCG_OUTPUT_HULLVIEW))
        return sc_fail_key(err, text, "key %s: ert5 (candidate lists) draws no hulls for the "
                           "hull view (out.hull) to show", text);
    if (missing)
        return sc_fail_key(err, text, "%s not implemented yet", missing);
    return SC_OK;
}
