/* step_isolate.c — Open CASCADE runs in a child process. The library is
 * not built for hostile input: a reference of the wrong entity type in a
 * well-formed file makes it dereference a null handle (found by
 * fuzz_step), which no exception handler catches. So the transfer and our
 * conversion run in a forked child, with an address-space limit, while
 * the parent waits with the time cap; the child sends the finished
 * surfaces, warnings and skipped-counts back through a pipe, and a child
 * that crashes, runs out of memory or out of time becomes an error
 * "file: ..." in the parent, whose memory it never touched. */
#include "step.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "envelope.h"

#ifdef SC_HAVE_OCCT

/* Address space of the child: the geometry budget, Open CASCADE's model
 * of the largest file admitted (about 20 times its size) and room for
 * the library itself. Not set under AddressSanitizer, whose shadow
 * memory needs terabytes of address space. */
#define CHILD_ADDRESS_SPACE ((rlim_t)6 << 30)
/* Bytes the parent accepts from the child: the geometry budget and the
 * records around it. */
#define MAX_REPLY (SC_GEOMETRY_BUDGET + ((size_t)64 << 20))

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif

/* ---- the child: writing records ---- */

static int child_fd = -1;

static void put(const void *p, size_t n)
{
    const char *c = p;
    while (n > 0) {
        ssize_t k = write(child_fd, c, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            _exit(3);
        c += k;
        n -= (size_t)k;
    }
}

static void put_int(int v) { put(&v, sizeof v); }

static void put_record(char kind, const void *p, size_t n)
{
    uint32_t len = (uint32_t)n;
    put(&kind, 1);
    put(&len, sizeof len);
    put(p, n);
}

static void child_logger(sc_log_level level, const char *msg, void *user)
{
    (void)user;
    size_t n = strlen(msg);
    char *buf = sc_alloc(n + 1, 1);
    buf[0] = (char)level;
    memcpy(buf + 1, msg, n);
    put_record('W', buf, n + 1);
    free(buf);
}

static void put_curve(const sc_curve *c)
{
    put_int(c->dim);
    put_int(c->degree);
    put_int(c->ncp);
    put(c->knots, sizeof(double) * (size_t)(c->ncp + c->degree + 1));
    put(c->cp, sizeof(double) * (size_t)(c->dim + 1) * (size_t)c->ncp);
}

/* A surface record: its size first, then the fields in order. */
static void put_surface(const sc_surface *s)
{
    size_t n = sizeof s->name + sizeof s->color + sizeof s->xform + 7 * sizeof(int) +
               sizeof(double) * ((size_t)(s->nu + s->deg_u + 1) + (size_t)(s->nv + s->deg_v + 1) +
                                 4 * (size_t)s->nu * (size_t)s->nv);
    for (int l = 0; l < s->nloops; l++) {
        n += 2 * sizeof(int);
        for (int k = 0; k < s->loops[l].ncurves; k++) {
            const sc_curve *c = &s->loops[l].curves[k];
            n += 3 * sizeof(int) + sizeof(double) * ((size_t)(c->ncp + c->degree + 1) +
                                                     (size_t)(c->dim + 1) * (size_t)c->ncp);
        }
    }
    char kind = 'S';
    uint32_t len = (uint32_t)n;
    if ((size_t)len != n)
        _exit(4);
    put(&kind, 1);
    put(&len, sizeof len);
    put(s->name, sizeof s->name);
    put(s->color, sizeof s->color);
    put(s->xform, sizeof s->xform);
    put_int(s->deg_u);
    put_int(s->deg_v);
    put_int(s->nu);
    put_int(s->nv);
    put_int(s->rational);
    put(s->knots_u, sizeof(double) * (size_t)(s->nu + s->deg_u + 1));
    put(s->knots_v, sizeof(double) * (size_t)(s->nv + s->deg_v + 1));
    put(s->cp, sizeof(double) * 4 * (size_t)s->nu * (size_t)s->nv);
    put_int(s->nloops);
    put_int(0);
    for (int l = 0; l < s->nloops; l++) {
        put_int(s->loops[l].is_hole);
        put_int(s->loops[l].ncurves);
        for (int k = 0; k < s->loops[l].ncurves; k++)
            put_curve(&s->loops[l].curves[k]);
    }
}

static void run_child(int fd, const char *text, size_t size, const char *name,
                      const sc_step_scan *scan, double max_seconds)
{
    child_fd = fd;
    /* A crash of the library ends the child plainly, with its signal:
     * handlers the caller installed (a sanitizer's, a fuzzer's that writes
     * a crash file) are for the caller's own faults. */
    static const int faults[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP};
    for (size_t i = 0; i < sizeof faults / sizeof faults[0]; i++) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = SIG_DFL;
        sigaction(faults[i], &sa, NULL);
    }
#ifndef UNDER_ASAN
    struct rlimit lim = {CHILD_ADDRESS_SPACE, CHILD_ADDRESS_SPACE};
    setrlimit(RLIMIT_AS, &lim);
#endif
    sc_set_logger(child_logger, NULL);
    sc_scene scene;
    sc_error err;
    memset(&err, 0, sizeof err);
    sc_scene_init(&scene);
    int status = sc_occt_read_step(text, size, name, scan, max_seconds, &scene, &err);
    if (status != SC_OK) {
        put_record('E', &err, sizeof err);
        _exit(0);
    }
    for (int i = 0; i < scene.nskipped; i++)
        put_record('K', &scene.skipped[i], sizeof scene.skipped[i]);
    for (int i = 0; i < scene.nsurfaces; i++)
        put_surface(&scene.surfaces[i]);
    put_record('O', "", 0);
    _exit(0);
}

/* ---- the parent: reading them back ---- */

typedef struct cursor {
    const char *p, *end;
} cursor;

static int take(cursor *c, void *out, size_t n)
{
    if ((size_t)(c->end - c->p) < n)
        return 0;
    memcpy(out, c->p, n);
    c->p += n;
    return 1;
}

static int take_int(cursor *c, int *v, int lo, int hi)
{
    return take(c, v, sizeof *v) && *v >= lo && *v <= hi;
}

/* Doubles of a count the record must hold. */
static int take_doubles(cursor *c, double *out, size_t n)
{
    return n <= (size_t)(c->end - c->p) / sizeof(double) && take(c, out, n * sizeof(double));
}

/* What taking a record from the child's reply returns besides 1 (taken)
 * and 0 (damaged). */
enum { TAKE_NO_MEMORY = -1 };

static int take_curve(cursor *c, sc_curve *out)
{
    int dim, degree, ncp;
    if (!take_int(c, &dim, 2, 3) || !take_int(c, &degree, 1, SC_READ_MAX_DEGREE) ||
        !take_int(c, &ncp, degree + 1, INT32_MAX / 8) ||
        (size_t)ncp * (size_t)(dim + 2) > (size_t)(c->end - c->p) / sizeof(double))
        return 0;
    if (sc_curve_try_alloc(out, dim, degree, ncp))
        return TAKE_NO_MEMORY;
    return take_doubles(c, out->knots, (size_t)(ncp + degree + 1)) &&
           take_doubles(c, out->cp, (size_t)(dim + 1) * (size_t)ncp);
}

/* A surface into the scene (freed with it when anything fails). */
static int take_surface(cursor *rec, sc_scene *scene)
{
    sc_surface *s = sc_scene_try_add_surface(scene);
    if (!s)
        return TAKE_NO_MEMORY;
    int du, dv, nu, nv, rational, nloops, pad;
    if (!take(rec, s->name, sizeof s->name) || !take(rec, s->color, sizeof s->color) ||
        !take(rec, s->xform, sizeof s->xform) || !take_int(rec, &du, 1, SC_READ_MAX_DEGREE) ||
        !take_int(rec, &dv, 1, SC_READ_MAX_DEGREE) || !take_int(rec, &nu, du + 1, INT32_MAX / 8) ||
        !take_int(rec, &nv, dv + 1, INT32_MAX / 8) || !take_int(rec, &rational, 0, 1) ||
        (size_t)nu * (size_t)nv > (size_t)(rec->end - rec->p) / (4 * sizeof(double)))
        return 0;
    s->name[sizeof s->name - 1] = 0;
    if (sc_surface_try_alloc(s, du, dv, nu, nv))
        return TAKE_NO_MEMORY;
    s->rational = rational;
    if (!take_doubles(rec, s->knots_u, (size_t)(nu + du + 1)) ||
        !take_doubles(rec, s->knots_v, (size_t)(nv + dv + 1)) ||
        !take_doubles(rec, s->cp, 4 * (size_t)nu * (size_t)nv) ||
        !take_int(rec, &nloops, 0, (int)((rec->end - rec->p) / 8)) || !take_int(rec, &pad, 0, 0))
        return 0;
    s->loops = nloops ? sc_try_alloc((size_t)nloops, sizeof *s->loops) : NULL;
    if (nloops && !s->loops)
        return TAKE_NO_MEMORY;
    for (int l = 0; l < nloops; l++) {
        sc_loop *loop = &s->loops[l];
        s->nloops = l + 1;
        int ncurves;
        if (!take_int(rec, &loop->is_hole, 0, 1) ||
            !take_int(rec, &ncurves, 1, (int)((rec->end - rec->p) / 12)))
            return 0;
        if (!(loop->curves = sc_try_alloc((size_t)ncurves, sizeof *loop->curves)))
            return TAKE_NO_MEMORY;
        for (int k = 0; k < ncurves; k++) {
            loop->ncurves = k + 1;
            int taken = take_curve(rec, &loop->curves[k]);
            if (taken != 1)
                return taken;
        }
    }
    return rec->p == rec->end;
}

/* Parses the child's reply into scene (warnings to the logger). */
static int parse_reply(const char *buf, size_t n, const char *name, sc_scene *scene,
                       sc_error *err, int *done)
{
    cursor c = {buf, buf + n};
    while (c.p < c.end) {
        char kind;
        uint32_t len;
        if (!take(&c, &kind, 1) || !take(&c, &len, sizeof len) || len > (size_t)(c.end - c.p))
            break;
        cursor rec = {c.p, c.p + len};
        c.p += len;
        if (kind == 'W' && len >= 1) {
            sc_log((sc_log_level)rec.p[0], "%.*s", (int)(len - 1), rec.p + 1);
        } else if (kind == 'K' && len == sizeof(sc_skipped)) {
            sc_skipped k;
            memcpy(&k, rec.p, sizeof k);
            k.type[sizeof k.type - 1] = 0;
            k.reason[sizeof k.reason - 1] = 0;
            sc_scene_skip(scene, k.type, k.reason, k.count);
        } else if (kind == 'S') {
            int taken = take_surface(&rec, scene);
            if (taken == TAKE_NO_MEMORY)
                return sc_fail_oom(err, name, 0, sc_alloc_failed_bytes(), 1, "a surface");
            if (!taken)
                return sc_fail(err, name, 0, "the STEP reader's child process sent a damaged "
                               "surface");
        } else if (kind == 'E' && len == sizeof(sc_error)) {
            memcpy(err, rec.p, sizeof *err);
            err->message[sizeof err->message - 1] = 0;
            err->file[sizeof err->file - 1] = 0;
            return SC_FAIL;
        } else if (kind == 'O') {
            *done = 1;
            return SC_OK;
        } else {
            break;
        }
    }
    return SC_OK;
}

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int sc_step_read_isolated(const char *text, size_t size, const char *name,
                          const sc_step_scan *scan, double max_seconds, sc_scene *scene,
                          sc_error *err)
{
    int fds[2];
    if (pipe(fds) != 0)
        return sc_fail(err, name, 0, "cannot start the STEP reader: %s", strerror(errno));
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        close(fds[0]);
        close(fds[1]);
        return sc_fail(err, name, 0, "cannot start the STEP reader: %s", strerror(errno));
    }
    if (pid == 0) {
        /* Injected failures (sc_alloc_fail_at) are for the caller's side:
         * the child's memory has its own limit. */
        sc_alloc_fail_at(0);
        close(fds[0]);
        run_child(fds[1], text, size, name, scan, max_seconds);
    }
    close(fds[1]);
    size_t cap = 1 << 16, n = 0;
    char *buf = sc_try_alloc(cap, 1);
    double deadline = now_seconds() + max_seconds + 5;
    int timed_out = 0, too_much = 0, no_memory = !buf;
    while (!no_memory) {
        double left = deadline - now_seconds();
        if (left <= 0) {
            timed_out = 1;
            break;
        }
        struct pollfd p = {fds[0], POLLIN, 0};
        int r = poll(&p, 1, (int)(left * 1000) + 1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            continue;
        if (cap - n < 4096) {
            if (cap >= MAX_REPLY) {
                too_much = 1;
                break;
            }
            char *grown = sc_try_realloc(buf, cap * 2, 1);
            if (!grown) {
                no_memory = 1;
                break;
            }
            buf = grown;
            cap *= 2;
        }
        ssize_t k = read(fds[0], buf + n, cap - n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            break;
        n += (size_t)k;
    }
    close(fds[0]);
    if (timed_out || too_much || no_memory)
        kill(pid, SIGKILL);
    int wstatus = 0;
    while (waitpid(pid, &wstatus, 0) < 0 && errno == EINTR)
        ;
    int done = 0, status;
    if (timed_out)
        status = sc_fail(err, name, 0, "reading took more than %.0f s (the limit; "
                         "docs/limits.md)", max_seconds);
    else if (too_much)
        status = sc_fail(err, name, 0, "the file expands to more than %zu MiB of geometry",
                         SC_GEOMETRY_BUDGET >> 20);
    else if (no_memory)
        status = sc_fail_oom(err, name, 0, buf ? cap * 2 : cap, 1, "the STEP reader's reply");
    else
        status = parse_reply(buf, n, name, scene, err, &done);
    free(buf);
    if (status == SC_OK && !done) {
        if (WIFSIGNALED(wstatus))
            status = sc_fail(err, name, 0, "Open CASCADE failed on this file (its reader "
                             "stopped with signal %d: %s)", WTERMSIG(wstatus),
                             WTERMSIG(wstatus) == SIGSEGV ? "a bad memory access, as on a "
                             "reference to an entity of the wrong type" : "killed");
        else
            status = sc_fail(err, name, 0, "Open CASCADE failed on this file (its reader "
                             "ran out of memory or stopped early)");
    }
    return status;
}

#endif
