/* iges_files.c — small IGES files for the IGES reader's tests
 * (iges_files.h). */
#include "iges_files.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

/* Warnings go to a buffer so that tests can check them and stay quiet. */
char iges_warnings[4096];
static void capture(sc_log_level level, const char *msg, void *user)
{
    (void)user;
    if (level >= SC_LOG_WARN && strlen(iges_warnings) + strlen(msg) + 2 < sizeof iges_warnings) {
        strcat(iges_warnings, msg);
        strcat(iges_warnings, "\n");
    }
}

int iges_read_path(const char *path, sc_scene *scene, sc_error *err)
{
    iges_warnings[0] = 0;
    sc_set_logger(capture, NULL);
    int status = sc_read_scene(path, scene, err);
    sc_set_logger(NULL, NULL);
    return status;
}

int iges_read_text(const char *text, sc_scene *scene, sc_error *err)
{
    iges_warnings[0] = 0;
    memset(err, 0, sizeof *err);
    sc_set_logger(capture, NULL);
    int status = sc_read_iges(text, strlen(text), "t.igs", scene, err);
    sc_set_logger(NULL, NULL);
    return status;
}

const char *iges_error_text(const sc_error *err)
{
    static char buf[1024];
    return sc_error_text(err, buf, sizeof buf);
}

int iges_skipped_count(const sc_scene *s, const char *type, const char *reason)
{
    for (int i = 0; i < s->nskipped; i++)
        if (!strcmp(s->skipped[i].type, type) && !strcmp(s->skipped[i].reason, reason))
            return s->skipped[i].count;
    return 0;
}

/* ---- writing small IGES files ---- */

static void append(char **buf, size_t *len, const char *text72, char section, int seq)
{
    char record[96];
    snprintf(record, sizeof record, "%-72.72s%c%7d\n", text72, section, seq % 10000000);
    /* The buffer holds a power of two of at least 1024 bytes, doubled when
     * full, so that files of thousands of records are written in linear time. */
    size_t have = 1024, need = 1024;
    while (have < *len + 1)
        have *= 2;
    while (need < *len + 82)
        need *= 2;
    if (!*buf || need > have)
        *buf = realloc(*buf, need);
    memcpy(*buf + *len, record, 82); /* 81 characters and the NUL */
    *len += 81;
}

/* A fixed-format file: one S, one G record, two D records per entity, the
 * parameters cut into 64-column P records. Entity k has DE 2k+1; its first
 * P record is at line 3 + 2n + (P records before it). */
char *iges_make_iges(const spec *e, int n)
{
    char *buf = NULL, line[128];
    size_t len = 0;
    append(&buf, &len, "splinecast test file", 'S', 1);
    append(&buf, &len, "1H,,1H;,4Htest,5Ht.igs,;", 'G', 1);
    int pline = 1, *first = calloc((size_t)n, sizeof(int)), *count = calloc((size_t)n, sizeof(int));
    for (int k = 0; k < n; k++) {
        first[k] = pline;
        count[k] = ((int)strlen(e[k].params) + 63) / 64;
        pline += count[k];
    }
    for (int k = 0; k < n; k++) {
        snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8d%8d%8d%8s", e[k].type, first[k], 0, 0, 0,
                 0, e[k].xform, 0, "00000000");
        append(&buf, &len, line, 'D', 2 * k + 1);
        snprintf(line, sizeof line, "%8d%8d%8d%8d%8d%8s%8s%8s%8d", e[k].type, 0, e[k].color,
                 count[k], 0, "", "", e[k].label ? e[k].label : "", 0);
        append(&buf, &len, line, 'D', 2 * k + 2);
    }
    int seq = 1;
    for (int k = 0; k < n; k++) {
        const char *p = e[k].params;
        for (int c = 0; c < count[k]; c++) {
            snprintf(line, sizeof line, "%-64.64s%8d", p + 64 * c, 2 * k + 1);
            append(&buf, &len, line, 'P', seq++);
        }
    }
    snprintf(line, sizeof line, "S%7dG%7dD%7dP%7d", 1, 1, 2 * n, seq - 1);
    append(&buf, &len, line, 'T', 1);
    free(first);
    free(count);
    return buf;
}

/* Reads the file make_iges writes for `e`; prints the error on failure. */
int iges_read_specs(const spec *e, int n, sc_scene *scene)
{
    char *text = iges_make_iges(e, n);
    sc_error err;
    int status = iges_read_text(text, scene, &err);
    free(text);
    if (status)
        fprintf(stderr, "  %s\n", iges_error_text(&err));
    return status;
}

/* "t.igs:N:" for the line of the file holding `needle`. */
const char *iges_position_of(const char *text, const char *needle)
{
    static char buf[32];
    const char *at = strstr(text, needle);
    int line = 1;
    for (const char *c = text; at && c < at; c++)
        line += *c == '\n';
    snprintf(buf, sizeof buf, "t.igs:%d:", at ? line : -1);
    return buf;
}

/* The plane (u, v, 0) over [0, size]^2, bilinear. */
char *iges_plane_params(double size)
{
    static char buf[8][256];
    static int next;
    char *b = buf[next++ % 8];
    snprintf(b, 256, "128,1,1,1,1,0,0,1,0,0,0.,0.,%g,%g,0.,0.,%g,%g,1.,1.,1.,1.,"
             "0.,0.,0.,%g,0.,0.,0.,%g,0.,%g,%g,0.,0.,%g,0.,%g;", size, size, size, size, size,
             size, size, size, size, size);
    return b;
}

void iges_eval2(const sc_curve *c, double t, double p[2]) { sc_curve_eval(c, t, p, NULL); }
