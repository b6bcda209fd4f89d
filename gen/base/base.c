/* base.c — error records, the logger and checked allocation (sc_base.h). */
#define _POSIX_C_SOURCE 200809L
#include "sc_base.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

int sc_vfail(sc_error *err, const char *file, int line, const char *fmt, va_list ap)
{
    if (!err)
        return SC_FAIL;
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    err->line = line;
    err->key[0] = 0;
    return SC_FAIL;
}

int sc_fail(sc_error *err, const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int status = sc_vfail(err, file, line, fmt, ap);
    va_end(ap);
    return status;
}

int sc_fail_key(sc_error *err, const char *key, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    sc_vfail(err, NULL, 0, fmt, ap);
    va_end(ap);
    if (err)
        snprintf(err->key, sizeof err->key, "%.*s", (int)sizeof err->key - 1, key ? key : "");
    return SC_FAIL;
}

const char *sc_error_text(const sc_error *err, char *buf, size_t size)
{
    if (err->file[0] && err->line > 0)
        snprintf(buf, size, "%s:%d: %s", err->file, err->line, err->message);
    else if (err->file[0])
        snprintf(buf, size, "%s: %s", err->file, err->message);
    else if (err->key[0])
        snprintf(buf, size, "key %s: %s", err->key, err->message);
    else
        snprintf(buf, size, "%s", err->message);
    return buf;
}

static sc_log_level log_threshold = SC_LOG_WARN;
static sc_logger_fn log_fn;
static void *log_user;

void sc_set_logger(sc_logger_fn fn, void *user)
{
    log_fn = fn;
    log_user = user;
}

void sc_set_log_level(sc_log_level level) { log_threshold = level; }

void sc_log(sc_log_level level, const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (log_fn) {
        log_fn(level, msg, log_user);
        return;
    }
    if (level < log_threshold)
        return;
    static const char *const names[] = {"debug", "info", "warning", "error"};
    fprintf(stderr, "splinecast: %s: %s\n", names[level], msg);
}

static void out_of_memory(size_t count, size_t size)
{
    fprintf(stderr, "splinecast: out of memory (%zu x %zu bytes)\n", count, size);
    abort();
}

/* The largest aborting allocation since sc_alloc_fail_at was last called
 * (sc_alloc_aborting_max). */
static size_t aborting_max;

static void note_aborting(size_t count, size_t size)
{
    size_t bytes = count > SIZE_MAX / size ? SIZE_MAX : count * size;
    size_t seen = __atomic_load_n(&aborting_max, __ATOMIC_RELAXED);
    while (bytes > seen &&
           !__atomic_compare_exchange_n(&aborting_max, &seen, bytes, 1, __ATOMIC_RELAXED,
                                        __ATOMIC_RELAXED))
        ;
}

void *sc_alloc(size_t count, size_t size)
{
    if (count == 0 || size == 0)
        count = size = 1;
    note_aborting(count, size);
    void *p = calloc(count, size);
    if (!p)
        out_of_memory(count, size);
    return p;
}

void *sc_realloc(void *ptr, size_t count, size_t size)
{
    if (count == 0 || size == 0)
        count = size = 1;
    note_aborting(count, size);
    if (count > SIZE_MAX / size)
        out_of_memory(count, size);
    void *p = realloc(ptr, count * size);
    if (!p)
        out_of_memory(count, size);
    return p;
}

/* The failure injection of sc_alloc_fail_at: tries made since the counter
 * was set, and the try that fails (0: none). Read from SC_ALLOC_FAIL once. */
static long try_count, try_fail_at = -1;

static int try_fails(void)
{
    if (try_fail_at < 0) {
        const char *env = getenv("SC_ALLOC_FAIL");
        try_fail_at = env ? strtol(env, NULL, 10) : 0;
        if (try_fail_at < 0)
            try_fail_at = 0;
    }
    /* Readers may run on several threads at once (the API is called from
     * any thread): the counter is atomic. */
    return __atomic_add_fetch(&try_count, 1, __ATOMIC_RELAXED) == try_fail_at;
}

long sc_alloc_fail_at(long n)
{
    __atomic_store_n(&aborting_max, 0, __ATOMIC_RELAXED);
    long made = __atomic_exchange_n(&try_count, 0, __ATOMIC_RELAXED);
    try_fail_at = n > 0 ? n : 0;
    return made;
}

/* The size of this thread's latest failed try, for messages from code that
 * did not make the allocation itself (sc_alloc_failed_bytes). */
static _Thread_local size_t failed_bytes;

static void *failed(size_t count, size_t size)
{
    failed_bytes = count > SIZE_MAX / size ? SIZE_MAX : count * size;
    return NULL;
}

void *sc_try_alloc(size_t count, size_t size)
{
    if (count == 0 || size == 0)
        count = size = 1;
    if (try_fails() || count > SIZE_MAX / size)
        return failed(count, size);
    void *p = calloc(count, size);
    return p ? p : failed(count, size);
}

void *sc_try_realloc(void *ptr, size_t count, size_t size)
{
    if (count == 0 || size == 0)
        count = size = 1;
    if (try_fails() || count > SIZE_MAX / size)
        return failed(count, size);
    void *p = realloc(ptr, count * size);
    return p ? p : failed(count, size);
}

size_t sc_alloc_failed_bytes(void) { return failed_bytes; }

size_t sc_alloc_aborting_max(void) { return __atomic_load_n(&aborting_max, __ATOMIC_RELAXED); }

int sc_fail_oom(sc_error *err, const char *file, int line, size_t count, size_t size,
                const char *what)
{
    if (size && count > SIZE_MAX / size)
        return sc_fail(err, file, line, "out of memory: %zu x %zu bytes for %s", count, size,
                       what);
    return sc_fail(err, file, line, "out of memory: %zu bytes for %s", count * size, what);
}

double sc_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int sc_out_open(sc_out_file *out, const char *path, sc_error *err)
{
    memset(out, 0, sizeof *out);
    if (strlen(path) >= sizeof out->path)
        return sc_fail(err, path, 0, "output path is too long");
    snprintf(out->path, sizeof out->path, "%s", path);
    snprintf(out->tmp, sizeof out->tmp, "%s.tmpXXXXXX", path);
    int fd = mkstemp(out->tmp);
    if (fd < 0)
        return sc_fail(err, path, 0, "cannot create a temporary file beside it: %s",
                       strerror(errno));
    mode_t mask = umask(0);
    umask(mask);
    fchmod(fd, 0666 & ~mask);
    out->f = fdopen(fd, "wb");
    if (!out->f) {
        int saved = errno;
        close(fd);
        unlink(out->tmp);
        return sc_fail(err, path, 0, "cannot write: %s", strerror(saved));
    }
    return SC_OK;
}

int sc_out_close(sc_out_file *out, sc_error *err)
{
    int failed = ferror(out->f);
    int saved = errno;
    if (fclose(out->f) != 0 && !failed) {
        failed = 1;
        saved = errno;
    }
    out->f = NULL;
    if (failed) {
        unlink(out->tmp);
        return sc_fail(err, out->path, 0, "writing failed: %s", strerror(saved));
    }
    return SC_OK;
}

int sc_out_rename(sc_out_file *out, sc_error *err)
{
    if (rename(out->tmp, out->path) != 0) {
        int saved = errno;
        unlink(out->tmp);
        return sc_fail(err, out->path, 0, "cannot move the finished file into place: %s",
                       strerror(saved));
    }
    return SC_OK;
}

int sc_out_commit(sc_out_file *out, sc_error *err)
{
    if (sc_out_close(out, err))
        return SC_FAIL;
    return sc_out_rename(out, err);
}

void sc_out_abandon(sc_out_file *out)
{
    if (out->f)
        fclose(out->f);
    out->f = NULL;
    unlink(out->tmp);
}

int sc_save_text(const char *path, const char *text, size_t size, sc_error *err)
{
    sc_out_file out;
    if (sc_out_open(&out, path, err))
        return SC_FAIL;
    if (fwrite(text, 1, size, out.f) != size) {
        sc_out_abandon(&out);
        return sc_fail(err, path, 0, "writing failed (disk full?)");
    }
    return sc_out_commit(&out, err);
}
