/* peer_glu.c — the GLU peer (peer.h): GLU's NURBS tessellator in
 * GLU_NURBS_TESSELLATOR mode, its triangles and normals taken through the
 * callbacks, sampled by GLU_PARAMETRIC_ERROR (the chordal deviation in
 * pixels, GLU_PARAMETRIC_TOLERANCE) for the view's matrices, given with
 * gluLoadSamplingMatrices since there is no GL state for GLU to read. Trim
 * loops go to GLU as NURBS trim curves, oriented by their nesting (GLU
 * keeps the left of each curve; the reference keeps odd crossings).
 * libGLU is opened with dlopen, as OSMesa is (gl_context.c): it links the
 * GL dispatch library, which must not join the program's symbols. */
#include "peer_private.h"

#include <dlfcn.h>
#include <pthread.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <GL/glu.h>

#include "nurbs.h"

/* The GLU entry points the peer calls, from dlsym. */
typedef struct glu_api {
    void *lib;
    GLUnurbs *(*NewNurbsRenderer)(void);
    void (*DeleteNurbsRenderer)(GLUnurbs *);
    void (*NurbsProperty)(GLUnurbs *, GLenum, GLfloat);
    void (*NurbsCallback)(GLUnurbs *, GLenum, void (*)(void));
    void (*NurbsCallbackData)(GLUnurbs *, GLvoid *);
    void (*LoadSamplingMatrices)(GLUnurbs *, const GLfloat *, const GLfloat *, const GLint *);
    void (*BeginSurface)(GLUnurbs *);
    void (*EndSurface)(GLUnurbs *);
    void (*NurbsSurface)(GLUnurbs *, GLint, GLfloat *, GLint, GLfloat *, GLint, GLint, GLfloat *,
                         GLint, GLint, GLenum);
    void (*BeginTrim)(GLUnurbs *);
    void (*EndTrim)(GLUnurbs *);
    void (*NurbsCurve)(GLUnurbs *, GLint, GLfloat *, GLint, GLfloat *, GLint, GLenum);
} glu_api;

static glu_api glu;

static int load_glu(sc_error *err)
{
    if (glu.lib)
        return SC_OK;
    void *lib = dlopen("libGLU.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib)
        return sc_fail(err, NULL, 0, "cannot open libGLU.so.1 (Debian: libglu1-mesa): %s",
                       dlerror());
#define SYM(name)                                                                        \
    if (!(*(void **)&glu.name = dlsym(lib, "glu" #name))) {                                \
        dlclose(lib);                                                                    \
        memset(&glu, 0, sizeof glu);                                                     \
        return sc_fail(err, NULL, 0, "libGLU.so.1 has no glu" #name);                    \
    }
    SYM(NewNurbsRenderer) SYM(DeleteNurbsRenderer) SYM(NurbsProperty) SYM(NurbsCallback)
    SYM(NurbsCallbackData) SYM(LoadSamplingMatrices) SYM(BeginSurface) SYM(EndSurface)
    SYM(NurbsSurface) SYM(BeginTrim) SYM(EndTrim) SYM(NurbsCurve)
#undef SYM
    glu.lib = lib;
    return SC_OK;
}

typedef struct glu_vertex {
    float pos[3];
    float normal[3];
    int32_t surface;
} glu_vertex;

/* A trim curve as GLU takes it: float knots and (u·w, v·w, w) points. */
typedef struct glu_curve {
    int nknots, order, rational;
    float *knots, *cp;        /* cp: 2 or 3 floats per point */
} glu_curve;

typedef struct glu_loop {
    int ncurves;
    glu_curve *curves;
} glu_loop;

typedef struct glu_state {
    GLUnurbs *nurbs;
    glu_loop **loops;         /* per surface, oriented for GLU */
    int *nloops;              /* per surface */
    /* the tessellation being collected */
    glu_vertex *vertices;
    long nvertices, cap_vertices;
    uint32_t *indices;
    long nindices, cap_indices;
    long prim_first;          /* first vertex of the current primitive */
    GLenum prim_type;
    float normal[3];
    int surface;
    long *surface_first;      /* per surface and one more: its first vertex */
} glu_state;

static int glu_errors;

static void GLAPIENTRY on_error(GLenum code)
{
    (void)code;
    glu_errors++;
}

static void GLAPIENTRY on_begin(GLenum type, void *user)
{
    glu_state *g = user;
    g->prim_type = type;
    g->prim_first = g->nvertices;
}

static void GLAPIENTRY on_normal(GLfloat *n, void *user)
{
    glu_state *g = user;
    memcpy(g->normal, n, sizeof g->normal);
}

/* As little as a program of its own would do per vertex (the surface's
 * transform is applied after the tessellation, where there is one). */
static void GLAPIENTRY on_vertex(GLfloat *v, void *user)
{
    glu_state *g = user;
    if (g->nvertices == g->cap_vertices) {
        g->cap_vertices = g->cap_vertices ? 2 * g->cap_vertices : 65536;
        g->vertices = sc_realloc(g->vertices, (size_t)g->cap_vertices, sizeof *g->vertices);
    }
    /* GLU returns object-space points (divided by w for VERTEX_4). */
    glu_vertex *out = &g->vertices[g->nvertices++];
    memcpy(out->pos, v, sizeof out->pos);
    memcpy(out->normal, g->normal, sizeof out->normal);
    out->surface = g->surface;
}

static void add_triangle(glu_state *g, long a, long b, long c)
{
    if (g->nindices + 3 > g->cap_indices) {
        g->cap_indices = g->cap_indices ? 2 * g->cap_indices : 196608;
        g->indices = sc_realloc(g->indices, (size_t)g->cap_indices, sizeof *g->indices);
    }
    g->indices[g->nindices++] = (uint32_t)a;
    g->indices[g->nindices++] = (uint32_t)b;
    g->indices[g->nindices++] = (uint32_t)c;
}

static void GLAPIENTRY on_end(void *user)
{
    glu_state *g = user;
    long f = g->prim_first, n = g->nvertices - f;
    switch (g->prim_type) {
    case GL_TRIANGLES:
        for (long k = 0; k + 2 < n; k += 3)
            add_triangle(g, f + k, f + k + 1, f + k + 2);
        break;
    case GL_TRIANGLE_STRIP:
    case GL_QUAD_STRIP:  /* the same vertex order as a triangle strip */
        for (long k = 0; k + 2 < n; k++)
            if (k & 1)
                add_triangle(g, f + k + 1, f + k, f + k + 2);
            else
                add_triangle(g, f + k, f + k + 1, f + k + 2);
        break;
    case GL_TRIANGLE_FAN:
    case GL_POLYGON:
        for (long k = 1; k + 1 < n; k++)
            add_triangle(g, f, f + k, f + k + 1);
        break;
    default:  /* points and lines carry no area */
        g->nvertices = f;
        break;
    }
}

/* ---- trim loops ---- */

/* A loop sampled into a polygon (u, v pairs). */
static double *sample_loop(const sc_loop *loop, int *count)
{
    enum { PER_CURVE = 64 };
    double *pts = sc_alloc((size_t)(loop->ncurves * PER_CURVE) * 2, sizeof(double));
    int n = 0;
    for (int c = 0; c < loop->ncurves; c++) {
        double t0, t1;
        sc_curve_domain(&loop->curves[c], &t0, &t1);
        for (int k = 0; k < PER_CURVE; k++) {
            double p[3];
            sc_curve_eval(&loop->curves[c], t0 + (t1 - t0) * k / PER_CURVE, p, NULL);
            pts[2 * n] = p[0];
            pts[2 * n + 1] = p[1];
            n++;
        }
    }
    *count = n;
    return pts;
}

static double polygon_area(const double *pts, int n)
{
    double a = 0;
    for (int i = 0; i < n; i++) {
        int j = (i + 1) % n;
        a += pts[2 * i] * pts[2 * j + 1] - pts[2 * j] * pts[2 * i + 1];
    }
    return 0.5 * a;
}

static int polygon_contains(const double *pts, int n, double u, double v)
{
    int inside = 0;
    for (int i = 0, j = n - 1; i < n; j = i++) {
        double ui = pts[2 * i], vi = pts[2 * i + 1], uj = pts[2 * j], vj = pts[2 * j + 1];
        if ((vi > v) != (vj > v) && u < (uj - ui) * (v - vi) / (vj - vi) + ui)
            inside = !inside;
    }
    return inside;
}

/* A trim curve for GLU, its control points clamped into the surface's
 * domain: a loop along the domain's edge that strays outside by rounding
 * (1e-15 in IGES files) makes GLU drop the whole surface. */
static void make_curve(const sc_curve *src, int reverse, const double domain[4], glu_curve *out)
{
    int nk = src->ncp + src->degree + 1, rational = 0;
    for (int i = 0; i < src->ncp; i++)
        rational |= fabs(src->cp[3 * i + 2] - src->cp[2]) > 1e-12 * fabs(src->cp[2]);
    out->nknots = nk;
    out->order = src->degree + 1;
    out->rational = rational;
    out->knots = sc_alloc((size_t)nk, sizeof(float));
    out->cp = sc_alloc((size_t)src->ncp * 3, sizeof(float));
    for (int i = 0; i < nk; i++)
        out->knots[i] = reverse ? (float)-src->knots[nk - 1 - i] : (float)src->knots[i];
    int dim = rational ? 3 : 2;
    for (int i = 0; i < src->ncp; i++) {
        const double *q = src->cp + 3 * (reverse ? src->ncp - 1 - i : i);
        double uv[2] = {fmin(fmax(q[0] / q[2], domain[0]), domain[1]),
                        fmin(fmax(q[1] / q[2], domain[2]), domain[3])};
        for (int c = 0; c < 2; c++)
            out->cp[dim * i + c] = (float)(rational ? uv[c] * q[2] : uv[c]);
        if (rational)
            out->cp[dim * i + 2] = (float)q[2];
    }
}

/* The domain's boundary, counter-clockwise: a surface whose loops are
 * all holes keeps what lies outside them (sc_trim_prepare's
 * kept_without_crossings), which GLU wants said with an outer loop. */
static void domain_loop(const sc_surface *s, glu_loop *out)
{
    double u0, u1, v0, v1;
    sc_surface_domain(s, &u0, &u1, &v0, &v1);
    const double corners[5][2] = {{u0, v0}, {u1, v0}, {u1, v1}, {u0, v1}, {u0, v0}};
    static const float knots[7] = {0, 0, 1, 2, 3, 4, 4};
    out->ncurves = 1;
    out->curves = sc_alloc(1, sizeof(glu_curve));
    glu_curve *c = out->curves;
    c->nknots = 7;
    c->order = 2;
    c->knots = sc_alloc(7, sizeof(float));
    memcpy(c->knots, knots, sizeof knots);
    c->cp = sc_alloc(10, sizeof(float));
    for (int i = 0; i < 5; i++) {
        c->cp[2 * i] = (float)corners[i][0];
        c->cp[2 * i + 1] = (float)corners[i][1];
    }
}

/* Loops oriented as GLU wants them: counter-clockwise at even nesting
 * depth (kept inside), clockwise at odd (holes), which is the parity rule
 * of the reference; with no outer loop, the domain's boundary first and
 * every depth one deeper. *count gets the loops made. */
static glu_loop *orient_loops(const sc_surface *s, int *count)
{
    int has_outer = 0;
    for (int l = 0; l < s->nloops; l++)
        has_outer |= !s->loops[l].is_hole;
    int first = !has_outer;
    double domain[4];
    sc_surface_domain(s, &domain[0], &domain[1], &domain[2], &domain[3]);
    glu_loop *loops = sc_alloc((size_t)(s->nloops + first), sizeof *loops);
    if (first)
        domain_loop(s, &loops[0]);
    double **poly = sc_alloc((size_t)s->nloops, sizeof *poly);
    int *npoly = sc_alloc((size_t)s->nloops, sizeof *npoly);
    for (int l = 0; l < s->nloops; l++)
        poly[l] = sample_loop(&s->loops[l], &npoly[l]);
    for (int l = 0; l < s->nloops; l++) {
        int depth = first;
        for (int o = 0; o < s->nloops; o++)
            if (o != l && npoly[o] > 2 && npoly[l] > 0 &&
                polygon_contains(poly[o], npoly[o], poly[l][0], poly[l][1]))
                depth++;
        int ccw = polygon_area(poly[l], npoly[l]) > 0;
        int reverse = ccw != (depth % 2 == 0);
        const sc_loop *src = &s->loops[l];
        glu_loop *dst = &loops[first + l];
        dst->ncurves = src->ncurves;
        dst->curves = sc_alloc((size_t)src->ncurves, sizeof(glu_curve));
        for (int c = 0; c < src->ncurves; c++)
            make_curve(&src->curves[reverse ? src->ncurves - 1 - c : c], reverse, domain,
                       &dst->curves[c]);
    }
    for (int l = 0; l < s->nloops; l++)
        free(poly[l]);
    free(poly);
    free(npoly);
    *count = s->nloops + first;
    return loops;
}

static void free_loops(glu_loop *loops, int n)
{
    for (int l = 0; loops && l < n; l++) {
        for (int c = 0; c < loops[l].ncurves; c++) {
            free(loops[l].curves[c].knots);
            free(loops[l].curves[c].cp);
        }
        free(loops[l].curves);
    }
    free(loops);
}

/* ---- the peer's half ---- */

static const char vertex_glsl[] =
    "#version 450 core\n"
    "layout(location = 0) uniform mat4 sc_vp;\n"
    "layout(location = 1) uniform vec3 sc_eye;\n"
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 2) in int a_surface;\n"
    "out vec3 p_world;\n"
    "out vec3 p_normal;\n"
    "out vec2 p_uv;\n"
    "flat out int p_surface;\n"
    "void main()\n"
    "{\n"
    "    p_world = a_pos;\n"
    "    p_normal = a_normal;\n"
    "    p_uv = vec2(0.0);\n"
    "    p_surface = a_surface;\n"
    "    gl_Position = sc_vp * vec4(a_pos - sc_eye, 1.0);\n"
    "}\n";

int sc_peer_glu_create(sc_peer *p, sc_error *err)
{
    if (load_glu(err) != SC_OK)
        return SC_FAIL;
    double t0 = sc_now();
    const char *stages[3] = {vertex_glsl, NULL, NULL};
    if (sc_peer_link_programs(p, stages, err) != SC_OK)
        return SC_FAIL;
    p->stats.compile_ms = 1e3 * (sc_now() - t0);
    glu_state *g = sc_alloc(1, sizeof *g);
    p->kind = g;
    g->loops = sc_alloc((size_t)(p->scene->nsurfaces ? p->scene->nsurfaces : 1), sizeof *g->loops);
    g->nloops = sc_alloc((size_t)(p->scene->nsurfaces ? p->scene->nsurfaces : 1), sizeof(int));
    g->surface_first = sc_alloc((size_t)p->scene->nsurfaces + 1, sizeof(long));
    for (int s = 0; s < p->scene->nsurfaces; s++)
        if (p->scene->surfaces[s].nloops)
            g->loops[s] = orient_loops(&p->scene->surfaces[s], &g->nloops[s]);
    g->nurbs = glu.NewNurbsRenderer();
    if (!g->nurbs)
        return sc_fail(err, NULL, 0, "gluNewNurbsRenderer failed");
    glu.NurbsProperty(g->nurbs, GLU_NURBS_MODE, GLU_NURBS_TESSELLATOR);
    glu.NurbsProperty(g->nurbs, GLU_AUTO_LOAD_MATRIX, GL_FALSE);
    glu.NurbsProperty(g->nurbs, GLU_SAMPLING_METHOD, GLU_PARAMETRIC_ERROR);
    glu.NurbsProperty(g->nurbs, GLU_PARAMETRIC_TOLERANCE, (GLfloat)p->config.tolerance_px);
    glu.NurbsProperty(g->nurbs, GLU_DISPLAY_MODE, GLU_FILL);
    glu.NurbsCallbackData(g->nurbs, g);
    glu.NurbsCallback(g->nurbs, GLU_NURBS_BEGIN_DATA, (void (*)(void))on_begin);
    glu.NurbsCallback(g->nurbs, GLU_NURBS_VERTEX_DATA, (void (*)(void))on_vertex);
    glu.NurbsCallback(g->nurbs, GLU_NURBS_NORMAL_DATA, (void (*)(void))on_normal);
    glu.NurbsCallback(g->nurbs, GLU_NURBS_END_DATA, (void (*)(void))on_end);
    glu.NurbsCallback(g->nurbs, GLU_NURBS_ERROR, (void (*)(void))on_error);

    const sc_gl *gl = p->gl;
    gl->CreateBuffers(1, &p->vertex_buffer);
    gl->CreateBuffers(1, &p->index_buffer);
    GLuint vao = p->vertex_array;
    gl->VertexArrayVertexBuffer(vao, 0, p->vertex_buffer, 0, sizeof(glu_vertex));
    gl->VertexArrayElementBuffer(vao, p->index_buffer);
    gl->EnableVertexArrayAttrib(vao, 0);
    gl->VertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(glu_vertex, pos));
    gl->VertexArrayAttribBinding(vao, 0, 0);
    gl->EnableVertexArrayAttrib(vao, 1);
    gl->VertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(glu_vertex, normal));
    gl->VertexArrayAttribBinding(vao, 1, 0);
    gl->EnableVertexArrayAttrib(vao, 2);
    gl->VertexArrayAttribIFormat(vao, 2, 1, GL_INT, offsetof(glu_vertex, surface));
    gl->VertexArrayAttribBinding(vao, 2, 0);
    return sc_gl_check(gl, "creating the GLU peer", err);
}

void sc_peer_glu_destroy(sc_peer *p)
{
    glu_state *g = p->kind;
    if (!g)
        return;
    if (g->nurbs)
        glu.DeleteNurbsRenderer(g->nurbs);
    for (int s = 0; s < p->scene->nsurfaces; s++)
        free_loops(g->loops[s], g->nloops[s]);
    free(g->loops);
    free(g->nloops);
    free(g->surface_first);
    free(g->vertices);
    free(g->indices);
    free(g);
    p->kind = NULL;
}

/* Column-major a · b. */
static void mat_mul(const double a[16], const double b[16], float out[16])
{
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += a[k * 4 + r] * b[c * 4 + k];
            out[c * 4 + r] = (float)sum;
        }
}

/* What the tessellating thread needs. */
typedef struct tess_job {
    sc_peer *p;
    float **knots_u, **knots_v, **cps;
    float (*modelview)[16];
    const float *proj;
    const GLint *viewport;
    double ms;
} tess_job;

/* GLU's tessellation of every surface. It runs on a thread of its own,
 * where no GL context is current: even in tessellator mode libGLU calls
 * the compatibility profile's glEnable(GL_MAP2_VERTEX_3), glPushAttrib, …,
 * which on the renderer's core context would be errors; with no context
 * they are no-ops. */
static void *tessellate(void *arg)
{
    tess_job *job = arg;
    sc_peer *p = job->p;
    glu_state *g = p->kind;
    const sc_scene *scene = p->scene;
    int ns = scene->nsurfaces;
    g->nvertices = g->nindices = 0;
    glu_errors = 0;
    double t0 = sc_now();
    for (int s = 0; s < ns; s++) {
        const sc_surface *sf = &scene->surfaces[s];
        int dim = sf->rational ? 4 : 3;
        g->surface = s;
        g->surface_first[s] = g->nvertices;
        glu.LoadSamplingMatrices(g->nurbs, job->modelview[s], job->proj, job->viewport);
        glu.BeginSurface(g->nurbs);
        glu.NurbsSurface(g->nurbs, sf->nu + sf->deg_u + 1, job->knots_u[s], sf->nv + sf->deg_v + 1,
                         job->knots_v[s], dim, dim * sf->nu, job->cps[s], sf->deg_u + 1, sf->deg_v + 1,
                         sf->rational ? GL_MAP2_VERTEX_4 : GL_MAP2_VERTEX_3);
        for (int l = 0; l < g->nloops[s]; l++) {
            const glu_loop *loop = &g->loops[s][l];
            glu.BeginTrim(g->nurbs);
            for (int c = 0; c < loop->ncurves; c++) {
                glu_curve *cv = &loop->curves[c];
                glu.NurbsCurve(g->nurbs, cv->nknots, cv->knots, cv->rational ? 3 : 2, cv->cp,
                               cv->order, cv->rational ? GLU_MAP1_TRIM_3 : GLU_MAP1_TRIM_2);
            }
            glu.EndTrim(g->nurbs);
        }
        glu.EndSurface(g->nurbs);
    }
    job->ms = 1e3 * (sc_now() - t0);
    g->surface_first[ns] = g->nvertices;
    return NULL;
}

int sc_peer_glu_update(sc_peer *p, const sc_camera *cam, sc_error *err)
{
    glu_state *g = p->kind;
    const sc_scene *scene = p->scene;
    double fwd[3], right[3], up[3];
    sc_camera_frame(cam, fwd, right, up);
    float view[16], proj[16];
    /* The depth range does not change a chordal error measured in x, y. */
    sc_camera_gl_matrices(cam, 0.01, 100, view, proj);
    double viewd[16];
    for (int i = 0; i < 16; i++)
        viewd[i] = view[i];
    GLint viewport[4] = {0, 0, cam->width, cam->height};
    /* The control points as GLU takes them, before the clock starts: a
     * program that uses GLU keeps them in float already. */
    int ns = scene->nsurfaces;
    float **knots_u = sc_alloc((size_t)(ns ? ns : 1), sizeof(float *));
    float **knots_v = sc_alloc((size_t)(ns ? ns : 1), sizeof(float *));
    float **cps = sc_alloc((size_t)(ns ? ns : 1), sizeof(float *));
    float (*modelview)[16] = sc_alloc((size_t)(ns ? ns : 1), sizeof *modelview);
    for (int s = 0; s < ns; s++) {
        const sc_surface *sf = &scene->surfaces[s];
        int nku = sf->nu + sf->deg_u + 1, nkv = sf->nv + sf->deg_v + 1, dim = sf->rational ? 4 : 3;
        knots_u[s] = sc_alloc((size_t)nku, sizeof(float));
        knots_v[s] = sc_alloc((size_t)nkv, sizeof(float));
        cps[s] = sc_alloc((size_t)(sf->nu * sf->nv * dim), sizeof(float));
        for (int i = 0; i < nku; i++)
            knots_u[s][i] = (float)sf->knots_u[i];
        for (int i = 0; i < nkv; i++)
            knots_v[s][i] = (float)sf->knots_v[i];
        for (int i = 0; i < sf->nu * sf->nv; i++)
            for (int c = 0; c < dim; c++)
                cps[s][dim * i + c] =
                    (float)(sf->rational ? sf->cp[4 * i + c] : sf->cp[4 * i + c] / sf->cp[4 * i + 3]);
        /* The sampling modelview: the view after the surface's transform. */
        double x[16] = {sf->xform[0], sf->xform[4], sf->xform[8], 0,
                        sf->xform[1], sf->xform[5], sf->xform[9], 0,
                        sf->xform[2], sf->xform[6], sf->xform[10], 0,
                        sf->xform[3], sf->xform[7], sf->xform[11], 1};
        mat_mul(viewd, x, modelview[s]);
    }
    tess_job job = {.p = p, .knots_u = knots_u, .knots_v = knots_v, .cps = cps,
                    .modelview = modelview, .proj = proj, .viewport = viewport};
    pthread_t thread;
    int started = pthread_create(&thread, NULL, tessellate, &job) == 0;
    if (started)
        pthread_join(thread, NULL);
    p->stats.tessellate_ms = job.ms;
    for (int s = 0; s < ns; s++) {
        free(knots_u[s]);
        free(knots_v[s]);
        free(cps[s]);
    }
    free(knots_u);
    free(knots_v);
    free(cps);
    free(modelview);
    p->stats.tessellator_errors = glu_errors;
    p->stats.vertices = g->nvertices;
    p->stats.triangles = g->nindices / 3;

    if (!started)
        return sc_fail(err, NULL, 0, "cannot start the thread GLU tessellates on");
    const sc_gl *gl = p->gl;
    double t0 = sc_now();
    /* Surfaces with a transform: their vertices to world space. */
    static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    for (int s = 0; s < ns; s++) {
        const double *x = scene->surfaces[s].xform;
        if (!memcmp(x, identity, sizeof identity))
            continue;
        for (long k = g->surface_first[s]; k < g->surface_first[s + 1]; k++) {
            glu_vertex *v = &g->vertices[k];
            double q[3] = {v->pos[0], v->pos[1], v->pos[2]}, n[3] = {v->normal[0], v->normal[1],
                                                                      v->normal[2]};
            sc_xform_point(x, q, q);
            sc_xform_normal(x, n, n);
            for (int c = 0; c < 3; c++) {
                v->pos[c] = (float)q[c];
                v->normal[c] = (float)n[c];
            }
        }
    }
    size_t vbytes = (size_t)g->nvertices * sizeof(glu_vertex);
    size_t ibytes = (size_t)g->nindices * sizeof(uint32_t);
    gl->NamedBufferData(p->vertex_buffer, (GLsizeiptr)(vbytes ? vbytes : 4), g->vertices,
                        GL_STREAM_DRAW);
    gl->NamedBufferData(p->index_buffer, (GLsizeiptr)(ibytes ? ibytes : 4), g->indices,
                        GL_STREAM_DRAW);
    gl->Finish();
    p->stats.upload_ms = 1e3 * (sc_now() - t0);
    p->index_count = g->nindices;
    p->data_bytes = vbytes + ibytes;
    p->stats.gpu_bytes = p->data_bytes + (size_t)scene->nsurfaces * 16;
    return sc_gl_check_upload(gl, "uploading GLU's triangles", vbytes + ibytes, err);
}

int sc_peer_glu_draw(sc_peer *p, sc_error *err)
{
    (void)err;
    if (p->index_count)
        p->gl->DrawElements(GL_TRIANGLES, (GLsizei)p->index_count, GL_UNSIGNED_INT, NULL);
    return SC_OK;
}
