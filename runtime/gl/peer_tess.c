/* peer_tess.c — the hardware-tessellation peer (peer.h): what a GL 4
 * programmer would write today. Every Bézier patch of the scene is one
 * GL patch of one vertex; the control stage reads its control points and
 * bounds from buffer textures and chooses the levels from a screen-space
 * bound on the chordal error (the second-difference bound of Filip, Magedson
 * and Markot: on an nu × nv grid the piecewise-linear surface is within
 * 1/8 (m(m-1) Muu / nu² + 2mn Muv / (nu nv) + n(n-1) Mvv / nv²) of the
 * patch, Muu … the largest second differences of the control net), turned
 * into pixels at the patch's nearest control point; the evaluation stage
 * computes exact points and normals (rational where the patch is). Edge
 * levels come from the edge's own control points alone, so neighbours that
 * share an edge split it alike. Levels above the driver's maximum are met
 * by drawing each patch as S × S sub-patches (instances), S chosen per
 * frame. Trimmed surfaces are left out (counted in skipped_surfaces): their
 * trims are not applied here. For rational patches the bound is taken on
 * the Euclidean net times the ratio of the largest to the smallest weight,
 * a heuristic, not a bound. */
#include "peer_private.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "nurbs.h"

enum { TESS_MAX_DEGREE = 15, RECORD_TEXELS = 4, MAX_SPLIT = 16 };

typedef struct tess_state {
    GLuint points_buffer, points_texture, records_buffer, records_texture;
    int npatches;
    float *records;           /* RECORD_TEXELS × 4 per patch (CPU copy for S) */
    float *points;            /* 4 per control point */
    float max_level;
} tess_state;

static const char vertex_glsl[] =
    "#version 450 core\n"
    "out int v_patch;\n"
    "out int v_sub;\n"
    "void main()\n"
    "{\n"
    "    v_patch = gl_VertexID;\n"
    "    v_sub = gl_InstanceID;\n"
    "}\n";

static const char control_glsl[] =
    "#version 450 core\n"
    "layout(vertices = 1) out;\n"
    "layout(location = 1) uniform vec3 sc_eye;\n"
    "layout(location = 2) uniform float sc_footprint;\n"
    "layout(location = 3) uniform float sc_tolerance;\n"
    "layout(location = 4) uniform int sc_split;\n"
    "layout(location = 5) uniform float sc_max_level;\n"
    "layout(binding = 0) uniform samplerBuffer sc_points;\n"
    "layout(binding = 2) uniform samplerBuffer sc_records;\n"
    "in int v_patch[];\n"
    "in int v_sub[];\n"
    "patch out int t_patch;\n"
    "patch out int t_sub;\n"
    "float dist(int index)\n"
    "{\n"
    "    vec4 p = texelFetch(sc_points, index);\n"
    "    return distance(p.xyz / p.w, sc_eye);\n"
    "}\n"
    "// Nearest of n control points from first, step apart.\n"
    "float nearest(int first, int step, int n)\n"
    "{\n"
    "    float d = 3.0e38;\n"
    "    for (int k = 0; k < n; k++)\n"
    "        d = min(d, dist(first + k * step));\n"
    "    return max(d, 1.0e-6);\n"
    "}\n"
    "// Segments for an error term e at distance d, in pixels.\n"
    "float segments(float e, float d)\n"
    "{\n"
    "    return sqrt(e / (sc_tolerance * sc_footprint * d));\n"
    "}\n"
    "void main()\n"
    "{\n"
    "    int rec = v_patch[0] * 4;\n"
    "    vec4 r0 = texelFetch(sc_records, rec);\n"
    "    vec4 r1 = texelFetch(sc_records, rec + 1);\n"
    "    vec4 r2 = texelFetch(sc_records, rec + 2);\n"
    "    int off = int(r0.x), du = int(r0.y), dv = int(r0.z), row = du + 1;\n"
    "    float d = 3.0e38;\n"
    "    for (int j = 0; j <= dv; j++)\n"
    "        d = min(d, nearest(off + j * row, 1, row));\n"
    "    d = max(d, 1.0e-6);\n"
    "    // A third of the tolerance to each term of the bound.\n"
    "    float nu = max(segments(3.0 * r1.x, d), 1.0);\n"
    "    float nv = max(segments(3.0 * r1.y, d), 1.0);\n"
    "    float cross = 3.0 * r1.z / (sc_tolerance * sc_footprint * d);\n"
    "    if (nu * nv < cross) {\n"
    "        float k = sqrt(cross / (nu * nv));\n"
    "        nu *= k;\n"
    "        nv *= k;\n"
    "    }\n"
    "    float s = float(sc_split);\n"
    "    int si = v_sub[0] % sc_split, sj = v_sub[0] / sc_split;\n"
    "    float iu = min(ceil(nu / s), sc_max_level), iv = min(ceil(nv / s), sc_max_level);\n"
    "    float e0 = si == 0 ? segments(r2.x, nearest(off, row, dv + 1)) : 0.0;\n"
    "    float e1 = sj == 0 ? segments(r2.y, nearest(off, 1, row)) : 0.0;\n"
    "    float e2 = si == sc_split - 1 ? segments(r2.z, nearest(off + du, row, dv + 1)) : 0.0;\n"
    "    float e3 = sj == sc_split - 1 ? segments(r2.w, nearest(off + dv * row, 1, row)) : 0.0;\n"
    "    gl_TessLevelOuter[0] = si == 0 ? clamp(ceil(e0 / s), 1.0, sc_max_level) : iv;\n"
    "    gl_TessLevelOuter[1] = sj == 0 ? clamp(ceil(e1 / s), 1.0, sc_max_level) : iu;\n"
    "    gl_TessLevelOuter[2] = si == sc_split - 1 ? clamp(ceil(e2 / s), 1.0, sc_max_level) : iv;\n"
    "    gl_TessLevelOuter[3] = sj == sc_split - 1 ? clamp(ceil(e3 / s), 1.0, sc_max_level) : iu;\n"
    "    gl_TessLevelInner[0] = iu;\n"
    "    gl_TessLevelInner[1] = iv;\n"
    "    t_patch = v_patch[0];\n"
    "    t_sub = v_sub[0];\n"
    "}\n";

static const char evaluation_glsl[] =
    "#version 450 core\n"
    "layout(quads, equal_spacing, ccw) in;\n"
    "layout(location = 0) uniform mat4 sc_vp;\n"
    "layout(location = 1) uniform vec3 sc_eye;\n"
    "layout(location = 4) uniform int sc_split;\n"
    "layout(binding = 0) uniform samplerBuffer sc_points;\n"
    "layout(binding = 2) uniform samplerBuffer sc_records;\n"
    "patch in int t_patch;\n"
    "patch in int t_sub;\n"
    "out vec3 p_world;\n"
    "out vec3 p_normal;\n"
    "out vec2 p_uv;\n"
    "flat out int p_surface;\n"
    "// Bernstein polynomials of degree d >= 1 at t and their derivatives.\n"
    "void basis(int d, float t, out float b[16], out float db[16])\n"
    "{\n"
    "    float s = 1.0 - t;\n"
    "    for (int i = 0; i < 16; i++) b[i] = 0.0;\n"
    "    b[0] = 1.0;\n"
    "    for (int k = 1; k < d; k++) {\n"
    "        float prev = 0.0;\n"
    "        for (int i = 0; i <= k; i++) { float cur = b[i]; b[i] = s * cur + t * prev; prev = cur; }\n"
    "    }\n"
    "    for (int i = 0; i <= d; i++)\n"
    "        db[i] = float(d) * ((i > 0 ? b[i - 1] : 0.0) - (i < d ? b[i] : 0.0));\n"
    "    float prev = 0.0;\n"
    "    for (int i = 0; i <= d; i++) { float cur = b[i]; b[i] = s * cur + t * prev; prev = cur; }\n"
    "}\n"
    "void eval(int off, int du, int dv, float u, float v, out vec3 p, out vec3 n)\n"
    "{\n"
    "    float bu[16], dbu[16], bv[16], dbv[16];\n"
    "    basis(du, u, bu, dbu);\n"
    "    basis(dv, v, bv, dbv);\n"
    "    vec4 s = vec4(0.0), su = vec4(0.0), sv = vec4(0.0);\n"
    "    for (int j = 0; j <= dv; j++) {\n"
    "        vec4 r = vec4(0.0), ru = vec4(0.0);\n"
    "        for (int i = 0; i <= du; i++) {\n"
    "            vec4 q = texelFetch(sc_points, off + j * (du + 1) + i);\n"
    "            r += bu[i] * q;\n"
    "            ru += dbu[i] * q;\n"
    "        }\n"
    "        s += bv[j] * r;\n"
    "        su += bv[j] * ru;\n"
    "        sv += dbv[j] * r;\n"
    "    }\n"
    "    p = s.xyz / s.w;\n"
    "    n = cross((su.xyz - p * su.w) / s.w, (sv.xyz - p * sv.w) / s.w);\n"
    "}\n"
    "void main()\n"
    "{\n"
    "    vec4 r0 = texelFetch(sc_records, t_patch * 4);\n"
    "    vec4 r3 = texelFetch(sc_records, t_patch * 4 + 3);\n"
    "    int off = int(r0.x), du = int(r0.y), dv = int(r0.z);\n"
    "    float s = float(sc_split);\n"
    "    float u = (float(t_sub % sc_split) + gl_TessCoord.x) / s;\n"
    "    float v = (float(t_sub / sc_split) + gl_TessCoord.y) / s;\n"
    "    vec3 p, n;\n"
    "    eval(off, du, dv, u, v, p, n);\n"
    "    // A collapsed edge has no normal of its own: take the limit from inside.\n"
    "    if (dot(n, n) < 1.0e-24) {\n"
    "        vec3 q;\n"
    "        eval(off, du, dv, mix(u, 0.5, 1.0e-3), mix(v, 0.5, 1.0e-3), q, n);\n"
    "    }\n"
    "    p_world = p;\n"
    "    p_normal = n;\n"
    "    p_uv = vec2(mix(r3.x, r3.y, u), mix(r3.z, r3.w, v));\n"
    "    p_surface = int(r0.w);\n"
    "    gl_Position = sc_vp * vec4(p - sc_eye, 1.0);\n"
    "}\n";

int sc_peer_tess_create(sc_peer *p, sc_error *err)
{
    const sc_gl *gl = p->gl;
    tess_state *t = sc_alloc(1, sizeof *t);
    p->kind = t;
    double t0 = sc_now();
    const char *stages[3] = {vertex_glsl, control_glsl, evaluation_glsl};
    if (sc_peer_link_programs(p, stages, err) != SC_OK)
        return SC_FAIL;
    p->stats.compile_ms = 1e3 * (sc_now() - t0);
    GLint max_level = 64;
    gl->GetIntegerv(GL_MAX_TESS_GEN_LEVEL, &max_level);
    t->max_level = (float)max_level;
    gl->CreateBuffers(1, &t->points_buffer);
    gl->CreateBuffers(1, &t->records_buffer);
    gl->CreateQueries(GL_PRIMITIVES_GENERATED, 1, &p->query);
    return sc_gl_check(gl, "creating the tessellation peer", err);
}

void sc_peer_tess_destroy(sc_peer *p)
{
    tess_state *t = p->kind;
    if (!t)
        return;
    const sc_gl *gl = p->gl;
    GLuint buffers[2] = {t->points_buffer, t->records_buffer};
    gl->DeleteBuffers(2, buffers);
    GLuint textures[2] = {t->points_texture, t->records_texture};
    for (int i = 0; i < 2; i++)
        if (textures[i])
            gl->DeleteTextures(1, &textures[i]);
    free(t->records);
    free(t->points);
    free(t);
    p->kind = NULL;
}

static double second_diff(const double *a, const double *b, const double *c)
{
    double d = 0;
    for (int k = 0; k < 3; k++)
        d += (a[k] - 2 * b[k] + c[k]) * (a[k] - 2 * b[k] + c[k]);
    return sqrt(d);
}

/* The largest second difference along `count` points `step` apart. */
static double row_diff(const double *pts, int first, int step, int count)
{
    double m = 0;
    for (int k = 0; k + 2 < count; k++)
        m = fmax(m, second_diff(pts + 3 * (first + k * step), pts + 3 * (first + (k + 1) * step),
                                pts + 3 * (first + (k + 2) * step)));
    return m;
}

/* One patch's record: where its points are, its degrees and surface, the
 * three terms and four edge terms of the error bound (world units at one
 * segment), and its parameter rectangle. */
static void patch_record(const sc_bezier_patch *bp, int offset, int surface, float rec[16])
{
    int du = bp->deg_u, dv = bp->deg_v, row = du + 1, n = row * (dv + 1);
    double *pts = sc_alloc((size_t)n * 3, sizeof(double));
    double wmin = INFINITY, wmax = 0;
    for (int i = 0; i < n; i++) {
        double w = bp->cp[4 * i + 3];
        wmin = fmin(wmin, fabs(w));
        wmax = fmax(wmax, fabs(w));
        for (int c = 0; c < 3; c++)
            pts[3 * i + c] = bp->cp[4 * i + c] / w;
    }
    double ratio = wmin > 0 ? wmax / wmin : 1;
    double muu = 0, mvv = 0, muv = 0;
    for (int j = 0; j <= dv; j++)
        muu = fmax(muu, row_diff(pts, j * row, 1, row));
    for (int i = 0; i <= du; i++)
        mvv = fmax(mvv, row_diff(pts, i, row, dv + 1));
    for (int j = 0; j < dv; j++)
        for (int i = 0; i < du; i++) {
            const double *a = pts + 3 * (j * row + i), *b = a + 3, *c = a + 3 * row, *d = c + 3;
            double s = 0;
            for (int k = 0; k < 3; k++)
                s += (d[k] - b[k] - c[k] + a[k]) * (d[k] - b[k] - c[k] + a[k]);
            muv = fmax(muv, sqrt(s));
        }
    double cu = du * (du - 1) / 8.0 * ratio, cv = dv * (dv - 1) / 8.0 * ratio;
    float r[16] = {
        (float)offset, (float)du, (float)dv, (float)surface,
        (float)(cu * muu), (float)(cv * mvv), (float)(du * dv / 4.0 * ratio * muv), 0,
        (float)(cv * row_diff(pts, 0, row, dv + 1)), (float)(cu * row_diff(pts, 0, 1, row)),
        (float)(cv * row_diff(pts, du, row, dv + 1)), (float)(cu * row_diff(pts, dv * row, 1, row)),
        (float)bp->u0, (float)bp->u1, (float)bp->v0, (float)bp->v1,
    };
    memcpy(rec, r, sizeof r);
    free(pts);
}

int sc_peer_tess_update(sc_peer *p, sc_error *err)
{
    const sc_gl *gl = p->gl;
    tess_state *t = p->kind;
    const sc_scene *scene = p->scene;
    double t0 = sc_now();
    int npatches = 0, npoints = 0, cap_patches = 64, cap_points = 1024, skipped = 0;
    float *records = sc_alloc((size_t)cap_patches * RECORD_TEXELS * 4, sizeof(float));
    float *points = sc_alloc((size_t)cap_points * 4, sizeof(float));
    for (int s = 0; s < scene->nsurfaces; s++) {
        const sc_surface *sf = &scene->surfaces[s];
        if (sf->nloops || sf->deg_u > TESS_MAX_DEGREE || sf->deg_v > TESS_MAX_DEGREE) {
            skipped++;
            continue;
        }
        sc_patch_list list;
        sc_surface_world_patches(sf, s, &list);
        for (int k = 0; k < list.count; k++) {
            const sc_bezier_patch *bp = &list.patches[k];
            int n = (bp->deg_u + 1) * (bp->deg_v + 1);
            if (npatches == cap_patches) {
                cap_patches *= 2;
                records = sc_realloc(records, (size_t)cap_patches * RECORD_TEXELS * 4, sizeof(float));
            }
            while (npoints + n > cap_points) {
                cap_points *= 2;
                points = sc_realloc(points, (size_t)cap_points * 4, sizeof(float));
            }
            patch_record(bp, npoints, s, records + (size_t)npatches * RECORD_TEXELS * 4);
            for (int i = 0; i < 4 * n; i++)
                points[4 * npoints + i] = (float)bp->cp[i];
            npoints += n;
            npatches++;
        }
        sc_patch_list_free(&list);
    }
    p->stats.tessellate_ms = 1e3 * (sc_now() - t0);
    p->stats.skipped_surfaces = skipped;
    free(t->records);
    free(t->points);
    t->records = records;
    t->points = points;
    t->npatches = npatches;

    t0 = sc_now();
    size_t pbytes = (size_t)(npoints ? npoints : 1) * 16;
    size_t rbytes = (size_t)(npatches ? npatches : 1) * RECORD_TEXELS * 16;
    gl->NamedBufferData(t->points_buffer, (GLsizeiptr)pbytes, points, GL_STREAM_DRAW);
    gl->NamedBufferData(t->records_buffer, (GLsizeiptr)rbytes, records, GL_STREAM_DRAW);
    /* Buffer storage may move: the views are made again. */
    GLuint textures[2] = {t->points_texture, t->records_texture};
    for (int i = 0; i < 2; i++)
        if (textures[i])
            gl->DeleteTextures(1, &textures[i]);
    gl->CreateTextures(GL_TEXTURE_BUFFER, 1, &t->points_texture);
    gl->TextureBuffer(t->points_texture, GL_RGBA32F, t->points_buffer);
    gl->CreateTextures(GL_TEXTURE_BUFFER, 1, &t->records_texture);
    gl->TextureBuffer(t->records_texture, GL_RGBA32F, t->records_buffer);
    gl->Finish();
    p->stats.upload_ms = 1e3 * (sc_now() - t0);
    p->index_count = npatches;
    p->data_bytes = pbytes + rbytes;
    p->stats.gpu_bytes = p->data_bytes + (size_t)scene->nsurfaces * 16;
    return sc_gl_check_upload(gl, "uploading the patches", pbytes + rbytes, err);
}

/* Sub-patches per side this frame: enough that no level the control
 * stage asks for exceeds the driver's maximum (the same bound, on the CPU). */
static int split_for(const tess_state *t, const sc_camera *cam, double tol_px, double footprint)
{
    double need = 1;
    for (int k = 0; k < t->npatches; k++) {
        const float *r = t->records + (size_t)k * RECORD_TEXELS * 4;
        int off = (int)r[0], n = ((int)r[1] + 1) * ((int)r[2] + 1);
        double d = INFINITY;
        for (int i = 0; i < n; i++) {
            const float *q = t->points + 4 * (size_t)(off + i);
            double s = 0;
            for (int c = 0; c < 3; c++)
                s += (q[c] / q[3] - cam->eye[c]) * (q[c] / q[3] - cam->eye[c]);
            d = fmin(d, sqrt(s));
        }
        double tol = tol_px * footprint * fmax(d, 1e-6);
        for (int e = 4; e < 12; e++)
            if (e != 7)
                need = fmax(need, sqrt(3.0 * r[e] / tol));
    }
    int split = (int)ceil(need / t->max_level);
    return split < 1 ? 1 : split > MAX_SPLIT ? MAX_SPLIT : split;
}

int sc_peer_tess_draw(sc_peer *p, const sc_camera *cam, const float vp[16], sc_error *err)
{
    (void)vp;
    const sc_gl *gl = p->gl;
    tess_state *t = p->kind;
    double footprint = 2.0 * tan(0.5 * cam->fovy_deg * M_PI / 180.0) / cam->height;
    int split = split_for(t, cam, p->config.tolerance_px, footprint);
    p->stats.subpatches = split;
    gl->ProgramUniform1f(p->program, PEER_LOC_FOOTPRINT, (float)footprint);
    gl->ProgramUniform1f(p->program, PEER_LOC_TOLERANCE, (float)p->config.tolerance_px);
    gl->ProgramUniform1i(p->program, PEER_LOC_SPLIT, split);
    gl->ProgramUniform1f(p->program, PEER_LOC_MAX_LEVEL, t->max_level);
    gl->BindTextureUnit(0, t->points_texture);
    gl->BindTextureUnit(2, t->records_texture);
    gl->PatchParameteri(GL_PATCH_VERTICES, 1);
    gl->BeginQuery(GL_PRIMITIVES_GENERATED, p->query);
    if (t->npatches)
        gl->DrawArraysInstanced(GL_PATCHES, 0, t->npatches, split * split);
    gl->EndQuery(GL_PRIMITIVES_GENERATED);
    GLuint64 prims = 0;
    gl->GetQueryObjectui64v(p->query, GL_QUERY_RESULT, &prims);
    p->stats.triangles = (long)prims;
    gl->BindTextureUnit(0, 0);
    gl->BindTextureUnit(2, 0);
    return sc_gl_check(gl, "drawing the tessellated patches", err);
}
