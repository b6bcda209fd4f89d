/* splinecast_base.h — the part of the public interface that the compiler
 * and the runtime share: status codes, the error record that library
 * functions fill instead of exiting, and the one logger. It knows nothing
 * of scenes, so that gen/ can use it without the runtime; splinecast.h
 * includes it, and `make install` installs it beside splinecast.h. */
#ifndef SPLINECAST_BASE_H
#define SPLINECAST_BASE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- status, errors, logging ---------------------------------------- */

/* Status codes returned by library functions. */
enum { SC_OK = 0, SC_FAIL = -1 };

/* Filled by a failing call. `file`/`line` name the input position (a scene
 * file and its line) when the failure is about input; `key` names the
 * variant key when it is about a generated program. */
typedef struct sc_error {
    char message[512];
    char file[256];
    int line;
    char key[128];
} sc_error;

/* "file:line: message", "key KEY: message" or just the message, into buf. */
const char *sc_error_text(const sc_error *err, char *buf, size_t size);

/* Log levels, lowest first. */
typedef enum sc_log_level {
    SC_LOG_DEBUG = 0,
    SC_LOG_INFO,
    SC_LOG_WARN,
    SC_LOG_ERROR
} sc_log_level;

typedef void (*sc_logger_fn)(sc_log_level level, const char *message, void *user);

/* The library's single logger. The default writes warnings and errors to
 * stderr, prefixed "splinecast: warning: " etc.; a logger set here gets
 * every message, whatever its level. NULL restores the default. */
void sc_set_logger(sc_logger_fn fn, void *user);
/* Messages below `level` are dropped by the default logger (default WARN). */
void sc_set_log_level(sc_log_level level);

/* A monotonic clock in seconds: the one the library's timings (render_ms,
 * compile_ms, …) are taken with, for a program's own timings beside them. */
double sc_now(void);

/* Writes `size` bytes to path through a temporary file beside it, renamed
 * into place: the file appears whole or not at all. */
int sc_save_text(const char *path, const char *text, size_t size, sc_error *err);

#ifdef __cplusplus
}
#endif

#endif
