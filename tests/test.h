/* test.h — the test framework: TEST(name) defines a test, found by the
 * Makefile (every line starting with "TEST(" in any file of tests/ goes into one
 * generated list), run by tests/main.c. Assertions print file, line, the
 * expression and both values, mark the test failed and return from it. */
#ifndef SC_TEST_H
#define SC_TEST_H

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "sc_base.h"

extern int test_failed_flag;
/* Folder of the shared test data (../shared/data), and of the project root;
 * set from the environment or defaulted by main.c. */
extern const char *test_data_dir;
extern const char *test_root_dir;
/* Path of the splinecast command under test (for end-to-end tests). */
extern const char *test_cli;

#define TEST(name) void test_##name(void)

#define TEST_FAIL_(...)                                                        \
    do {                                                                       \
        fprintf(stderr, "  %s:%d: ", __FILE__, __LINE__);                      \
        fprintf(stderr, __VA_ARGS__);                                          \
        fprintf(stderr, "\n");                                                 \
        test_failed_flag = 1;                                                  \
    } while (0)

#define CHECK(expr)                                                            \
    do {                                                                       \
        if (!(expr)) {                                                         \
            TEST_FAIL_("CHECK(%s) failed", #expr);                             \
            return;                                                            \
        }                                                                      \
    } while (0)

#define CHECK_INT(a, b)                                                        \
    do {                                                                       \
        long long a_ = (long long)(a), b_ = (long long)(b);                    \
        if (a_ != b_) {                                                        \
            TEST_FAIL_("CHECK_INT(%s, %s): %lld != %lld", #a, #b, a_, b_);     \
            return;                                                            \
        }                                                                      \
    } while (0)

#define CHECK_NEAR(a, b, tol)                                                  \
    do {                                                                       \
        double a_ = (double)(a), b_ = (double)(b), t_ = (double)(tol);         \
        if (!(fabs(a_ - b_) <= t_)) {                                          \
            TEST_FAIL_("CHECK_NEAR(%s, %s, %s): %.17g vs %.17g (diff %.3g)",   \
                       #a, #b, #tol, a_, b_, fabs(a_ - b_));                   \
            return;                                                            \
        }                                                                      \
    } while (0)

#define CHECK_STR(a, b)                                                        \
    do {                                                                       \
        const char *a_ = (a), *b_ = (b);                                       \
        if (!a_ || !b_ || strcmp(a_, b_) != 0) {                               \
            TEST_FAIL_("CHECK_STR(%s, %s): \"%s\" != \"%s\"", #a, #b,          \
                       a_ ? a_ : "(null)", b_ ? b_ : "(null)");                \
            return;                                                            \
        }                                                                      \
    } while (0)

/* True when haystack contains needle. */
#define CHECK_CONTAINS(hay, needle)                                            \
    do {                                                                       \
        const char *h_ = (hay), *n_ = (needle);                                \
        if (!h_ || !strstr(h_, n_)) {                                          \
            TEST_FAIL_("CHECK_CONTAINS(%s, %s): \"%s\" not in \"%s\"", #hay,   \
                       #needle, n_, h_ ? h_ : "(null)");                       \
            return;                                                            \
        }                                                                      \
    } while (0)

/* Marks the running test skipped and returns; the reason is printed on its
 * `skip` line, so that no test skips silently. */
#define SKIP(...)                                                              \
    do {                                                                       \
        snprintf(test_skip_reason, sizeof test_skip_reason, __VA_ARGS__);      \
        test_skipped_flag = 1;                                                 \
        return;                                                                \
    } while (0)
extern int test_skipped_flag;
extern char test_skip_reason[1024];

/* Skips the running test when a shared model it needs is not there. */
#define REQUIRE_DATA(rel)                                                      \
    do {                                                                       \
        if (access(test_data(rel), R_OK) != 0)                                 \
            SKIP("%s: not found (set SC_DATA to the shared models' folder)", test_data(rel)); \
    } while (0)

/* Helpers (tests/util.c). */
/* Runs a shell command, captures stdout and stderr (each malloc'd, may be
 * NULL pointers to ignore) and returns the exit status (or -1). */
int test_run(const char *cmd, char **out, char **err);
/* A fresh temporary directory for this test run (same for all tests). */
const char *test_tmpdir(void);
/* "data_dir/rel" into a static rotating buffer: the shared models
 * (SC_DATA, default ../shared/data), which a checkout need not have. */
const char *test_data(const char *rel);
/* "root_dir/rel": a file of this repository (static rotating buffer). */
const char *test_root(const char *rel);
/* The teapot's 32 patches, shipped in the repository (the same bytes as the
 * tea set's teapot32.bpt). */
#define TEST_TEAPOT32 test_root("examples/scenes/teapot32.bpt")
/* Writes text to tmpdir/name and returns the path (static rotating buffer). */
const char *test_write_tmp(const char *name, const char *text);
/* The whole file, NUL-terminated and malloc'd; NULL when it cannot be read. */
char *test_read_file(const char *path);
/* Deterministic random numbers in [0, 1). */
double test_rand(unsigned long long *state);

/* Warnings (and errors) gathered through the library's logger:
 * sc_set_logger(test_gather_warnings, &w) with a zeroed test_warnings. */
typedef struct test_warnings {
    int count;
    char text[8192];    /* the messages, one per line (cut when full) */
} test_warnings;
void test_gather_warnings(sc_log_level level, const char *message, void *user);

#endif
