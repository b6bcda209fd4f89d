/* commands.h — the subcommands of the splinecast command line. Each one
 * lives in its own cmd_NAME.c, takes argv from its own name on, prints its
 * contract lines on stdout and progress and warnings on stderr, and returns
 * the process exit status (0 ok, 1 failure, 2 bad usage). */
#ifndef SC_COMMANDS_H
#define SC_COMMANDS_H

typedef int (*command_fn)(int argc, char **argv);

typedef struct command {
    const char *name;
    command_fn run;
    const char *summary;   /* one line for `splinecast --help` */
} command;

int cmd_info(int argc, char **argv);
int cmd_eval(int argc, char **argv);
int cmd_convert(int argc, char **argv);

/* Shared helpers (cli.c). */
/* True when argv has -h or --help. */
int cli_wants_help(int argc, char **argv);
/* Prints "splinecast NAME: message" to stderr and returns 2 (bad usage). */
int cli_usage_error(const char *name, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Prints a library error as "file:line: message" to stderr; returns 1. */
struct sc_error;
int cli_report(const struct sc_error *err);

#endif
