/* iges_sections.c — the record layer of the IGES reader: 80-column records
 * cut from the text (lenient about line breaks, CRLF and blank lines,
 * strict about section letters and order), the global section's
 * delimiters, and the directory entries. */
#include "iges_local.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char section_letters[SEC_COUNT] = {'S', 'G', 'D', 'P', 'T'};

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
        return iges_fail_at(r, line, "record of %d columns: IGES records have 80, with the section "
                       "letter in column 73", n);
    char letter = s[SECTION_COL];
    if (r->nrec == 0 && (letter == 'B' || letter == 'C'))
        return iges_fail_at(r, line, "%s IGES is not supported (only the fixed 80-column ASCII form)",
                       letter == 'B' ? "binary" : "compressed ASCII");
    int sec = 0;
    while (sec < SEC_COUNT && section_letters[sec] != letter)
        sec++;
    if (sec == SEC_COUNT)
        return iges_fail_at(r, line, "column 73 holds '%c', not a section letter (S, G, D, P or T): "
                       "this is not a fixed-format IGES file", isprint((unsigned char)letter) ? letter : '?');
    if (sec < *last_section)
        return iges_fail_at(r, line, "a %c record after the %c section: sections must come in the "
                       "order S, G, D, P, T", letter, section_letters[*last_section]);
    if (sec != *last_section)
        r->sec_first[sec] = r->nrec;
    *last_section = sec;
    r->sec_count[sec]++;
    if (r->nrec == *cap) {
        int grow = *cap ? 2 * *cap : 1024;
        record *grown = sc_try_realloc(r->rec, (size_t)grow, sizeof(record));
        if (!grown)
            return sc_fail_oom(r->err, r->name, line, (size_t)grow, sizeof(record),
                               "the records");
        r->rec = grown;
        *cap = grow;
    }
    r->rec[r->nrec++] = (record){s, n, line};
    return SC_OK;
}

/* Cuts the text into 80-column records. A physical line longer than 80
 * columns (a file without line breaks) holds several records. */
int iges_read_records(reader *r, const char *text, size_t size)
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
        return iges_fail_at(r, 0, "empty file: no IGES records");
    if (r->sec_count[SEC_D] == 0)
        return iges_fail_at(r, r->rec[r->nrec - 1].line,
                       "no directory section (D records): not an IGES file, or truncated");
    if (r->sec_count[SEC_D] % 2)
        return iges_fail_at(r, r->rec[r->sec_first[SEC_D] + r->sec_count[SEC_D] - 1].line,
                       "the directory section has an odd number of records (%d): every entity "
                       "needs two (truncated file?)", r->sec_count[SEC_D]);
    if (r->sec_count[SEC_T] == 0)
        sc_log(SC_LOG_WARN, "%s:%d: no terminate (T) record: the file may be truncated", r->name,
               r->rec[r->nrec - 1].line);
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
int iges_read_global(reader *r)
{
    r->pdelim = ',';
    r->rdelim = ';';
    int ng = r->sec_count[SEC_G];
    if (ng == 0)
        return SC_OK;
    int first = r->sec_first[SEC_G], line = r->rec[first].line;
    char *g = sc_try_alloc((size_t)ng * GLOBAL_COLS, 1);
    if (!g)
        return sc_fail_oom(r->err, r->name, line, (size_t)ng, GLOBAL_COLS, "the global section");
    int n = iges_gather(r, first, ng, GLOBAL_COLS, g), pos = 0;
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
        return iges_fail_at(r, line, "global section: delimiters '%c' (parameter) and '%c' (record) "
                       "are not usable: they must differ and be neither blanks, digits, signs, "
                       "'.', 'D', 'E' nor 'H'", isprint((unsigned char)r->pdelim) ? r->pdelim : '?',
                       isprint((unsigned char)r->rdelim) ? r->rdelim : '?');
    }
    params gp = {0};
    int at, status = iges_tokenize(g, n, r->pdelim, r->rdelim, &gp, &at);
    int bad_line = r->rec[first + (at < n ? at : n - 1) / GLOBAL_COLS].line;
    if (status == TOK_NO_MEMORY) {
        size_t want = (size_t)gp.cap * 2;
        iges_params_free(&gp);
        free(g);
        return sc_fail_oom(r->err, r->name, bad_line, want, sizeof(token),
                           "the global section's parameters");
    }
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
        !iges_parse_real(g + gp.tok[13].start, gp.tok[13].len, &flag) && flag >= 1 && flag <= 11)
        sc_log(SC_LOG_DEBUG, "%s: units %s", r->name, units[(int)flag]);
    else if (gp.ntok >= 14)
        sc_log(SC_LOG_DEBUG, "%s:%d: global section: no valid unit flag (field 14)", r->name, line);
    iges_params_free(&gp);
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
        return iges_fail_at(r, rc->line, "directory entry D %d: field %d (%s) is not an integer: '%s'",
                       de, k + 1, what, buf);
    *out = (int)v;
    return SC_OK;
}

int iges_read_directory(reader *r)
{
    r->nent = r->sec_count[SEC_D] / 2;
    if (!(r->ent = sc_try_alloc((size_t)r->nent, sizeof(entity))))
        return sc_fail_oom(r->err, r->name, 0, (size_t)r->nent, sizeof(entity),
                           "the directory entries");
    for (int e = 0; e < r->nent; e++) {
        const record *a = &r->rec[r->sec_first[SEC_D] + 2 * e], *b = a + 1;
        entity *en = &r->ent[e];
        int de = 2 * e + 1;
        en->line = a->line;
        if (dir_int(r, a, 0, de, "entity type", &en->type) ||
            dir_int(r, a, 1, de, "parameter data pointer", &en->pdata) ||
            dir_int(r, a, 6, de, "transformation matrix", &en->xform) ||
            dir_int(r, b, 2, de, "colour", &en->color) ||
            dir_int(r, b, 3, de, "parameter line count", &en->nlines) ||
            dir_int(r, b, 4, de, "form number", &en->form))
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

