/* read_iges.c — reader for IGES 5.x fixed-format (80-column) files: the
 * trimmed NURBS surfaces of CAD models (128 surfaces under 144 trimmed
 * surfaces, 143 bounded surfaces and 510 B-rep faces, plus every 128 that
 * nothing references), with their parameter-space trim loops converted
 * exactly to 2D NURBS curves (lines, arcs as rational quadratics, B-splines,
 * composites). The file is long on purpose: it is the one entity table of
 * a large format, read in one pass from the surfaces down, and splitting it
 * would spread one format's parser across files.
 *
 * Real files are sloppy where it costs nothing to forgive (no line breaks,
 * CRLF, wrong sequence numbers and status flags, a global section without a
 * terminator), so the record layer and the global section are read
 * leniently. Entity data is read strictly: a count larger than the data, a
 * pointer outside the directory or a reference cycle fails the file with a
 * message naming the entity, because reading on would mean interpreting
 * someone else's numbers. Allocations are bounded by the data and by envelope.h.
 * Entities are parsed on demand from the surfaces down. */
#include "envelope.h"
#include "io.h"
#include "nurbs.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
    RECORD_COLS = 80,
    SECTION_COL = 72,   /* 0-based column of the section letter */
    GLOBAL_COLS = 72,   /* data columns of G records */
    PARAM_COLS = 64,    /* data columns of P records */
    MAX_NESTING = 64    /* composite curves inside composite curves */
};

enum section { SEC_S, SEC_G, SEC_D, SEC_P, SEC_T, SEC_COUNT };
static const char section_letters[SEC_COUNT] = {'S', 'G', 'D', 'P', 'T'};

/* What building a trim loop can end in besides SC_FAIL / SC_OK. */
enum { LOOP_NO_PCURVE = 1, LOOP_UNSUPPORTED = 2 };

typedef struct record {
    const char *text;
    int len;  /* at most 80; missing columns read as blanks */
    int line; /* line in the file, 1-based */
} record;

typedef struct entity {
    int type, pdata, xform, color, nlines, subscript;
    char label[9];
    int line;                 /* file line of its first directory record */
    unsigned char busy;       /* on the current conversion path: a revisit is a cycle */
    unsigned char referenced; /* used as the surface of a 142/144/143/141/510/140 */
    unsigned char has_matrix;
    unsigned char counting;   /* on the current path of count_pieces */
    int pieces;               /* curves it expands into (count_pieces), 0 until counted */
    double matrix[12];        /* its own matrix, for a 124, once parsed */
} entity;

typedef struct token {
    int start, len;
    int is_string;
} token;

/* The parameters of one entity: columns 1-64 of its P records concatenated
 * and cut into tokens; tok[0] is the entity type, tok[i] the i-th parameter
 * of the specification's tables. */
typedef struct params {
    int entity;
    int first_record;
    char *text;
    token *tok;
    int ntok, cap;
    int borrowed;  /* text and tok belong to the reader's cache */
} params;

/* A parameter record tokenised once, by its first P line, however many
 * entities point at it: `status` is what stopped tokenize, `at` and `n` where. */
typedef struct parsed_record {
    int done, status, at, n;
    params p;
} parsed_record;

typedef struct curve_list {
    sc_curve *items;
    int n, cap;
} curve_list;

typedef struct reader {
    const char *name;
    sc_scene *scene;
    sc_error *err;
    record *rec;
    int nrec;
    int sec_first[SEC_COUNT], sec_count[SEC_COUNT];
    char pdelim, rdelim;
    entity *ent;
    int nent;
    parsed_record *parsed;   /* per P record, filled on demand */
    size_t tokenised;        /* characters tokenised so far (bounded, see tokenise_record) */
    sc_budget budget;        /* geometry charged so far (envelope.h) */
    int warned_no_pcurve, warned_unsupported;
    int unsupported_entity; /* the curve that stopped the last loop */
} reader;

static const double identity_xform[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

/* ------------------------------------------------------------------ */
/* Messages                                                             */
/* ------------------------------------------------------------------ */

static int fail_at(reader *r, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail_at(reader *r, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int status = sc_vfail(r->err, r->name, line, fmt, ap);
    va_end(ap);
    return status;
}

/* "entity TYPE (D n): ..." at `line`, or at the entity's directory line. */
static int fail_entity(reader *r, int e, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int fail_entity(reader *r, int e, int line, const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return sc_fail(r->err, r->name, line > 0 ? line : r->ent[e].line, "entity %d (D %d): %s",
                   r->ent[e].type, 2 * e + 1, msg);
}

/* ------------------------------------------------------------------ */
/* Records and sections                                                 */
/* ------------------------------------------------------------------ */

static int all_blank(const char *s, int n)
{
    for (int i = 0; i < n; i++)
        if (!isspace((unsigned char)s[i]))
            return 0;
    return 1;
}

static int add_record(reader *r, int *cap, const char *s, int n, int line, int *last_section)
{
    if (n < RECORD_COLS && all_blank(s, n))
        return SC_OK;
    if (n <= SECTION_COL)
        return fail_at(r, line, "record of %d columns: IGES records have 80, with the section "
                       "letter in column 73", n);
    char letter = s[SECTION_COL];
    if (r->nrec == 0 && (letter == 'B' || letter == 'C'))
        return fail_at(r, line, "%s IGES is not supported (only the fixed 80-column ASCII form)",
                       letter == 'B' ? "binary" : "compressed ASCII");
    int sec = 0;
    while (sec < SEC_COUNT && section_letters[sec] != letter)
        sec++;
    if (sec == SEC_COUNT)
        return fail_at(r, line, "column 73 holds '%c', not a section letter (S, G, D, P or T): "
                       "this is not a fixed-format IGES file", isprint((unsigned char)letter) ? letter : '?');
    if (sec < *last_section)
        return fail_at(r, line, "a %c record after the %c section: sections must come in the "
                       "order S, G, D, P, T", letter, section_letters[*last_section]);
    if (sec != *last_section)
        r->sec_first[sec] = r->nrec;
    *last_section = sec;
    r->sec_count[sec]++;
    if (r->nrec == *cap)
        r->rec = sc_realloc(r->rec, (size_t)(*cap = *cap ? 2 * *cap : 1024), sizeof(record));
    r->rec[r->nrec++] = (record){s, n, line};
    return SC_OK;
}

/* Cuts the text into 80-column records. A physical line longer than 80
 * columns (a file without line breaks) holds several records. */
static int read_records(reader *r, const char *text, size_t size)
{
    int cap = 0, line = 1, last_section = SEC_S;
    size_t pos = 0;
    while (pos < size) {
        size_t end = pos;
        while (end < size && text[end] != '\n')
            end++;
        size_t stop = end;
        while (stop > pos && text[stop - 1] == '\r')
            stop--;
        for (size_t at = pos; at < stop; at += RECORD_COLS) {
            size_t n = stop - at < RECORD_COLS ? stop - at : RECORD_COLS;
            if (add_record(r, &cap, text + at, (int)n, line, &last_section))
                return SC_FAIL;
        }
        pos = end + 1;
        line++;
    }
    if (r->nrec == 0)
        return fail_at(r, 0, "empty file: no IGES records");
    if (r->sec_count[SEC_D] == 0)
        return fail_at(r, r->rec[r->nrec - 1].line,
                       "no directory section (D records): not an IGES file, or truncated");
    if (r->sec_count[SEC_D] % 2)
        return fail_at(r, r->rec[r->sec_first[SEC_D] + r->sec_count[SEC_D] - 1].line,
                       "the directory section has an odd number of records (%d): every entity "
                       "needs two (truncated file?)", r->sec_count[SEC_D]);
    if (r->sec_count[SEC_T] == 0)
        sc_log(SC_LOG_WARN, "%s:%d: no terminate (T) record: the file may be truncated", r->name,
               r->rec[r->nrec - 1].line);
    return SC_OK;
}

/* Copies columns [0, cols) of records [first, first + n) into buf (blank-
 * padded) and returns its length. */
static int gather(const reader *r, int first, int n, int cols, char *buf)
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

enum { TOK_END, TOK_CUT, TOK_BAD_STRING };

static void push_token(params *p, token t)
{
    if (p->ntok == p->cap)
        p->tok = sc_realloc(p->tok, (size_t)(p->cap = p->cap ? 2 * p->cap : 64), sizeof(token));
    p->tok[p->ntok++] = t;
}

/* Cuts t[0, n) into tokens up to the record delimiter (TOK_END). TOK_CUT:
 * the text ends first, *at = n, or a Hollerith string's count runs past
 * the end, *at = its offset; TOK_BAD_STRING: a Hollerith string is followed
 * by something other than a delimiter, *at = its offset. */
static int tokenize(const char *t, int n, char pd, char rd, params *p, int *at)
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
        push_token(p, tk);
        if (t[pos] == rd)
            return TOK_END;
        pos++;
    }
}

static void params_free(params *p)
{
    if (!p->borrowed) {
        free(p->text);
        free(p->tok);
    }
    memset(p, 0, sizeof *p);
}

static int token_line(const reader *r, const params *p, int i)
{
    int offset = i < p->ntok ? p->tok[i].start : 0;
    return r->rec[p->first_record + offset / PARAM_COLS].line;
}

static int parse_real(const char *s, int len, double *out)
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

static int get_real(reader *r, const params *p, int i, double *out)
{
    if (i >= p->ntok)
        return fail_entity(r, p->entity, token_line(r, p, p->ntok - 1),
                           "parameter %d is missing (the entity has %d)", i, p->ntok - 1);
    const token *t = &p->tok[i];
    if (t->is_string)
        return fail_entity(r, p->entity, token_line(r, p, i),
                           "parameter %d: expected a number, found a string", i);
    if (t->len == 0) {
        *out = 0;
        return SC_OK;
    }
    if (parse_real(p->text + t->start, t->len, out))
        return fail_entity(r, p->entity, token_line(r, p, i),
                           "parameter %d: '%.*s' is not a finite number", i,
                           t->len > 40 ? 40 : t->len, p->text + t->start);
    return SC_OK;
}

/* Integers written as reals ("3.", "3.0E0") are accepted when integral. */
static int get_int(reader *r, const params *p, int i, int *out)
{
    double v;
    if (get_real(r, p, i, &v))
        return SC_FAIL;
    if (v != floor(v))
        return fail_entity(r, p->entity, token_line(r, p, i),
                           "parameter %d: expected an integer, found %.17g", i, v);
    if (fabs(v) > 1e9)
        return fail_entity(r, p->entity, token_line(r, p, i),
                           "parameter %d: integer %.17g is out of range (at most 1e9 in "
                           "magnitude)", i, v);
    *out = (int)v;
    return SC_OK;
}

/* A directory pointer: entity index in *target, or -1 for a null (0)
 * pointer. */
static int get_pointer(reader *r, const params *p, int i, int *target)
{
    int v;
    if (get_int(r, p, i, &v))
        return SC_FAIL;
    if (v == 0) {
        *target = -1;
        return SC_OK;
    }
    if (v < 0 || v % 2 == 0 || v > 2 * r->nent - 1)
        return fail_entity(r, p->entity, token_line(r, p, i),
                           "parameter %d: pointer %d is not a directory entry (odd, 1..%d)", i, v,
                           2 * r->nent - 1);
    *target = (v - 1) / 2;
    return SC_OK;
}

/* Fails unless the entity has at least n parameters after its type. */
static int need_params(reader *r, const params *p, long long n)
{
    if (n > p->ntok - 1)
        return fail_entity(r, p->entity, token_line(r, p, p->ntok - 1),
                           "needs %lld parameters, has %d (counts larger than the data)", n,
                           p->ntok - 1);
    return SC_OK;
}

/* A count read from the data, to be followed by at least `per` values
 * each: bounded by what is left, so it never drives an allocation. */
static int get_count(reader *r, const params *p, int i, int per, int *out)
{
    if (get_int(r, p, i, out))
        return SC_FAIL;
    if (*out < 0)
        return fail_entity(r, p->entity, token_line(r, p, i), "parameter %d: count %d is negative",
                           i, *out);
    if ((long long)*out * per > p->ntok - 1 - i)
        return fail_entity(r, p->entity, token_line(r, p, i),
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
        p->text = sc_realloc(p->text, (size_t)want * PARAM_COLS, 1);
        pr->n = gather(r, p->first_record, want, PARAM_COLS, p->text);
        pr->status = tokenize(p->text, pr->n, r->pdelim, r->rdelim, p, &pr->at);
        const token *last = pr->status == TOK_END ? &p->tok[p->ntok - 1] : NULL;
        r->tokenised += last ? (size_t)(last->start + last->len) : (size_t)pr->n;
        if (r->tokenised > (size_t)4 * np * PARAM_COLS + ((size_t)1 << 20))
            return fail_entity(r, e, r->rec[p->first_record].line, "parameter data pointers "
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
static int load_params(reader *r, int e, params *p)
{
    memset(p, 0, sizeof *p);
    p->entity = e;
    const entity *en = &r->ent[e];
    int np = r->sec_count[SEC_P];
    if (en->pdata < 1 || en->pdata > np)
        return fail_entity(r, e, 0, "parameter data pointer %d is outside the P section (1..%d)",
                           en->pdata, np);
    if (!r->parsed)
        r->parsed = sc_alloc((size_t)np, sizeof *r->parsed);
    parsed_record *pr = &r->parsed[en->pdata - 1];
    if (!pr->done && tokenise_record(r, e, en->pdata, pr))
        return SC_FAIL;
    *p = pr->p;
    p->entity = e;
    int n = pr->n, at = pr->at;
    int line = r->rec[p->first_record + (at < n ? at : n - 1) / PARAM_COLS].line;
    if (pr->status == TOK_BAD_STRING)
        return fail_entity(r, e, line, "text after a Hollerith string where a delimiter "
                           "('%c' or '%c') belongs", r->pdelim, r->rdelim);
    if (pr->status == TOK_CUT && at < n)
        return fail_entity(r, e, line, "a Hollerith string runs past the end of the "
                           "parameter data (its count is larger than the text)");
    if (pr->status == TOK_CUT)
        return fail_entity(r, e, line, "the parameter data ends before the record delimiter "
                           "'%c' (truncated file?)", r->rdelim);
    int type;
    if (p->ntok < 1 || p->tok[0].is_string || get_int(r, p, 0, &type) || type != en->type)
        return fail_entity(r, e, token_line(r, p, 0), "its parameter data (P line %d) does not "
                           "start with its type %d: wrong parameter data pointer?", en->pdata,
                           en->type);
    return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Global and directory sections                                        */
/* ------------------------------------------------------------------ */

static int delimiter_allowed(char c)
{
    return isprint((unsigned char)c) && !isspace((unsigned char)c) &&
           !isdigit((unsigned char)c) && !strchr("+-.DEH", c);
}

/* The global section matters for its delimiters; its other fields (names,
 * units, dates) are checked and reported, never fatal: real files get them
 * wrong and they change nothing in the geometry's own units. */
static int read_global(reader *r)
{
    r->pdelim = ',';
    r->rdelim = ';';
    int ng = r->sec_count[SEC_G];
    if (ng == 0)
        return SC_OK;
    int first = r->sec_first[SEC_G], line = r->rec[first].line;
    char *g = sc_alloc((size_t)ng * GLOBAL_COLS, 1);
    int n = gather(r, first, ng, GLOBAL_COLS, g), pos = 0;
    while (pos < n && g[pos] == ' ')
        pos++;
    if (pos + 2 < n && g[pos] == '1' && g[pos + 1] == 'H') {
        r->pdelim = g[pos + 2];
        pos += 3;
        while (pos < n && g[pos] == ' ')
            pos++;
    }
    if (pos < n && g[pos] == r->pdelim) {
        pos++;
        while (pos < n && g[pos] == ' ')
            pos++;
        if (pos + 2 < n && g[pos] == '1' && g[pos + 1] == 'H')
            r->rdelim = g[pos + 2];
    }
    if (!delimiter_allowed(r->pdelim) || !delimiter_allowed(r->rdelim) || r->pdelim == r->rdelim) {
        free(g);
        return fail_at(r, line, "global section: delimiters '%c' (parameter) and '%c' (record) "
                       "are not usable: they must differ and be neither blanks, digits, signs, "
                       "'.', 'D', 'E' nor 'H'", isprint((unsigned char)r->pdelim) ? r->pdelim : '?',
                       isprint((unsigned char)r->rdelim) ? r->rdelim : '?');
    }
    params gp = {0};
    int at, status = tokenize(g, n, r->pdelim, r->rdelim, &gp, &at);
    int bad_line = r->rec[first + (at < n ? at : n - 1) / GLOBAL_COLS].line;
    if (status == TOK_BAD_STRING || (status == TOK_CUT && at < n))
        sc_log(SC_LOG_WARN, "%s:%d: global section: a Hollerith string does not fit its count; "
               "the rest of the global section is ignored", r->name, bad_line);
    else if (status == TOK_CUT)
        sc_log(SC_LOG_DEBUG, "%s:%d: global section ends without the record delimiter '%c'",
               r->name, bad_line, r->rdelim);
    /* Field 14 is the unit flag (1..11), field 15 the unit name. */
    const char *units[] = {"?", "IN", "MM", "(field 15)", "FT", "MI", "M", "KM", "MIL", "UM",
                           "CM", "UIN"};
    double flag = 0;
    if (gp.ntok >= 14 && !gp.tok[13].is_string && gp.tok[13].len > 0 &&
        !parse_real(g + gp.tok[13].start, gp.tok[13].len, &flag) && flag >= 1 && flag <= 11)
        sc_log(SC_LOG_DEBUG, "%s: units %s", r->name, units[(int)flag]);
    else if (gp.ntok >= 14)
        sc_log(SC_LOG_DEBUG, "%s:%d: global section: no valid unit flag (field 14)", r->name, line);
    params_free(&gp);
    free(g);
    return SC_OK;
}

/* Integer directory field k (0..8) of a record: blanks read as 0. */
static int dir_int(reader *r, const record *rc, int k, int de, const char *what, int *out)
{
    char buf[9];
    int start = 8 * k, n = 0;
    for (int c = start; c < start + 8; c++)
        if (c < rc->len && rc->text[c] != ' ')
            buf[n++] = rc->text[c];
    buf[n] = 0;
    if (n == 0) {
        *out = 0;
        return SC_OK;
    }
    char *end;
    long v = strtol(buf, &end, 10);
    if (*end)
        return fail_at(r, rc->line, "directory entry D %d: field %d (%s) is not an integer: '%s'",
                       de, k + 1, what, buf);
    *out = (int)v;
    return SC_OK;
}

static int read_directory(reader *r)
{
    r->nent = r->sec_count[SEC_D] / 2;
    r->ent = sc_alloc((size_t)r->nent, sizeof(entity));
    for (int e = 0; e < r->nent; e++) {
        const record *a = &r->rec[r->sec_first[SEC_D] + 2 * e], *b = a + 1;
        entity *en = &r->ent[e];
        int de = 2 * e + 1;
        en->line = a->line;
        if (dir_int(r, a, 0, de, "entity type", &en->type) ||
            dir_int(r, a, 1, de, "parameter data pointer", &en->pdata) ||
            dir_int(r, a, 6, de, "transformation matrix", &en->xform) ||
            dir_int(r, b, 2, de, "colour", &en->color) ||
            dir_int(r, b, 3, de, "parameter line count", &en->nlines))
            return SC_FAIL;
        /* The subscript is cosmetic: junk there only loses the name suffix. */
        int subscript;
        if (dir_int(r, b, 8, de, "subscript", &subscript) == SC_OK)
            en->subscript = subscript;
        int n = 0;
        for (int c = 56; c < 64 && c < b->len; c++)
            if (isgraph((unsigned char)b->text[c]))
                en->label[n++] = b->text[c];
        en->label[n] = 0;
    }
    return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Transformations and colour                                           */
/* ------------------------------------------------------------------ */

/* out = a ∘ b (b applied first); out may alias either. */
static void compose(const double a[12], const double b[12], double out[12])
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
        int status = load_params(r, t, &p);
        if (status == SC_OK)
            status = need_params(r, &p, 12);
        for (int i = 0; i < 12 && status == SC_OK; i++)
            status = get_real(r, &p, i + 1, &en->matrix[i]);
        if (status)
            return SC_FAIL;
        en->has_matrix = 1;
    }
    memcpy(m, en->matrix, sizeof en->matrix);
    return SC_OK;
}

/* The entity's transformation: its 124 (directory field 7), that 124's own
 * 124, and so on, the innermost applied first. */
static int chained_xform(reader *r, int e, double m[12])
{
    memcpy(m, identity_xform, sizeof identity_xform);
    int ptr = r->ent[e].xform, steps = 0;
    while (ptr != 0) {
        if (ptr < 0 || ptr % 2 == 0 || ptr > 2 * r->nent - 1)
            return fail_entity(r, e, 0, "transformation matrix pointer %d (directory field 7) is "
                               "not a directory entry (odd, 1..%d)", ptr, 2 * r->nent - 1);
        int t = (ptr - 1) / 2;
        if (r->ent[t].type != 124)
            return fail_entity(r, e, 0, "directory field 7 points to entity %d (D %d), not to a "
                               "124 transformation matrix", r->ent[t].type, ptr);
        if (++steps > r->nent)
            return fail_entity(r, e, 0, "its transformation matrices refer to each other in a "
                               "cycle (through D %d)", ptr);
        double a[12];
        if (matrix_of_124(r, t, a))
            return SC_FAIL;
        compose(a, m, m);
        ptr = r->ent[t].xform;
    }
    return SC_OK;
}

/* Colour from directory field 13: 1..8 index the standard table, a
 * negative value points to a 314 colour definition (RGB in percent).
 * Returns 1 when the entity defines a colour. */
static int entity_color(reader *r, int e, float rgb[3])
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
        return fail_entity(r, e, 0, "colour pointer %d (directory field 13) is not a directory "
                           "entry (odd, 1..%d)", c, 2 * r->nent - 1);
    int t = (ptr - 1) / 2;
    if (r->ent[t].type != 314)
        return fail_entity(r, e, 0, "colour field 13 points to entity %d (D %d), not to a 314 "
                           "colour definition", r->ent[t].type, ptr);
    params p;
    double v[3];
    int status = load_params(r, t, &p);
    if (status == SC_OK)
        status = need_params(r, &p, 3);
    for (int i = 0; i < 3 && status == SC_OK; i++)
        status = get_real(r, &p, i + 1, &v[i]);
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
static int check_knot_vector(reader *r, const params *p, int first_param, const double *k,
                             int nk, int degree, const char *what)
{
    for (int i = 1; i < nk; i++)
        if (k[i] < k[i - 1])
            return fail_entity(r, p->entity, token_line(r, p, first_param + i),
                               "%s knots decrease at knot %d (%.17g after %.17g)", what, i, k[i],
                               k[i - 1]);
    if (!(k[degree] < k[nk - 1 - degree]))
        return fail_entity(r, p->entity, token_line(r, p, first_param),
                           "%s knot vector has an empty domain [%.17g, %.17g]", what, k[degree],
                           k[nk - 1 - degree]);
    return SC_OK;
}

/* Reads nk knots from parameter `at` on, then checks them. */
static int read_knot_vector(reader *r, const params *p, int at, double *k, int nk, int degree,
                            const char *what)
{
    for (int i = 0; i < nk; i++)
        if (get_real(r, p, at + i, &k[i]))
            return SC_FAIL;
    return check_knot_vector(r, p, at, k, nk, degree, what);
}

/* ------------------------------------------------------------------ */
/* Entity 128: rational B-spline surface                                */
/* ------------------------------------------------------------------ */

static int read_128_into(reader *r, const params *p, sc_surface *s)
{
    int e = p->entity, k1, k2, m1, m2, prop[5];
    if (need_params(r, p, 9) || get_int(r, p, 1, &k1) || get_int(r, p, 2, &k2) ||
        get_int(r, p, 3, &m1) || get_int(r, p, 4, &m2))
        return SC_FAIL;
    for (int i = 0; i < 5; i++)
        if (get_int(r, p, 5 + i, &prop[i]))
            return SC_FAIL;
    if (m1 < 1 || m2 < 1)
        return fail_entity(r, e, token_line(r, p, 3), "degree %d x %d: a surface needs degree 1 "
                           "or more in both directions", m1, m2);
    if (m1 > SC_READ_MAX_DEGREE || m2 > SC_READ_MAX_DEGREE)
        return fail_entity(r, e, token_line(r, p, 3), "degree %d x %d: above the %d this reader "
                           "accepts (docs/limits.md)", m1, m2, SC_READ_MAX_DEGREE);
    if (k1 < m1 || k2 < m2)
        return fail_entity(r, e, token_line(r, p, 1), "degree %d x %d needs at least %d x %d "
                           "control points, has %d x %d", m1, m2, m1 + 1, m2 + 1, k1 + 1, k2 + 1);
    long long nu = (long long)k1 + 1, nv = (long long)k2 + 1;
    if (nu > p->ntok || nv > p->ntok || nu * nv > p->ntok)
        return fail_entity(r, e, token_line(r, p, 1), "%lld x %lld control points: more than "
                           "the %d parameters present (counts larger than the data)", nu, nv,
                           p->ntok - 1);
    long long nku = nu + m1 + 1, nkv = nv + m2 + 1;
    if (need_params(r, p, 9 + nku + nkv + 4 * nu * nv) ||
        sc_budget_charge(&r->budget, sc_surface_bytes(m1, m2, (int)nu, (int)nv), "surface",
                         r->name, token_line(r, p, 1), r->err))
        return SC_FAIL;
    sc_surface_alloc(s, m1, m2, (int)nu, (int)nv);
    int at = 10;
    if (read_knot_vector(r, p, at, s->knots_u, (int)nku, m1, "u"))
        return SC_FAIL;
    at += (int)nku;
    if (read_knot_vector(r, p, at, s->knots_v, (int)nkv, m2, "v"))
        return SC_FAIL;
    at += (int)nkv;
    int npts = (int)(nu * nv), polynomial = prop[2] == 1, bad_weight = -1;
    for (int i = 0; i < npts; i++) {
        if (get_real(r, p, at + i, &s->cp[4 * i + 3]))
            return SC_FAIL;
        if (!(s->cp[4 * i + 3] > 0) && bad_weight < 0)
            bad_weight = i;
    }
    /* A polynomial surface's weights carry no information; some writers
     * leave them zero. */
    if (bad_weight >= 0 && !polynomial)
        return fail_entity(r, e, token_line(r, p, at + bad_weight), "weight %d is %.17g (weights "
                           "of a rational surface must be > 0)", bad_weight,
                           s->cp[4 * bad_weight + 3]);
    at += npts;
    for (int i = 0; i < npts; i++) {
        double w = bad_weight >= 0 ? 1.0 : s->cp[4 * i + 3];
        s->cp[4 * i + 3] = w;
        for (int d = 0; d < 3; d++) {
            double x;
            if (get_real(r, p, at + 3 * i + d, &x))
                return SC_FAIL;
            s->cp[4 * i + d] = x * w;
        }
    }
    at += 3 * npts;
    /* U(0), U(1), V(0), V(1): the used part of the domain. */
    double range[4];
    if (p->ntok - 1 >= at + 3) {
        for (int i = 0; i < 4; i++)
            if (get_real(r, p, at + i, &range[i]))
                return SC_FAIL;
        if (range[0] < range[1])
            sc_surface_restrict(s, 0, range[0], range[1]);
        if (range[2] < range[3])
            sc_surface_restrict(s, 1, range[2], range[3]);
    } else {
        sc_surface_restrict(s, 0, s->knots_u[m1], s->knots_u[s->nu]);
        sc_surface_restrict(s, 1, s->knots_v[m2], s->knots_v[s->nv]);
    }
    sc_surface_update_rational(s);
    sc_error check;
    if (sc_surface_check(s, &check))
        return fail_entity(r, e, token_line(r, p, 1), "%s", check.message);
    return SC_OK;
}

static int read_128(reader *r, int e, sc_surface *s)
{
    memset(s, 0, sizeof *s);
    params p;
    int status = load_params(r, e, &p);
    if (status == SC_OK)
        status = read_128_into(r, &p, s);
    if (status)
        sc_surface_free(s);
    return status;
}

/* ------------------------------------------------------------------ */
/* Parameter-space curves                                               */
/* ------------------------------------------------------------------ */

static sc_curve *list_push(curve_list *l)
{
    if (l->n == l->cap)
        l->items = sc_realloc(l->items, (size_t)(l->cap = l->cap ? 2 * l->cap : 8),
                              sizeof(sc_curve));
    sc_curve *c = &l->items[l->n++];
    memset(c, 0, sizeof *c);
    return c;
}

static void list_free(curve_list *l)
{
    for (int i = 0; i < l->n; i++)
        sc_curve_free(&l->items[i]);
    free(l->items);
    memset(l, 0, sizeof *l);
}

/* Homogeneous 2D control point from a model point: the transformation is
 * applied to (x, y, z) and (x', y') kept, as in the surface's (u, v). */
static void put_point(sc_curve *c, int i, const double m[12], double x, double y, double z,
                      double w)
{
    c->cp[3 * i + 0] = (m[0] * x + m[1] * y + m[2] * z + m[3]) * w;
    c->cp[3 * i + 1] = (m[4] * x + m[5] * y + m[6] * z + m[7]) * w;
    c->cp[3 * i + 2] = w;
}

/* The entity's first n parameters, all real. */
static int leading_reals(reader *r, const params *p, int n, double *v)
{
    if (need_params(r, p, n))
        return SC_FAIL;
    for (int i = 0; i < n; i++)
        if (get_real(r, p, i + 1, &v[i]))
            return SC_FAIL;
    return SC_OK;
}

static int read_110(reader *r, const params *p, const double m[12], curve_list *out)
{
    double v[6];
    if (leading_reals(r, p, 6, v))
        return SC_FAIL;
    sc_curve *c = list_push(out);
    sc_curve_alloc(c, 2, 1, 2);
    c->knots[0] = c->knots[1] = 0;
    c->knots[2] = c->knots[3] = 1;
    put_point(c, 0, m, v[0], v[1], v[2], 1);
    put_point(c, 1, m, v[3], v[4], v[5], 1);
    return SC_OK;
}

/* A circular arc, counter-clockwise from start to end about the centre in
 * the plane z = ZT of its definition space, as rational quadratic pieces
 * of at most 90° (middle weight cos(half the piece's angle)). */
static int read_100(reader *r, const params *p, const double m[12], curve_list *out)
{
    double v[7];
    if (leading_reals(r, p, 7, v))
        return SC_FAIL;
    double zt = v[0], cx = v[1], cy = v[2];
    double radius = hypot(v[3] - cx, v[4] - cy);
    if (!(radius > 0) || !isfinite(radius))
        return fail_entity(r, p->entity, token_line(r, p, 2), "circular arc of radius %g",
                           radius);
    double a0 = atan2(v[4] - cy, v[3] - cx), a1 = atan2(v[6] - cy, v[5] - cx);
    double sweep = a1 - a0;
    if (hypot(v[5] - v[3], v[6] - v[4]) <= 1e-12 * radius)
        sweep = 2 * M_PI;
    while (sweep <= 0)
        sweep += 2 * M_PI;
    int pieces = (int)ceil(sweep / (M_PI / 2) - 1e-9);
    if (pieces < 1)
        pieces = 1;
    double half = sweep / pieces / 2, w = cos(half);
    sc_curve *c = list_push(out);
    sc_curve_alloc(c, 2, 2, 2 * pieces + 1);
    for (int i = 0; i < 3; i++) {
        c->knots[i] = 0;
        c->knots[2 * pieces + 1 + i] = pieces;
    }
    for (int i = 1; i < pieces; i++)
        c->knots[2 * i + 1] = c->knots[2 * i + 2] = i;
    for (int i = 0; i <= 2 * pieces; i++) {
        double angle = a0 + i * half;
        double reach = i % 2 ? radius / w : radius;
        put_point(c, i, m, cx + reach * cos(angle), cy + reach * sin(angle), zt, i % 2 ? w : 1);
    }
    return SC_OK;
}

static int read_126(reader *r, const params *p, const double m[12], curve_list *out)
{
    int e = p->entity, k, deg, prop[4];
    if (need_params(r, p, 6) || get_int(r, p, 1, &k) || get_int(r, p, 2, &deg))
        return SC_FAIL;
    for (int i = 0; i < 4; i++)
        if (get_int(r, p, 3 + i, &prop[i]))
            return SC_FAIL;
    if (deg < 1)
        return fail_entity(r, e, token_line(r, p, 2), "degree %d: a curve needs degree 1 or more",
                           deg);
    if (deg > SC_READ_MAX_DEGREE)
        return fail_entity(r, e, token_line(r, p, 2), "degree %d: above the %d this reader "
                           "accepts (docs/limits.md)", deg, SC_READ_MAX_DEGREE);
    if (k < deg)
        return fail_entity(r, e, token_line(r, p, 1), "degree %d needs at least %d control "
                           "points, has %d", deg, deg + 1, k + 1);
    long long n = (long long)k + 1, nk = n + deg + 1;
    if (need_params(r, p, 6 + nk + 4 * n))
        return SC_FAIL;
    sc_curve *c = list_push(out);
    sc_curve_alloc(c, 2, deg, (int)n);
    int at = 7;
    if (read_knot_vector(r, p, at, c->knots, (int)nk, deg, "curve"))
        return SC_FAIL;
    at += (int)nk;
    int bad_weight = -1;
    for (int i = 0; i < n; i++) {
        if (get_real(r, p, at + i, &c->cp[3 * i + 2]))
            return SC_FAIL;
        if (!(c->cp[3 * i + 2] > 0) && bad_weight < 0)
            bad_weight = i;
    }
    if (bad_weight >= 0 && prop[2] != 1)
        return fail_entity(r, e, token_line(r, p, at + bad_weight), "weight %d is %.17g (weights "
                           "of a rational curve must be > 0)", bad_weight,
                           c->cp[3 * bad_weight + 2]);
    at += (int)n;
    for (int i = 0; i < n; i++) {
        double x[3];
        for (int d = 0; d < 3; d++)
            if (get_real(r, p, at + 3 * i + d, &x[d]))
                return SC_FAIL;
        put_point(c, i, m, x[0], x[1], x[2], bad_weight >= 0 ? 1.0 : c->cp[3 * i + 2]);
    }
    at += 3 * (int)n;
    /* V(0), V(1): the used part of the parameter range. */
    double range[2];
    if (p->ntok - 1 >= at + 1) {
        if (get_real(r, p, at, &range[0]) || get_real(r, p, at + 1, &range[1]))
            return SC_FAIL;
        if (range[0] < range[1])
            sc_curve_restrict(c, range[0], range[1]);
        else
            sc_curve_restrict(c, c->knots[deg], c->knots[n]);
    } else {
        sc_curve_restrict(c, c->knots[deg], c->knots[n]);
    }
    return SC_OK;
}

/* Charges the curves [first, n) just read from entity e to the budget. */
static int charge_curves(reader *r, int e, const curve_list *l, int first)
{
    if (l->n > SC_MAX_LOOP_PIECES)
        return fail_entity(r, e, 0, "a trim loop of more than %d curves (docs/limits.md)",
                           SC_MAX_LOOP_PIECES);
    size_t bytes = 0;
    char what[64];
    for (int i = first; i < l->n; i++)
        bytes += sc_curve_bytes(2, l->items[i].degree, l->items[i].ncp);
    snprintf(what, sizeof what, "entity %d (D %d) in a trim loop", r->ent[e].type, 2 * e + 1);
    return sc_budget_charge(&r->budget, bytes, what, r->name, r->ent[e].line, r->err);
}

/* How many curves entity e expands into as a trim curve, at most
 * SC_MAX_LOOP_PIECES + 1, remembered per entity so that a composite listing
 * another many times is counted in time linear in the entities. Anything
 * that is not a composite is one curve; errors (cycles, bad pointers) count
 * as one here and are reported when the loop is built. */
static int count_pieces(reader *r, int e, int depth)
{
    entity *en = &r->ent[e];
    if (en->pieces)
        return en->pieces;
    if (en->type != 102 || en->counting || depth > MAX_NESTING)
        return 1;
    params p; /* the cache's: nothing to free */
    int count = 0, member;
    long long total = 0;
    sc_error *err = r->err;
    r->err = NULL;
    if (!load_params(r, e, &p) && !need_params(r, &p, 1) && !get_count(r, &p, 1, 1, &count)) {
        en->counting = 1;
        for (int i = 0; i < count && total <= SC_MAX_LOOP_PIECES; i++)
            if (get_pointer(r, &p, 2 + i, &member) == SC_OK && member >= 0)
                total += count_pieces(r, member, depth + 1);
        en->counting = 0;
    }
    r->err = err;
    en->pieces = total > SC_MAX_LOOP_PIECES ? SC_MAX_LOOP_PIECES + 1 : total < 1 ? 1 : (int)total;
    return en->pieces;
}

/* Curves [first, n) of the list run backwards: last first, each reversed. */
static void reverse_chain(curve_list *l, int first)
{
    for (int i = first, j = l->n - 1; i < j; i++, j--) {
        sc_curve t = l->items[i];
        l->items[i] = l->items[j];
        l->items[j] = t;
    }
    for (int i = first; i < l->n; i++)
        sc_curve_reverse(&l->items[i]);
}

/* Appends the 2D curves of a parameter-space curve entity to `out`, in the
 * entity's own order or reversed. `parent` is the transformation of the
 * referring composite. Returns SC_OK, SC_FAIL, or LOOP_UNSUPPORTED for a
 * curve type this reader does not convert (r->unsupported_entity). */
static int trim_curves(reader *r, int e, const double parent[12], int reversed, curve_list *out,
                       int depth)
{
    entity *en = &r->ent[e];
    if (en->busy)
        return fail_entity(r, e, 0, "reference cycle: the entity contains itself");
    if (depth > MAX_NESTING)
        return fail_entity(r, e, 0, "composite curves nested more than %d deep", MAX_NESTING);
    if (en->type != 100 && en->type != 102 && en->type != 110 && en->type != 126) {
        r->unsupported_entity = e;
        return LOOP_UNSUPPORTED;
    }
    double own[12], m[12];
    if (chained_xform(r, e, own))
        return SC_FAIL;
    compose(parent, own, m);
    params p;
    if (load_params(r, e, &p))
        return SC_FAIL;
    int first = out->n, status = SC_OK;
    en->busy = 1;
    switch (en->type) {
    case 100: status = read_100(r, &p, m, out); break;
    case 110: status = read_110(r, &p, m, out); break;
    case 126: status = read_126(r, &p, m, out); break;
    case 102: {
        int count = 0;
        /* Members may repeat: the expansion is counted before it is built. */
        if (count_pieces(r, e, depth) > SC_MAX_LOOP_PIECES - out->n) {
            en->busy = 0;
            return fail_entity(r, e, 0, "composite curve expands to more than %d curves in one "
                               "trim loop (members listed repeatedly; docs/limits.md)",
                               SC_MAX_LOOP_PIECES);
        }
        status = need_params(r, &p, 1);
        if (status == SC_OK)
            status = get_count(r, &p, 1, 1, &count);
        for (int i = 0; i < count && status == SC_OK; i++) {
            int member;
            status = get_pointer(r, &p, 2 + i, &member);
            if (status == SC_OK && member < 0)
                status = fail_entity(r, e, token_line(r, &p, 2 + i), "member %d is a null "
                                     "pointer", i + 1);
            if (status == SC_OK)
                status = trim_curves(r, member, m, 0, out, depth + 1);
        }
        break;
    }
    }
    en->busy = 0;
    if (status == SC_OK && en->type != 102)
        status = charge_curves(r, e, out, first);
    if (status == SC_OK && reversed)
        reverse_chain(out, first);
    return status;
}

static double point_distance(const sc_curve *a, int ia, const sc_curve *b, int ib)
{
    const double *p = a->cp + 3 * ia, *q = b->cp + 3 * ib;
    return hypot(p[0] / p[2] - q[0] / q[2], p[1] / p[2] - q[1] / q[2]);
}

/* Members of a composite are sometimes written against the direction of
 * the chain: a curve whose end, not its start, meets the previous curve's
 * end is turned around. */
static void orient_chain(curve_list *l)
{
    if (l->n < 2)
        return;
    sc_curve *c = l->items;
    int last1 = c[1].ncp - 1, last0 = c[0].ncp - 1;
    double fwd = fmin(point_distance(&c[0], last0, &c[1], 0), point_distance(&c[0], last0, &c[1], last1));
    double rev = fmin(point_distance(&c[0], 0, &c[1], 0), point_distance(&c[0], 0, &c[1], last1));
    if (rev < fwd)
        sc_curve_reverse(&c[0]);
    for (int i = 1; i < l->n; i++) {
        int prev_end = c[i - 1].ncp - 1;
        if (point_distance(&c[i - 1], prev_end, &c[i], c[i].ncp - 1) <
            point_distance(&c[i - 1], prev_end, &c[i], 0))
            sc_curve_reverse(&c[i]);
    }
}

/* ------------------------------------------------------------------ */
/* Trim loops: 142 (under 144), 141 (under 143), 508 (under 510)        */
/* ------------------------------------------------------------------ */

static int expect_type(reader *r, const params *p, int i, int target, int type)
{
    if (r->ent[target].type != type)
        return fail_entity(r, p->entity, token_line(r, p, i), "parameter %d points to entity %d "
                           "(D %d), expected a %d", i, r->ent[target].type, 2 * target + 1, type);
    return SC_OK;
}

static int loop_of_142(reader *r, int e, curve_list *out)
{
    params p;
    int sptr, bptr = -1, status = load_params(r, e, &p);
    if (status == SC_OK)
        status = need_params(r, &p, 5);
    /* SPTR is not followed (the owner names the surface), but a used
     * entity is checked whole. */
    if (status == SC_OK)
        status = get_pointer(r, &p, 2, &sptr);
    if (status == SC_OK)
        status = get_pointer(r, &p, 3, &bptr);
    if (status)
        return SC_FAIL;
    if (bptr < 0)
        return LOOP_NO_PCURVE;
    return trim_curves(r, bptr, identity_xform, 0, out, 0);
}

/* Appends the parameter-space curves of one boundary edge (141 or 508):
 * `count` pointers from parameter `first` on, `stride` apart, reversed as
 * a whole when the edge runs against the loop. */
static int edge_curves(reader *r, const params *p, int first, int count, int stride,
                       int reversed, curve_list *out)
{
    int start = out->n;
    for (int k = 0; k < count; k++) {
        int c;
        if (get_pointer(r, p, first + k * stride, &c))
            return SC_FAIL;
        if (c < 0)
            return LOOP_NO_PCURVE;
        int status = trim_curves(r, c, identity_xform, 0, out, 0);
        if (status)
            return status;
    }
    if (reversed)
        reverse_chain(out, start);
    return SC_OK;
}

/* 141: TYPE, PREF, SPTR, N, then per model-space curve CRVPT, SENSE
 * (2 = reversed), K and K parameter-space curves. */
static int loop_of_141_params(reader *r, const params *p, curve_list *out)
{
    int sptr, n, at = 5, missing = 0;
    if (need_params(r, p, 4) || get_pointer(r, p, 3, &sptr) || get_count(r, p, 4, 3, &n))
        return SC_FAIL;
    for (int i = 0; i < n; i++) {
        int sense, k;
        if (need_params(r, p, at + 2) || get_int(r, p, at + 1, &sense) ||
            get_count(r, p, at + 2, 1, &k))
            return SC_FAIL;
        if (k == 0)
            missing = 1;
        else if (!missing) {
            int status = edge_curves(r, p, at + 3, k, 1, sense == 2, out);
            if (status)
                return status;
        }
        at += 3 + k;
    }
    return missing ? LOOP_NO_PCURVE : SC_OK;
}

/* 508: N, then per edge TYPE (0 edge, 1 vertex), EDGE, NDX, OF (1 = the
 * edge runs along the loop), K and K pairs (ISOP, CURV). A vertex "edge"
 * (a pole) without parameter-space curves adds nothing. */
static int loop_of_508_params(reader *r, const params *p, curve_list *out)
{
    int n, at = 2, missing = 0;
    if (need_params(r, p, 1) || get_count(r, p, 1, 5, &n))
        return SC_FAIL;
    for (int i = 0; i < n; i++) {
        int type, orient, k;
        if (need_params(r, p, at + 4) || get_int(r, p, at, &type) ||
            get_int(r, p, at + 3, &orient) || get_count(r, p, at + 4, 2, &k))
            return SC_FAIL;
        if (k == 0 && type == 0)
            missing = 1;
        else if (k > 0 && !missing) {
            int status = edge_curves(r, p, at + 6, k, 2, orient == 0, out);
            if (status)
                return status;
        }
        at += 5 + 2 * k;
    }
    return missing ? LOOP_NO_PCURVE : SC_OK;
}

static int loop_of(reader *r, int e, curve_list *out)
{
    if (r->ent[e].type == 142)
        return loop_of_142(r, e, out);
    params p;
    if (load_params(r, e, &p))
        return SC_FAIL;
    int status = r->ent[e].type == 141 ? loop_of_141_params(r, &p, out)
                                       : loop_of_508_params(r, &p, out);
    return status;
}

static void add_loop(sc_surface *s, int is_hole, curve_list *l)
{
    s->loops = sc_realloc(s->loops, (size_t)s->nloops + 1, sizeof(sc_loop));
    s->loops[s->nloops++] = (sc_loop){is_hole, l->n, l->items};
    memset(l, 0, sizeof *l);
}

/* The domain rectangle as an outer loop: a surface whose outer boundary is
 * its domain but which has holes keeps its parity test simple. */
static void add_domain_loop(sc_surface *s)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    double corner[5][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}, {u0, v0}};
    curve_list l = {0};
    for (int i = 0; i < 4; i++) {
        sc_curve *c = list_push(&l);
        sc_curve_alloc(c, 2, 1, 2);
        c->knots[0] = c->knots[1] = 0;
        c->knots[2] = c->knots[3] = 1;
        for (int k = 0; k < 2; k++) {
            c->cp[3 * k + 0] = corner[i + k][0];
            c->cp[3 * k + 1] = corner[i + k][1];
            c->cp[3 * k + 2] = 1;
        }
    }
    add_loop(s, 0, &l);
    /* The outer loop goes first. */
    sc_loop outer = s->loops[s->nloops - 1];
    memmove(s->loops + 1, s->loops, sizeof(sc_loop) * (size_t)(s->nloops - 1));
    s->loops[0] = outer;
}

/* Builds the loop whose entity is `e` (142, 141 or 508) and attaches it to
 * the surface, or counts and reports (once per file) why it cannot be.
 * *added is set when the loop was attached. */
static int attach_loop(reader *r, int owner, int e, int is_hole, sc_surface *s, int *added)
{
    curve_list l = {0};
    *added = 0;
    int status = loop_of(r, e, &l);
    if (status == SC_OK) {
        orient_chain(&l);
        for (int i = 0; i < l.n; i++) {
            sc_error check;
            if (sc_curve_check(&l.items[i], &check)) {
                list_free(&l);
                return fail_entity(r, e, 0, "trim curve %d: %s", i + 1, check.message);
            }
        }
        if (l.n > 0) {
            add_loop(s, is_hole, &l);
            *added = 1;
        }
        list_free(&l);
        return SC_OK;
    }
    list_free(&l);
    if (status == SC_FAIL)
        return SC_FAIL;
    const char *fate = is_hole ? "the hole is dropped" : "the surface is kept untrimmed";
    char type[32];
    if (status == LOOP_NO_PCURVE) {
        snprintf(type, sizeof type, "iges-%d", r->ent[e].type);
        sc_scene_skip(r->scene, type, "no-parameter-curve", 1);
        if (!r->warned_no_pcurve++)
            sc_log(SC_LOG_WARN, "%s:%d: entity %d (D %d) of surface D %d: a trim loop has only "
                   "model-space (3D) curves and %s (projecting 3D edges is not supported; "
                   "further cases are counted in `skipped`, not reported)", r->name,
                   r->ent[e].line, r->ent[e].type, 2 * e + 1, 2 * owner + 1, fate);
    } else {
        int u = r->unsupported_entity;
        snprintf(type, sizeof type, "iges-%d", r->ent[u].type);
        sc_scene_skip(r->scene, type, "unsupported-trim-curve", 1);
        if (!r->warned_unsupported++)
            sc_log(SC_LOG_WARN, "%s:%d: entity %d (D %d): trim curve of unsupported type %d; %s "
                   "(further cases are counted in `skipped`, not reported)", r->name,
                   r->ent[u].line, r->ent[u].type, 2 * u + 1, r->ent[u].type, fate);
    }
    return SC_OK;
}

/* ------------------------------------------------------------------ */
/* Surfaces                                                             */
/* ------------------------------------------------------------------ */

/* Transformation, colour and name of a surface from its owner (the 144,
 * 143 or 510; the 128 itself for a free surface) and its 128, then into
 * the scene. */
static int finish_surface(reader *r, int owner, int base, sc_surface *s)
{
    double own[12], outer[12];
    if (chained_xform(r, base, own))
        return SC_FAIL;
    if (owner != base) {
        if (chained_xform(r, owner, outer))
            return SC_FAIL;
        compose(outer, own, own);
    }
    memcpy(s->xform, own, sizeof own);
    float rgb[3];
    int has = entity_color(r, owner, rgb);
    if (has == 0 && owner != base)
        has = entity_color(r, base, rgb);
    if (has < 0)
        return SC_FAIL;
    if (has)
        memcpy(s->color, rgb, sizeof rgb);
    int named = r->ent[owner].label[0] ? owner : r->ent[base].label[0] ? base : -1;
    if (named < 0)
        snprintf(s->name, sizeof s->name, "iges%d", 2 * owner + 1);
    else if (r->ent[named].subscript)
        snprintf(s->name, sizeof s->name, "%s.%d", r->ent[named].label, r->ent[named].subscript);
    else
        snprintf(s->name, sizeof s->name, "%s", r->ent[named].label);
    sc_surface *dst = sc_scene_add_surface(r->scene);
    float default_color[3];
    memcpy(default_color, dst->color, sizeof default_color);
    *dst = *s;
    if (!has) /* colour 0 in field 13: none assigned, so the scene's default */
        memcpy(dst->color, default_color, sizeof default_color);
    memset(s, 0, sizeof *s);
    return SC_OK;
}

/* The 128 a trimmed surface stands on; 0 with a count when it is another
 * surface type (1 when it is a 128). */
static int base_surface(reader *r, const params *p, int i, int *base)
{
    if (get_pointer(r, p, i, base))
        return SC_FAIL;
    if (*base < 0)
        return fail_entity(r, p->entity, token_line(r, p, i), "its surface pointer (parameter "
                           "%d) is null", i);
    if (r->ent[*base].type == 128)
        return 1;
    char type[32];
    snprintf(type, sizeof type, "iges-%d", r->ent[p->entity].type);
    sc_scene_skip(r->scene, type, "unsupported-surface", 1);
    return 0;
}

/* ------------------------------------------------------------------ */
/* Trims across the seam of a closed surface                            */
/* ------------------------------------------------------------------ */

/* Range along dir of the trim curves' control points (a bound of the
 * curves themselves). */
static void trims_range(const sc_surface *s, int dir, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (int l = 0; l < s->nloops; l++)
        for (int c = 0; c < s->loops[l].ncurves; c++) {
            const sc_curve *k = &s->loops[l].curves[c];
            for (int i = 0; i < k->ncp; i++) {
                double x = k->cp[3 * i + dir] / k->cp[3 * i + 2];
                *lo = fmin(*lo, x);
                *hi = fmax(*hi, x);
            }
        }
}

static const double *row_point(const sc_surface *s, int dir, int along, int across)
{
    return s->cp + 4 * (dir ? (size_t)along * s->nu + across : (size_t)across * s->nu + along);
}

/* Closed along dir: the first and last rows of control points coincide
 * (homogeneous, so that a copy can share them). */
static int closed_along(const sc_surface *s, int dir)
{
    int n = dir ? s->nv : s->nu, m = dir ? s->nu : s->nv;
    double scale = 0;
    for (size_t k = 0; k < 4 * (size_t)s->nu * s->nv; k++)
        scale = fmax(scale, fabs(s->cp[k]));
    for (int j = 0; j < m; j++) {
        const double *a = row_point(s, dir, 0, j), *b = row_point(s, dir, n - 1, j);
        for (int d = 0; d < 4; d++)
            if (fabs(a[d] - b[d]) > 1e-9 * scale)
                return 0;
    }
    return 1;
}

/* Joins a copy of the (clamped, closed) surface shifted by one period
 * before (left) or after it along dir: the seam becomes an interior knot of
 * multiplicity degree, the shape is unchanged. */
static void join_period(sc_surface *s, int dir, int left)
{
    int p = dir ? s->deg_v : s->deg_u, n = dir ? s->nv : s->nu, nk = n + p + 1;
    const double *k = dir ? s->knots_v : s->knots_u;
    double period = k[nk - 1] - k[0], shift = left ? -period : period;
    sc_surface out = *s;
    out.loops = NULL;
    out.nloops = 0;
    sc_surface_alloc(&out, s->deg_u, s->deg_v, dir ? s->nu : 2 * n - 1, dir ? 2 * n - 1 : s->nv);
    memcpy(dir ? out.knots_u : out.knots_v, dir ? s->knots_u : s->knots_v,
           sizeof(double) * (size_t)(dir ? s->nu + s->deg_u + 1 : s->nv + s->deg_v + 1));
    double *ko = dir ? out.knots_v : out.knots_u;
    /* first copy without its last knot, second without its first p+1 */
    const double first_shift = left ? shift : 0, second_shift = left ? 0 : shift;
    for (int i = 0; i < nk - 1; i++)
        ko[i] = k[i] + first_shift;
    for (int i = p + 1; i < nk; i++)
        ko[nk - 1 + i - (p + 1)] = k[i] + second_shift;
    int m = dir ? s->nu : s->nv;
    for (int j = 0; j < m; j++)
        for (int i = 0; i < 2 * n - 1; i++) {
            int src = i < n ? i : i - n + 1;
            double *dst = (double *)row_point(&out, dir, i, j);
            memcpy(dst, row_point(s, dir, src, j), 4 * sizeof(double));
        }
    sc_surface_free(s);
    *s = out;
}

/* Trims of a closed surface may run across its seam (a torus trimmed at
 * u in [-pi/2, pi/2] on a [0, 2pi] domain). The surface is then extended by
 * whole periods and restricted to the trims' range, so that every trimmed
 * point has its own parameters. */
static void unwrap_seams(sc_surface *s)
{
    if (s->nloops == 0)
        return;
    /* Restriction and joining rebuild the surface without its loops. */
    sc_loop *loops = s->loops;
    int nloops = s->nloops;
    for (int dir = 0; dir < 2; dir++) {
        double lo, hi, a, b, c, d;
        sc_surface_domain(s, &a, &b, &c, &d);
        if (dir) {
            a = c;
            b = d;
        }
        double period = b - a, slack = 1e-6 * period;
        trims_range(s, dir, &lo, &hi);
        if (!(lo < a - slack || hi > b + slack) || hi - lo > period + slack ||
            !closed_along(s, dir))
            continue;
        s->loops = NULL;
        s->nloops = 0;
        if (lo < a - slack)
            join_period(s, dir, 1);
        if (hi > b + slack)
            join_period(s, dir, 0);
        sc_surface_restrict(s, dir, lo, hi);
        s->loops = loops;
        s->nloops = nloops;
    }
}

/* Loops of one trimmed surface: `loops` entities, the first of which is the
 * outer boundary when has_outer. Without a usable outer loop the domain is
 * the outer boundary. */
static int build_trimmed(reader *r, int owner, int base, const int *loops, int nloops,
                         int has_outer)
{
    /* Loop entities may be listed many times: each costs its curves. */
    if (sc_budget_charge(&r->budget, (size_t)nloops * sizeof(sc_loop), "trimmed surface",
                         r->name, r->ent[owner].line, r->err))
        return SC_FAIL;
    sc_surface s;
    if (read_128(r, base, &s))
        return SC_FAIL;
    int outer_added = 0;
    for (int i = 0; i < nloops; i++) {
        int is_hole = !(has_outer && i == 0), added;
        if (attach_loop(r, owner, loops[i], is_hole, &s, &added)) {
            sc_surface_free(&s);
            return SC_FAIL;
        }
        outer_added |= added && !is_hole;
    }
    if (!outer_added && s.nloops > 0)
        add_domain_loop(&s);
    unwrap_seams(&s);
    if (finish_surface(r, owner, base, &s)) {
        sc_surface_free(&s);
        return SC_FAIL;
    }
    return SC_OK;
}

/* Loop entity pointers from parameters first.. (stride apart) checked to
 * be of `type`. */
static int loop_pointers(reader *r, const params *p, int first, int count, int type, int *out)
{
    for (int i = 0; i < count; i++) {
        if (get_pointer(r, p, first + i, &out[i]))
            return SC_FAIL;
        if (out[i] < 0)
            return fail_entity(r, p->entity, token_line(r, p, first + i), "loop pointer "
                               "(parameter %d) is null", first + i);
        if (expect_type(r, p, first + i, out[i], type))
            return SC_FAIL;
    }
    return SC_OK;
}

/* 144: PTS, N1 (0: the outer boundary is the domain's), N2, PTO, PTI(N2). */
static int convert_144(reader *r, const params *p)
{
    int base, n1, n2;
    if (need_params(r, p, 4) || get_int(r, p, 2, &n1) || get_count(r, p, 3, 1, &n2))
        return SC_FAIL;
    int kind = base_surface(r, p, 1, &base), outer;
    if (kind <= 0)
        return kind;
    /* A null outer pointer means the domain boundary, whatever N1 says. */
    if (n1 != 0 && get_pointer(r, p, 4, &outer))
        return SC_FAIL;
    if (n1 != 0 && outer < 0)
        n1 = 0;
    int *loops = sc_alloc((size_t)n2 + 1, sizeof(int)), n = 0;
    int status = SC_OK;
    if (n1 != 0) {
        status = loop_pointers(r, p, 4, 1, 142, loops);
        n = 1;
    }
    if (status == SC_OK)
        status = loop_pointers(r, p, 5, n2, 142, loops + n);
    if (status == SC_OK)
        status = build_trimmed(r, p->entity, base, loops, n + n2, n1 != 0);
    free(loops);
    return status;
}

/* 143: TYPE, SPTR, N, BDPT(N) — the first boundary is the outer one. */
static int convert_143(reader *r, const params *p)
{
    int base, n;
    if (need_params(r, p, 3) || get_count(r, p, 3, 1, &n))
        return SC_FAIL;
    int kind = base_surface(r, p, 2, &base);
    if (kind <= 0)
        return kind;
    int *loops = sc_alloc((size_t)n + 1, sizeof(int));
    int status = loop_pointers(r, p, 4, n, 141, loops);
    if (status == SC_OK)
        status = build_trimmed(r, p->entity, base, loops, n, 1);
    free(loops);
    return status;
}

/* 510: SURF, N, OF (1: the first loop is the outer one), LOOP(N). */
static int convert_510(reader *r, const params *p)
{
    int base, n, outer_first;
    if (need_params(r, p, 3) || get_count(r, p, 2, 1, &n) || get_int(r, p, 3, &outer_first))
        return SC_FAIL;
    int kind = base_surface(r, p, 1, &base);
    if (kind <= 0)
        return kind;
    int *loops = sc_alloc((size_t)n + 1, sizeof(int));
    int status = loop_pointers(r, p, 4, n, 508, loops);
    if (status == SC_OK)
        status = build_trimmed(r, p->entity, base, loops, n, outer_first == 1);
    free(loops);
    return status;
}

/* Which parameter of an entity points to the surface it uses: 128s
 * referenced this way are not surfaces of their own. */
static int surface_param(int type)
{
    switch (type) {
    case 142: return 2;
    case 144: return 1;
    case 143: return 2;
    case 141: return 3;
    case 510: return 1;
    case 140: return 5;
    default: return 0;
    }
}

/* Only finds which 128s are referenced, so a broken entity here is not an
 * error: whether it matters is known only when a surface uses it, and then
 * its conversion reports it. Until then it references nothing. */
static void mark_references(reader *r)
{
    sc_error *err = r->err;
    r->err = NULL;
    for (int e = 0; e < r->nent; e++) {
        int i = surface_param(r->ent[e].type);
        if (!i)
            continue;
        params p;
        int target = -1, status = load_params(r, e, &p);
        if (status == SC_OK)
            status = need_params(r, &p, i);
        if (status == SC_OK)
            status = get_pointer(r, &p, i, &target);
        if (status == SC_OK && target >= 0)
            r->ent[target].referenced = 1;
    }
    r->err = err;
}

static int is_known_type(int type)
{
    static const int known[] = {0,   100, 102, 110, 124, 126, 128, 141, 142, 143,
                                144, 186, 314, 502, 504, 508, 510, 514};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (known[i] == type)
            return 1;
    return 0;
}

static int convert_all(reader *r)
{
    for (int e = 0; e < r->nent; e++) {
        int type = r->ent[e].type, status = SC_OK;
        if (type == 144 || type == 143 || type == 510) {
            params p;
            status = load_params(r, e, &p);
            if (status == SC_OK)
                status = type == 144 ? convert_144(r, &p)
                         : type == 143 ? convert_143(r, &p) : convert_510(r, &p);
        } else if (type == 128 && !r->ent[e].referenced) {
            sc_surface s;
            status = read_128(r, e, &s);
            if (status == SC_OK && finish_surface(r, e, e, &s)) {
                sc_surface_free(&s);
                status = SC_FAIL;
            }
        } else if (!is_known_type(type)) {
            char name[32];
            snprintf(name, sizeof name, "iges-%d", type);
            sc_scene_skip(r->scene, name, "unsupported", 1);
        }
        if (status)
            return SC_FAIL;
    }
    return SC_OK;
}

int sc_read_iges(const char *text, size_t size, const char *name, sc_scene *scene, sc_error *err)
{
    sc_scene_init(scene);
    if (sc_check_text(text, size, name, err))
        return SC_FAIL;
    reader r = {.name = name, .scene = scene, .err = err};
    int status;
    if (size > (size_t)1 << 30)
        status = fail_at(&r, 0, "file of %zu bytes: larger than this reader accepts (1 GiB)", size);
    else
        status = read_records(&r, text, size);
    if (status == SC_OK)
        status = read_global(&r);
    if (status == SC_OK)
        status = read_directory(&r);
    if (status == SC_OK) {
        mark_references(&r);
        status = convert_all(&r);
    }
    for (int i = 0; r.parsed && i < r.sec_count[SEC_P]; i++) {
        free(r.parsed[i].p.text);
        free(r.parsed[i].p.tok);
    }
    free(r.parsed);
    free(r.rec);
    free(r.ent);
    return sc_finish_read(status, name, scene);
}
