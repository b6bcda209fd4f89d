/* bench_chart.c — `splinecast bench SCENE --chart DIR` (chart.h): speed
 * against accuracy for every configuration of the ray caster and for the
 * two tessellation peers, in three views. One CSV row per view ×
 * configuration, written and flushed as it completes, progress on stderr,
 * then the chart drawn by gnuplot with the Pareto front of each panel.
 *
 * The configurations are a table of families (`families` below), each a
 * function that appends its rows; a new family (for example rows chosen
 * from an accuracy target) is one more function and one more table line,
 * and the chart gives it its own symbol without another edit. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "chart.h"
#include "commands.h"
#include "deform.h"
#include "options.h"

static const char usage[] =
    "usage: splinecast bench [SCENE] --chart DIR [options]\n"
    "\n"
    "Times every configuration of the ray caster (methods, starts, iteration\n"
    "caps, hull subdivision) and the tessellation peers (GLU's NURBS\n"
    "tessellator: glu-TOL; GL 4 tessellation shaders: tess-TOL, TOL the chordal\n"
    "tolerance in pixels: 2, 1, 0.5, 0.2, 0.1, 0.05) on SCENE (default: the\n"
    "embedded teapot) in three views, compares each with the CPU reference, and\n"
    "writes DIR/points.csv with the columns\n"
    "  " CHART_COLUMNS "\n"
    "one row per view x configuration as it completes, then DIR/chart.png and\n"
    "DIR/chart.svg (gnuplot; the script is DIR/chart.gp, the Pareto fronts\n"
    "DIR/front.csv). Views: whole (the camera), closeup8 (the same eye and\n"
    "target, the field of view / 8), deforming (every control point moves each\n"
    "frame: a travelling sine wave along z).\n"
    "  frame_ms  drawing prepared data, to GPU completion (median of frames)\n"
    "  image_ms  from the current control points to the image: ray casting\n"
    "            update + draw, GLU tessellate + upload + draw, tessellation\n"
    "            shaders extract + upload + draw (static views: no update for\n"
    "            ray casting)\n"
    "  accuracy  from a separate frame with its AOVs, against the reference\n"
    "tess-TOL rows are left out of scenes with trimmed surfaces (noted on\n"
    "stderr): the tessellation shaders do not apply trims.\n"
    "\n"
    "options:\n"
    "  --size WxH             image size (default 1024x1024)\n"
    "  --camera EX,EY,EZ,TX,TY,TZ,FOVY   the whole view (default: framing the scene)\n"
    "  --frames N             timed frames per row (default 3; fewer, at least\n"
    "                         one, once a row's frames have taken 2 s)\n"
    "  --configs LIST         only these configurations: comma list of names or\n"
    "                         families (default, newton, broyden, subdiv, bclip,\n"
    "                         hybrid, hull, accuracy, glu, tess); accuracy-PX\n"
    "                         rows choose their settings from a target of PX\n"
    "                         pixels, met in the narrowest view drawn\n"
    "  --views LIST           only these views (comma list)\n"
    "  --backend egl|osmesa   GL context (default: EGL, falling back to OSMesa)\n";

/* ---- configurations ---- */

typedef enum config_kind { KIND_RAY, KIND_GLU, KIND_TESS } config_kind;

typedef struct config {
    char name[48];
    config_kind kind;
    sc_renderer_desc desc;   /* KIND_RAY */
    double tolerance_px;     /* the peers */
} config;

typedef struct config_list {
    int count;
    config items[96];
} config_list;

static config *add(config_list *l, config_kind kind, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static config *add(config_list *l, config_kind kind, const char *fmt, ...)
{
    config *c = &l->items[l->count++];
    memset(c, 0, sizeof *c);
    c->kind = kind;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->name, sizeof c->name, fmt, ap);
    va_end(ap);
    return c;
}

static const double peer_tolerances[] = {2, 1, 0.5, 0.2, 0.1, 0.05};

static void family_default(config_list *l) { add(l, KIND_RAY, "default"); }

/* Every method with every start it takes; subdiv and bclip take none. */
static void family_methods(config_list *l)
{
    static const sc_method methods[] = {SC_METHOD_NEWTON, SC_METHOD_BROYDEN, SC_METHOD_HYBRID};
    static const sc_start starts[] = {SC_START_MID, SC_START_CPMAP, SC_START_VIEW};
    for (size_t m = 0; m < sizeof methods / sizeof methods[0]; m++)
        for (size_t s = 0; s < sizeof starts / sizeof starts[0]; s++) {
            if (methods[m] == SC_METHOD_HYBRID && starts[s] == SC_START_CPMAP)
                continue;  /* the default row */
            config *c = add(l, KIND_RAY, "%s-%s", cli_method_name(methods[m]),
                            cli_start_name(starts[s]));
            c->desc.method = methods[m];
            c->desc.start = starts[s];
        }
    add(l, KIND_RAY, "subdiv")->desc.method = SC_METHOD_SUBDIV;
    add(l, KIND_RAY, "bclip")->desc.method = SC_METHOD_BCLIP;
}

/* Iteration caps around the default (6), for Newton and the hybrid. */
static void family_iterations(config_list *l)
{
    static const int iters[] = {2, 4, 12};
    for (size_t i = 0; i < sizeof iters / sizeof iters[0]; i++) {
        config *c = add(l, KIND_RAY, "newton-cpmap-it%d", iters[i]);
        c->desc.method = SC_METHOD_NEWTON;
        c->desc.start = SC_START_CPMAP;
        c->desc.max_iters = iters[i];
        add(l, KIND_RAY, "hybrid-it%d", iters[i])->desc.max_iters = iters[i];
    }
}

/* Hull subdivision: uniform and adaptive around the default. */
static void family_hulls(config_list *l)
{
    static const int divisions[] = {1, 4};
    static const double tolerances[] = {0.01, 0.001};
    for (size_t i = 0; i < sizeof divisions / sizeof divisions[0]; i++) {
        config *c = add(l, KIND_RAY, "hull-uniform%d", divisions[i]);
        c->desc.hull_split = SC_SPLIT_UNIFORM;
        c->desc.hull_divisions = divisions[i];
    }
    for (size_t i = 0; i < sizeof tolerances / sizeof tolerances[0]; i++) {
        config *c = add(l, KIND_RAY, "hull-adaptive%g", tolerances[i]);
        c->desc.hull_split = SC_SPLIT_ADAPTIVE;
        c->desc.hull_tolerance = tolerances[i];
    }
}

/* Settings chosen from an accuracy target (docs/accuracy.md): where the
 * choice lands against the front. */
static void family_accuracy(config_list *l)
{
    static const double targets[] = {1, 0.1};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++)
        add(l, KIND_RAY, "accuracy-%g", targets[i])->desc.accuracy_px = targets[i];
}

static void family_glu(config_list *l)
{
    for (size_t i = 0; i < sizeof peer_tolerances / sizeof peer_tolerances[0]; i++)
        add(l, KIND_GLU, "glu-%g", peer_tolerances[i])->tolerance_px = peer_tolerances[i];
}

static void family_tess(config_list *l)
{
    for (size_t i = 0; i < sizeof peer_tolerances / sizeof peer_tolerances[0]; i++)
        add(l, KIND_TESS, "tess-%g", peer_tolerances[i])->tolerance_px = peer_tolerances[i];
}

/* The sweep's families, in the order their rows run. */
static void (*const families[])(config_list *) = {
    family_default, family_methods, family_iterations, family_hulls, family_accuracy,
    family_glu,     family_tess,
};

/* A config's family: its name up to the first '-'. */
static void family_of(const char *name, char *out, size_t size)
{
    size_t n = strcspn(name, "-");
    snprintf(out, size, "%.*s", (int)n, name);
}

/* True when the comma list names `name` or its family (or there is no list). */
static int selected(const char *list, const char *name)
{
    if (!list)
        return 1;
    char family[48];
    family_of(name, family, sizeof family);
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, ",");
        if ((n == strlen(name) && !strncmp(p, name, n)) ||
            (n == strlen(family) && !strncmp(p, family, n)))
            return 1;
        p += n + (p[n] == ',');
    }
    return 0;
}

/* ---- views and the deformation ---- */

enum { VIEW_WHOLE, VIEW_CLOSEUP8, VIEW_DEFORMING, VIEW_COUNT };
static const char *const view_names[VIEW_COUNT] = {"whole", "closeup8", "deforming"};

/* Time one row's timed frames may take before the next is left out (ms). */
static const double row_budget_ms = 2000;

/* The phase of the frame the accuracy of the deforming view is taken at. */
static const double accuracy_phase = 1.0;

/* ---- one row ---- */

typedef struct row {
    double frame_ms, image_ms, compile_ms;
    int frames;              /* timed */
    double tessellate_ms;    /* the peers: median over the timed frames */
    double update_ms;        /* ray casting, deforming: the sc_update_surface
                                calls of a frame, median */
    sc_comparison acc;
    size_t gpu_bytes;
    long triangles;
} row;

/* What draws a configuration: a renderer or a peer. */
typedef struct drawer {
    const config *cfg;
    sc_renderer_id renderer;
    sc_peer_id peer;
} drawer;

/* Brings the drawer's data up to the scene's current control points for
 * the view; ray casting: nothing (sc_update_surface already did). */
static int drawer_update(drawer *d, const sc_camera_desc *cam, sc_error *err)
{
    return d->cfg->kind == KIND_RAY ? SC_OK : sc_update_peer(d->peer, cam, err);
}

static int drawer_draw(drawer *d, const sc_camera_desc *cam, sc_error *err)
{
    return d->cfg->kind == KIND_RAY ? sc_draw(d->renderer, cam, err)
                                    : sc_draw_peer(d->peer, cam, err);
}

static int drawer_frame(drawer *d, const sc_camera_desc *cam, sc_frame_id *out, sc_error *err)
{
    if (drawer_draw(d, cam, err) != SC_OK)
        return SC_FAIL;
    return d->cfg->kind == KIND_RAY ? sc_read_frame(d->renderer, out, err)
                                    : sc_read_peer_frame(d->peer, out, err);
}

static void drawer_sizes(drawer *d, row *r)
{
    if (d->cfg->kind == KIND_RAY) {
        sc_renderer_info info;
        if (sc_query_renderer_info(d->renderer, &info, NULL) == SC_OK) {
            r->gpu_bytes = info.gpu_bytes;
            r->triangles = info.triangles;
        }
    } else {
        sc_peer_info info;
        if (sc_query_peer_info(d->peer, &info, NULL) == SC_OK) {
            r->gpu_bytes = info.gpu_bytes;
            r->triangles = info.triangles;
        }
    }
}

/* Times one view: frame_ms from draws of prepared data, image_ms from the
 * control points to the image (deforming: the points move before every
 * frame; ray casting's update is sc_update_surface itself, the peers'
 * their own update after it), then the accuracy frame. */
static int measure(drawer *d, sc_scene_id scene, const deformation *def, int view,
                   const sc_camera_desc *cam, sc_frame_id reference, int frames, row *r,
                   sc_error *err)
{
    double *draw = calloc((size_t)frames, sizeof(double));
    double *image = calloc((size_t)frames, sizeof(double));
    double *tessellate = calloc((size_t)frames, sizeof(double));
    double *update = calloc((size_t)frames, sizeof(double));
    int ray = d->cfg->kind == KIND_RAY, status = SC_OK, timed = 0, drawn = 0;
    /* Frames beyond the first stop once a row has spent its time budget:
     * a configuration whose frame takes seconds (subdivision at 1024²)
     * gets the median of fewer frames, not minutes. */
    double spent = 0;
    for (; timed < frames && status == SC_OK && (timed == 0 || spent < row_budget_ms); timed++) {
        double t0 = sc_now();
        if (view == VIEW_DEFORMING)
            status = deform(scene, def, 2 * M_PI * (timed + 1) / 16.0, err);
        double t1 = sc_now();
        update[timed] = 1e3 * (t1 - t0);
        if (status == SC_OK && (view == VIEW_DEFORMING || !ray))
            status = drawer_update(d, cam, err);
        double t2 = sc_now();
        sc_peer_info info;
        if (status == SC_OK && !ray && sc_query_peer_info(d->peer, &info, err) == SC_OK)
            tessellate[timed] = info.tessellate_ms;
        if (status == SC_OK)
            status = drawer_draw(d, cam, err);
        double t3 = sc_now();
        draw[timed] = 1e3 * (t3 - t2);
        image[timed] = 1e3 * (t3 - (ray ? t0 : t1));
        spent += 1e3 * (t3 - t0);
    }
    /* The peers' static frame time: draws of the data prepared above. */
    for (; drawn < timed && status == SC_OK && !ray && view != VIEW_DEFORMING; drawn++) {
        double t0 = sc_now();
        status = drawer_draw(d, cam, err);
        draw[drawn] = 1e3 * (sc_now() - t0);
    }
    if (status == SC_OK) {
        r->frame_ms = cli_median(draw, timed);
        r->image_ms = cli_median(image, timed);
        r->tessellate_ms = cli_median(tessellate, timed);
        r->update_ms = cli_median(update, timed);
        r->frames = timed;
    }
    free(draw);
    free(image);
    free(tessellate);
    free(update);
    if (status == SC_OK && view == VIEW_DEFORMING)
        status = deform(scene, def, accuracy_phase, err);
    sc_frame_id frame = {0};
    if (status == SC_OK)
        status = drawer_update(d, cam, err);
    if (status == SC_OK)
        status = drawer_frame(d, cam, &frame, err);
    if (status == SC_OK)
        status = sc_compare_frames(reference, frame, &r->acc, err);
    sc_destroy_frame(frame);
    if (status == SC_OK)
        drawer_sizes(d, r);
    if (view == VIEW_DEFORMING) {
        sc_error ignored = {0};
        if (deform(scene, def, NAN, status == SC_OK ? err : &ignored) != SC_OK)
            status = SC_FAIL;
    }
    return status;
}

/* ---- the chart ---- */

typedef struct point {
    int view;
    char config[48];
    double frame_ms, pos, normal, fail;
} point;

/* Rows whose failures stay below this share of the reference's pixels
 * compete for the front: a configuration that drops pixels is not
 * exact wherever it still hits. */
static const double front_fail_pct = 1.0;

static int by_error(const void *a, const void *b, int normal)
{
    const point *p = a, *q = b;
    double x = normal ? p->normal : p->pos, y = normal ? q->normal : q->pos;
    if (x != y)
        return x < y ? -1 : 1;
    return p->frame_ms < q->frame_ms ? -1 : p->frame_ms > q->frame_ms;
}
static int by_pos(const void *a, const void *b) { return by_error(a, b, 0); }
static int by_normal(const void *a, const void *b) { return by_error(a, b, 1); }

/* The fronts: per view and metric, the rows no other row beats in both
 * frame time and error, in order of error. */
static int write_fronts(const char *path, point *pts, int n)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return SC_FAIL;
    fprintf(f, "view,metric,error,frame_ms,config\n");
    point *sorted = malloc((size_t)(n ? n : 1) * sizeof *sorted);
    for (int metric = 0; metric < 2; metric++)
        for (int v = 0; v < VIEW_COUNT; v++) {
            int m = 0;
            for (int i = 0; i < n; i++)
                if (pts[i].view == v && pts[i].fail <= front_fail_pct && isfinite(pts[i].pos))
                    sorted[m++] = pts[i];
            qsort(sorted, (size_t)m, sizeof *sorted, metric ? by_normal : by_pos);
            double best = INFINITY;
            for (int i = 0; i < m; i++)
                if (sorted[i].frame_ms < best) {
                    best = sorted[i].frame_ms;
                    fprintf(f, "%s,%s,%g,%g,%s\n", view_names[v], metric ? "normal" : "pos",
                            metric ? sorted[i].normal : sorted[i].pos, sorted[i].frame_ms,
                            sorted[i].config);
                }
        }
    free(sorted);
    return fclose(f) == 0 ? SC_OK : SC_FAIL;
}

/* The gnuplot script: a panel per view and metric, one symbol per family
 * present, the front as a line. Errors of exactly 0 sit at the axis's
 * floor so that the log scale can show them. */
static int write_script(const char *dir, const char *scene, const char *families_text,
                        const int *views, int nviews)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/chart.gp", dir);
    FILE *f = fopen(path, "w");
    if (!f)
        return SC_FAIL;
    fprintf(f, "# Drawn by splinecast bench --chart; run from anywhere: gnuplot %s\n", path);
    fprintf(f, "set datafile separator ','\n");
    fprintf(f, "points = '%s/points.csv'\nfront = '%s/front.csv'\n", dir, dir);
    fprintf(f, "floor = 1e-4\nclip(x) = x > floor ? x : floor\n");
    fprintf(f, "fam(s) = strstrt(s, '-') > 0 ? s[1:strstrt(s, '-') - 1] : s\n");
    fprintf(f, "set logscale xy\nset grid\nset key outside right top font ',8'\n");
    const char *outputs[2][2] = {{"pngcairo size 1600,%d font ',9'", "chart.png"},
                                 {"svg size 1600,%d font 'sans,9'", "chart.svg"}};
    for (int o = 0; o < 2; o++) {
        fprintf(f, "set terminal ");
        fprintf(f, outputs[o][0], 420 * nviews);
        /* Names are printed as they are: no '_' subscripts. */
        fprintf(f, "\nset termoption noenhanced\nset output '%s/%s'\n", dir, outputs[o][1]);
        fprintf(f, "set multiplot layout %d,2 title '%s: frame time against accuracy "
                   "(line: Pareto front of rows failing <= %g %% of pixels)'\n",
                nviews, scene, front_fail_pct);
        for (int i = 0; i < nviews; i++)
            for (int metric = 0; metric < 2; metric++) {
                const char *view = view_names[views[i]];
                int col = metric ? 9 : 7;
                fprintf(f, "set title '%s'\n", view);
                fprintf(f, "set xlabel '%s'\nset ylabel 'frame ms'\n",
                        metric ? "normal error p99 (degrees)" : "position error p99 (pixels)");
                fprintf(f, "plot front using (strcol(1) eq '%s' && strcol(2) eq '%s' ? "
                           "clip($3) : NaN):4 with lines lc 'black' dt 2 title 'front'",
                        view, metric ? "normal" : "pos");
                int k = 0;
                for (const char *p = families_text; *p; k++) {
                    size_t n = strcspn(p, ",");
                    fprintf(f, ", \\\n  points using (strcol(2) eq '%s' && fam(strcol(3)) eq "
                               "'%.*s' ? clip($%d) : NaN):4 with points pt %d ps 1.2 title '%.*s'",
                            view, (int)n, p, col, 1 + k % 14, (int)n, p);
                    p += n + (p[n] == ',');
                }
                fprintf(f, "\n");
            }
        fprintf(f, "unset multiplot\n");
    }
    if (fclose(f) != 0)
        return SC_FAIL;
    char cmd[8400];
    snprintf(cmd, sizeof cmd, "gnuplot '%s'", path);
    return system(cmd) == 0 ? SC_OK : SC_FAIL;
}

static void scene_name(const char *path, char *out, size_t size)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t n = strcspn(base, ".");
    snprintf(out, size, "%.*s", (int)n, base);
}

static int make_dir(const char *dir)
{
    if (mkdir(dir, 0777) == 0 || errno == EEXIST)
        return SC_OK;
    return SC_FAIL;
}

/* Runs one configuration in every view; appends its rows. */
static int run_config(sc_context_id ctx, sc_scene_id scene, const config *cfg,
                      const deformation *def, const int *views, int nviews,
                      const sc_camera_desc *cams, const sc_frame_id *refs, int frames,
                      FILE *csv, const char *name, point *pts, int *npts, int index, int total)
{
    sc_error err = {0};
    drawer d = {.cfg = cfg};
    double compile_ms = 0;
    int status = SC_OK;
    if (cfg->kind == KIND_RAY) {
        sc_renderer_desc desc = cfg->desc;
        desc.own_programs = 1;  /* compile_ms: compiling, not a cache hit */
        /* Timed as the peers are and as an application draws, the colour
         * and depth alone; the accuracy frame is read with the AOVs
         * (docs/chart.md). */
        /* One renderer serves every view: a target is met in the most
         * demanding of them, the narrowest. */
        if (desc.accuracy_px > 0) {
            desc.accuracy_view = &cams[views[0]];
            for (int v = 1; v < nviews; v++)
                if (cams[views[v]].fovy_deg < desc.accuracy_view->fovy_deg)
                    desc.accuracy_view = &cams[views[v]];
        }
        if (sc_make_renderer(ctx, scene, &desc, &d.renderer, &err) != SC_OK) {
            /* A method or start the compiler does not build (yet) is not a
             * failure of the sweep: noted, as bench --stability does. */
            fprintf(stderr, "chart: %s skipped: %s\n", cfg->name, err.message);
            return SC_OK;
        }
        sc_renderer_info info;
        if (status == SC_OK && sc_query_renderer_info(d.renderer, &info, &err) == SC_OK)
            compile_ms = info.compile_ms;
    } else {
        sc_peer_desc pd = {.kind = cfg->kind == KIND_GLU ? SC_PEER_GLU : SC_PEER_TESS_SHADER,
                           .tolerance_px = cfg->tolerance_px};
        status = sc_make_peer(ctx, scene, &pd, &d.peer, &err);
        sc_peer_info info;
        if (status == SC_OK && (status = sc_update_peer(d.peer, &cams[0], &err)) == SC_OK &&
            sc_query_peer_info(d.peer, &info, &err) == SC_OK) {
            compile_ms = info.compile_ms;
            if (cfg->kind == KIND_TESS && info.skipped_surfaces) {
                fprintf(stderr, "chart: %s left out: %d trimmed surfaces (the tessellation "
                                "shaders apply no trims)\n", cfg->name, info.skipped_surfaces);
                sc_destroy_peer(d.peer);
                return SC_OK;
            }
        }
    }
    for (int i = 0; i < nviews && status == SC_OK; i++) {
        int v = views[i];
        /* A warm-up frame: first-use costs (the programs' first draw) go to
         * compile_ms, as bench does. The peers' data is for the view, so
         * they warm up in every view; ray casting once. */
        double t0 = sc_now(), warm_up = 0;
        if (i == 0 || cfg->kind != KIND_RAY) {
            status = drawer_update(&d, &cams[v], &err);
            if (status == SC_OK)
                status = drawer_draw(&d, &cams[v], &err);
            warm_up = 1e3 * (sc_now() - t0);
        }
        row r = {0};
        if (status == SC_OK)
            status = measure(&d, scene, def, v, &cams[v], refs[v], frames, &r, &err);
        if (status != SC_OK)
            break;
        if (i == 0)
            compile_ms += fmax(warm_up - r.image_ms, 0);
        r.compile_ms = compile_ms;
        fprintf(csv, "%s,%s,%s,%.3f,%.3f,%.4f,%.4f,%.4f,%.4f,%zu,%ld,%.1f\n", name,
                view_names[v], cfg->name, r.frame_ms, r.image_ms, r.acc.fail_pct, r.acc.pos_p99_px,
                r.acc.normal_mean_deg, r.acc.normal_p99_deg, r.gpu_bytes, r.triangles,
                r.compile_ms);
        fflush(csv);
        /* The peers' image split: the median tessellation of the timed
         * frames, the accuracy frame's upload and draw; ray casting's
         * deforming rows: the median of the frames' surface updates. */
        char split[160] = "";
        sc_peer_info pi;
        if (cfg->kind != KIND_RAY && sc_query_peer_info(d.peer, &pi, NULL) == SC_OK)
            snprintf(split, sizeof split, " tessellate_ms=%.2f upload_ms=%.2f draw_ms=%.2f "
                     "vertices=%ld", r.tessellate_ms, pi.upload_ms, pi.draw_ms, pi.vertices);
        else if (cfg->kind == KIND_RAY && v == VIEW_DEFORMING)
            snprintf(split, sizeof split, " update_ms=%.2f", r.update_ms);
        fprintf(stderr, "chart: [%d/%d] %s %s frame_ms=%.2f image_ms=%.2f fail_pct=%.3f "
                        "pos_p99_px=%.3f normal_p99_deg=%.2f triangles=%ld frames=%d%s\n",
                index, total, view_names[v], cfg->name, r.frame_ms, r.image_ms, r.acc.fail_pct,
                r.acc.pos_p99_px, r.acc.normal_p99_deg, r.triangles, r.frames, split);
        pts[*npts] = (point){.view = v, .frame_ms = r.frame_ms, .pos = r.acc.pos_p99_px,
                             .normal = r.acc.normal_p99_deg, .fail = r.acc.fail_pct};
        snprintf(pts[*npts].config, sizeof pts[*npts].config, "%s", cfg->name);
        (*npts)++;
    }
    if (cfg->kind == KIND_RAY)
        sc_destroy_renderer(d.renderer);
    else
        sc_destroy_peer(d.peer);
    if (status != SC_OK) {
        fprintf(stderr, "chart: %s: ", cfg->name);
        cli_report(&err);
        return SC_FAIL;
    }
    return SC_OK;
}

int chart_run(const chart_desc *desc)
{
    const char *scene_path = desc->scene ? desc->scene : "teapot";
    int width = desc->width ? desc->width : 1024, height = desc->height ? desc->height : 1024;
    int frames = desc->frames ? desc->frames : 3;
    int views[VIEW_COUNT], nviews = 0;
    for (int v = 0; v < VIEW_COUNT; v++)
        if (selected(desc->views, view_names[v]))
            views[nviews++] = v;
    if (!nviews)
        return cli_usage_error("bench", "--views names none of whole, closeup8, deforming");
    config_list *list = calloc(1, sizeof *list), *chosen = calloc(1, sizeof *chosen);
    for (size_t i = 0; i < sizeof families / sizeof families[0]; i++)
        families[i](list);
    /* Every view has its default and glu-0.1 rows, whatever the list. */
    for (int i = 0; i < list->count; i++)
        if (selected(desc->configs, list->items[i].name) ||
            !strcmp(list->items[i].name, "default") || !strcmp(list->items[i].name, "glu-0.1"))
            chosen->items[chosen->count++] = list->items[i];
    free(list);
    if (make_dir(desc->dir) != SC_OK) {
        fprintf(stderr, "%s: cannot make the folder: %s\n", desc->dir, strerror(errno));
        free(chosen);
        return 1;
    }
    sc_error err = {0};
    sc_context_id ctx = {0};
    sc_scene_id scene = {0};
    sc_context_info ctx_info;
    sc_context_desc cd = {.backend = desc->backend};
    if (sc_make_scene(&(sc_scene_desc){.path = scene_path}, &scene, &err) != SC_OK ||
        sc_make_context(&cd, &ctx, &err) != SC_OK ||
        sc_query_context_info(ctx, &ctx_info, &err) != SC_OK) {
        sc_destroy_scene(scene);
        sc_destroy_context(ctx);
        free(chosen);
        return cli_report(&err);
    }
    char name[128];
    scene_name(scene_path, name, sizeof name);
    fprintf(stderr, "chart: %s on %s, %dx%d, %d configurations x %d views\n", name,
            ctx_info.description, width, height, chosen->count, nviews);

    /* The views: the camera given (or framing the scene), the same with a
     * field of view eight times narrower. */
    sc_camera_desc cams[VIEW_COUNT];
    sc_frame_id refs[VIEW_COUNT] = {{0}};
    deformation def = {0};
    int status = deformation_init(scene, &def, &err);
    sc_frame_id probe = {0};
    sc_frame_info probe_info;
    sc_camera_desc base = {.text = desc->camera, .width = 8, .height = 8};
    if (status == SC_OK)
        status = sc_render_reference(scene, &base, NULL, &probe, &err);
    if (status == SC_OK)
        status = sc_query_frame_info(probe, &probe_info, &err);
    if (status == SC_OK) {
        for (int v = 0; v < VIEW_COUNT; v++) {
            cams[v] = (sc_camera_desc){.fovy_deg = probe_info.fovy_deg, .width = width,
                                       .height = height};
            memcpy(cams[v].eye, probe_info.eye, sizeof cams[v].eye);
            memcpy(cams[v].target, probe_info.target, sizeof cams[v].target);
        }
        cams[VIEW_CLOSEUP8].fovy_deg /= 8;
        fprintf(stderr, "chart: camera %s (closeup8: fovy / 8)\n", probe_info.camera);
    }
    sc_destroy_frame(probe);
    for (int i = 0; i < nviews && status == SC_OK; i++) {
        int v = views[i];
        double t0 = sc_now();
        if (v == VIEW_DEFORMING)
            status = deform(scene, &def, accuracy_phase, &err);
        if (status == SC_OK)
            status = sc_render_reference(scene, &cams[v], NULL, &refs[v], &err);
        if (v == VIEW_DEFORMING && status == SC_OK)
            status = deform(scene, &def, NAN, &err);
        fprintf(stderr, "chart: reference %s %.1f s\n", view_names[v], sc_now() - t0);
    }
    char path[4096];
    FILE *csv = NULL;
    if (status == SC_OK) {
        snprintf(path, sizeof path, "%s/points.csv", desc->dir);
        if (!(csv = fopen(path, "w"))) {
            fprintf(stderr, "%s: cannot write: %s\n", path, strerror(errno));
            status = SC_FAIL;
            err.message[0] = 0;
        }
    }
    int failed = status != SC_OK;
    if (failed && err.message[0])
        cli_report(&err);
    point *pts = calloc((size_t)chosen->count * VIEW_COUNT + 1, sizeof *pts);
    int npts = 0;
    char families_text[512] = "";
    double t_start = sc_now();
    if (csv) {
        fprintf(csv, "%s\n", CHART_COLUMNS);
        fflush(csv);
        for (int i = 0; i < chosen->count; i++) {
            const config *cfg = &chosen->items[i];
            int before = npts;
            if (run_config(ctx, scene, cfg, &def, views, nviews, cams, refs, frames, csv, name,
                           pts, &npts, i + 1, chosen->count) != SC_OK)
                failed = 1;
            char family[48];
            family_of(cfg->name, family, sizeof family);
            if (npts > before && !selected(families_text[0] ? families_text : "", family)) {
                size_t len = strlen(families_text);
                snprintf(families_text + len, sizeof families_text - len, "%s%s",
                         len ? "," : "", family);
            }
        }
        fclose(csv);
        fprintf(stderr, "chart: %d rows in %.0f s\n", npts, sc_now() - t_start);
        snprintf(path, sizeof path, "%s/front.csv", desc->dir);
        if (write_fronts(path, pts, npts) != SC_OK ||
            write_script(desc->dir, name, families_text, views, nviews) != SC_OK) {
            fprintf(stderr, "%s: gnuplot could not draw the chart\n", desc->dir);
            failed = 1;
        }
    }
    free(pts);
    for (int v = 0; v < VIEW_COUNT; v++)
        sc_destroy_frame(refs[v]);
    deformation_free(&def);
    sc_destroy_scene(scene);
    sc_destroy_context(ctx);
    free(chosen);
    return failed ? 1 : 0;
}

int bench_chart(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(usage, stdout);
        return 0;
    }
    chart_desc desc = {0};
    sc_error err = {0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *next = i + 1 < argc ? argv[i + 1] : NULL;
        char *end;
        if (!strcmp(a, "--chart") && next) {
            desc.dir = argv[++i];
        } else if (!strcmp(a, "--size") && next) {
            i++;
            if (sscanf(argv[i], "%dx%d", &desc.width, &desc.height) != 2 || desc.width < 1 ||
                desc.height < 1 || desc.width > 16384 || desc.height > 16384)
                return cli_usage_error("bench", "--size takes WxH, not '%s'", argv[i]);
        } else if (!strcmp(a, "--camera") && next) {
            desc.camera = argv[++i];
            sc_camera_desc cam = {.text = desc.camera};
            if (sc_check_camera(&cam, &err) != SC_OK)
                return cli_usage_error("bench", "--camera: %s", err.message);
        } else if (!strcmp(a, "--frames") && next) {
            long n = strtol(argv[++i], &end, 10);
            if (end == argv[i] || *end || n < 1 || n > 1000)
                return cli_usage_error("bench", "--frames takes 1 to 1000, not '%s'", argv[i]);
            desc.frames = (int)n;
        } else if (!strcmp(a, "--configs") && next) {
            desc.configs = argv[++i];
        } else if (!strcmp(a, "--views") && next) {
            desc.views = argv[++i];
        } else if (!strcmp(a, "--backend") && next) {
            if (cli_backend_parse(argv[++i], &desc.backend, &err) != SC_OK)
                return cli_usage_error("bench", "%s", err.message);
        } else if (a[0] != '-' && !desc.scene) {
            desc.scene = a;
        } else {
            return cli_usage_error("bench", "--chart: unexpected argument '%s'", a);
        }
    }
    if (!desc.dir)
        return cli_usage_error("bench", "--chart takes a folder");
    return chart_run(&desc);
}
