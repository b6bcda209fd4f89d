/* bench_stability.c — `splinecast bench --stability`: every scene of the
 * stability suite (examples/scenes/stability/, one row per scene and
 * camera) under every intersection method and start this build
 * implements, each image compared with the CPU reference of the same
 * view. The methods and starts are not listed here: every spelling the
 * command line knows is tried and those the compiler refuses are skipped
 * with a note on stderr, so a method added to the compiler joins the suite
 * without an edit. One line per scene × method × start on stdout;
 * progress on stderr. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "stability.h"

static const char usage[] =
    "usage: splinecast bench --stability [options]\n"
    "\n"
    "Renders every scene of the stability suite with every intersection method\n"
    "and start the compiler builds, and compares each image with the CPU\n"
    "reference of the same view. One line per scene x method x start:\n"
    "  stability scene=S method=M init=I fail_pct=P holes=N false_hits=N off=N\n"
    "            iters_mean=I iters_max=I frame_ms=T\n"
    "Methods or starts the compiler refuses are skipped, with a note on stderr.\n"
    "\n"
    "options:\n"
    "  --size WxH             image size (default 128x128)\n"
    "  --suite DIR            the suite's folder (default: examples/scenes/stability\n"
    "                         of the working directory or of the checkout the\n"
    "                         executable was built in)\n"
    "  --scenes LIST          only these scenes (comma list of the table's names)\n"
    "  --frames N             timed frames per renderer (default 3)\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n";

/* True when `name` is one of the comma list's entries (or there is no list). */
static int listed(const char *list, const char *name)
{
    if (!list)
        return 1;
    size_t len = strlen(name);
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, ",");
        if (n == len && !strncmp(p, name, n))
            return 1;
        p += n + (p[n] == ',');
    }
    return 0;
}

/* Refusals already noted, by method and start: the text's hash, so that
 * a method refused everywhere ("not implemented") is noted once and one
 * refused for some scene's keys alone (another message) again. */
typedef struct refusals {
    unsigned long hash[16][16];
} refusals;

static int first_time(refusals *seen, int m, int s, const char *text)
{
    /* The key at the start of the message names the scene's degrees; only
     * the words after it say why. */
    const char *why = strstr(text, ": ");
    unsigned long h = 5381;
    for (const char *p = why ? why : text; *p; p++)
        h = h * 33 + (unsigned char)*p;
    if (m >= 16 || s >= 16)
        return 1;
    if (seen->hash[m][s] == h)
        return 0;
    seen->hash[m][s] = h;
    return 1;
}

/* Every method × start of one row; returns 0 or the exit status. */
static int run_row(sc_context_id ctx, const stab_suite *suite, const stab_row *row, int width,
                   int height, int frames, refusals *seen)
{
    sc_error err = {0};
    sc_scene_id scene;
    sc_camera_desc cam;
    if (stab_load_row(suite, row, width, height, &scene, &cam, &err) != SC_OK) {
        fprintf(stderr, "stability: scene %s (%s):\n", row->name, row->file);
        return cli_report(&err);
    }
    sc_frame_id ref;
    sc_frame_info ref_info;
    if (sc_render_reference(scene, &cam, NULL, &ref, &err) != SC_OK ||
        sc_query_frame_info(ref, &ref_info, &err) != SC_OK) {
        sc_destroy_scene(scene);
        return cli_report(&err);
    }
    fprintf(stderr, "stability: %s: reference %ld hits in %.2f s\n", row->name,
            ref_info.reference.hits, ref_info.reference.seconds);
    /* Results of this row by the hash of their keys: a start the method
     * ignores draws with the programs of an earlier start, so its line
     * repeats that one's figures instead of drawing the same image again. */
    enum { MAX_DONE = 64 };
    unsigned long done_hash[MAX_DONE];
    stab_result done[MAX_DONE];
    int ndone = 0, status = 0;
    for (int m = 1; status == 0 && strcmp(cli_method_name((sc_method)m), "default"); m++) {
        for (int s = 1; status == 0 && strcmp(cli_start_name((sc_start)s), "default"); s++) {
            const char *mname = cli_method_name((sc_method)m), *sname = cli_start_name((sc_start)s);
            unsigned long hash;
            if (stab_check_method(scene, (sc_method)m, (sc_start)s, &hash, &err) != SC_OK) {
                char text[768];
                sc_error_text(&err, text, sizeof text);
                if (first_time(seen, m, s, text))
                    fprintf(stderr, "stability: %s method=%s init=%s skipped, refused: %s\n",
                            row->name, mname, sname, text);
                continue;
            }
            int k = 0;
            while (k < ndone && done_hash[k] != hash)
                k++;
            stab_result res;
            if (k < ndone) {
                res = done[k];
            } else {
                sc_renderer_desc desc = {.method = (sc_method)m, .start = (sc_start)s};
                if (stab_measure(ctx, scene, &desc, &cam, ref, frames, 0, &res, &err) != SC_OK) {
                    status = cli_report(&err);
                    break;
                }
                if (ndone < MAX_DONE) {
                    done_hash[ndone] = hash;
                    done[ndone++] = res;
                }
            }
            printf("stability scene=%s method=%s init=%s fail_pct=%.4g holes=%ld false_hits=%ld "
                   "off=%ld iters_mean=%.3f iters_max=%.0f frame_ms=%.2f\n",
                   row->name, mname, sname, res.cmp.fail_pct, res.cmp.holes,
                   res.cmp.false_hits, res.cmp.off, res.cmp.iters_mean, res.cmp.iters_max,
                   res.frame_ms);
            fflush(stdout);
        }
    }
    sc_destroy_frame(ref);
    sc_destroy_scene(scene);
    return status;
}

int bench_stability(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    const char *suite_arg = NULL, *only = NULL;
    int width = 128, height = 128, frames = 3;
    sc_context_desc ctx_desc = {0};
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (!strcmp(a, "--stability")) {
            continue;
        } else if (!strcmp(a, "--size") && next) {
            i++;
            if (sscanf(argv[i], "%dx%d", &width, &height) != 2 || width < 1 || height < 1 ||
                width > 16384 || height > 16384)
                return cli_usage_error("bench", "--size takes WxH, not '%s'", argv[i]);
        } else if (!strcmp(a, "--suite") && next) {
            suite_arg = argv[++i];
        } else if (!strcmp(a, "--scenes") && next) {
            only = argv[++i];
        } else if (!strcmp(a, "--frames") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000)
                return cli_usage_error("bench", "--frames takes 1 to 1000, not '%s'", argv[i]);
            frames = (int)n;
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &ctx_desc.backend, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else {
            return cli_usage_error("bench", "--stability takes no scene and no '%s' "
                                   "(bench --stability --help)", a);
        }
    }
    char dir[1024];
    stab_suite suite;
    if (stab_find_suite(suite_arg, dir, sizeof dir, &err) != SC_OK ||
        stab_read_suite(dir, &suite, &err) != SC_OK)
        return cli_report(&err);
    int selected = 0;
    for (int r = 0; r < suite.count; r++)
        selected += listed(only, suite.rows[r].name);
    if (!selected) {
        stab_free_suite(&suite);
        return cli_usage_error("bench", "--scenes %s names no scene of %s/README.md", only, dir);
    }
    sc_context_id ctx;
    sc_context_info ctx_info;
    if (sc_make_context(&ctx_desc, &ctx, &err) != SC_OK ||
        sc_query_context_info(ctx, &ctx_info, &err) != SC_OK) {
        stab_free_suite(&suite);
        return cli_report(&err);
    }
    fprintf(stderr, "stability: %s, suite %s, %d of %d scenes, %dx%d\n", ctx_info.description,
            dir, selected, suite.count, width, height);
    double t0 = sc_now();
    int status = 0, done = 0;
    refusals seen = {{{0}}};
    for (int r = 0; r < suite.count && status == 0; r++) {
        if (!listed(only, suite.rows[r].name))
            continue;
        fprintf(stderr, "stability: [%d/%d] %s (%s) camera %s\n", ++done, selected,
                suite.rows[r].name, suite.rows[r].file, suite.rows[r].camera);
        status = run_row(ctx, &suite, &suite.rows[r], width, height, frames, &seen);
    }
    fprintf(stderr, "stability: %.1f s\n", sc_now() - t0);
    sc_destroy_context(ctx);
    stab_free_suite(&suite);
    return status;
}
