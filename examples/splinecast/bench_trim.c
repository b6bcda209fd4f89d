/* bench_trim.c — `splinecast bench --trim-table`: the cost of exact
 * trimming on the GPU, in the setting of Pabst et al. 2006, Table 4: one
 * bicubic patch filling the whole image (every pixel runs the intersection
 * program), at most 4 Newton iterations, 4 × 4 uniform sub-patches, with
 * 0, 2, 8 and 9 trim curves, and beyond the paper with polygons of 100 and
 * 1000 pieces. For each trim and method (clip, left, fast) the frame time is
 * taken in the same rounds as the untrimmed patch's, renderer after
 * renderer, so that the ratio trimmed / untrimmed is measured on one
 * machine state; the ratio is what the table reports, per image size. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "options.h"
#include "gl_context.h"
#include "gl_render.h"
#include "trim_pack.h"

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

/* ---- the patch and its trims, in the unit parameter domain ---- */

/* A bicubic bump over [-1, 1]² (the example scenes' surface: corners 0,
 * edges 0.1, inner points 0.5), parameters [0, 1]². */
static sc_surface *add_bump(sc_scene *scene)
{
    static const double height[4] = {0.0, 0.1, 0.1, 0.0};
    sc_surface *s = sc_scene_add_surface(scene);
    snprintf(s->name, sizeof s->name, "bump");
    sc_surface_alloc(s, 3, 3, 4, 4);
    for (int k = 0; k < 8; k++)
        s->knots_u[k] = s->knots_v[k] = k < 4 ? 0.0 : 1.0;
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *cp = s->cp + 4 * (4 * j + i);
            int inner = (i == 1 || i == 2) && (j == 1 || j == 2);
            cp[0] = -1 + 2.0 * i / 3;
            cp[1] = -1 + 2.0 * j / 3;
            cp[2] = inner ? 0.5 : height[i] + height[j];
            cp[3] = 1;
        }
    sc_surface_update_rational(s);
    return s;
}

static sc_loop *add_loop(sc_surface *s, int is_hole, int ncurves)
{
    s->loops = sc_realloc(s->loops, (size_t)s->nloops + 1, sizeof *s->loops);
    sc_loop *loop = &s->loops[s->nloops++];
    loop->is_hole = is_hole;
    loop->ncurves = ncurves;
    loop->curves = sc_alloc((size_t)ncurves, sizeof *loop->curves);
    return loop;
}

/* A closed polygon as one degree-1 B-spline. */
static void add_polygon(sc_surface *s, int is_hole, const double (*pts)[2], int n)
{
    sc_curve *c = &add_loop(s, is_hole, 1)->curves[0];
    sc_curve_alloc(c, 2, 1, n + 1);
    for (int i = 0; i <= n + 2; i++)
        c->knots[i] = i == 0 ? 0.0 : i > n ? (double)n : (double)(i - 1);
    for (int i = 0; i <= n; i++) {
        c->cp[3 * i] = pts[i % n][0];
        c->cp[3 * i + 1] = pts[i % n][1];
        c->cp[3 * i + 2] = 1;
    }
}

/* A loop of cubic Bézier curves through the corners pts; each edge's inner
 * control points are pushed sideways by bulge1, bulge2 times its length
 * (equal: an arch; opposite: an S-wave). */
static void add_cubic_loop(sc_surface *s, int is_hole, const double (*pts)[2], int n,
                           double bulge1, double bulge2)
{
    sc_loop *loop = add_loop(s, is_hole, n);
    for (int k = 0; k < n; k++) {
        const double *a = pts[k], *b = pts[(k + 1) % n];
        double dx = b[0] - a[0], dy = b[1] - a[1];
        double ctrl[4][2] = {{a[0], a[1]},
                             {a[0] + dx / 3 - bulge1 * dy, a[1] + dy / 3 + bulge1 * dx},
                             {a[0] + 2 * dx / 3 - bulge2 * dy, a[1] + 2 * dy / 3 + bulge2 * dx},
                             {b[0], b[1]}};
        sc_curve *c = &loop->curves[k];
        sc_curve_alloc(c, 2, 3, 4);
        for (int i = 0; i < 8; i++)
            c->knots[i] = i < 4 ? 0.0 : 1.0;
        for (int i = 0; i < 4; i++) {
            c->cp[3 * i] = ctrl[i][0];
            c->cp[3 * i + 1] = ctrl[i][1];
            c->cp[3 * i + 2] = 1;
        }
    }
}

static const double outer_square[4][2] = {{0.05, 0.05}, {0.95, 0.05}, {0.95, 0.95}, {0.05, 0.95}};

/* The trims: an oval hole of 2 arches; an outer loop of 4 waves with a
 * diamond hole of 4; the same outer loop with a rounded pentagon of 5 (the
 * example trim_nine.obj); a square with a wavy polygon hole of 98 or 998
 * edges (100 or 1000 pieces with the square's two vertical edges). */
static void build_scene(sc_scene *scene, trim_shape shape)
{
    sc_scene_init(scene);
    sc_surface *s = add_bump(scene);
    switch (shape) {
    case TRIM_TWO: {
        static const double ends[2][2] = {{0.2, 0.5}, {0.8, 0.5}};
        add_cubic_loop(s, 1, ends, 2, 0.5, 0.5);
        break;
    }
    case TRIM_EIGHT: {
        static const double diamond[4][2] = {{0.5, 0.2}, {0.8, 0.5}, {0.5, 0.8}, {0.2, 0.5}};
        add_cubic_loop(s, 0, outer_square, 4, 0.06, -0.06);
        add_cubic_loop(s, 1, diamond, 4, -0.1, 0.1);
        break;
    }
    case TRIM_NINE: {
        double penta[5][2];
        for (int k = 0; k < 5; k++) {
            double a = 2 * M_PI * k / 5 + 0.3;
            penta[k][0] = 0.5 + 0.28 * cos(a);
            penta[k][1] = 0.5 + 0.28 * sin(a);
        }
        add_cubic_loop(s, 0, outer_square, 4, 0.06, -0.06);
        add_cubic_loop(s, 1, (const double(*)[2])penta, 5, -0.15, 0.15);
        break;
    }
    case TRIM_POLY100:
    case TRIM_POLY1000: {
        int n = shape == TRIM_POLY100 ? 98 : 998;
        double(*pts)[2] = sc_alloc((size_t)n, sizeof *pts);
        for (int k = 0; k < n; k++) {
            double a = 2 * M_PI * k / n, r = 0.3 + 0.08 * sin(7 * a) + 0.03 * sin(23 * a);
            pts[k][0] = 0.5 + r * cos(a);
            pts[k][1] = 0.5 + r * sin(a);
        }
        add_polygon(s, 0, outer_square, 4);
        add_polygon(s, 1, (const double(*)[2])pts, n);
        free(pts);
        break;
    }
    }
    sc_scene_validate_loops(scene);
}

/* ---- timing ---- */

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static long covered_pixels(sc_renderer *r, sc_error *err)
{
    sc_aov aov;
    if (sc_renderer_read(r, NULL, &aov, err) != SC_OK)
        return -1;
    long covered = 0;
    for (int p = 0; p < aov.width * aov.height; p++)
        covered += aov.surface[p] >= 0;
    sc_aov_free(&aov);
    return covered;
}

/* Draws every renderer once (warm-up: targets, the driver's deferred
 * compilation), then `frames` rounds of one frame each, in turn, and
 * stores each renderer's median. */
static int time_round_robin(sc_renderer **r, int n, const sc_camera *cam, int frames,
                            double *median_ms, sc_error *err)
{
    double *times = sc_alloc((size_t)n * (size_t)frames, sizeof *times);
    int status = SC_OK;
    for (int k = 0; k < n && status == SC_OK; k++)
        status = sc_renderer_draw(r[k], cam, err);
    for (int f = 0; f < frames && status == SC_OK; f++)
        for (int k = 0; k < n && status == SC_OK; k++) {
            double t0 = sc_now();
            status = sc_renderer_draw(r[k], cam, err);
            times[k * frames + f] = 1e3 * (sc_now() - t0);
        }
    for (int k = 0; k < n && status == SC_OK; k++)
        median_ms[k] = median(times + k * frames, frames);
    free(times);
    return status;
}

/* ---- options ---- */

typedef struct options {
    sc_gl_context_desc context;
    sc_render_desc desc;
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
    o->desc.hulls = (sc_hull_desc){.mode = SC_SPLIT_UNIFORM, .divisions = 4};
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
            if (end == argv[i] || *end || n < 1 || n > SCG_MAX_ITERS)
                return cli_usage_error("bench", "--iters takes 1 to %d, not '%s'",
                                       SCG_MAX_ITERS, argv[i]);
            o->desc.max_iters = (int)n;
        } else if (!strcmp(a, "--hull") && next) {
            if (cli_hulls_parse(argv[++i], &o->desc.hulls.mode, &o->desc.hulls.divisions,
                                &o->desc.hulls.tolerance, &err) != SC_OK)
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
static int bench_shape(const sc_gl *gl, const options *o, const sc_scene *untrimmed,
                       trim_shape shape, row *rows, double *untrimmed_ms, sc_error *err)
{
    sc_scene scene;
    build_scene(&scene, shape);
    sc_trim_block block;
    int status = sc_trim_pack(&scene.surfaces[0], sc_surface_trim_degree(&scene.surfaces[0]),
                              &block, err);
    int pieces = block.npieces;
    if (status == SC_OK)
        fprintf(stderr, "bench: %s trim block: %d loops, %d pieces, %d x %d cells, %d entries, "
                "%d bytes\n", shapes[shape].name, block.nloops, block.npieces, block.grid_u,
                block.grid_v, block.nentries, 16 * block.ntexels);
    sc_trim_block_free(&block);
    sc_renderer *r[1 + MAX_METHODS] = {0};
    int n = 1 + o->nmethods;
    if (status == SC_OK)
        status = sc_renderer_create(gl, untrimmed, &o->desc, &r[0], err);
    for (int m = 0; m < o->nmethods && status == SC_OK; m++) {
        sc_render_desc desc = o->desc;
        desc.trim_method = o->methods[m];
        desc.trim_iters = o->method_iters[m];
        status = sc_renderer_create(gl, &scene, &desc, &r[1 + m], err);
        if (status == SC_OK) {
            char key[SCG_KEY_MAX];
            scg_key_format(sc_renderer_surface_key(r[1 + m], 0), key, sizeof key);
            fprintf(stderr, "bench: %s with %s\n", shapes[shape].name, key);
        }
    }
    for (int z = 0; z < o->nsizes && status == SC_OK; z++) {
        sc_camera cam = {.eye = {0, 0, 3}, .target = {0, 0, 0}, .fovy_deg = 33,
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
            rw->pieces = pieces;
            if (o->method_iters[k - 1])
                snprintf(rw->method, sizeof rw->method, "%s:%d", method_name(o->methods[k - 1]),
                         o->method_iters[k - 1]);
            else
                snprintf(rw->method, sizeof rw->method, "%s", method_name(o->methods[k - 1]));
            rw->ratio[z] = ms[k] / ms[0];
            printf("trim shape=%s curves=%d pieces=%d method=%s size=%d frame_ms=%.2f "
                   "untrimmed_ms=%.2f ratio=%.2f covered=%ld\n",
                   shapes[shape].name, shapes[shape].curves, pieces, rw->method, o->sizes[z],
                   ms[k], ms[0], rw->ratio[z], covered);
        }
        fflush(stdout);
    }
    for (int k = 0; k < n; k++)
        sc_renderer_destroy(r[k]);
    sc_scene_free(&scene);
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
    sc_gl_context *ctx;
    if (sc_gl_context_create(&o.context, &ctx, &err) != SC_OK)
        return cli_report(&err);
    fprintf(stderr, "bench: %s\n", sc_gl_context_description(ctx));
    const sc_gl *gl = sc_gl_context_gl(ctx);
    sc_scene untrimmed;
    sc_scene_init(&untrimmed);
    add_bump(&untrimmed);
    row *rows = sc_alloc((size_t)o.ntrims * (size_t)o.nmethods, sizeof *rows);
    double untrimmed_ms[MAX_SIZES];
    int status = SC_OK;
    for (int t = 0; t < o.ntrims && status == SC_OK; t++)
        status = bench_shape(gl, &o, &untrimmed, o.trims[t], rows + t * o.nmethods,
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
    sc_scene_free(&untrimmed);
    sc_gl_context_destroy(ctx);
    return status == SC_OK ? 0 : cli_report(&err);
}
