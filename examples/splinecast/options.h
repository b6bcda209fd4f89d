/* options.h — the spellings users type for the options (`--view iters`,
 * `--ert manual`, `--order hybrid`, `--trim fast:16`, `--hulls uniform:2`,
 * `--backend egl`), read into the public enums of splinecast_options.h and
 * printed back. Spellings are the command line's business: the library
 * takes enums. A bad spelling fails with a message that lists the good
 * ones. */
#ifndef SC_CLI_OPTIONS_H
#define SC_CLI_OPTIONS_H

#include "splinecast_base.h"
#include "splinecast_options.h"

/* shade, uv, iters, normal, depth, hull. */
int cli_show_parse(const char *text, sc_show *out, sc_error *err);
/* clip, left or fast, optionally ":ITERS" (1 … SC_MAX_TRIM_ITERS); *iters is left alone
 * when no cap is given. */
int cli_trim_parse(const char *text, sc_trim_method *out, int *iters, sc_error *err);
/* none, conservative, manual, manual-both, peel, lists; and back ("default" for
 * SC_TERMINATION_DEFAULT). */
int cli_termination_parse(const char *text, sc_ray_termination *out, sc_error *err);
/* `--lists-below off|PX` (sc_renderer_desc.list_below_px: off is
 * SC_LISTS_OFF). */
int cli_list_below_parse(const char *text, int *out, sc_error *err);
/* --threads N: 1 to 1024 (sc_renderer_desc.threads). */
int cli_threads_parse(const char *text, int *out, sc_error *err);
const char *cli_termination_name(sc_ray_termination termination);
/* front-to-back, by-program, hybrid; and back. */
int cli_order_parse(const char *text, sc_hull_order *out, sc_error *err);
const char *cli_order_name(sc_hull_order order);
/* newton, broyden, bclip, subdiv, hybrid; and back ("default" for
 * SC_METHOD_DEFAULT). The library refuses what is not implemented, by
 * name. */
int cli_method_parse(const char *text, sc_method *out, sc_error *err);
const char *cli_method_name(sc_method method);
/* dc, bern, pow; and back ("default" for SC_EVAL_DEFAULT). */
int cli_eval_parse(const char *text, sc_eval *out, sc_error *err);
const char *cli_eval_name(sc_eval eval);
/* mid, cpmap, view; and back ("default" for SC_START_DEFAULT and values
 * without a spelling). */
int cli_start_parse(const char *text, sc_start *out, sc_error *err);
const char *cli_start_name(sc_start start);
/* egl, osmesa, default; and back. */
int cli_backend_parse(const char *text, sc_backend *out, sc_error *err);
const char *cli_backend_name(sc_backend backend);
/* "uniform:N" (N from 1 to
 * SC_MAX_HULL_DIVISIONS) or "adaptive:TOL" (0 < TOL < 1, a fraction
 * of the scene's size); the other mode's number is set to 0 (default). */
int cli_hulls_parse(const char *text, sc_hull_split *split, int *divisions, double *tolerance,
                    sc_error *err);
/* "PX" or "PX,DEG": an accuracy target, position bound in pixel
 * footprints and optionally a normal bound in degrees
 * (docs/accuracy.md); the library checks the ranges. */
int cli_accuracy_parse(const char *text, double *px, double *deg, sc_error *err);

#endif
