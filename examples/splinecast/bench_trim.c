/* bench_trim.c — `splinecast bench --trim-table`: the cost of exact
 * trimming on the GPU, in the setting of Pabst et al. 2006, Table 4: one
 * bicubic patch filling the whole image (every pixel runs the intersection
 * program), at most 4 Newton iterations, 4 × 4 uniform sub-patches, with
 * 0, 2, 8 and 9 trim curves, and beyond the paper with polygons of 100 and
 * 1000 pieces. For each trim and method (clip, left, fast) the frame time is
 * taken in the same rounds as the untrimmed patch's, renderer after
 * renderer, so that the ratio trimmed / untrimmed is measured on one
 * machine state; the ratio is what the table reports, per image size.
 * It uses the library as any program would (splinecast.h alone): the
 * scenes go in as OBJ text, the piece counts come from
 * sc_query_surface_trim. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "splinecast.h"

#include "commands.h"
#include "options.h"

static const char usage[] =
    "usage: splinecast bench --trim-table [options]\n"
    "\n"
    "Times one bicubic patch filling the image, untrimmed and with each trim\n"
    "(2, 8 and 9 cubic curves as in Pabst et al. 2006 Table 4; polygons of 100\n"
    "and 1000 pieces) and each trim method, and prints per image size:\n"
    "  trim shape=S curves=C pieces=P method=M size=N frame_ms=T untrimmed_ms=U\n"
    "       ratio=R covered=K\n"
    "(frame_ms and untrimmed_ms: medians of the timed frames, taken in the same\n"
    "rounds; ratio = frame_ms / untrimmed_ms; covered: pixels kept), then the\n"
    "table of ratios, one `table` line per trim and method.\n"
    "\n"
    "options:\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n"
    "  --sizes N,N,...        square image sizes (default 400,600,800,1000)\n"
    "  --frames N             timed frames per renderer and size (default 5)\n"
    "  --methods M,M,...      trim methods among clip, left, fast[:ITERS]\n"
    "                         (default clip,left,fast)\n"
    "  --trims T,T,...        among 2, 8, 9, 100p, 1000p (default all)\n"
    "  --iters N              Newton iterations at most (default 4, as the paper)\n"
    "  --hull uniform:N|adaptive:TOL   proxy hulls (default uniform:4, as the paper)\n";

enum { MAX_SIZES = 8, MAX_METHODS = 3, MAX_TRIMS = 5 };

typedef enum trim_shape { TRIM_TWO, TRIM_EIGHT, TRIM_NINE, TRIM_POLY100, TRIM_POLY1000 } trim_shape;

static const struct {
    const char *option;      /* --trims name */
    const char *name;        /* shape= */
    int curves;              /* trim curves (line segments for the polygons) */
} shapes[MAX_TRIMS] = {
    {"2", "oval", 2},
    {"8", "diamond", 8},
    {"9", "pentagon", 9},
    {"100p", "poly100", 102},
    {"1000p", "poly1000", 1002},
};

/* ---- the patch and its trims, in the unit parameter domain ----
 *
 * Each scene is written as OBJ free-form text (docs/formats.md) and read
 * back by sc_make_scene, as any program would give the library a trimmed
 * surface. Numbers are printed with 17 digits, which read back to the same
 * doubles, so the scene is the one built in memory before. Trim curves come
 * first: a `trim` or `hole` statement may only name curves already read. */

typedef struct obj_text {
    FILE *f;
    int vps;                 /* vp statements so far (curv2 indices count them) */
    int curves;              /* curv2 statements so far */
    int nloops;
    struct {
        int is_hole, first, count;   /* curves first .. first + count - 1 */
        int end;                     /* each curve's parameter range: [0, end] */
    } loops[2];
} obj_text;

static void begin_loop(obj_text *o, int is_hole, int ncurves, int end)
{
    o->loops[o->nloops].end = end;
    o->loops[o->nloops].is_hole = is_hole;
    o->loops[o->nloops].first = o->curves + 1;
    o->loops[o->nloops++].count = ncurves;
}

/* One non-rational B-spline curv2 through `n` points with knots `knots`. */
static void write_curve(obj_text *o, const double (*pts)[2], int n, int degree,
                        const double *knots)
{
    for (int i = 0; i < n; i++)
        fprintf(o->f, "vp %.17g %.17g\n", pts[i][0], pts[i][1]);
    fprintf(o->f, "cstype bspline\ndeg %d\ncurv2", degree);
    for (int i = 0; i < n; i++)
        fprintf(o->f, " %d", o->vps + 1 + i);
    fputs("\nparm u", o->f);
    for (int i = 0; i < n + degree + 1; i++)
        fprintf(o->f, " %.17g", knots[i]);
    fputs("\nend\n", o->f);
    o->vps += n;
    o->curves++;
}

/* A closed polygon as one degree-1 B-spline: knots 0 0 1 … n-1 n n. */
static void add_polygon(obj_text *o, int is_hole, const double (*pts)[2], int n)
{
    begin_loop(o, is_hole, 1, n);
    double(*closed)[2] = malloc((size_t)(n + 1) * sizeof *closed);
    double *knots = malloc((size_t)(n + 3) * sizeof *knots);
    for (int i = 0; i <= n; i++)
        memcpy(closed[i], pts[i % n], sizeof closed[i]);
    for (int i = 0; i <= n + 2; i++)
        knots[i] = i == 0 ? 0.0 : i > n ? (double)n : (double)(i - 1);
    write_curve(o, (const double(*)[2])closed, n + 1, 1, knots);
    free(knots);
    free(closed);
}

/* A loop of cubic Bézier curves through the corners pts; each edge's inner
 * control points are pushed sideways by bulge1, bulge2 times its length
 * (equal: an arch; opposite: an S-wave). */
static void add_cubic_loop(obj_text *o, int is_hole, const double (*pts)[2], int n,
                           double bulge1, double bulge2)
{
    static const double bezier_knots[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    begin_loop(o, is_hole, n, 1);
    for (int k = 0; k < n; k++) {
        const double *a = pts[k], *b = pts[(k + 1) % n];
        double dx = b[0] - a[0], dy = b[1] - a[1];
        double ctrl[4][2] = {{a[0], a[1]},
                             {a[0] + dx / 3 - bulge1 * dy, a[1] + dy / 3 + bulge1 * dx},
                             {a[0] + 2 * dx / 3 - bulge2 * dy, a[1] + 2 * dy / 3 + bulge2 * dx},
                             {b[0], b[1]}};
        write_curve(o, (const double(*)[2])ctrl, 4, 3, bezier_knots);
    }
}

/* A bicubic bump over [-1, 1]² (the example scenes' surface: corners 0,
 * edges 0.1, inner points 0.5), parameters [0, 1]², bounded by the loops
 * written before it. */
static void write_bump(obj_text *o)
{
    static const double height[4] = {0.0, 0.1, 0.1, 0.0};
    fputs("o bump\n", o->f);
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            int inner = (i == 1 || i == 2) && (j == 1 || j == 2);
            fprintf(o->f, "v %.17g %.17g %.17g\n", -1 + 2.0 * i / 3, -1 + 2.0 * j / 3,
                    inner ? 0.5 : height[i] + height[j]);
        }
    fputs("cstype bspline\ndeg 3 3\nsurf 0 1 0 1", o->f);
    for (int k = 1; k <= 16; k++)
        fprintf(o->f, " %d", k);
    fputs("\nparm u 0 0 0 0 1 1 1 1\nparm v 0 0 0 0 1 1 1 1\n", o->f);
    for (int l = 0; l < o->nloops; l++) {
        fputs(o->loops[l].is_hole ? "hole" : "trim", o->f);
        for (int c = 0; c < o->loops[l].count; c++)
            fprintf(o->f, " 0 %d %d", o->loops[l].end, o->loops[l].first + c);
        fputc('\n', o->f);
    }
    fputs("end\n", o->f);
}
static const double outer_square[4][2] = {{0.05, 0.05}, {0.95, 0.05}, {0.95, 0.95}, {0.05, 0.95}};

/* The trims: an oval hole of 2 arches; an outer loop of 4 waves with a
 * diamond hole of 4; the same outer loop with a rounded pentagon of 5 (the
 * example trim_nine.obj); a square with a wavy polygon hole of 98 or 998
 * edges (100 or 1000 pieces with the square's two vertical edges). */
static void write_shape(obj_text *o, trim_shape shape)
{
    switch (shape) {
    case TRIM_TWO: {
        static const double ends[2][2] = {{0.2, 0.5}, {0.8, 0.5}};
        add_cubic_loop(o, 1, ends, 2, 0.5, 0.5);
        break;
    }
    case TRIM_EIGHT: {
        static const double diamond[4][2] = {{0.5, 0.2}, {0.8, 0.5}, {0.5, 0.8}, {0.2, 0.5}};
        add_cubic_loop(o, 0, outer_square, 4, 0.06, -0.06);
        add_cubic_loop(o, 1, diamond, 4, -0.1, 0.1);
        break;
    }
    case TRIM_NINE: {
        double penta[5][2];
        for (int k = 0; k < 5; k++) {
            double a = 2 * M_PI * k / 5 + 0.3;
            penta[k][0] = 0.5 + 0.28 * cos(a);
            penta[k][1] = 0.5 + 0.28 * sin(a);
        }
        add_cubic_loop(o, 0, outer_square, 4, 0.06, -0.06);
        add_cubic_loop(o, 1, (const double(*)[2])penta, 5, -0.15, 0.15);
        break;
    }
    case TRIM_POLY100:
    case TRIM_POLY1000: {
        int n = shape == TRIM_POLY100 ? 98 : 998;
        double(*pts)[2] = malloc((size_t)n * sizeof *pts);
        for (int k = 0; k < n; k++) {
            double a = 2 * M_PI * k / n, r = 0.3 + 0.08 * sin(7 * a) + 0.03 * sin(23 * a);
            pts[k][0] = 0.5 + r * cos(a);
            pts[k][1] = 0.5 + r * sin(a);
        }
        add_polygon(o, 0, outer_square, 4);
        add_polygon(o, 1, (const double(*)[2])pts, n);
        free(pts);
        break;
    }
    }
}

/* The bump with the trims of `shape`, or untrimmed when shape < 0. */
static int make_bump_scene(int shape, sc_scene_id *out, sc_error *err)
{
    char *text = NULL;
    size_t size = 0;
    obj_text o = {.f = open_memstream(&text, &size)};
    if (!o.f) {
        snprintf(err->message, sizeof err->message, "out of memory writing the bench scene");
        return SC_FAIL;
    }
    if (shape >= 0)
        write_shape(&o, (trim_shape)shape);
    write_bump(&o);
    fclose(o.f);
    char name[64];
    snprintf(name, sizeof name, "%s.obj", shape >= 0 ? shapes[shape].name : "bump");
    int status = sc_make_scene(&(sc_scene_desc){.text = text, .size = size, .name = name}, out,
                               err);
    free(text);
    return status;
}

/* ---- timing ---- */

static long covered_pixels(sc_renderer_id r, sc_error *err)
{
    sc_frame_id frame;
    sc_frame_info info;
    if (sc_read_frame(r, &frame, err) != SC_OK)
        return -1;
    long covered = -1;
    if (sc_query_frame_info(frame, &info, err) == SC_OK) {
        covered = 0;
        for (int p = 0; p < info.width * info.height; p++)
            covered += info.surface[p] >= 0;
    }
    sc_destroy_frame(frame);
    return covered;
}

/* Draws every renderer once (warm-up: targets, the driver's deferred
 * compilation), then `frames` rounds of one frame each, in turn, and
 * stores each renderer's median. */
static int time_round_robin(const sc_renderer_id *r, int n, const sc_camera_desc *cam,
                            int frames, double *median_ms, sc_error *err)
{
    double *times = calloc((size_t)n * (size_t)frames, sizeof *times);
    int status = SC_OK;
    for (int k = 0; k < n && status == SC_OK; k++)
        status = sc_draw(r[k], cam, err);
    for (int f = 0; f < frames && status == SC_OK; f++)
        for (int k = 0; k < n && status == SC_OK; k++) {
            double t0 = sc_now();
            status = sc_draw(r[k], cam, err);
            times[k * frames + f] = 1e3 * (sc_now() - t0);
        }
    for (int k = 0; k < n && status == SC_OK; k++)
        median_ms[k] = cli_median(times + k * frames, frames);
    free(times);
    return status;
}

/* ---- options ---- */

typedef struct options {
    sc_context_desc context;
    sc_renderer_desc desc;
    int sizes[MAX_SIZES], nsizes;
    int frames;
    sc_trim_method methods[MAX_METHODS];
    int method_iters[MAX_METHODS];
    int nmethods;
    trim_shape trims[MAX_TRIMS];
    int ntrims;
} options;

/* Splits a comma list into at most `max` items of `size` bytes each. */
static int split_list(const char *text, char (*items)[32], int max)
{
    int n = 0;
    const char *p = text;
    while (*p) {
        const char *comma = strchr(p, ',');
        size_t len = comma ? (size_t)(comma - p) : strlen(p);
        if (n == max || len == 0 || len >= 32)
            return -1;
        memcpy(items[n], p, len);
        items[n++][len] = 0;
        p += len + (comma ? 1 : 0);
        if (comma && !*p)
            return -1;
    }
    return n;
}

static int parse_options(int argc, char **argv, options *o)
{
    static const int default_sizes[] = {400, 600, 800, 1000};
    memset(o, 0, sizeof *o);
    o->nsizes = 4;
    memcpy(o->sizes, default_sizes, sizeof default_sizes);
    o->frames = 5;
    o->nmethods = 3;
    o->methods[0] = SC_TRIM_CLIP;
    o->methods[1] = SC_TRIM_LEFT;
    o->methods[2] = SC_TRIM_FAST;
    o->ntrims = MAX_TRIMS;
    for (int t = 0; t < MAX_TRIMS; t++)
        o->trims[t] = (trim_shape)t;
    o->desc.max_iters = 4;
    o->desc.hull_split = SC_SPLIT_UNIFORM;
    o->desc.hull_divisions = 4;
    /* Each renderer compiles its programs, as one made alone would. */
    o->desc.own_programs = 1;
    sc_error err = {0};
    char items[MAX_SIZES][32];
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (!strcmp(a, "--trim-table")) {
            continue;
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &o->context.backend, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (!strcmp(a, "--sizes") && next) {
            int n = split_list(argv[++i], items, MAX_SIZES);
            for (int k = 0; k < n; k++) {
                long v = strtol(items[k], &end, 10);
                if (*end || v < 16 || v > 4096)
                    n = -1;
                else
                    o->sizes[k] = (int)v;
            }
            if (n <= 0)
                return cli_usage_error("bench", "--sizes takes up to %d sizes of 16 to 4096 "
                                       "separated by commas, not '%s'", MAX_SIZES, argv[i]);
            o->nsizes = n;
        } else if (!strcmp(a, "--frames") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000)
                return cli_usage_error("bench", "--frames takes 1 to 1000, not '%s'", argv[i]);
            o->frames = (int)n;
        } else if (!strcmp(a, "--methods") && next) {
            int n = split_list(argv[++i], items, MAX_METHODS);
            if (n <= 0)
                return cli_usage_error("bench", "--methods takes up to 3 of clip, left, "
                                       "fast[:ITERS], not '%s'", argv[i]);
            for (int k = 0; k < n; k++) {
                o->method_iters[k] = 0;
                if (cli_trim_parse(items[k], &o->methods[k], &o->method_iters[k], &err) !=
                    SC_OK)
                    return cli_usage_error("bench", "--methods: %s", err.message);
            }
            o->nmethods = n;
        } else if (!strcmp(a, "--trims") && next) {
            int n = split_list(argv[++i], items, MAX_TRIMS);
            for (int k = 0; k < n; k++) {
                int found = -1;
                for (int t = 0; t < MAX_TRIMS; t++)
                    if (!strcmp(items[k], shapes[t].option))
                        found = t;
                if (found < 0)
                    n = -1;
                else
                    o->trims[k] = (trim_shape)found;
            }
            if (n <= 0)
                return cli_usage_error("bench", "--trims takes some of 2, 8, 9, 100p, 1000p "
                                       "separated by commas, not '%s'", argv[i]);
            o->ntrims = n;
        } else if (!strcmp(a, "--iters") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > SC_MAX_ITERS)
                return cli_usage_error("bench", "--iters takes 1 to %d, not '%s'",
                                       SC_MAX_ITERS, argv[i]);
            o->desc.max_iters = (int)n;
        } else if (!strcmp(a, "--hull") && next) {
            if (cli_hulls_parse(argv[++i], &o->desc.hull_split, &o->desc.hull_divisions,
                                &o->desc.hull_tolerance, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else {
            return cli_usage_error("bench", "--trim-table: unexpected argument '%s'", a);
        }
    }
    return 0;
}

static const char *method_name(sc_trim_method m)
{
    return m == SC_TRIM_CLIP ? "clip" : m == SC_TRIM_LEFT ? "left" : "fast";
}

/* ---- the table ---- */

typedef struct row {
    trim_shape shape;
    int pieces;
    char method[16];
    double ratio[MAX_SIZES];
} row;

/* One trim: a renderer per method beside the untrimmed one, timed in the
 * same rounds at every size. */
static int bench_shape(sc_context_id ctx, const options *o, sc_scene_id untrimmed,
                       trim_shape shape, row *rows, double *untrimmed_ms, sc_error *err)
{
    sc_scene_id scene;
    if (make_bump_scene((int)shape, &scene, err) != SC_OK)
        return SC_FAIL;
    sc_surface_trim_info trim;
    int status = sc_query_surface_trim(scene, 0, &trim, err);
    if (status == SC_OK)
        fprintf(stderr, "bench: %s trim block: %d loops, %d pieces, %d x %d cells, %d entries, "
                "%zu bytes\n", shapes[shape].name, trim.loops, trim.pieces, trim.grid_u,
                trim.grid_v, trim.entries, trim.bytes);
    sc_renderer_id r[1 + MAX_METHODS] = {{0}};
    int n = 1 + o->nmethods;
    if (status == SC_OK)
        status = sc_make_renderer(ctx, untrimmed, &o->desc, &r[0], err);
    for (int m = 0; m < o->nmethods && status == SC_OK; m++) {
        sc_renderer_desc desc = o->desc;
        desc.trim = o->methods[m];
        desc.trim_iters = o->method_iters[m];
        status = sc_make_renderer(ctx, scene, &desc, &r[1 + m], err);
        sc_key key;
        int nkeys;
        /* One surface: the renderer's one key. */
        if (status == SC_OK)
            status = sc_query_renderer_keys(r[1 + m], &key, 1, &nkeys, err);
        if (status == SC_OK)
            fprintf(stderr, "bench: %s with %s\n", shapes[shape].name, key.text);
    }
    for (int z = 0; z < o->nsizes && status == SC_OK; z++) {
        sc_camera_desc cam = {.eye = {0, 0, 3}, .target = {0, 0, 0}, .fovy_deg = 33,
                              .width = o->sizes[z], .height = o->sizes[z]};
        double ms[1 + MAX_METHODS];
        status = time_round_robin(r, n, &cam, o->frames, ms, err);
        for (int k = 0; k < n && status == SC_OK; k++) {
            long covered = covered_pixels(r[k], err);
            if (covered < 0) {
                status = SC_FAIL;
                break;
            }
            if (k == 0) {
                untrimmed_ms[z] = ms[0];
                printf("trim shape=none curves=0 pieces=0 method=none size=%d frame_ms=%.2f "
                       "untrimmed_ms=%.2f ratio=1.00 covered=%ld\n",
                       o->sizes[z], ms[0], ms[0], covered);
                continue;
            }
            row *rw = &rows[k - 1];
            rw->shape = shape;
            rw->pieces = trim.pieces;
            if (o->method_iters[k - 1])
                snprintf(rw->method, sizeof rw->method, "%s:%d", method_name(o->methods[k - 1]),
                         o->method_iters[k - 1]);
            else
                snprintf(rw->method, sizeof rw->method, "%s", method_name(o->methods[k - 1]));
            rw->ratio[z] = ms[k] / ms[0];
            printf("trim shape=%s curves=%d pieces=%d method=%s size=%d frame_ms=%.2f "
                   "untrimmed_ms=%.2f ratio=%.2f covered=%ld\n",
                   shapes[shape].name, shapes[shape].curves, trim.pieces, rw->method,
                   o->sizes[z], ms[k], ms[0], rw->ratio[z], covered);
        }
        fflush(stdout);
    }
    for (int k = 0; k < n; k++)
        sc_destroy_renderer(r[k]);
    sc_destroy_scene(scene);
    return status;
}

int bench_trim_table(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    options o;
    int bad = parse_options(argc, argv, &o);
    if (bad)
        return bad;
    sc_error err = {0};
    sc_context_id ctx;
    sc_context_info info;
    if (sc_make_context(&o.context, &ctx, &err) != SC_OK)
        return cli_report(&err);
    if (sc_query_context_info(ctx, &info, &err) != SC_OK) {
        sc_destroy_context(ctx);
        return cli_report(&err);
    }
    fprintf(stderr, "bench: %s\n", info.description);
    sc_scene_id untrimmed;
    int status = make_bump_scene(-1, &untrimmed, &err);
    row *rows = calloc((size_t)o.ntrims * (size_t)o.nmethods, sizeof *rows);
    double untrimmed_ms[MAX_SIZES];
    for (int t = 0; t < o.ntrims && status == SC_OK; t++)
        status = bench_shape(ctx, &o, untrimmed, o.trims[t], rows + t * o.nmethods,
                             untrimmed_ms, &err);
    if (status == SC_OK) {
        printf("table %-8s %6s %6s %-7s", "trim", "curves", "pieces", "method");
        for (int z = 0; z < o.nsizes; z++)
            printf(" %6d", o.sizes[z]);
        printf("\n");
        for (int k = 0; k < o.ntrims * o.nmethods; k++) {
            const row *rw = &rows[k];
            printf("table %-8s %6d %6d %-7s", shapes[rw->shape].name, shapes[rw->shape].curves,
                   rw->pieces, rw->method);
            for (int z = 0; z < o.nsizes; z++)
                printf(" %5.2fx", rw->ratio[z]);
            printf("\n");
        }
    }
    free(rows);
    sc_destroy_scene(untrimmed);
    sc_destroy_context(ctx);
    return status == SC_OK ? 0 : cli_report(&err);
}
