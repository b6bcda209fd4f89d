/* main.c — runs the tests listed in the generated tests_list.h (one line
 * X(name) per TEST in the files of tests/), in order, or only those whose names
 * contain one of the command-line arguments. Last line: N passed, N failed.
 * SC_CLI overrides the command line under test (by default the splinecast
 * beside run_tests). */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>
#include <unistd.h>

#include "sc_base.h"

int test_failed_flag;
int test_skipped_flag;
char test_skip_reason[1024];
const char *test_data_dir;
const char *test_root_dir;
const char *test_cli;

#define X(name) void test_##name(void);
#include "tests_list.h"
#undef X

static const struct {
    const char *name;
    void (*fn)(void);
} tests[] = {
#define X(name) {#name, test_##name},
#include "tests_list.h"
#undef X
};

static int selected(const char *name, int argc, char **argv)
{
    if (argc <= 1)
        return 1;
    for (int i = 1; i < argc; i++)
        if (strstr(name, argv[i]))
            return 1;
    return 0;
}

/* The splinecast built with this run_tests sits in the same folder, so a
 * test run from any build folder checks its own command line. */
static const char *cli_beside_self(const char *argv0)
{
    static char path[4096 + sizeof "splinecast"];
    char self[4096];
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n > 0)
        self[n] = 0;
    else
        snprintf(self, sizeof self, "%s", argv0);
    char *slash = strrchr(self, '/');
    if (!slash) /* found through PATH: so is splinecast */
        return "splinecast";
    slash[1] = 0;
    snprintf(path, sizeof path, "%ssplinecast", self);
    return path;
}

int main(int argc, char **argv)
{
    test_root_dir = getenv("SC_ROOT") ? getenv("SC_ROOT") : ".";
    test_data_dir = getenv("SC_DATA") ? getenv("SC_DATA") : "../shared/data";
    test_cli = getenv("SC_CLI") ? getenv("SC_CLI") : cli_beside_self(argv[0]);
    int passed = 0, failed = 0, skipped = 0;
    for (size_t i = 0; i < sizeof tests / sizeof tests[0]; i++) {
        if (!selected(tests[i].name, argc, argv))
            continue;
        test_failed_flag = 0;
        test_skipped_flag = 0;
        test_skip_reason[0] = 0;
        double t0 = sc_now();
        tests[i].fn();
        double dt = sc_now() - t0;
        if (test_failed_flag) {
            failed++;
            printf("FAIL %s (%.2f s)\n", tests[i].name, dt);
        } else if (test_skipped_flag) {
            skipped++;
            printf("skip %s: %s\n", tests[i].name, test_skip_reason);
        } else {
            passed++;
            printf("ok   %s (%.2f s)\n", tests[i].name, dt);
        }
        fflush(stdout);
    }
    if (skipped)
        printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    else
        printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
