/* optimize.c — the pass list, run to a fixed point with validation after
 * every pass. A file of its own because metaprograms call it too (the trim
 * probe optimises its program), and they are called by program.c: here it
 * closes no call cycle between files. */
#include "ir.h"

typedef struct pass {
    const char *name;
    bool (*run)(scg_program *);
} pass;

/* The pass list. Folding first exposes equal constants to CSE; copy
 * propagation hands folding and CSE the values stored rather than loads;
 * CSE leaves duplicates dead for DCE. */
static const pass passes[] = {
    {"fold", scg_opt_fold},
    {"copy", scg_opt_copy},
    {"cse", scg_opt_cse},
    {"dce", scg_opt_dce},
};

int scg_optimize(scg_program *prog, scg_stage_fn on_stage, void *user, sc_error *err)
{
    sc_error local;
    if (!err)
        err = &local;
    /* Each pass only removes or simplifies, so a fixed point comes in a few
     * rounds; the cap keeps a pass that undid another's work from looping
     * (the program is valid after every pass either way). */
    for (int round = 0; round < 100; round++) {
        bool progress = false;
        for (size_t i = 0; i < sizeof passes / sizeof passes[0]; i++) {
            if (!passes[i].run(prog))
                continue;
            progress = true;
            if (scg_validate(prog, err) != SC_OK) {
                char msg[sizeof err->message];
                snprintf(msg, sizeof msg, "after pass %s: %.480s", passes[i].name, err->message);
                snprintf(err->message, sizeof err->message, "%s", msg);
                return SC_FAIL;
            }
            if (on_stage)
                on_stage(passes[i].name, prog, user);
        }
        if (!progress)
            return SC_OK;
    }
    return SC_OK;
}
