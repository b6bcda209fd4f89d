/* embed_util.c — building example programs against an installed copy
 * (embed_util.h), as install_example_against_installed_copy does for
 * render_scene.c. */
#define _POSIX_C_SOURCE 200809L
#include "embed_util.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test.h"

#if defined(__SANITIZE_ADDRESS__)
static const char sanitizer_flags[] = "-fsanitize=address,undefined";
#else
static const char sanitizer_flags[] = "";
#endif

static int installed;

/* CHECK_INT returns from the function it is in: a void one. */
static void check_status(int status) { CHECK_INT(status, 0); }

static const char *build_folder(void)
{
    const char *env = getenv("SC_BUILD");
    return env && env[0] ? env : "build";
}

int test_build_example(const char *name, char *exe, size_t size)
{
    char dest[600], cmd[4096];
    snprintf(dest, sizeof dest, "%s/embed-stage", test_tmpdir());
    const char *build = build_folder();
    char *errs = NULL;
    if (!installed) {
        /* -o: nothing rebuilt; the parent make's flags are not this make's. */
        snprintf(cmd, sizeof cmd,
                 "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -s -C '%s' install BUILD='%s' "
                 "-o '%s/libsplinecast.a' -o '%s/splinecast' PREFIX=/opt/splinecast "
                 "DESTDIR='%s'",
                 test_root_dir, build, build, build, dest);
        int status = test_run(cmd, NULL, &errs);
        if (status != 0)
            fprintf(stderr, "  %s\n%s", cmd, errs ? errs : "");
        free(errs);
        errs = NULL;
        check_status(status);
        if (status != 0)
            return 1;
        installed = 1;
    }
    snprintf(exe, size, "%s/%s", test_tmpdir(), name);
    snprintf(cmd, sizeof cmd,
             "PKG_CONFIG_PATH='%s/opt/splinecast/lib/pkgconfig' PKG_CONFIG_SYSROOT_DIR='%s' && "
             "export PKG_CONFIG_PATH PKG_CONFIG_SYSROOT_DIR && "
             "cc -std=c11 -pedantic -Wall -Wextra -Werror %s '%s/examples/%s.c' "
             "$(pkg-config --cflags --libs splinecast) -lm -o '%s'",
             dest, dest, sanitizer_flags, test_root_dir, name, exe);
    int status = test_run(cmd, NULL, &errs);
    if (status != 0)
        fprintf(stderr, "  %s\n%s", cmd, errs ? errs : "");
    free(errs);
    check_status(status);
    return status != 0;
}
