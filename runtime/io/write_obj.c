/* write_obj.c — a scene as Wavefront OBJ free-form geometry that the OBJ
 * reader takes back bit for bit: every surface as a `cstype [rat] bspline`
 * surf with its clamped knots in parm statements, trim loops as curv2 +
 * trim/hole, names as `o`, colours as materials of a .mtl beside the file,
 * transforms baked into the control points. Both files are written to
 * temporary names and renamed, so a failure leaves no half-written output. */
#include "io.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

/* OBJ stores x y z beside the weight; the scene stores x·w. Pick the
 * double e next to X / w whose product with w rounds back to X, so that the
 * reader's e·w gives the stored coordinate exactly. Such an e exists
 * whenever X itself was a product with w (as every reader makes it); for
 * other data the nearest quotient is written, 1 ulp off at most. */
static double euclidean(double X, double w)
{
    double e = X / w;
    if (e * w == X)
        return e;
    double up = e, down = e;
    for (int i = 0; i < 4; i++) {
        up = nextafter(up, INFINITY);
        if (up * w == X)
            return up;
        down = nextafter(down, -INFINITY);
        if (down * w == X)
            return down;
    }
    return e;
}

static int any_weight_not_one(const double *cp, size_t n, int stride)
{
    for (size_t k = 0; k < n; k++)
        if (cp[k * (size_t)stride + (size_t)stride - 1] != 1.0)
            return 1;
    return 0;
}

/* Writes `values` after `head`, a few per line with continuations. */
static void write_list_double(FILE *f, const char *head, const double *values, int n)
{
    fputs(head, f);
    for (int i = 0; i < n; i++)
        fprintf(f, "%s%.17g", i && i % 8 == 0 ? " \\\n    " : " ", values[i]);
    fputc('\n', f);
}

static void write_index_run(FILE *f, const char *head, long first, int n)
{
    fputs(head, f);
    for (int i = 0; i < n; i++)
        fprintf(f, "%s%ld", i && i % 16 == 0 ? " \\\n    " : " ", first + i);
    fputc('\n', f);
}

typedef struct obj_counts {
    long vertices, pvertices, curves;
} obj_counts;

static void write_curve(FILE *f, const sc_curve *c, obj_counts *n)
{
    int rational = any_weight_not_one(c->cp, (size_t)c->ncp, 3);
    for (int i = 0; i < c->ncp; i++) {
        const double *p = c->cp + 3 * i;
        if (rational)
            fprintf(f, "vp %.17g %.17g %.17g\n", euclidean(p[0], p[2]), euclidean(p[1], p[2]),
                    p[2]);
        else
            fprintf(f, "vp %.17g %.17g\n", p[0], p[1]);
    }
    fprintf(f, "cstype %sbspline\ndeg %d\n", rational ? "rat " : "", c->degree);
    write_index_run(f, "curv2", n->pvertices + 1, c->ncp);
    write_list_double(f, "parm u", c->knots, c->ncp + c->degree + 1);
    fputs("end\n", f);
    n->pvertices += c->ncp;
    n->curves++;
}

static void write_name(FILE *f, const char *name, int index)
{
    fputs("o ", f);
    if (!name[0])
        fprintf(f, "surface%d", index);
    for (const char *p = name; *p; p++)
        fputc((unsigned char)*p <= ' ' || *p == '#' || *p == '\\' ? '_' : *p, f);
    fputc('\n', f);
}

static void write_surface(FILE *f, const sc_surface *s, int index, int material, obj_counts *n)
{
    write_name(f, s->name, index);
    fprintf(f, "usemtl color%d\n", material);
    size_t ncp = (size_t)s->nu * (size_t)s->nv;
    int rational = any_weight_not_one(s->cp, ncp, 4);
    for (size_t k = 0; k < ncp; k++) {
        const double *p = s->cp + 4 * k;
        if (rational)
            fprintf(f, "v %.17g %.17g %.17g %.17g\n", euclidean(p[0], p[3]),
                    euclidean(p[1], p[3]), euclidean(p[2], p[3]), p[3]);
        else
            fprintf(f, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
    }
    long first_curve = n->curves + 1;
    for (int l = 0; l < s->nloops; l++)
        for (int c = 0; c < s->loops[l].ncurves; c++)
            write_curve(f, &s->loops[l].curves[c], n);
    fprintf(f, "cstype %sbspline\ndeg %d %d\n", rational ? "rat " : "", s->deg_u, s->deg_v);
    char head[160];
    snprintf(head, sizeof head, "surf %.17g %.17g %.17g %.17g", s->knots_u[s->deg_u],
             s->knots_u[s->nu], s->knots_v[s->deg_v], s->knots_v[s->nv]);
    write_index_run(f, head, n->vertices + 1, (int)ncp);
    n->vertices += (long)ncp;
    write_list_double(f, "parm u", s->knots_u, s->nu + s->deg_u + 1);
    write_list_double(f, "parm v", s->knots_v, s->nv + s->deg_v + 1);
    long curve = first_curve;
    for (int l = 0; l < s->nloops; l++) {
        const sc_loop *loop = &s->loops[l];
        if (!loop->ncurves)
            continue;
        fputs(loop->is_hole ? "hole" : "trim", f);
        for (int c = 0; c < loop->ncurves; c++) {
            const sc_curve *cv = &loop->curves[c];
            fprintf(f, "%s%.17g %.17g %ld", c && c % 4 == 0 ? " \\\n    " : " ",
                    cv->knots[cv->degree], cv->knots[cv->ncp], curve++);
        }
        fputc('\n', f);
    }
    fputs("end\n", f);
}

/* Index of s's colour among the distinct colours, adding it if new. */
static int colour_index(float (*colours)[3], int *ncolours, const float c[3])
{
    for (int i = 0; i < *ncolours; i++)
        if (!memcmp(colours[i], c, sizeof colours[i]))
            return i;
    memcpy(colours[*ncolours], c, sizeof colours[0]);
    return (*ncolours)++;
}

static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};

int sc_write_obj(const char *path, const sc_scene *scene, sc_error *err)
{
    char mtl_path[1024];
    size_t len = strlen(path);
    if (len >= sizeof mtl_path - 8)
        return sc_fail(err, path, 0, "output path is too long");
    if (len > 4 && !strcasecmp(path + len - 4, ".obj"))
        snprintf(mtl_path, sizeof mtl_path, "%.*s.mtl", (int)(len - 4), path);
    else
        snprintf(mtl_path, sizeof mtl_path, "%s.mtl", path);
    const char *mtl_base = strrchr(mtl_path, '/') ? strrchr(mtl_path, '/') + 1 : mtl_path;

    float (*colours)[3] = sc_alloc((size_t)scene->nsurfaces + 1, sizeof *colours);
    int *material = sc_alloc((size_t)scene->nsurfaces + 1, sizeof(int));
    int ncolours = 0;
    for (int i = 0; i < scene->nsurfaces; i++)
        material[i] = colour_index(colours, &ncolours, scene->surfaces[i].color);

    /* The .obj names the .mtl: both are finished before either appears. */
    int status = SC_FAIL;
    sc_out_file mtl, obj;
    if (sc_out_open(&mtl, mtl_path, err))
        goto done;
    fprintf(mtl.f, "# materials of %s: one per distinct surface colour\n",
            strrchr(path, '/') ? strrchr(path, '/') + 1 : path);
    for (int i = 0; i < ncolours; i++)
        fprintf(mtl.f, "newmtl color%d\nKd %.9g %.9g %.9g\n", i, colours[i][0], colours[i][1],
                colours[i][2]);
    if (sc_out_close(&mtl, err))
        goto done;
    if (sc_out_open(&obj, path, err)) {
        sc_out_abandon(&mtl);
        goto done;
    }
    fprintf(obj.f, "# splinecast scene: %d free-form surfaces (rational B-spline form, clamped "
            "knots)\nmtllib %s\n", scene->nsurfaces, mtl_base);
    obj_counts counts = {0, 0, 0};
    for (int i = 0; i < scene->nsurfaces; i++) {
        sc_surface world;
        sc_surface_copy(&world, &scene->surfaces[i]);
        /* Baking divides by the weight and multiplies back: skip it for the
         * identity so that untransformed data stays bit-exact. */
        if (memcmp(world.xform, identity, sizeof identity))
            sc_surface_bake_xform(&world);
        write_surface(obj.f, &world, i, material[i], &counts);
        sc_surface_free(&world);
    }
    if (sc_out_close(&obj, err)) {
        sc_out_abandon(&mtl);
        goto done;
    }
    if (sc_out_rename(&mtl, err)) {
        sc_out_abandon(&obj);
        goto done;
    }
    if (sc_out_rename(&obj, err)) {
        /* An .mtl without the .obj that names it is a half-written result
         * (say, OUT.obj is a folder): take it back. */
        remove(mtl_path);
        goto done;
    }
    status = SC_OK;
done:
    free(colours);
    free(material);
    return status;
}
