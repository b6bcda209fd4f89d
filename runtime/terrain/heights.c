/* heights.c — height grids from PGM and CSV files and from Franke's
 * function. The readers parse the whole file before they build anything, so
 * that a refused file leaves *out untouched. */
#include "heights.h"

#include "envelope.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void sc_heights_free(sc_heights *h)
{
    free(h->z);
    memset(h, 0, sizeof *h);
}

/* SC_FAIL (h empty) when memory runs out: the grid's size comes from a
 * file or a caller's count. */
static int heights_alloc(sc_heights *h, int nx, int ny, int pad)
{
    memset(h, 0, sizeof *h);
    h->z = sc_try_alloc((size_t)(nx + 2 * pad) * (size_t)(ny + 2 * pad), sizeof *h->z);
    if (!h->z)
        return SC_FAIL;
    h->nx = nx; h->ny = ny; h->pad = pad;
    return SC_OK;
}

static double *heights_ref(sc_heights *h, int i, int j)
{
    return &h->z[(size_t)(j + h->pad) * (size_t)(h->nx + 2 * h->pad) + (size_t)(i + h->pad)];
}

/* Franke, "Scattered data interpolation: tests of some methods" (1982). */
double sc_franke(double x, double y)
{
    double a = 9 * x, b = 9 * y;
    return 0.75 * exp(-((a - 2) * (a - 2) + (b - 2) * (b - 2)) / 4)
         + 0.75 * exp(-(a + 1) * (a + 1) / 49 - (b + 1) / 10)
         + 0.5 * exp(-((a - 7) * (a - 7) + (b - 3) * (b - 3)) / 4)
         - 0.2 * exp(-(a - 4) * (a - 4) - (b - 7) * (b - 7));
}

int sc_heights_franke(int n, int pad, sc_heights *out)
{
    if (heights_alloc(out, n + 1, n + 1, pad))
        return SC_FAIL;
    out->dx = out->dy = 1.0 / n;
    for (int j = -pad; j <= n + pad; j++)
        for (int i = -pad; i <= n + pad; i++)
            *heights_ref(out, i, j) = sc_franke((double)i / n, (double)j / n);
    return SC_OK;
}

int sc_heights_padded(const sc_heights *in, int pad, sc_heights *out)
{
    sc_heights h;
    if (heights_alloc(&h, in->nx, in->ny, pad)) {
        memset(out, 0, sizeof *out);
        return SC_FAIL;
    }
    h.x0 = in->x0; h.y0 = in->y0; h.dx = in->dx; h.dy = in->dy;
    int nx = in->nx, ny = in->ny;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) *heights_ref(&h, i, j) = sc_heights_at(in, i, j);
    /* Rows first, then whole columns, so that corners are extrapolated in
     * both directions; a mirror index past the far side is clamped. */
    for (int j = 0; j < ny; j++)
        for (int k = 1; k <= pad; k++) {
            int kk = k < nx ? k : nx - 1;
            *heights_ref(&h, -k, j) = 2 * sc_heights_at(&h, 0, j) - sc_heights_at(&h, kk, j);
            *heights_ref(&h, nx - 1 + k, j) =
                2 * sc_heights_at(&h, nx - 1, j) - sc_heights_at(&h, nx - 1 - kk, j);
        }
    for (int i = -pad; i < nx + pad; i++)
        for (int k = 1; k <= pad; k++) {
            int kk = k < ny ? k : ny - 1;
            *heights_ref(&h, i, -k) = 2 * sc_heights_at(&h, i, 0) - sc_heights_at(&h, i, kk);
            *heights_ref(&h, i, ny - 1 + k) =
                2 * sc_heights_at(&h, i, ny - 1) - sc_heights_at(&h, i, ny - 1 - kk);
        }
    *out = h;
    return SC_OK;
}

/* Builds the grid from values read top row first; fails (v freed) when
 * memory runs out. */
static int from_rows(double *v, int w, int hgt, double spacing, double scale, sc_heights *out,
                     const char *path, sc_error *err)
{
    memset(out, 0, sizeof *out);
    out->nx = w; out->ny = hgt;
    if (!(out->z = sc_try_alloc((size_t)w * (size_t)hgt, sizeof *out->z))) {
        free(v);
        memset(out, 0, sizeof *out);
        return sc_fail_oom(err, path, 0, (size_t)w * (size_t)hgt, sizeof *out->z, "the heights");
    }
    out->dx = out->dy = spacing;
    for (int r = 0; r < hgt; r++)
        for (int c = 0; c < w; c++)
            *heights_ref(out, c, hgt - 1 - r) = v[(size_t)r * w + c] * scale;
    free(v);
    return SC_OK;
}

/* PGM header and P2 tokens: skips white space and '#' comments, counting
 * lines; returns the token's start or NULL at the end. */
static const char *pgm_token(const char *p, const char *end, int *line)
{
    while (p < end) {
        if (*p == '#') {
            while (p < end && *p != '\n') p++;
        } else if (isspace((unsigned char)*p)) {
            if (*p == '\n') (*line)++;
            p++;
        } else
            return p;
    }
    return NULL;
}

/* A decimal unsigned integer token (at most 9 digits); NULL when not. */
static const char *pgm_uint(const char *p, const char *end, long *v)
{
    long x = 0;
    int digits = 0;
    while (p < end && isdigit((unsigned char)*p)) {
        if (++digits > 9) return NULL;
        x = x * 10 + (*p++ - '0');
    }
    if (digits == 0 || (p < end && !isspace((unsigned char)*p) && *p != '#')) return NULL;
    *v = x;
    return p;
}

static int read_pgm(const char *path, const char *buf, size_t len, double spacing,
                    double zscale, sc_heights *out, sc_error *err)
{
    const char *end = buf + len, *p = buf + 2;
    int line = 1, binary = buf[1] == '5';
    long hdr[3];
    const char *names[3] = {"width", "height", "maxval"};
    for (int t = 0; t < 3; t++) {
        const char *s = pgm_token(p, end, &line);
        if (!s) return sc_fail(err, path, line, "PGM header ends before its %s", names[t]);
        if (!(p = pgm_uint(s, end, &hdr[t])))
            return sc_fail(err, path, line, "PGM %s is not a number", names[t]);
    }
    long w = hdr[0], h = hdr[1], maxval = hdr[2];
    if (w < 2 || h < 2)
        return sc_fail(err, path, line, "PGM of %ld x %ld: a terrain needs at least 2 x 2 heights",
                       w, h);
    if (maxval < 1 || maxval > 65535)
        return sc_fail(err, path, line, "PGM maxval %ld is not in 1..65535", maxval);
    if ((double)w * (double)h > SC_MAX_HEIGHT_SAMPLES)
        return sc_fail(err, path, line, "PGM of %ld x %ld is larger than the limit of %d "
                       "heights (docs/limits.md)", w, h, SC_MAX_HEIGHT_SAMPLES);
    size_t count = (size_t)w * (size_t)h;
    /* The header is checked against the bytes present before anything is
     * allocated from it: a short file cannot ask for a large grid. */
    size_t bps = maxval > 255 ? 2 : 1;
    if (binary) {
        /* Exactly one white-space byte ends the header. */
        if (p >= end || !isspace((unsigned char)*p))
            return sc_fail(err, path, line, "PGM raster missing after the header");
        p++;
        size_t need = count * bps, have = (size_t)(end - p);
        if (have != need)
            return sc_fail(err, path, line,
                           "PGM raster has %zu bytes, the header's %ld x %ld at %zu byte%s per "
                           "sample needs %zu", have, w, h, bps, bps > 1 ? "s" : "", need);
    } else if ((size_t)(end - p) < 2 * count - 1) {
        /* A plain sample is a digit and a separator at least. */
        return sc_fail(err, path, line, "PGM has %zu bytes after its header, too few for the "
                       "header's %ld x %ld samples", (size_t)(end - p), w, h);
    }
    double *v = sc_try_alloc(count, sizeof *v);
    if (!v)
        return sc_fail_oom(err, path, line, count, sizeof *v, "the PGM's samples");
    double inv = 1.0 / (double)maxval;
    if (binary) {
        const unsigned char *u = (const unsigned char *)p;
        for (size_t k = 0; k < count; k++) {
            long s = bps == 2 ? (long)u[2 * k] << 8 | u[2 * k + 1] : u[k];
            if (s > maxval) {
                free(v);
                return sc_fail(err, path, line, "PGM sample %zu is %ld, above maxval %ld", k, s,
                               maxval);
            }
            v[k] = s * inv;
        }
    } else {
        int last = line;    /* where the file's last sample was */
        for (size_t k = 0; k <= count; k++) {
            const char *s = pgm_token(p, end, &line);
            if (!s) {
                if (k == count) break;
                free(v);
                return sc_fail(err, path, last,
                               "PGM has %zu samples, its header says %ld x %ld = %zu", k, w, h,
                               count);
            }
            if (k == count) {
                free(v);
                return sc_fail(err, path, line,
                               "PGM has more samples than its header's %ld x %ld", w, h);
            }
            long x;
            if (!(p = pgm_uint(s, end, &x))) {
                free(v);
                return sc_fail(err, path, line, "PGM sample is not a non-negative integer");
            }
            if (x > maxval) {
                free(v);
                return sc_fail(err, path, line, "PGM sample %ld is above maxval %ld", x, maxval);
            }
            v[k] = x * inv;
            last = line;
        }
    }
    return from_rows(v, (int)w, (int)h, spacing, zscale, out, path, err);
}

static int read_csv(const char *path, char *buf, size_t len, double spacing, double zscale,
                    sc_heights *out, sc_error *err)
{
    if (memchr(buf, 0, len)) {
        int line = 1;
        for (const char *q = buf; *q; q++) line += *q == '\n';
        return sc_fail(err, path, line, "NUL byte in a CSV file");
    }
    size_t cap = 1024, n = 0;
    double *v = sc_try_alloc(cap, sizeof *v);
    if (!v)
        return sc_fail_oom(err, path, 1, cap, sizeof *v, "the heights");
    long width = -1, rows = 0;
    int line = 0, first_line = 0;
    char *save = NULL;
    for (char *ln = buf; ln; ln = save) {
        line++;
        save = strchr(ln, '\n');
        if (save) {
            *save++ = 0;
            if (!*save) save = NULL;   /* a final newline ends the last line */
        }
        char *s = ln;
        while (*s == ' ' || *s == '\t' || *s == '\r') s++;
        if (*s == 0 || *s == '#') continue;
        long count = 0;
        for (;;) {
            while (*s == ' ' || *s == '\t' || *s == '\r') s++;
            char *e;
            errno = 0;
            double x = strtod(s, &e);
            char *t = e;
            while (*t == ' ' || *t == '\t' || *t == '\r') t++;
            if (e == s || (*t != ',' && *t != 0 && e == t)) {
                free(v);
                return sc_fail(err, path, line, "value %ld is not a number", count + 1);
            }
            if (!isfinite(x)) {
                free(v);
                return sc_fail(err, path, line, "value %ld is not finite", count + 1);
            }
            if (n == (size_t)SC_MAX_HEIGHT_SAMPLES) {
                free(v);
                return sc_fail(err, path, line, "more than the limit of %d heights "
                               "(docs/limits.md)", SC_MAX_HEIGHT_SAMPLES);
            }
            if (n == cap) {
                double *grown = sc_try_realloc(v, cap * 2, sizeof *v);
                if (!grown) {
                    free(v);
                    return sc_fail_oom(err, path, line, cap * 2, sizeof *v, "the heights");
                }
                v = grown;
                cap *= 2;
            }
            v[n++] = x;
            count++;
            if (*t == ',') t++;
            s = t;
            while (*s == ' ' || *s == '\t' || *s == '\r') s++;
            if (*s == 0) break;
        }
        if (width < 0) {
            width = count;
            first_line = line;
        } else if (count != width) {
            free(v);
            return sc_fail(err, path, line, "row has %ld values, the first row (line %d) has %ld",
                           count, first_line, width);
        }
        rows++;
    }
    if (rows == 0) {
        free(v);
        return sc_fail(err, path, line > 0 ? line : 1, "no heights in the file");
    }
    if (width < 2 || rows < 2) {
        free(v);
        return sc_fail(err, path, line, "%ld x %ld heights: a terrain needs at least 2 x 2",
                       width, rows);
    }
    return from_rows(v, (int)width, (int)rows, spacing, zscale, out, path, err);
}

int sc_heights_parse(char *data, size_t len, const char *name, double spacing, double zscale,
                     sc_heights *out, sc_error *err)
{
    memset(out, 0, sizeof *out);
    if (!(spacing > 0) || !isfinite(spacing) || !isfinite(zscale))
        return sc_fail(err, name, 0, "grid spacing must be positive and finite, height scale "
                       "finite");
    if (len >= 2 && data[0] == 'P' && (data[1] == '2' || data[1] == '5'))
        return read_pgm(name, data, len, spacing, zscale, out, err);
    if (len == 0)
        return sc_fail(err, name, 1, "empty file: no heights");
    return read_csv(name, data, len, spacing, zscale, out, err);
}

int sc_heights_read(const char *path, double spacing, double zscale, sc_heights *out,
                    sc_error *err)
{
    memset(out, 0, sizeof *out);
    char *data;
    size_t len;
    if (sc_read_file_max(path, SC_MAX_HEIGHT_FILE_BYTES, 0, &data, &len, err) != SC_OK)
        return SC_FAIL;
    int rc = sc_heights_parse(data, len, path, spacing, zscale, out, err);
    free(data);
    return rc;
}
