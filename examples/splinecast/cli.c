/* cli.c — helpers shared by the subcommands. */
#include <stdarg.h>
#include <stdio.h>
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

int cli_report(const struct sc_error *err)
{
    char buf[1024];
    fprintf(stderr, "%s\n", sc_error_text(err, buf, sizeof buf));
    return 1;
}
