/* glu_tessellate.c — GLU's NURBS tessellator alone, with nothing of
 * splinecast: the check that the chart's GLU rows (bench --chart, glu-TOL)
 * do not handicap GLU. Reads a .bpt file of bicubic Bézier patches (the
 * teapot: examples/scenes/teapot32.bpt), tessellates every patch with
 * GLU_NURBS_TESSELLATOR and GLU_PARAMETRIC_ERROR at TOL pixels for the
 * view, keeping the vertices and normals the callbacks give, and prints the
 * median time of RUNS tessellations and the vertex and triangle counts:
 *   glu_tessellate FILE.bpt EX,EY,EZ,TX,TY,TZ,FOVY WIDTH HEIGHT TOL [RUNS]
 * Built by `make glu-tessellate` (build/glu_tessellate); docs/chart.md
 * has the comparison. No GL context: GLU_AUTO_LOAD_MATRIX is off and the
 * matrices come from gluLoadSamplingMatrices. */
#include <GL/gl.h>
#include <GL/glu.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static float *vertices;
static long nvertices, cap, triangles, prim_first;
static GLenum prim;

static void GLAPIENTRY on_begin(GLenum type) { prim = type; prim_first = nvertices; }
static void GLAPIENTRY on_normal(GLfloat *n) { (void)n; }
static void GLAPIENTRY on_vertex(GLfloat *v)
{
    if (nvertices == cap) {
        cap = cap ? 2 * cap : 65536;
        vertices = realloc(vertices, (size_t)cap * 3 * sizeof(float));
    }
    memcpy(vertices + 3 * nvertices++, v, 3 * sizeof(float));
}
static void GLAPIENTRY on_end(void)
{
    long n = nvertices - prim_first;
    triangles += prim == GL_TRIANGLES ? n / 3 : n > 2 ? n - 2 : 0;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

int main(int argc, char **argv)
{
    double cam[7];
    if (argc < 6 || sscanf(argv[2], "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &cam[0], &cam[1], &cam[2],
                           &cam[3], &cam[4], &cam[5], &cam[6]) != 7) {
        fprintf(stderr, "usage: glu_tessellate FILE.bpt EX,EY,EZ,TX,TY,TZ,FOVY WIDTH HEIGHT TOL "
                        "[RUNS]\n");
        return 2;
    }
    int width = atoi(argv[3]), height = atoi(argv[4]), runs = argc > 6 ? atoi(argv[6]) : 5;
    float tol = (float)atof(argv[5]);
    FILE *f = fopen(argv[1], "r");
    int npatches = 0, du, dv;
    if (!f || fscanf(f, "%d", &npatches) != 1) {
        fprintf(stderr, "%s: cannot read\n", argv[1]);
        return 1;
    }
    float *cp = malloc((size_t)npatches * 16 * 3 * sizeof(float));
    for (int p = 0; p < npatches; p++) {
        if (fscanf(f, "%d %d", &du, &dv) != 2 || du != 3 || dv != 3) {
            fprintf(stderr, "%s: patch %d is not bicubic\n", argv[1], p);
            return 1;
        }
        for (int i = 0; i < 48; i++)
            if (fscanf(f, "%f", &cp[p * 48 + i]) != 1) {
                fprintf(stderr, "%s: patch %d is short\n", argv[1], p);
                return 1;
            }
    }
    fclose(f);
    /* gluLookAt and gluPerspective's matrices, column-major; +z up. */
    double e[3] = {cam[0], cam[1], cam[2]}, fw[3], r[3], u[3], len = 0;
    for (int k = 0; k < 3; k++) {
        fw[k] = cam[3 + k] - e[k];
        len += fw[k] * fw[k];
    }
    for (int k = 0; k < 3; k++)
        fw[k] /= sqrt(len);
    r[0] = fw[1], r[1] = -fw[0], r[2] = 0;  /* forward × (0, 0, 1) */
    len = sqrt(r[0] * r[0] + r[1] * r[1]);
    r[0] /= len, r[1] /= len;
    u[0] = r[1] * fw[2] - r[2] * fw[1], u[1] = r[2] * fw[0] - r[0] * fw[2],
    u[2] = r[0] * fw[1] - r[1] * fw[0];
    float mv[16] = {0}, pj[16] = {0};
    for (int k = 0; k < 3; k++) {
        mv[k * 4 + 0] = (float)r[k];
        mv[k * 4 + 1] = (float)u[k];
        mv[k * 4 + 2] = (float)-fw[k];
    }
    mv[12] = (float)-(r[0] * e[0] + r[1] * e[1] + r[2] * e[2]);
    mv[13] = (float)-(u[0] * e[0] + u[1] * e[1] + u[2] * e[2]);
    mv[14] = (float)(fw[0] * e[0] + fw[1] * e[1] + fw[2] * e[2]);
    mv[15] = 1;
    double cot = 1 / tan(0.5 * cam[6] * M_PI / 180), zn = 0.01, zf = 100;
    pj[0] = (float)(cot * height / width);
    pj[5] = (float)cot;
    pj[10] = (float)((zf + zn) / (zn - zf));
    pj[11] = -1;
    pj[14] = (float)(2 * zf * zn / (zn - zf));
    GLint viewport[4] = {0, 0, width, height};

    GLUnurbs *nurbs = gluNewNurbsRenderer();
    gluNurbsProperty(nurbs, GLU_NURBS_MODE, GLU_NURBS_TESSELLATOR);
    gluNurbsProperty(nurbs, GLU_AUTO_LOAD_MATRIX, GL_FALSE);
    gluNurbsProperty(nurbs, GLU_SAMPLING_METHOD, GLU_PARAMETRIC_ERROR);
    gluNurbsProperty(nurbs, GLU_PARAMETRIC_TOLERANCE, tol);
    gluNurbsCallback(nurbs, GLU_NURBS_BEGIN, (void (*)(void))on_begin);
    gluNurbsCallback(nurbs, GLU_NURBS_NORMAL, (void (*)(void))on_normal);
    gluNurbsCallback(nurbs, GLU_NURBS_VERTEX, (void (*)(void))on_vertex);
    gluNurbsCallback(nurbs, GLU_NURBS_END, (void (*)(void))on_end);
    gluLoadSamplingMatrices(nurbs, mv, pj, viewport);
    float knots[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    double *times = malloc((size_t)(runs > 0 ? runs : 1) * sizeof(double));
    for (int run = 0; run < runs; run++) {
        nvertices = triangles = 0;
        double t0 = now();
        for (int p = 0; p < npatches; p++) {
            gluBeginSurface(nurbs);
            gluNurbsSurface(nurbs, 8, knots, 8, knots, 3, 12, cp + p * 48, 4, 4, GL_MAP2_VERTEX_3);
            gluEndSurface(nurbs);
        }
        times[run] = 1e3 * (now() - t0);
    }
    qsort(times, (size_t)runs, sizeof *times, compare);
    printf("glu_tessellate tol=%g size=%dx%d tessellate_ms=%.2f vertices=%ld triangles=%ld\n", tol,
           width, height, runs ? times[runs / 2] : 0, nvertices, triangles);
    gluDeleteNurbsRenderer(nurbs);
    free(times);
    free(cp);
    free(vertices);
    return 0;
}
