/* sc_base.h — what every part of libsplinecast shares: the error record that
 * library functions fill instead of exiting, the one logger, and checked
 * allocation. Only the command line decides to exit. */
#ifndef SC_BASE_H
#define SC_BASE_H

#include <stddef.h>
#include <stdio.h>
#include <stdarg.h>

/* SC_OK / SC_FAIL, the error record sc_error, sc_error_text and the logger
 * are part of the public interface: defined once, there. */
#include "splinecast_base.h"

/* Record a failure in `err` (which may be NULL) and return SC_FAIL.
 * `file` may be NULL and `line` 0 when there is no input position. The
 * key is cleared, so that a reused record never names a stale key. */
int sc_fail(sc_error *err, const char *file, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* sc_fail with a va_list, for readers' own fail helpers. */
int sc_vfail(sc_error *err, const char *file, int line, const char *fmt, va_list ap)
    __attribute__((format(printf, 4, 0)));
/* A failure about the generated program of variant key `key` (no input
 * position): sc_error_text then gives "key KEY: message". */
int sc_fail_key(sc_error *err, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* Emits a message through the logger (sc_set_logger). */
void sc_log(sc_log_level level, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Allocation that aborts with a message on exhaustion: the library never
 * continues with a NULL it did not expect. Sizes are checked for overflow. */
void *sc_alloc(size_t count, size_t size);          /* zeroed */
void *sc_realloc(void *ptr, size_t count, size_t size);

/* Allocation that may fail: for every size that comes from the input (a
 * file, a header, a count of the API's caller), so that memory that is not
 * there is an error, not an abort. They return NULL on exhaustion or on an
 * overflowing count (sc_try_realloc leaves `ptr` as it was). sc_alloc and
 * sc_realloc remain for small fixed sizes (handles, records of a few
 * hundred bytes), whose failure leaves nothing sensible to report. */
void *sc_try_alloc(size_t count, size_t size);          /* zeroed */
void *sc_try_realloc(void *ptr, size_t count, size_t size);
/* Records "out of memory: N bytes for WHAT" at file:line and returns
 * SC_FAIL: the error a failed sc_try_alloc becomes. */
int sc_fail_oom(sc_error *err, const char *file, int line, size_t count, size_t size,
                const char *what);
/* For tests: makes the `n`th sc_try_alloc / sc_try_realloc from now fail
 * (1: the next one; 0: none), so that every failure path can be driven.
 * Returns how many tries have been made since the last call. The
 * environment variable SC_ALLOC_FAIL=N does the same from the start of a
 * process (the command line's tests). */
long sc_alloc_fail_at(long n);
/* For tests: the largest sc_alloc / sc_realloc (in bytes) since
 * sc_alloc_fail_at was last called, so that a test can check that a read
 * left only small fixed allocations to the aborting form. */
size_t sc_alloc_aborting_max(void);
/* The bytes the calling thread's latest failed sc_try_alloc / sc_try_realloc
 * asked for: what a caller reports when the failure happened deep inside
 * an operation that only says that it failed. */
size_t sc_alloc_failed_bytes(void);

/* Whole file into memory (NUL-terminated, the NUL not counted in *size),
 * at most `max` bytes, checked as the data arrives (a device or a pipe can
 * be endless); with `regular_only` anything but a regular file is refused
 * before reading. Fails with a message naming the file. */
int sc_read_file_max(const char *path, size_t max, int regular_only, char **data, size_t *size,
                     sc_error *err);

/* Output files that never appear half-written: sc_out_open writes to a
 * temporary file beside `path`, with the permissions a plain fopen would
 * give (not mkstemp's private ones). sc_out_commit closes it, checks that
 * every write succeeded and renames it into place. Several files that must
 * appear together are closed first (sc_out_close) and renamed afterwards
 * (sc_out_rename). Any failure removes the temporary file;
 * sc_out_abandon removes it on purpose. */
typedef struct sc_out_file {
    FILE *f;
    char path[1024];
    char tmp[1040];
} sc_out_file;
int sc_out_open(sc_out_file *out, const char *path, sc_error *err);
int sc_out_close(sc_out_file *out, sc_error *err);
int sc_out_rename(sc_out_file *out, sc_error *err);
int sc_out_commit(sc_out_file *out, sc_error *err);
void sc_out_abandon(sc_out_file *out);

#endif
