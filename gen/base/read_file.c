/* read_file.c — whole input files into memory with a cap (sc_base.h):
 * the scene readers and the height-grid reader share it, so every file the
 * library reads is bounded the same way. */
#include "sc_base.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int sc_read_file_max(const char *path, size_t max, int regular_only, char **data, size_t *size,
                     sc_error *err)
{
    *data = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return sc_fail(err, path, 0, "cannot open: %s", strerror(errno));
    /* The size is known before reading for a regular file; a device or a
     * pipe can be endless, so the cap is also checked as the data arrives. */
    struct stat st;
    int regular = fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode);
    if (regular_only && !regular) {
        fclose(f);
        return sc_fail(err, path, 0, "not a regular file (a device or a pipe is not read)");
    }
    if (regular && (unsigned long long)st.st_size > max) {
        fclose(f);
        return sc_fail(err, path, 0, "larger than the limit (at most %zu MiB are read; "
                       "docs/limits.md)", max >> 20);
    }
    size_t cap = regular ? (size_t)st.st_size + 2 : (size_t)1 << 16, n = 0;
    char *buf = sc_try_alloc(cap, 1);
    while (buf && n <= max) {
        if (cap - n < 2) {
            size_t grow = cap < max / 2 ? 2 * cap : max + 2;
            char *grown = sc_try_realloc(buf, grow, 1);
            if (!grown)
                free(buf);
            buf = grown;
            cap = grow;
            continue;
        }
        /* One byte past the cap tells that there is more. */
        size_t want = cap - n - 1 < max + 1 - n ? cap - n - 1 : max + 1 - n;
        size_t got = fread(buf + n, 1, want, f);
        n += got;
        if (got == 0)
            break;
    }
    int failed = ferror(f), saved = errno;
    fclose(f);
    if (!buf || n > max || failed) {
        const char *why = !buf ? "out of memory reading it" : "larger than the limit";
        free(buf);
        if (failed)
            return sc_fail(err, path, 0, "cannot read: %s", strerror(saved));
        return sc_fail(err, path, 0, "%s (at most %zu MiB are read; docs/limits.md)", why,
                       max >> 20);
    }
    buf[n] = 0;
    *data = buf;
    *size = n;
    return SC_OK;
}
