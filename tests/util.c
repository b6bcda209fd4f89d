/* util.c — helpers shared by the tests: running the command line and
 * capturing its output, temporary files, deterministic random numbers. */
#define _POSIX_C_SOURCE 200809L
#include "test.h"

#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sc_base.h"

char *test_read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    size_t got;
    while ((got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (cap - n - 1 == 0)
            buf = realloc(buf, cap *= 2);
    }
    buf[n] = 0;
    fclose(f);
    return buf;
}

const char *test_tmpdir(void)
{
    static char dir[256];
    if (!dir[0]) {
        const char *base = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
        snprintf(dir, sizeof dir, "%s/sctest.XXXXXX", base);
        if (!mkdtemp(dir)) {
            perror("mkdtemp");
            exit(2);
        }
    }
    return dir;
}

int test_run(const char *cmd, char **out, char **err)
{
    static int counter;
    char outp[512], errp[512], full[4096];
    snprintf(outp, sizeof outp, "%s/run%d.out", test_tmpdir(), counter);
    snprintf(errp, sizeof errp, "%s/run%d.err", test_tmpdir(), counter++);
    snprintf(full, sizeof full, "%s >%s 2>%s </dev/null", cmd, outp, errp);
    int status = system(full);
    if (out)
        *out = test_read_file(outp);
    if (err)
        *err = test_read_file(errp);
    if (status == -1 || !WIFEXITED(status))
        return -1;
    return WEXITSTATUS(status);
}

static const char *rotate(void)
{
    static char bufs[8][1024];
    static int next;
    return bufs[next++ % 8];
}

const char *test_data(const char *rel)
{
    char *b = (char *)rotate();
    snprintf(b, 1024, "%s/%s", test_data_dir, rel);
    return b;
}

const char *test_root(const char *rel)
{
    char *b = (char *)rotate();
    snprintf(b, 1024, "%s/%s", test_root_dir, rel);
    return b;
}

const char *test_write_tmp(const char *name, const char *text)
{
    char *b = (char *)rotate();
    snprintf(b, 1024, "%s/%s", test_tmpdir(), name);
    FILE *f = fopen(b, "wb");
    if (!f) {
        perror(b);
        exit(2);
    }
    fputs(text, f);
    fclose(f);
    return b;
}

double test_rand(unsigned long long *state)
{
    /* splitmix64: small, good enough, the same on every machine. */
    unsigned long long z = (*state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

void test_gather_warnings(sc_log_level level, const char *message, void *user)
{
    test_warnings *w = user;
    if (level < SC_LOG_WARN)
        return;
    w->count++;
    size_t used = strlen(w->text);
    snprintf(w->text + used, sizeof w->text - used, "%s\n", message);
}
