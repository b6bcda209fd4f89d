/* cli.c — helpers shared by the subcommands. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "splinecast_base.h"

int cli_wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (!strcmp(argv[i], "-h") || !strcmp(argv[i], "--help"))
            return 1;
    return 0;
}

int cli_usage_error(const char *name, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "splinecast %s: ", name);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, " (see splinecast %s --help)\n", name);
    va_end(ap);
    return 2;
}

void cli_aov_path(const char *image_path, char *buf, size_t size)
{
    size_t n = strlen(image_path);
    const char *dot = strrchr(image_path, '.');
    const char *slash = strrchr(image_path, '/');
    if (dot && (!slash || dot > slash) && dot != image_path && (!slash || dot > slash + 1))
        n = (size_t)(dot - image_path);
    snprintf(buf, size, "%.*s.aov", (int)n, image_path);
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

double cli_median(double *values, int n)
{
    qsort(values, (size_t)n, sizeof *values, compare_double);
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

int cli_report(const struct sc_error *err)
{
    char buf[1024];
    fprintf(stderr, "%s\n", sc_error_text(err, buf, sizeof buf));
    return 1;
}
