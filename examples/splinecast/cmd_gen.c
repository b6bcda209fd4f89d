/* cmd_gen.c — `splinecast gen`: build-time shader generation. Turns variant
 * keys (given, or the ones a scene needs) into validated GLSL files and a
 * manifest; nothing is written unless every program passes glslang. Also
 * the key selection that `audit` shares (--key, --scene, --family). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"
#include "emit_glsl.h"
#include "io.h"
#include "key.h"
#include "scene_keys.h"
#include "splinecast.h"

static const char usage[] =
    "usage: splinecast gen KEYS -o DIR [--dump-ir]\n"
    "\n"
    "Generates the GLSL of every distinct variant key, validates each program\n"
    "with glslang (both stages parsed and linked together) and writes, only when\n"
    "all pass:\n"
    "  DIR/KEY.frag         one fragment program per key\n"
    "  DIR/NAME.vert        the vertex programs those keys need\n"
    "  DIR/manifest.tsv     key, stage, file, bytes (a header line, then one row\n"
    "                       per key and stage)\n"
    "stdout: one line `FILE BYTES` per file written, then `keys N files M`.\n"
    "A program glslang rejects fails with the key, glslang's message and the\n"
    "offending GLSL line on stderr, and nothing is written (exit 1). Files of\n"
    "earlier runs in DIR are left alone: manifest.tsv lists this run's.\n"
    "  --dump-ir          first print each key's IR listing after the build and\n"
    "                     after every optimisation pass that changed it\n"
    "\n";

const char gen_keys_usage[] =
    "KEYS, exactly one of:\n"
    "  --key KEY...       variant keys in canonical form (docs/variant-key.md)\n"
    "  --scene SCENE      the keys SCENE's surfaces need (one per degree pair,\n"
    "                     rationality and trimming)\n"
    "  --family LO..HI    bez keys of every degree pair LO..HI x LO..HI, rational\n"
    "                     and not\n"
    "with --scene and --family:\n"
    "  --like KEY         method, start, iterations, tolerance, early ray\n"
    "                     termination and outputs (default: those of\n"
    "                     bez3x3-poly-dc-trim0-newton-cp-it6-tol0.05-ert1-out.shade.aov,\n"
    "                     the programs `render` draws with by default)\n"
    "with any of them:\n"
    "  --iters N[,N...]   each key at each of these iteration counts\n";

/* ---- key selection shared with `audit` ---- */

/* What --like gives every key a scene's surfaces need (scene_keys.h
 * decides kind, degrees, rationality, evaluation form and trimming). */
static void options_like(const scg_key *like, sc_key_options *opts)
{
    memset(opts, 0, sizeof *opts);
    opts->nurbs_direct = like->kind == SCG_PATCH_NURBS;
    opts->max_iters = like->max_iters;
    opts->tol_milli = like->tol_milli;
    opts->start = like->start;
    opts->outputs = like->outputs;
}

/* Keys while they are chosen: parsed, so that --iters can vary them. */
typedef struct key_set {
    scg_key *keys;
    int count;
} key_set;

static void add_key(key_set *set, const scg_key *key)
{
    for (int i = 0; i < set->count; i++)
        if (scg_key_equal(&set->keys[i], key))
            return;
    set->keys = sc_realloc(set->keys, (size_t)set->count + 1, sizeof *set->keys);
    set->keys[set->count++] = *key;
}

/* "1,4,16" into iters[]; returns the count or -1. */
static int parse_iters(const char *text, int *iters, int max)
{
    int n = 0;
    const char *p = text;
    while (*p) {
        char *end;
        long v = strtol(p, &end, 10);
        if (end == p || v < 1 || v > SCG_MAX_ITERS || n == max)
            return -1;
        iters[n++] = (int)v;
        if (*end == ',')
            end++;
        else if (*end)
            return -1;
        p = end;
    }
    return n;
}

/* The keys the scene's surfaces need, each at every iteration count.
 * Returns 0, or 1 after printing why the scene could not be read. */
static int add_scene_keys(const char *path, const scg_key *like, const int *iters, int niters,
                          key_set *set)
{
    sc_scene scene;
    sc_error err = {0};
    if (sc_read_scene(path, &scene, &err) != SC_OK)
        return cli_report(&err);
    sc_key_options opts;
    options_like(like, &opts);
    for (int s = 0; s < scene.nsurfaces; s++) {
        /* `render` refuses such a scene: no program would draw it. */
        if (sc_surface_drawable(&scene, s, &err) != SC_OK) {
            sc_scene_free(&scene);
            return cli_report(&err);
        }
        for (int k = 0; k < niters; k++) {
            scg_key key;
            opts.max_iters = iters[k];
            sc_surface_key(&scene.surfaces[s], &opts, &key);
            /* --like names what the program does (ertN), not a renderer's
             * termination option, so it is copied, not mapped. */
            key.ert = like->ert;
            add_key(set, &key);
        }
    }
    sc_scene_free(&scene);
    return 0;
}

/* The bez keys of every degree pair in LO..HI, rational and not, each at
 * every iteration count. Returns 0, or 2 after printing a usage error. */
static int add_family_keys(const char *cmd, const char *family, const scg_key *like,
                           const int *iters, int niters, key_set *set)
{
    int lo, hi, used = 0;
    if (sscanf(family, "%d..%d%n", &lo, &hi, &used) != 2 || family[used] || lo < 1 || hi < lo ||
        hi > SCG_MAX_DEGREE)
        return cli_usage_error(cmd, "--family wants LO..HI with 1 <= LO <= HI <= %d",
                               SCG_MAX_DEGREE);
    for (int du = lo; du <= hi; du++)
        for (int dv = lo; dv <= hi; dv++)
            for (int rational = 0; rational < 2; rational++)
                for (int k = 0; k < niters; k++) {
                    scg_key key = *like;
                    key.deg_u = du;
                    key.deg_v = dv;
                    key.rational = rational;
                    key.max_iters = iters[k];
                    if (key.eval == SCG_EVAL_LOOP)
                        key.eval = SCG_EVAL_DC;
                    add_key(set, &key);
                }
    return 0;
}

int gen_parse_keys(const char *cmd, int argc, char **argv, gen_keys *out, int *first_other)
{
    memset(out, 0, sizeof *out);
    key_set chosen = {0}, *set = &chosen;
    scg_key like;
    scg_key_default(&like, SCG_PATCH_BEZIER, 3, 3);
    like.ert = sc_key_ert(SC_TERMINATION_DEFAULT);
    like.outputs = SC_KEY_DEFAULT_OUTPUTS;
    const char *scene_path = NULL, *family = NULL;
    int iters[SCG_MAX_ITERS], niters = 0, iters_given = 0;
    char **given = sc_alloc((size_t)argc, sizeof *given);
    int ngiven = 0, status = 0;
    sc_error err = {0};
    int i = 1, kept = 1;
    while (i < argc && status == 0) {
        const char *arg = argv[i];
        if (!strcmp(arg, "--key")) {
            int start = ++i;
            while (i < argc && argv[i][0] != '-')
                given[ngiven++] = argv[i++];
            if (i == start)
                status = cli_usage_error(cmd, "--key needs at least one KEY");
        } else if (!strcmp(arg, "--scene") && i + 1 < argc) {
            scene_path = argv[i + 1];
            i += 2;
        } else if (!strcmp(arg, "--family") && i + 1 < argc) {
            family = argv[i + 1];
            i += 2;
        } else if (!strcmp(arg, "--like") && i + 1 < argc) {
            if (scg_key_parse(argv[i + 1], &like, &err) != SC_OK) {
                fprintf(stderr, "splinecast %s: --like: %s\n", cmd, err.message);
                status = 2;
            }
            i += 2;
        } else if (!strcmp(arg, "--iters") && i + 1 < argc) {
            niters = parse_iters(argv[i + 1], iters, SCG_MAX_ITERS);
            iters_given = 1;
            if (niters < 0)
                status = cli_usage_error(cmd, "--iters wants counts 1..%d joined by ','",
                                         SCG_MAX_ITERS);
            i += 2;
        } else if (!strcmp(arg, "--scene") || !strcmp(arg, "--family") ||
                   !strcmp(arg, "--like") || !strcmp(arg, "--iters")) {
            status = cli_usage_error(cmd, "%s needs a value", arg);
        } else {
            argv[kept++] = argv[i++];   /* the command's own options, in order */
        }
    }
    *first_other = kept;
    if (status == 0 && !!scene_path + !!family + (ngiven > 0) != 1)
        status = cli_usage_error(cmd, "give exactly one of --key, --scene, --family");
    if (status == 0 && niters == 0)
        iters[niters++] = like.max_iters;

    for (int g = 0; g < ngiven && status == 0; g++) {
        scg_key key;
        if (scg_key_parse(given[g], &key, &err) != SC_OK) {
            fprintf(stderr, "splinecast %s: %s\n", cmd, err.message);
            status = 2;
        } else {
            add_key(set, &key);
        }
    }
    if (status == 0 && scene_path)
        status = add_scene_keys(scene_path, &like, iters, niters, set);
    if (status == 0 && family)
        status = add_family_keys(cmd, family, &like, iters, niters, set);
    if (status == 0 && iters_given && ngiven > 0) {
        /* --iters with --key: every given key at every count. */
        key_set expanded = {0};
        for (int g = 0; g < set->count; g++)
            for (int k = 0; k < niters; k++) {
                scg_key key = set->keys[g];
                key.max_iters = iters[k];
                add_key(&expanded, &key);
            }
        free(set->keys);
        *set = expanded;
    }
    free(given);
    if (status == 0) {
        out->keys = sc_alloc((size_t)(set->count ? set->count : 1), sizeof *out->keys);
        for (int k = 0; k < set->count; k++)
            scg_key_format(&set->keys[k], out->keys[k].text, sizeof out->keys[k].text);
        out->count = set->count;
    }
    free(set->keys);
    return status;
}

/* ---- writing ---- */

/* Written to a temporary name and renamed, so a reader never sees half a
 * file. */
static int write_file(const char *path, const char *text, size_t size, sc_error *err)
{
    sc_out_file out;
    if (sc_out_open(&out, path, err))
        return SC_FAIL;
    if (fwrite(text, 1, size, out.f) != size) {
        sc_out_abandon(&out);
        return sc_fail(err, path, 0, "writing failed (disk full?)");
    }
    return sc_out_commit(&out, err);
}

/* Creates dir and any missing parents, as mkdir -p. */
static int ensure_dir(const char *dir, sc_error *err)
{
    char path[1024];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1;; p++) {
        int last = *p == 0;
        if (*p != '/' && !last)
            continue;
        *p = 0;
        struct stat st;
        if (stat(path, &st) != 0 && mkdir(path, 0777) != 0 && errno != EEXIST)
            return sc_fail(err, path, 0, "cannot create the directory: %s", strerror(errno));
        if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode))
            return sc_fail(err, path, 0, "not a directory");
        if (last)
            return SC_OK;
        *p = '/';
    }
}

static int write_outputs(const char *dir, scg_generated *gens, int count, int *files,
                         sc_error *err)
{
    /* The longest name: DIR/KEY.frag; a longer DIR would be cut silently. */
    if (strlen(dir) + SCG_KEY_MAX + 8 > 1024)
        return sc_fail(err, dir, 0, "output directory name too long (at most %d characters)",
                       1024 - SCG_KEY_MAX - 8);
    if (ensure_dir(dir, err) != SC_OK)
        return SC_FAIL;
    char path[1024];
    scg_text manifest = {0};
    scg_text_append(&manifest, "key\tstage\tfile\tbytes\n");
    int status = SC_OK;
    *files = 0;
    for (int i = 0; i < count && status == SC_OK; i++) {
        const scg_generated *g = &gens[i];
        size_t frag_bytes = g->fragment.len, vert_bytes = g->vertex.len;
        const char *frag = scg_stage_extension(SCG_STAGE_FRAGMENT);
        const char *vert = scg_stage_extension(SCG_STAGE_VERTEX);
        scg_text_printf(&manifest, "%s\t%s\t%s.%s\t%zu\n", g->key, frag, g->key, frag,
                        frag_bytes);
        scg_text_printf(&manifest, "%s\t%s\t%s.%s\t%zu\n", g->key, vert, g->vertex_name, vert,
                        vert_bytes);
        snprintf(path, sizeof path, "%s/%s.%s", dir, g->key, frag);
        status = write_file(path, scg_text_str(&g->fragment), frag_bytes, err);
        if (status == SC_OK) {
            printf("%s %zu\n", path, frag_bytes);
            (*files)++;
        }
        int vertex_written = 0;
        for (int j = 0; j < i; j++)
            vertex_written |= !strcmp(gens[j].vertex_name, g->vertex_name);
        if (status == SC_OK && !vertex_written) {
            snprintf(path, sizeof path, "%s/%s.%s", dir, g->vertex_name, vert);
            status = write_file(path, scg_text_str(&g->vertex), vert_bytes, err);
            if (status == SC_OK) {
                printf("%s %zu\n", path, vert_bytes);
                (*files)++;
            }
        }
    }
    if (status == SC_OK) {
        snprintf(path, sizeof path, "%s/manifest.tsv", dir);
        status = write_file(path, scg_text_str(&manifest), manifest.len, err);
        if (status == SC_OK) {
            printf("%s %zu\n", path, manifest.len);
            (*files)++;
        }
    }
    scg_text_free(&manifest);
    return status;
}

static void print_stage(const char *stage, const scg_program *prog, void *user)
{
    (void)user;
    printf("# after %s\n", stage);
    scg_dump_ir(stdout, prog);
}

/* The IR listing of every stage of every key, for --dump-ir. */
static int dump_ir(const gen_keys *set)
{
    int failures = 0;
    for (int k = 0; k < set->count; k++) {
        scg_program *prog = NULL;
        sc_error err = {0};
        scg_key key;
        if (scg_key_parse(set->keys[k].text, &key, &err) != SC_OK ||
            scg_compile_stages(&key, print_stage, NULL, &prog, &err) != SC_OK) {
            cli_report(&err);
            failures++;
        }
        if (prog)
            scg_program_free(prog);
    }
    return failures;
}

int cmd_gen(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        fputs(gen_keys_usage, stdout);
        return 0;
    }
    gen_keys set;
    int first_other;
    int status = gen_parse_keys("gen", argc, argv, &set, &first_other);
    if (status)
        return status;
    const char *dir = NULL;
    int want_ir = 0;
    for (int i = 1; i < first_other && status == 0; i++) {
        if (!strcmp(argv[i], "-o") && i + 1 < first_other)
            dir = argv[++i];
        else if (!strcmp(argv[i], "--dump-ir"))
            want_ir = 1;
        else
            status = cli_usage_error("gen", "unknown option '%s'", argv[i]);
    }
    if (status == 0 && !dir)
        status = cli_usage_error("gen", "-o DIR is required");
    if (status) {
        free(set.keys);
        return status;
    }

    if (want_ir && dump_ir(&set)) {
        free(set.keys);
        return 1;
    }
    double t0 = sc_now();
    scg_generated *gens = sc_alloc((size_t)set.count, sizeof *gens);
    int failures = 0;
    for (int k = 0; k < set.count; k++) {
        sc_error err = {0};
        scg_key key;
        if (scg_key_parse(set.keys[k].text, &key, &err) != SC_OK ||
            scg_generate(&key, &gens[k], &err) != SC_OK) {
            cli_report(&err);
            failures++;
        }
    }
    double elapsed = sc_now() - t0;
    fprintf(stderr, "splinecast gen: %d keys generated and validated in %.3f s\n",
            set.count - failures, elapsed);
    int files = 0;
    if (!failures) {
        sc_error err = {0};
        if (write_outputs(dir, gens, set.count, &files, &err) != SC_OK) {
            cli_report(&err);
            failures++;
        } else {
            printf("keys %d files %d\n", set.count, files);
        }
    } else {
        fprintf(stderr, "splinecast gen: %d of %d keys failed; nothing written\n", failures,
                set.count);
    }
    for (int k = 0; k < set.count; k++)
        scg_generated_free(&gens[k]);
    free(gens);
    free(set.keys);
    return failures ? 1 : 0;
}
