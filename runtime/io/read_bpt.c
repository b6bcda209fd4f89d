/* read_bpt.c — Paul Bourke's .bpt Bézier patch format (Newell's tea set):
 * the patch count, then per patch "DU DV" and (DU+1)(DV+1) points "x y z",
 * the index within a row being u and the row being v. Each patch becomes a
 * polynomial NURBS surface with clamped knots [0..0 1..1]. Any degree is
 * read; every count is checked against what is left of the file before
 * anything is allocated from it. */
#include "envelope.h"
#include "io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct bpt_lexer {
    const char *text, *end, *pos;
    const char *name;
    int line;          /* line of the current position */
    int token_line;    /* line of the last token read */
    sc_error *err;
    sc_budget budget;  /* geometry charged so far (envelope.h) */
} bpt_lexer;

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/* The next whitespace-separated token; 0 at the end of the text. */
static int next_token(bpt_lexer *lx, const char **tok, size_t *len)
{
    while (lx->pos < lx->end && is_space(*lx->pos)) {
        if (*lx->pos == '\n')
            lx->line++;
        lx->pos++;
    }
    if (lx->pos >= lx->end)
        return 0;
    *tok = lx->pos;
    while (lx->pos < lx->end && !is_space(*lx->pos))
        lx->pos++;
    *len = (size_t)(lx->pos - *tok);
    lx->token_line = lx->line;
    return 1;
}

/* Upper bound on the number of tokens left: each needs a character and a
 * separator. Counts from the file are checked against it. */
static size_t tokens_left(const bpt_lexer *lx)
{
    return (size_t)(lx->end - lx->pos) / 2 + 1;
}

static int read_number(bpt_lexer *lx, const char *what, double *out)
{
    const char *tok;
    size_t len;
    if (!next_token(lx, &tok, &len))
        return sc_fail(lx->err, lx->name, lx->token_line, "file ends early: expected %s", what);
    char buf[64];
    if (len >= sizeof buf)
        return sc_fail(lx->err, lx->name, lx->token_line, "expected %s, found a %zu-character "
                       "word", what, len);
    memcpy(buf, tok, len);
    buf[len] = 0;
    char *endp;
    double v = strtod(buf, &endp);
    if (endp == buf || *endp)
        return sc_fail(lx->err, lx->name, lx->token_line, "expected %s, found '%s'", what, buf);
    if (!isfinite(v))
        return sc_fail(lx->err, lx->name, lx->token_line, "%s '%s' is not a finite number", what,
                       buf);
    *out = v;
    return SC_OK;
}

static int read_count(bpt_lexer *lx, const char *what, long lo, long hi, long *out)
{
    const char *tok;
    size_t len;
    if (!next_token(lx, &tok, &len))
        return sc_fail(lx->err, lx->name, lx->token_line, "file ends early: expected %s", what);
    char buf[32];
    if (len >= sizeof buf)
        return sc_fail(lx->err, lx->name, lx->token_line, "%s is not a small whole number", what);
    memcpy(buf, tok, len);
    buf[len] = 0;
    char *endp;
    long v = strtol(buf, &endp, 10);
    if (endp == buf || *endp)
        return sc_fail(lx->err, lx->name, lx->token_line, "expected %s (a whole number), found "
                       "'%s'", what, buf);
    if (v < lo || v > hi)
        return sc_fail(lx->err, lx->name, lx->token_line, "%s %ld is out of range (%ld to %ld)",
                       what, v, lo, hi);
    *out = v;
    return SC_OK;
}

/* Reads one patch into a new surface of `scene`. */
static int read_patch(bpt_lexer *lx, int index, sc_scene *scene)
{
    size_t left = tokens_left(lx);
    long du, dv;
    long max_degree = left < SC_READ_MAX_DEGREE ? (long)left : SC_READ_MAX_DEGREE;
    if (read_count(lx, "degree u", 1, max_degree, &du))
        return SC_FAIL;
    int patch_line = lx->token_line;
    if (read_count(lx, "degree v", 1, max_degree, &dv))
        return SC_FAIL;
    size_t npoints = (size_t)(du + 1) * (size_t)(dv + 1);
    if (npoints * 3 > tokens_left(lx))
        return sc_fail(lx->err, lx->name, patch_line, "file ends early: patch %d of degree %ld x "
                       "%ld needs %zu control points, more than the rest of the file can hold", index, du, dv,
                       npoints);
    if (sc_budget_charge(&lx->budget, sc_surface_bytes((int)du, (int)dv, (int)du + 1, (int)dv + 1),
                         "patch", lx->name, patch_line, lx->err))
        return SC_FAIL;
    sc_surface *s = sc_scene_try_add_surface(scene);
    if (!s || sc_surface_try_alloc(s, (int)du, (int)dv, (int)du + 1, (int)dv + 1))
        return sc_fail_oom(lx->err, lx->name, patch_line, 1,
                           sc_surface_bytes((int)du, (int)dv, (int)du + 1, (int)dv + 1), "a patch");
    snprintf(s->name, sizeof s->name, "patch%d", index);
    for (int k = 0; k <= du; k++) {
        s->knots_u[k] = 0;
        s->knots_u[du + 1 + k] = 1;
    }
    for (int k = 0; k <= dv; k++) {
        s->knots_v[k] = 0;
        s->knots_v[dv + 1 + k] = 1;
    }
    for (size_t k = 0; k < npoints; k++) {
        char what[64];
        for (int d = 0; d < 3; d++) {
            snprintf(what, sizeof what, "coordinate %c of control point %zu of patch %d",
                     "xyz"[d], k, index);
            if (read_number(lx, what, &s->cp[4 * k + d]))
                return SC_FAIL;
        }
        s->cp[4 * k + 3] = 1;
    }
    sc_surface_update_rational(s);
    sc_error check;
    if (sc_surface_check(s, &check))
        return sc_fail(lx->err, lx->name, patch_line, "patch %d: %s", index, check.message);
    return SC_OK;
}

static int read_all(bpt_lexer *lx, sc_scene *scene)
{
    /* The smallest patch (1 x 1) holds 2 + 12 numbers. */
    size_t max_patches = tokens_left(lx) / 14 + 1;
    long count;
    if (read_count(lx, "the patch count", 0, max_patches < 100000000 ? (long)max_patches : 100000000,
                   &count))
        return SC_FAIL;
    for (long i = 0; i < count; i++)
        if (read_patch(lx, (int)i, scene))
            return SC_FAIL;
    const char *tok;
    size_t len;
    if (next_token(lx, &tok, &len))
        return sc_fail(lx->err, lx->name, lx->token_line, "unexpected data after the last of %ld "
                       "patches (wrong patch count?)", count);
    return SC_OK;
}

int sc_read_bpt(const char *text, size_t size, const char *name, sc_scene *scene, sc_error *err)
{
    sc_scene_init(scene);
    if (sc_check_text(text, size, name, err))
        return SC_FAIL;
    bpt_lexer lx = {text, text + size, text, name, 1, 1, err, {0, 0}};
    return sc_finish_read(read_all(&lx, scene), name, scene, err);
}
