/* commands.h — the subcommands of the splinecast command line. Each one
 * lives in its own cmd_NAME.c, takes argv from its own name on, prints its
 * contract lines on stdout and progress and warnings on stderr, and returns
 * the process exit status (0 ok, 1 failure, 2 bad usage). */
#ifndef SC_COMMANDS_H
#define SC_COMMANDS_H

#include <stddef.h>

typedef int (*command_fn)(int argc, char **argv);

typedef struct command {
    const char *name;
    command_fn run;
    const char *summary;   /* one line for `splinecast --help` */
} command;

int cmd_info(int argc, char **argv);
int cmd_eval(int argc, char **argv);
int cmd_convert(int argc, char **argv);
int cmd_ref(int argc, char **argv);
int cmd_diff(int argc, char **argv);
int cmd_gen(int argc, char **argv);
int cmd_audit(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_terrain(int argc, char **argv);
int cmd_splines(int argc, char **argv);
int cmd_pick(int argc, char **argv);
int cmd_pack(int argc, char **argv);
/* `bench --trim-table` (bench_trim.c). */
int bench_trim_table(int argc, char **argv);
/* `bench --stability` (bench_stability.c). */
int bench_stability(int argc, char **argv);

/* Shared helpers (cli.c). */
/* True when argv has -h or --help. */
int cli_wants_help(int argc, char **argv);
/* Prints "splinecast NAME: message" to stderr and returns 2 (bad usage). */
int cli_usage_error(const char *name, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* The median of n > 0 values (sorted in place): frame times. */
double cli_median(double *values, int n);
/* The AOV file written beside an image: "out.png" -> "out.aov". */
void cli_aov_path(const char *image_path, char *buf, size_t size);
/* Prints a library error as "file:line: message" to stderr; returns 1. */
struct sc_error;
int cli_report(const struct sc_error *err);

/* Key selection shared by gen and audit (cmd_gen.c). */
/* Help text of the KEYS options. */
extern const char gen_keys_usage[];
struct sc_key;
typedef struct gen_keys {
    struct sc_key *keys;    /* canonical texts, distinct, in order of first
                               appearance */
    int count;
} gen_keys;
/* Takes the KEYS options out of argv, compacting the others (from argv[1])
 * so that argv[1 .. *first_other - 1] are the command's own. Returns 0, or
 * the exit status after printing the problem (2 usage, 1 unreadable scene). */
int gen_parse_keys(const char *cmd, int argc, char **argv, gen_keys *set, int *first_other);

#endif
