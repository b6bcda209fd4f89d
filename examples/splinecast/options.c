/* options.c — one table per option: the command line's spellings and the
 * public enum values they stand for (options.h). */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

typedef struct spelling {
    const char *text;
    int value;
} spelling;

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

static const spelling shows[] = {
    {"shade", SC_SHOW_SHADE}, {"uv", SC_SHOW_UV},       {"iters", SC_SHOW_ITERS},
    {"normal", SC_SHOW_NORMAL}, {"depth", SC_SHOW_DEPTH}, {"hull", SC_SHOW_HULL},
    {"reflect", SC_SHOW_REFLECT}};
static const spelling trims[] = {
    {"clip", SC_TRIM_CLIP}, {"left", SC_TRIM_LEFT}, {"fast", SC_TRIM_FAST}};
static const spelling terminations[] = {
    {"none", SC_TERMINATION_NONE}, {"conservative", SC_TERMINATION_CONSERVATIVE},
    {"manual", SC_TERMINATION_MANUAL}, {"manual-both", SC_TERMINATION_MANUAL_BOTH},
    {"peel", SC_TERMINATION_PEEL}, {"lists", SC_TERMINATION_LISTS}};
static const spelling orders[] = {
    {"front-to-back", SC_HULL_ORDER_FRONT_TO_BACK}, {"by-program", SC_HULL_ORDER_BY_PROGRAM},
    {"hybrid", SC_HULL_ORDER_HYBRID}};
static const spelling methods[] = {
    {"newton", SC_METHOD_NEWTON}, {"broyden", SC_METHOD_BROYDEN}, {"bclip", SC_METHOD_BCLIP},
    {"subdiv", SC_METHOD_SUBDIV}, {"hybrid", SC_METHOD_HYBRID}};
static const spelling evals[] = {
    {"dc", SC_EVAL_DC}, {"bern", SC_EVAL_BERN}, {"pow", SC_EVAL_POW}};
static const spelling starts[] = {
    {"mid", SC_START_MID}, {"cpmap", SC_START_CPMAP}, {"view", SC_START_VIEW}};
static const spelling backends[] = {
    {"egl", SC_BACKEND_EGL}, {"osmesa", SC_BACKEND_OSMESA}, {"default", SC_BACKEND_DEFAULT}};

/* The library's error record, filled as its own functions fill it: a
 * message, no input position, no key. */
__attribute__((format(printf, 2, 3))) static int fail(sc_error *err, const char *fmt, ...)
{
    if (err) {
        memset(err, 0, sizeof *err);
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->message, sizeof err->message, fmt, ap);
        va_end(ap);
    }
    return SC_FAIL;
}

/* Index of the entry spelled `text` (its first `len` bytes), or -1. */
static int lookup(const spelling *table, int n, const char *text, size_t len)
{
    for (int i = 0; i < n; i++)
        if (strlen(table[i].text) == len && !strncmp(text, table[i].text, len))
            return i;
    return -1;
}

static const char *name_of(const spelling *table, int n, int value, const char *otherwise)
{
    for (int i = 0; i < n; i++)
        if (table[i].value == value)
            return table[i].text;
    return otherwise;
}

int cli_show_parse(const char *text, sc_show *out, sc_error *err)
{
    int i = lookup(shows, COUNT(shows), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown view '%s' (shade, uv, iters, normal, depth or hull)", text);
    *out = (sc_show)shows[i].value;
    return SC_OK;
}

int cli_trim_parse(const char *text, sc_trim_method *out, int *iters, sc_error *err)
{
    const char *colon = strchr(text, ':');
    int i = lookup(trims, COUNT(trims), text, colon ? (size_t)(colon - text) : strlen(text));
    if (i < 0)
        return fail(err, "unknown trim method '%s' (clip, left or fast[:ITERS])", text);
    if (colon) {
        char *end;
        long n = strtol(colon + 1, &end, 10);
        if (end == colon + 1 || *end || n < 1 || n > SC_MAX_TRIM_ITERS)
            return fail(err, "trim iterations take 1 to %d, not '%s'", SC_MAX_TRIM_ITERS, colon + 1);
        *iters = (int)n;
    }
    *out = (sc_trim_method)trims[i].value;
    return SC_OK;
}

int cli_termination_parse(const char *text, sc_ray_termination *out, sc_error *err)
{
    int i = lookup(terminations, COUNT(terminations), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown early ray termination '%s' "
                         "(none, conservative, manual, manual-both, peel or lists)", text);
    *out = (sc_ray_termination)terminations[i].value;
    return SC_OK;
}

int cli_list_below_parse(const char *text, int *out, sc_error *err)
{
    if (!strcmp(text, "off")) {
        *out = SC_LISTS_OFF;
        return SC_OK;
    }
    char *end;
    long n = strtol(text, &end, 10);
    if (end == text || *end || n < 1 || n > 65536)
        return fail(err, "--lists-below takes off or 1 to 65536 pixels, not '%s'", text);
    *out = (int)n;
    return SC_OK;
}

int cli_threads_parse(const char *text, int *out, sc_error *err)
{
    char *end;
    long n = strtol(text, &end, 10);
    if (end == text || *end || n < 1 || n > 1024)
        return fail(err, "--threads takes 1 to 1024 threads, not '%s'", text);
    *out = (int)n;
    return SC_OK;
}

const char *cli_termination_name(sc_ray_termination termination)
{
    if (termination == SC_TERMINATION_DEFAULT)
        return "default";
    return name_of(terminations, COUNT(terminations), termination, "?");
}

int cli_order_parse(const char *text, sc_hull_order *out, sc_error *err)
{
    int i = lookup(orders, COUNT(orders), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown draw order '%s' (front-to-back, by-program or hybrid)", text);
    *out = (sc_hull_order)orders[i].value;
    return SC_OK;
}

const char *cli_order_name(sc_hull_order order)
{
    if (order == SC_HULL_ORDER_DEFAULT)
        return "default";
    return name_of(orders, COUNT(orders), order, "?");
}

int cli_backend_parse(const char *text, sc_backend *out, sc_error *err)
{
    int i = lookup(backends, COUNT(backends), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown backend '%s' (egl, osmesa or default)", text);
    *out = (sc_backend)backends[i].value;
    return SC_OK;
}

const char *cli_backend_name(sc_backend backend)
{
    return name_of(backends, COUNT(backends), backend, "default");
}

int cli_hulls_parse(const char *text, sc_hull_split *split, int *divisions, double *tolerance,
                    sc_error *err)
{
    char *end;
    if (!strncmp(text, "uniform:", 8)) {
        long n = strtol(text + 8, &end, 10);
        if (end == text + 8 || *end || n < 1 || n > SC_MAX_HULL_DIVISIONS)
            return fail(err, "hull '%s': uniform:N needs a whole N from 1 to %d", text,
                        SC_MAX_HULL_DIVISIONS);
        *split = SC_SPLIT_UNIFORM;
        *divisions = (int)n;
        *tolerance = 0;
        return SC_OK;
    }
    if (!strncmp(text, "adaptive:", 9)) {
        double tol = strtod(text + 9, &end);
        if (end == text + 9 || *end || !(tol > 0) || !(tol < 1))
            return fail(err, "hull '%s': adaptive:TOL needs 0 < TOL < 1 (a fraction of "
                             "the scene's size)", text);
        *split = SC_SPLIT_ADAPTIVE;
        *divisions = 0;
        *tolerance = tol;
        return SC_OK;
    }
    return fail(err, "hull '%s': expected uniform:N or adaptive:TOL", text);
}

int cli_method_parse(const char *text, sc_method *out, sc_error *err)
{
    int i = lookup(methods, COUNT(methods), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown method '%s' (newton, broyden, bclip, subdiv or hybrid)", text);
    *out = (sc_method)methods[i].value;
    return SC_OK;
}

const char *cli_method_name(sc_method method)
{
    return name_of(methods, COUNT(methods), method, "default");
}

int cli_eval_parse(const char *text, sc_eval *out, sc_error *err)
{
    int i = lookup(evals, COUNT(evals), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown evaluation form '%s' (dc, bern or pow)", text);
    *out = (sc_eval)evals[i].value;
    return SC_OK;
}

const char *cli_eval_name(sc_eval eval)
{
    return name_of(evals, COUNT(evals), eval, "default");
}

int cli_start_parse(const char *text, sc_start *out, sc_error *err)
{
    int i = lookup(starts, COUNT(starts), text, strlen(text));
    if (i < 0)
        return fail(err, "unknown start '%s' (mid, cpmap or view)", text);
    *out = (sc_start)starts[i].value;
    return SC_OK;
}

const char *cli_start_name(sc_start start)
{
    return name_of(starts, COUNT(starts), start, "default");
}

int cli_accuracy_parse(const char *text, double *px, double *deg, sc_error *err)
{
    char *end;
    double p = strtod(text, &end), d = 0;
    if (end == text || (*end && *end != ','))
        return fail(err, "--accuracy takes PX or PX,DEG (e.g. 0.1 or 0.1,1), not '%s'", text);
    if (*end == ',') {
        const char *second = end + 1;
        d = strtod(second, &end);
        if (end == second || *end)
            return fail(err, "--accuracy takes PX or PX,DEG (e.g. 0.1 or 0.1,1), not '%s'",
                        text);
    }
    if (!(p >= 0.001 && p <= 100))
        return fail(err, "--accuracy: the position bound takes 0.001 to 100 pixel footprints, "
                         "not '%s'", text);
    if (!(d >= 0 && d <= 90))
        return fail(err, "--accuracy: the normal bound takes 0 (none) to 90 degrees, not '%s'",
                    text);
    *px = p;
    *deg = d;
    return SC_OK;
}
