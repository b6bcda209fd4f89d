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
    "                     rationality and trimming; for gen, a key whose\n"
    "                     outputs are shade.aov also without aov, since a\n"
    "                     renderer draws with that one and reads frames back\n"
    "                     with the other, and each of these also as the\n"
    "                     renderer's candidate lists draw it, ert5)\n"
    "  --family LO..HI    bez keys of every degree pair LO..HI x LO..HI, rational\n"
    "                     and not\n"
    "with --scene and --family:\n"
    "  --like KEY         every field of KEY except those each surface (or\n"
    "                     degree pair) decides: kind, degrees, poly|rat, the\n"
    "                     generic program (loop) where a degree needs it, and\n"
    "                     whether it is trimmed and its trim-curve degree. So\n"
    "                     dc, bern or pow, the trim method and its cap, method,\n"
    "                     start, iterations, tolerance, ert and outputs all\n"
    "                     come from KEY; a field that cannot apply is an error\n"
    "                     naming it (default: those of the programs `render`\n"
    "                     draws with by default, but Newton's method; with\n"
    "                     --family the evaluation form of each degree pair,\n"
    "                     pow up to degree 4 and dc above)\n"
    "with any of them:\n"
    "  --iters N[,N...]   each key at each of these iteration counts\n";

/* ---- key selection shared with `audit` ---- */

static void add_key(gen_keys *set, const sc_key *key)
{
    for (int i = 0; i < set->count; i++)
        if (!strcmp(set->keys[i].text, key->text))
            return;   /* canonical texts: equal keys, equal texts */
    sc_key *grown = realloc(set->keys, ((size_t)set->count + 1) * sizeof *set->keys);
    if (!grown) {
        fprintf(stderr, "splinecast: out of memory\n");
        exit(1);
    }
    set->keys = grown;
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
        if (end == p || v < 1 || v > SC_MAX_ITERS || n == max)
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

/* The keys the scene's surfaces need, each at every iteration count, with
 * what --like gives (the scene decides kind, degrees, rationality, the
 * generic program where a degree needs it, and whether it is trimmed); for
 * gen (drawing_keys) also every key a renderer draws them with. Returns 0,
 * or 1 after printing why the scene could not be read or drawn (`render`
 * refuses a surface no program draws). */
static int add_scene_keys(const char *path, const char *like, const int *iters, int niters,
                          int drawing_keys, gen_keys *set)
{
    sc_scene_id scene;
    sc_scene_info info;
    sc_error err = {0};
    if (sc_make_scene(&(sc_scene_desc){.path = path}, &scene, &err) != SC_OK)
        return cli_report(&err);
    int status = sc_query_scene_info(scene, &info, &err);
    for (int s = 0; s < info.surfaces && status == SC_OK; s++)
        for (int k = 0; k < niters && status == SC_OK; k++) {
            sc_key key[2];
            int nkeys = 0;
            sc_keys_desc desc = {.like = like, .max_iters = iters[k]};
            status = sc_query_surface_key(scene, s, &desc, &key[nkeys], &err);
            nkeys += status == SC_OK;
            /* For gen: a renderer's frames write the AOVs on demand only
             * (sc_renderer_desc.aovs), so it draws with the key without
             * them; audit measures the scene keys alone. */
            size_t n = status == SC_OK ? strlen(key[0].text) : 0;
            if (drawing_keys && n > 14 && !strcmp(key[0].text + n - 14, "-out.shade.aov")) {
                desc.outputs = SC_OUTPUT_SHADE;
                status = sc_query_surface_key(scene, s, &desc, &key[nkeys], &err);
                nkeys += status == SC_OK;
            }
            for (int i = 0; i < nkeys && status == SC_OK; i++) {
                add_key(set, &key[i]);
                /* Small hulls go through candidate lists by default, with
                 * programs of their own; a folder without them draws those
                 * hulls as hulls. */
                sc_key listed;
                if (drawing_keys) {
                    status = sc_make_key(&(sc_key_desc){.like = key[i].text, .lists = 1}, &listed,
                                         &err);
                    if (status == SC_OK)
                        add_key(set, &listed);
                }
            }
        }
    sc_destroy_scene(scene);
    return status == SC_OK ? 0 : cli_report(&err);
}

/* The keys of every degree pair in LO..HI, rational and not, each at
 * every iteration count. Returns 0, or 2 after printing a usage error. */
static int add_family_keys(const char *cmd, const char *family, const char *like,
                           const int *iters, int niters, gen_keys *set)
{
    int lo, hi, used = 0;
    if (sscanf(family, "%d..%d%n", &lo, &hi, &used) != 2 || family[used] || lo < 1 || hi < lo ||
        hi > SC_MAX_DEGREE)
        return cli_usage_error(cmd, "--family wants LO..HI with 1 <= LO <= HI <= %d",
                               SC_MAX_DEGREE);
    for (int du = lo; du <= hi; du++)
        for (int dv = lo; dv <= hi; dv++)
            for (int rational = 0; rational < 2; rational++)
                for (int k = 0; k < niters; k++) {
                    sc_key key;
                    sc_key_desc desc = {.like = like, .deg_u = du, .deg_v = dv,
                                        .rational = rational ? 1 : 2, .max_iters = iters[k]};
                    sc_error err = {0};
                    if (sc_make_key(&desc, &key, &err) != SC_OK)
                        return cli_report(&err);
                    add_key(set, &key);
                }
    return 0;
}

int gen_parse_keys(const char *cmd, int argc, char **argv, gen_keys *set, int *first_other)
{
    memset(set, 0, sizeof *set);
    const char *like = NULL, *scene_path = NULL, *family = NULL;
    int iters[SC_MAX_ITERS], niters = 0, iters_given = 0;
    char **given = calloc((size_t)argc, sizeof *given);
    int ngiven = 0, status = 0;
    sc_error err = {0};
    sc_key like_key;
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
            if (sc_make_key(&(sc_key_desc){.like = argv[i + 1]}, &like_key, &err) != SC_OK) {
                fprintf(stderr, "splinecast %s: --like: %s\n", cmd, err.message);
                status = 2;
            }
            like = like_key.text;
            i += 2;
        } else if (!strcmp(arg, "--iters") && i + 1 < argc) {
            niters = parse_iters(argv[i + 1], iters, SC_MAX_ITERS);
            iters_given = 1;
            if (niters < 0)
                status = cli_usage_error(cmd, "--iters wants counts 1..%d joined by ','",
                                         SC_MAX_ITERS);
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
    /* Without --iters, each key keeps like's count (0: as in like). */
    if (status == 0 && niters == 0)
        iters[niters++] = 0;

    for (int g = 0; g < ngiven && status == 0; g++) {
        sc_key key;
        if (sc_make_key(&(sc_key_desc){.like = given[g]}, &key, &err) != SC_OK) {
            fprintf(stderr, "splinecast %s: %s\n", cmd, err.message);
            status = 2;
        } else {
            add_key(set, &key);
        }
    }
    if (status == 0 && scene_path)
        status = add_scene_keys(scene_path, like, iters, niters, !strcmp(cmd, "gen"), set);
    if (status == 0 && family)
        status = add_family_keys(cmd, family, like, iters, niters, set);
    if (status == 0 && iters_given && ngiven > 0) {
        /* --iters with --key: every given key at every count. */
        gen_keys expanded = {0};
        for (int g = 0; g < set->count && status == 0; g++)
            for (int k = 0; k < niters && status == 0; k++) {
                sc_key key;
                sc_key_desc desc = {.like = set->keys[g].text, .max_iters = iters[k]};
                if (sc_make_key(&desc, &key, &err) != SC_OK)
                    status = cli_report(&err);
                else
                    add_key(&expanded, &key);
            }
        free(set->keys);
        *set = expanded;
    }
    free(given);
    if (status != 0) {
        free(set->keys);
        memset(set, 0, sizeof *set);
    }
    return status;
}

/* ---- writing ---- */

/* Creates dir and any missing parents, as mkdir -p. */
static int ensure_dir(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s", dir);
    for (char *p = path + 1;; p++) {
        int last = *p == 0;
        if (*p != '/' && !last)
            continue;
        *p = 0;
        struct stat st;
        if (stat(path, &st) != 0 && mkdir(path, 0777) != 0 && errno != EEXIST) {
            fprintf(stderr, "%s: cannot create the directory: %s\n", path, strerror(errno));
            return 1;
        }
        if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
            fprintf(stderr, "%s: not a directory\n", path);
            return 1;
        }
        if (last)
            return 0;
        *p = '/';
    }
}

/* One file of the output, its `FILE BYTES` line printed once written. */
static int write_one(const char *path, const char *text, size_t size, int *files)
{
    sc_error err = {0};
    if (sc_save_text(path, text, size, &err) != SC_OK)
        return cli_report(&err);
    printf("%s %zu\n", path, size);
    (*files)++;
    return 0;
}

/* The file extensions are the stage names of the manifest. */
static const char frag[] = "frag", vert[] = "vert";

/* Writes every program and the manifest; returns 0 or 1 after printing why. */
static int write_outputs(const char *dir, const sc_glsl *glsl, int count, int *files)
{
    /* The longest name: DIR/KEY.frag; a longer DIR would be cut silently. */
    if (strlen(dir) + SC_KEY_SIZE + 8 > 1024) {
        fprintf(stderr, "%s: output directory name too long (at most %d characters)\n", dir,
                1024 - SC_KEY_SIZE - 8);
        return 1;
    }
    if (ensure_dir(dir))
        return 1;
    char path[1024];
    char *manifest = NULL;
    size_t manifest_size = 0;
    FILE *m = open_memstream(&manifest, &manifest_size);
    if (!m) {
        fprintf(stderr, "splinecast gen: out of memory\n");
        return 1;
    }
    fprintf(m, "key\tstage\tfile\tbytes\n");
    int status = 0;
    *files = 0;
    for (int i = 0; i < count && status == 0; i++) {
        const sc_glsl *g = &glsl[i];
        fprintf(m, "%s\t%s\t%s.%s\t%zu\n", g->key, frag, g->key, frag, g->fragment_size);
        fprintf(m, "%s\t%s\t%s.%s\t%zu\n", g->key, vert, g->vertex_name, vert, g->vertex_size);
        snprintf(path, sizeof path, "%s/%s.%s", dir, g->key, frag);
        status = write_one(path, g->fragment, g->fragment_size, files);
        int vertex_written = 0;
        for (int j = 0; j < i; j++)
            vertex_written |= !strcmp(glsl[j].vertex_name, g->vertex_name);
        if (status == 0 && !vertex_written) {
            snprintf(path, sizeof path, "%s/%s.%s", dir, g->vertex_name, vert);
            status = write_one(path, g->vertex, g->vertex_size, files);
        }
    }
    fclose(m);
    if (status == 0) {
        snprintf(path, sizeof path, "%s/manifest.tsv", dir);
        status = write_one(path, manifest, manifest_size, files);
    }
    free(manifest);
    return status;
}

/* The IR listing of every stage of every key, for --dump-ir. */
static int dump_ir(const gen_keys *set)
{
    int failures = 0;
    for (int k = 0; k < set->count; k++) {
        sc_error err = {0};
        if (sc_dump_ir(set->keys[k].text, stdout, &err) != SC_OK) {
            cli_report(&err);
            failures++;
        }
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
    sc_glsl *glsl = calloc(set.count > 0 ? (size_t)set.count : 1, sizeof *glsl);
    int failures = 0;
    for (int k = 0; k < set.count; k++) {
        sc_error err = {0};
        if (sc_generate_glsl(&(sc_glsl_desc){.key = set.keys[k].text}, &glsl[k], &err) != SC_OK) {
            cli_report(&err);
            failures++;
        }
    }
    double elapsed = sc_now() - t0;
    fprintf(stderr, "splinecast gen: %d keys generated and validated in %.3f s\n",
            set.count - failures, elapsed);
    int files = 0;
    if (!failures) {
        if (write_outputs(dir, glsl, set.count, &files))
            failures++;
        else
            printf("keys %d files %d\n", set.count, files);
    } else {
        fprintf(stderr, "splinecast gen: %d of %d keys failed; nothing written\n", failures,
                set.count);
    }
    for (int k = 0; k < set.count; k++)
        sc_free_glsl(&glsl[k]);
    free(glsl);
    free(set.keys);
    return failures ? 1 : 0;
}
