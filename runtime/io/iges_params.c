/* iges_params.c — the bottom of the IGES reader: messages naming the entity
 * and line, free-format parameters (tokenised once per record, read with
 * checks that bound every count by the data present), transformation
 * chains and colours, knot checks, and curve lists. */
#include "iges_local.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const double iges_identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

/* ------------------------------------------------------------------ */
/* Messages                                                             */
/* ------------------------------------------------------------------ */

int iges_fail_at(reader *r, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int status = sc_vfail(r->err, r->name, line, fmt, ap);
    va_end(ap);
    return status;
}

/* A failed sc_try_alloc of `bytes` for entity e (e < 0: for the file). */
int iges_fail_oom(reader *r, int e, size_t bytes, const char *what)
{
    if (e < 0)
        return sc_fail_oom(r->err, r->name, 0, bytes, 1, what);
    return iges_fail(r, e, 0, "out of memory: %zu bytes for %s", bytes, what);
}

/* "entity TYPE (D n): ..." at `line`, or at the entity's directory line. */
int iges_fail(reader *r, int e, int line, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sc_fail(r->err, r->name, line > 0 ? line : r->ent[e].line, "entity %d (D %d): %s",
                   r->ent[e].type, 2 * e + 1, msg);
}

/* Copies columns [0, cols) of records [first, first + n) into buf (blank-
 * padded) and returns its length. */
int iges_gather(const reader *r, int first, int n, int cols, char *buf)
{
    for (int i = 0; i < n; i++) {
        const record *rc = &r->rec[first + i];
        int have = rc->len < cols ? rc->len : cols;
        memcpy(buf + (size_t)i * cols, rc->text, (size_t)have);
        memset(buf + (size_t)i * cols + have, ' ', (size_t)(cols - have));
    }
    return n * cols;
}

/* ------------------------------------------------------------------ */
/* Free-format parameters                                               */
/* ------------------------------------------------------------------ */


static int push_token(params *p, token t)
{
    if (p->ntok == p->cap) {
        int cap = p->cap ? 2 * p->cap : 64;
        token *grown = sc_try_realloc(p->tok, (size_t)cap, sizeof(token));
        if (!grown)
            return SC_FAIL;
        p->tok = grown;
        p->cap = cap;
    }
    p->tok[p->ntok++] = t;
    return SC_OK;
}

/* Cuts t[0, n) into tokens up to the record delimiter (TOK_END). TOK_CUT:
 * the text ends first, *at = n, or a Hollerith string's count runs past
 * the end, *at = its offset; TOK_BAD_STRING: a Hollerith string is followed
 * by something other than a delimiter, *at = its offset; TOK_NO_MEMORY: the
 * tokens do not fit in memory. */
int iges_tokenize(const char *t, int n, char pd, char rd, params *p, int *at)
{
    p->ntok = 0;
    int pos = 0;
    for (;;) {
        while (pos < n && t[pos] == ' ')
            pos++;
        *at = n;
        if (pos >= n)
            return TOK_CUT;
        token tk = {pos, 0, 0};
        int q = pos;
        long long count = 0;
        /* Every digit belongs to the count, even past the text's length:
         * "99999H" is a Hollerith string too long to fit, not text. */
        for (; q < n && isdigit((unsigned char)t[q]); q++)
            if (count <= n)
                count = count * 10 + (t[q] - '0');
        if (q > pos && q < n && t[q] == 'H') {
            if (count > n - (q + 1)) {
                *at = pos;
                return TOK_CUT;
            }
            tk.start = q + 1;
            tk.len = (int)count;
            tk.is_string = 1;
            pos = q + 1 + (int)count;
            while (pos < n && t[pos] == ' ')
                pos++;
            if (pos >= n)
                return TOK_CUT;
            if (t[pos] != pd && t[pos] != rd) {
                *at = tk.start;
                return TOK_BAD_STRING;
            }
        } else {
            while (pos < n && t[pos] != pd && t[pos] != rd)
                pos++;
            if (pos >= n)
                return TOK_CUT;
            int end = pos;
            while (end > tk.start && t[end - 1] == ' ')
                end--;
            tk.len = end - tk.start;
        }
        if (push_token(p, tk)) {
            *at = pos;
            return TOK_NO_MEMORY;
        }
        if (t[pos] == rd)
            return TOK_END;
        pos++;
    }
}

void iges_params_free(params *p)
{
    if (!p->borrowed) {
        free(p->text);
        free(p->tok);
    }
    memset(p, 0, sizeof *p);
}

int iges_line(const reader *r, const params *p, int i)
{
    int offset = i < p->ntok ? p->tok[i].start : 0;
    return r->rec[p->first_record + offset / PARAM_COLS].line;
}

int iges_parse_real(const char *s, int len, double *out)
{
    char buf[64];
    if (len <= 0 || len >= (int)sizeof buf)
        return -1;
    for (int i = 0; i < len; i++)
        buf[i] = (s[i] == 'D' || s[i] == 'd') ? 'E' : s[i];
    buf[len] = 0;
    char *end;
    double v = strtod(buf, &end);
    if (end != buf + len || !isfinite(v))
        return -1;
    *out = v;
    return 0;
}

int iges_real(reader *r, const params *p, int i, double *out)
{
    if (i >= p->ntok)
        return iges_fail(r, p->entity, iges_line(r, p, p->ntok - 1),
                           "parameter %d is missing (the entity has %d)", i, p->ntok - 1);
    const token *t = &p->tok[i];
    if (t->is_string)
        return iges_fail(r, p->entity, iges_line(r, p, i),
                           "parameter %d: expected a number, found a string", i);
    if (t->len == 0) {
        *out = 0;
        return SC_OK;
    }
    if (iges_parse_real(p->text + t->start, t->len, out))
        return iges_fail(r, p->entity, iges_line(r, p, i),
                           "parameter %d: '%.*s' is not a finite number", i,
                           t->len > 40 ? 40 : t->len, p->text + t->start);
    return SC_OK;
}

/* Integers written as reals ("3.", "3.0E0") are accepted when integral. */
int iges_int(reader *r, const params *p, int i, int *out)
{
    double v;
    if (iges_real(r, p, i, &v))
        return SC_FAIL;
    if (v != floor(v))
        return iges_fail(r, p->entity, iges_line(r, p, i),
                           "parameter %d: expected an integer, found %.17g", i, v);
    if (fabs(v) > 1e9)
        return iges_fail(r, p->entity, iges_line(r, p, i),
                           "parameter %d: integer %.17g is out of range (at most 1e9 in "
                           "magnitude)", i, v);
    *out = (int)v;
    return SC_OK;
}

/* A directory pointer: entity index in *target, or -1 for a null (0)
 * pointer. */
int iges_pointer(reader *r, const params *p, int i, int *target)
{
    int v;
    if (iges_int(r, p, i, &v))
        return SC_FAIL;
    if (v == 0) {
        *target = -1;
        return SC_OK;
    }
    if (v < 0 || v % 2 == 0 || v > 2 * r->nent - 1)
        return iges_fail(r, p->entity, iges_line(r, p, i),
                           "parameter %d: pointer %d is not a directory entry (odd, 1..%d)", i, v,
                           2 * r->nent - 1);
    *target = (v - 1) / 2;
    return SC_OK;
}

/* Fails unless the entity has at least n parameters after its type. */
int iges_need(reader *r, const params *p, long long n)
{
    if (n > p->ntok - 1)
        return iges_fail(r, p->entity, iges_line(r, p, p->ntok - 1),
                           "needs %lld parameters, has %d (counts larger than the data)", n,
                           p->ntok - 1);
    return SC_OK;
}

/* A count read from the data, to be followed by at least `per` values
 * each: bounded by what is left, so it never drives an allocation. */
int iges_count(reader *r, const params *p, int i, int per, int *out)
{
    if (iges_int(r, p, i, out))
        return SC_FAIL;
    if (*out < 0)
        return iges_fail(r, p->entity, iges_line(r, p, i), "parameter %d: count %d is negative",
                           i, *out);
    if ((long long)*out * per > p->ntok - 1 - i)
        return iges_fail(r, p->entity, iges_line(r, p, i),
                           "parameter %d: count %d needs %lld more parameters, the entity has %d "
                           "(counts larger than the data)", i, *out, (long long)*out * per,
                           p->ntok - 1 - i);
    return SC_OK;
}

/* Tokenises the record at P line `pdata` into the cache. The directory's
 * line count is a hint (up to 64 lines are trusted): lines are added until
 * the record delimiter, doubling so that a wrong count stays cheap. Pointers
 * into the middle of a long record would each tokenise the rest: the lines
 * tokenised per file are bounded. */
static int tokenise_record(reader *r, int e, int pdata, parsed_record *pr)
{
    int np = r->sec_count[SEC_P];
    params *p = &pr->p;
    p->first_record = r->sec_first[SEC_P] + pdata - 1;
    int avail = np - (pdata - 1), nlines = r->ent[e].nlines;
    int want = nlines < 1 ? 1 : nlines < avail ? nlines : avail;
    want = want < 64 ? want : 64;
    for (;;) {
        char *text = sc_try_realloc(p->text, (size_t)want * PARAM_COLS, 1);
        if (!text)
            return iges_fail_oom(r, e, (size_t)want * PARAM_COLS, "parameter data");
        p->text = text;
        pr->n = iges_gather(r, p->first_record, want, PARAM_COLS, p->text);
        pr->status = iges_tokenize(p->text, pr->n, r->pdelim, r->rdelim, p, &pr->at);
        if (pr->status == TOK_NO_MEMORY)
            return iges_fail_oom(r, e, (size_t)p->cap * 2 * sizeof(token), "parameters");
        const token *last = pr->status == TOK_END ? &p->tok[p->ntok - 1] : NULL;
        r->tokenised += last ? (size_t)(last->start + last->len) : (size_t)pr->n;
        if (r->tokenised > (size_t)4 * np * PARAM_COLS + ((size_t)1 << 20))
            return iges_fail(r, e, r->rec[p->first_record].line, "parameter data pointers "
                               "into the middle of other entities' data: tokenising them takes "
                               "more than 4 times the parameter section");
        if (pr->status != TOK_CUT || want == avail)
            break;
        want = want > avail / 2 ? avail : 2 * want;
    }
    p->borrowed = 1;
    pr->done = 1;
    return SC_OK;
}

/* The entity's parameters: a view of the cache, never to be freed. */
int iges_params(reader *r, int e, params *p)
{
    memset(p, 0, sizeof *p);
    p->entity = e;
    const entity *en = &r->ent[e];
    int np = r->sec_count[SEC_P];
    if (en->pdata < 1 || en->pdata > np)
        return iges_fail(r, e, 0, "parameter data pointer %d is outside the P section (1..%d)",
                           en->pdata, np);
    if (!r->parsed && !(r->parsed = sc_try_alloc((size_t)np, sizeof *r->parsed)))
        return iges_fail_oom(r, e, (size_t)np * sizeof *r->parsed, "the parameter records");
    parsed_record *pr = &r->parsed[en->pdata - 1];
    if (!pr->done && tokenise_record(r, e, en->pdata, pr))
        return SC_FAIL;
    *p = pr->p;
    p->entity = e;
    int n = pr->n, at = pr->at;
    int line = r->rec[p->first_record + (at < n ? at : n - 1) / PARAM_COLS].line;
    if (pr->status == TOK_BAD_STRING)
        return iges_fail(r, e, line, "text after a Hollerith string where a delimiter "
                           "('%c' or '%c') belongs", r->pdelim, r->rdelim);
    if (pr->status == TOK_CUT && at < n)
        return iges_fail(r, e, line, "a Hollerith string runs past the end of the "
                           "parameter data (its count is larger than the text)");
    if (pr->status == TOK_CUT)
        return iges_fail(r, e, line, "the parameter data ends before the record delimiter "
                           "'%c' (truncated file?)", r->rdelim);
    int type;
    if (p->ntok < 1 || p->tok[0].is_string || iges_int(r, p, 0, &type) || type != en->type)
        return iges_fail(r, e, iges_line(r, p, 0), "its parameter data (P line %d) does not "
                           "start with its type %d: wrong parameter data pointer?", en->pdata,
                           en->type);
    return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Transformations and colour                                           */
/* ------------------------------------------------------------------ */

/* out = a ∘ b (b applied first); out may alias either. */
void iges_compose(const double a[12], const double b[12], double out[12])
{
    double m[12];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++)
            m[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j];
        m[4 * i + 3] += a[4 * i + 3];
    }
    memcpy(out, m, sizeof m);
}

static int matrix_of_124(reader *r, int t, double m[12])
{
    entity *en = &r->ent[t];
    if (!en->has_matrix) {
        params p;
        int status = iges_params(r, t, &p);
        if (status == SC_OK)
            status = iges_need(r, &p, 12);
        for (int i = 0; i < 12 && status == SC_OK; i++)
            status = iges_real(r, &p, i + 1, &en->matrix[i]);
        if (status)
            return SC_FAIL;
        en->has_matrix = 1;
    }
    memcpy(m, en->matrix, sizeof en->matrix);
    return SC_OK;
}

/* The entity's transformation: its 124 (directory field 7), that 124's own
 * 124, and so on, the innermost applied first. */
int iges_xform(reader *r, int e, double m[12])
{
    memcpy(m, iges_identity, sizeof iges_identity);
    int ptr = r->ent[e].xform, steps = 0;
    while (ptr != 0) {
        if (ptr < 0 || ptr % 2 == 0 || ptr > 2 * r->nent - 1)
            return iges_fail(r, e, 0, "transformation matrix pointer %d (directory field 7) is "
                               "not a directory entry (odd, 1..%d)", ptr, 2 * r->nent - 1);
        int t = (ptr - 1) / 2;
        if (r->ent[t].type != 124)
            return iges_fail(r, e, 0, "directory field 7 points to entity %d (D %d), not to a "
                               "124 transformation matrix", r->ent[t].type, ptr);
        if (++steps > r->nent)
            return iges_fail(r, e, 0, "its transformation matrices refer to each other in a "
                               "cycle (through D %d)", ptr);
        double a[12];
        if (matrix_of_124(r, t, a))
            return SC_FAIL;
        iges_compose(a, m, m);
        ptr = r->ent[t].xform;
    }
    return SC_OK;
}

/* Colour from directory field 13: 1..8 index the standard table, a
 * negative value points to a 314 colour definition (RGB in percent).
 * Returns 1 when the entity defines a colour. */
int iges_color(reader *r, int e, float rgb[3])
{
    static const float table[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1},
                                      {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    int c = r->ent[e].color;
    if (c >= 1 && c <= 8) {
        memcpy(rgb, table[c - 1], sizeof table[0]);
        return 1;
    }
    if (c >= 0)
        return 0;
    int ptr = -c;
    if (ptr % 2 == 0 || ptr > 2 * r->nent - 1)
        return iges_fail(r, e, 0, "colour pointer %d (directory field 13) is not a directory "
                           "entry (odd, 1..%d)", c, 2 * r->nent - 1);
    int t = (ptr - 1) / 2;
    if (r->ent[t].type != 314)
        return iges_fail(r, e, 0, "colour field 13 points to entity %d (D %d), not to a 314 "
                           "colour definition", r->ent[t].type, ptr);
    params p;
    double v[3];
    int status = iges_params(r, t, &p);
    if (status == SC_OK)
        status = iges_need(r, &p, 3);
    for (int i = 0; i < 3 && status == SC_OK; i++)
        status = iges_real(r, &p, i + 1, &v[i]);
    if (status)
        return SC_FAIL;
    for (int i = 0; i < 3; i++)
        rgb[i] = (float)(v[i] < 0 ? 0 : v[i] > 100 ? 1 : v[i] / 100);
    return 1;
}

/* ------------------------------------------------------------------ */
/* Domains: knot checks (clamping and sub-ranges are in nurbs.h)        */
/* ------------------------------------------------------------------ */

/* Knots: finite and non-decreasing with a non-empty domain. */
int iges_check_knots(reader *r, const params *p, int first_param, const double *k,
                             int nk, int degree, const char *what)
{
    for (int i = 1; i < nk; i++)
        if (k[i] < k[i - 1])
            return iges_fail(r, p->entity, iges_line(r, p, first_param + i),
                               "%s knots decrease at knot %d (%.17g after %.17g)", what, i, k[i],
                               k[i - 1]);
    if (!(k[degree] < k[nk - 1 - degree]))
        return iges_fail(r, p->entity, iges_line(r, p, first_param),
                           "%s knot vector has an empty domain [%.17g, %.17g]", what, k[degree],
                           k[nk - 1 - degree]);
    return SC_OK;
}

/* Reads nk knots from parameter `at` on, then checks them. */
int iges_read_knots(reader *r, const params *p, int at, double *k, int nk, int degree,
                            const char *what)
{
    for (int i = 0; i < nk; i++)
        if (iges_real(r, p, at + i, &k[i]))
            return SC_FAIL;
    return iges_check_knots(r, p, at, k, nk, degree, what);
}

/* ------------------------------------------------------------------ */
/* Parameter-space curves                                               */
/* ------------------------------------------------------------------ */

sc_curve *iges_list_push(curve_list *l)
{
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 8;
        sc_curve *grown = sc_try_realloc(l->items, (size_t)cap, sizeof(sc_curve));
        if (!grown)
            return NULL;
        l->items = grown;
        l->cap = cap;
    }
    sc_curve *c = &l->items[l->n++];
    memset(c, 0, sizeof *c);
    return c;
}

void iges_list_free(curve_list *l)
{
    for (int i = 0; i < l->n; i++)
        sc_curve_free(&l->items[i]);
    free(l->items);
    memset(l, 0, sizeof *l);
}

/* Homogeneous control point from a model point: the transformation is
 * applied to (x, y, z); a 2D curve keeps (x', y'), as in the surface's
 * (u, v), a 3D one all three. */
void iges_put_point(sc_curve *c, int i, const double m[12], double x, double y, double z,
                    double w)
{
    double *q = c->cp + (size_t)(c->dim + 1) * i;
    for (int d = 0; d < c->dim; d++)
        q[d] = (m[4 * d] * x + m[4 * d + 1] * y + m[4 * d + 2] * z + m[4 * d + 3]) * w;
    q[c->dim] = w;
}

/* The entity's first n parameters, all real. */
int iges_leading_reals(reader *r, const params *p, int n, double *v)
{
    if (iges_need(r, p, n))
        return SC_FAIL;
    for (int i = 0; i < n; i++)
        if (iges_real(r, p, i + 1, &v[i]))
            return SC_FAIL;
    return SC_OK;
}
