/* heights.h — gridded height data for the terrain splines: read from a PGM
 * image (P2/P5, 8 or 16 bits) or a CSV of rows, or sampled from Franke's
 * test function (seed 004, Table I). Bad input is refused with
 * "file:line: what is wrong" and nothing half-built. */
#ifndef SC_HEIGHTS_H
#define SC_HEIGHTS_H

#include "sc_base.h"

/* nx x ny samples of a uniform grid; sample (i, j) lies at
 * (x0 + i dx, y0 + j dy). Around them lie `pad` more samples on every side
 * (i, j from -pad to n - 1 + pad), which the smooth schemes need next to
 * the boundary (the paper's "additional values covering one layer of
 * patches"). */
typedef struct sc_heights {
    int nx, ny, pad;
    double x0, y0, dx, dy;
    double *z;            /* (nx + 2 pad) * (ny + 2 pad), rows of rising y */
} sc_heights;

/* The height of sample (i, j), -pad <= i < nx + pad (likewise j). */
static inline double sc_heights_at(const sc_heights *h, int i, int j)
{
    return h->z[(size_t)(j + h->pad) * (size_t)(h->nx + 2 * h->pad) + (size_t)(i + h->pad)];
}

/* Reads a PGM (P2 or P5; maxval 1..65535, 16-bit P5 big-endian) or a CSV
 * (rows of numbers separated by commas, spaces or tabs; blank lines and
 * lines starting with '#' skipped), chosen by the file's first bytes ("P2"
 * / "P5" is a PGM). Both are read as images: the first row is the top of
 * the terrain (largest y). Sample spacing `spacing` in x and y, heights
 * multiplied by `zscale` (a PGM's gray levels divided by maxval first, so
 * that 8- and 16-bit files of one terrain agree). The grid starts at
 * (0, 0), with pad 0. */
int sc_heights_read(const char *path, double spacing, double zscale, sc_heights *out,
                    sc_error *err);
/* The same from memory (`data` NUL-terminated at data[len], and changed:
 * CSV lines are cut in place); `name` names the input in errors. */
int sc_heights_parse(char *data, size_t len, const char *name, double spacing, double zscale,
                     sc_heights *out, sc_error *err);

/* Franke's test function on [0,1]^2 (its maximum is about 1.22). */
double sc_franke(double x, double y);

/* Franke's function sampled at (n + 1)^2 points i/n, j/n, i, j = 0..n, and
 * `pad` more on every side (outside [0,1]^2, where the function is still
 * defined). */
int sc_heights_franke(int n, int pad, sc_heights *out);

/* Both return SC_FAIL (*out empty) when memory runs out. */
/* A copy of `in` (any pad) with pad `pad`: samples beyond the data are
 * extrapolated linearly from the boundary (2 z(0) - z(k)), which keeps
 * linear data linear. */
int sc_heights_padded(const sc_heights *in, int pad, sc_heights *out);

void sc_heights_free(sc_heights *h);

#endif
