/* peer_common.c — what both tessellation peers share (peer_private.h):
 * the render target of the ray caster's outputs, the fragment stage that
 * writes them, linking, the frame's matrices and the read-back. */
#include "peer_private.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "key.h"
#include "shader_contract.h"

/* The outputs the ray caster's shaded AOV programs write, at the same
 * locations and in the same formats, and the same headlight
 * (templates/shade_headlight.glsl): the pictures and the comparison see no
 * difference but the geometry. PEER_FRAGMENT(declarations, writes) is the
 * stage with the AOVs' declarations and writes, or without them for the
 * frames that write colour and depth alone. */
#define PEER_FRAGMENT(AOV_DECLARATIONS, AOV_WRITES)                                      \
    "#version 450 core\n"                                                                \
    "layout(location = 1) uniform vec3 sc_eye;\n"                                        \
    "layout(binding = 3) uniform samplerBuffer sc_colours;\n"                            \
    "in vec3 p_world;\n"                                                                 \
    "in vec3 p_normal;\n"                                                                \
    "in vec2 p_uv;\n"                                                                    \
    "flat in int p_surface;\n"                                                           \
    "layout(location = 0) out vec4 sc_colour;\n" AOV_DECLARATIONS                        \
    "void main()\n"                                                                      \
    "{\n"                                                                                \
    "    vec3 to_eye = sc_eye - p_world;\n"                                              \
    "    float t = length(to_eye);\n"                                                    \
    "    to_eye /= t;\n"                                                                 \
    "    vec3 n = normalize(p_normal);\n"                                                \
    "    if (dot(n, to_eye) < 0.0) n = -n;\n"                                            \
    "    vec3 base = texelFetch(sc_colours, p_surface).rgb;\n"                           \
    "    const float ambient = 0.15;\n"                                                  \
    "    sc_colour = vec4(base * (ambient + (1.0 - ambient) * max(dot(n, to_eye), 0.0)), 1.0);\n" \
    AOV_WRITES "}\n"

const char *const sc_peer_fragment_glsl =
    PEER_FRAGMENT("layout(location = 1) out int sc_aov_surface;\n"
                  "layout(location = 2) out vec4 sc_aov_uvt;\n"
                  "layout(location = 3) out vec4 sc_aov_point;\n"
                  "layout(location = 4) out vec4 sc_aov_normal;\n",
                  "    sc_aov_surface = p_surface;\n"
                  "    sc_aov_uvt = vec4(p_uv, t, 0.0);\n"
                  "    sc_aov_point = vec4(p_world, 1.0);\n"
                  "    sc_aov_normal = vec4(n, 0.0);\n");
const char *const sc_peer_colour_fragment_glsl = PEER_FRAGMENT("", "");

static int compile(const sc_gl *gl, GLenum stage, const char *source, GLuint *out, sc_error *err)
{
    GLuint shader = gl->CreateShader(stage);
    gl->ShaderSource(shader, 1, &source, NULL);
    gl->CompileShader(shader);
    GLint ok = 0;
    gl->GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetShaderInfoLog(shader, sizeof log, NULL, log);
        gl->DeleteShader(shader);
        return sc_fail(err, NULL, 0, "built-in shader (stage 0x%x) does not compile: %s", stage, log);
    }
    *out = shader;
    return SC_OK;
}

/* Compiles the n stages given (a NULL source: absent) and links them. */
static int link_stages(const sc_gl *gl, int n, const GLenum *stages, const char *const *sources,
                       GLuint *program, sc_error *err)
{
    GLuint shaders[5] = {0};
    *program = 0;
    for (int i = 0; i < n; i++)
        if (sources[i] && compile(gl, stages[i], sources[i], &shaders[i], err) != SC_OK) {
            for (int k = 0; k < i; k++)
                if (shaders[k])
                    gl->DeleteShader(shaders[k]);
            return SC_FAIL;
        }
    GLuint prog = gl->CreateProgram();
    for (int i = 0; i < n; i++)
        if (shaders[i])
            gl->AttachShader(prog, shaders[i]);
    gl->LinkProgram(prog);
    for (int i = 0; i < n; i++)
        if (shaders[i])
            gl->DeleteShader(shaders[i]);
    GLint ok = 0;
    gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetProgramInfoLog(prog, sizeof log, NULL, log);
        gl->DeleteProgram(prog);
        return sc_fail(err, NULL, 0, "built-in program does not link: %s", log);
    }
    *program = prog;
    return sc_gl_check(gl, "linking a built-in program", err);
}

int sc_peer_link(const sc_gl *gl, const char *const sources[4], GLuint *program, sc_error *err)
{
    static const GLenum stages[4] = {GL_VERTEX_SHADER, GL_TESS_CONTROL_SHADER,
                                     GL_TESS_EVALUATION_SHADER, GL_FRAGMENT_SHADER};
    return link_stages(gl, 4, stages, sources, program, err);
}

int sc_peer_link_programs(sc_peer *p, const char *const stages[3], sc_error *err)
{
    const char *aov[4] = {stages[0], stages[1], stages[2], sc_peer_fragment_glsl};
    const char *colour[4] = {stages[0], stages[1], stages[2], sc_peer_colour_fragment_glsl};
    return sc_peer_link(p->gl, aov, &p->aov_program, err) == SC_OK &&
                   sc_peer_link(p->gl, colour, &p->colour_program, err) == SC_OK
               ? SC_OK
               : SC_FAIL;
}

int sc_peer_link_compute(const sc_gl *gl, const char *source, GLuint *program, sc_error *err)
{
    static const GLenum stage = GL_COMPUTE_SHADER;
    return link_stages(gl, 1, &stage, &source, program, err);
}

const char *const sc_fullscreen_vertex_glsl =
    "#version 450 core\n"
    "// One triangle that covers the viewport.\n"
    "void main()\n"
    "{\n"
    "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n"
    "}\n";

void sc_peer_upload_colours(sc_peer *p)
{
    const sc_gl *gl = p->gl;
    int n = p->scene->nsurfaces;
    float *rgba = sc_alloc((size_t)(n ? n : 1) * 4, sizeof(float));
    for (int s = 0; s < n; s++) {
        memcpy(rgba + 4 * s, p->scene->surfaces[s].color, 3 * sizeof(float));
        rgba[4 * s + 3] = 1;
    }
    gl->CreateBuffers(1, &p->colour_buffer);
    gl->NamedBufferData(p->colour_buffer, (GLsizeiptr)((size_t)(n ? n : 1) * 16), rgba,
                        GL_STATIC_DRAW);
    gl->CreateTextures(GL_TEXTURE_BUFFER, 1, &p->colour_texture);
    gl->TextureBuffer(p->colour_texture, GL_RGBA32F, p->colour_buffer);
    free(rgba);
}




/* Depth range holding the scene: its control points' box along the view
 * direction (the surfaces lie in their hull). */
static void depth_range(const sc_scene *scene, const sc_camera *cam, const double fwd[3],
                        double *znear, double *zfar)
{
    double lo[3], hi[3], zlo = INFINITY, zhi = 0;
    sc_scene_bounds(scene, lo, hi);
    for (int c = 0; c < 8; c++) {
        double q[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
        double z = 0;
        for (int k = 0; k < 3; k++)
            z += (q[k] - cam->eye[k]) * fwd[k];
        zlo = fmin(zlo, z);
        zhi = fmax(zhi, z);
    }
    if (!(zhi > 0))
        zhi = 1;
    *zfar = zhi * 1.01;
    *znear = fmax(zlo * 0.99, *zfar * 1e-5);
}

int sc_peer_begin(sc_peer *p, const sc_camera *cam, int aovs, float vp[16], sc_error *err)
{
    const sc_gl *gl = p->gl;
    /* A frame without the AOVs has the colour attachment alone, as the
     * renderer's own (made again when the size or the AOVs change). */
    int has_aovs = p->target.formats[SCG_FRAG_OUT_SURFACE] != 0;
    if (p->target.width != cam->width || p->target.height != cam->height || has_aovs != aovs) {
        sc_gl_target_destroy(gl, &p->target);
        sc_gl_target_desc td = {.width = cam->width, .height = cam->height};
        for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++) {
            const scg_frag_out_info *o = &scg_frag_outs[i];
            if (!aovs && o->location != SCG_FRAG_OUT_COLOUR)
                continue;
            if (o->location == SCG_FRAG_OUT_COLOUR)
                td.formats[o->location] = GL_SRGB8_ALPHA8;
            else if (o->location == SCG_FRAG_OUT_SURFACE)
                td.formats[o->location] = GL_R32I;
            else if (o->key_output == SCG_OUTPUT_AOV)
                td.formats[o->location] = GL_RGBA32F;
        }
        if (sc_gl_target_create(gl, &td, &p->target, err) != SC_OK)
            return SC_FAIL;
    }
    p->camera = *cam;
    double fwd[3], right[3], up[3], znear, zfar;
    sc_camera_frame(cam, fwd, right, up);
    depth_range(p->scene, cam, fwd, &znear, &zfar);
    float view[16], proj[16];
    sc_camera_gl_matrices(cam, znear, zfar, view, proj);
    /* The eye at the origin: vertices are sent relative to it. */
    view[12] = view[13] = view[14] = 0;
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double sum = 0;
            for (int k = 0; k < 4; k++)
                sum += (double)proj[k * 4 + row] * view[col * 4 + k];
            vp[col * 4 + row] = (float)sum;
        }
    float bg = (float)pow((0.2 + 0.055) / 1.055, 2.4);
    float clear[SC_GL_TARGET_MAX_COLOURS][4] = {{0}};
    unsigned uncleared = 0;  /* read only at hits: 32 of the 56 bytes a pixel */
    for (int i = 0; i < SCG_FRAG_OUT_ENTRIES; i++) {
        const scg_frag_out_info *o = &scg_frag_outs[i];
        const float background[4] = {bg, bg, bg, 1};
        memcpy(clear[o->location], o->clear_background ? background : o->clear, sizeof clear[0]);
        uncleared |= (unsigned)o->not_cleared << o->location;
    }
    p->frame_aovs = aovs;
    p->program = aovs ? p->aov_program : p->colour_program;
    gl->Enable(GL_FRAMEBUFFER_SRGB);
    sc_gl_target_begin(gl, &p->target, clear, uncleared);
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    /* Open surfaces: both sides are seen. */
    gl->Disable(GL_CULL_FACE);
    float eye[3] = {(float)cam->eye[0], (float)cam->eye[1], (float)cam->eye[2]};
    gl->UseProgram(p->program);
    gl->ProgramUniformMatrix4fv(p->program, PEER_LOC_VP, 1, GL_FALSE, vp);
    gl->ProgramUniform3fv(p->program, PEER_LOC_EYE, 1, eye);
    gl->BindTextureUnit(SCG_UNIT_COLOURS, p->colour_texture);
    gl->BindVertexArray(p->vertex_array);
    return SC_OK;
}


int sc_peer_read_target(sc_peer *p, sc_image *img, sc_aov *aov, sc_error *err)
{
    const sc_gl *gl = p->gl;
    const sc_gl_target *t = &p->target;
    if (!t->framebuffer)
        return sc_fail(err, NULL, 0, "nothing drawn yet");
    size_t n = (size_t)t->width * (size_t)t->height;
    sc_aov own;
    sc_aov *a = aov ? aov : &own;
    sc_aov_alloc(a, &p->camera, 0);
    float *uvt = sc_alloc(n * 4, sizeof(float)), *point = sc_alloc(n * 4, sizeof(float));
    float *normal = sc_alloc(n * 4, sizeof(float));
    int status = sc_gl_target_read_attachment(gl, t, SCG_FRAG_OUT_SURFACE, a->surface, err);
    if (status == SC_OK)
        status = sc_gl_target_read_attachment(gl, t, SCG_FRAG_OUT_UVT, uvt, err);
    if (status == SC_OK)
        status = sc_gl_target_read_attachment(gl, t, SCG_FRAG_OUT_POINT, point, err);
    if (status == SC_OK)
        status = sc_gl_target_read_attachment(gl, t, SCG_FRAG_OUT_NORMAL, normal, err);
    for (size_t q = 0; q < n && status == SC_OK; q++) {
        if (a->surface[q] < 0) {
            a->surface[q] = -1;
            continue;
        }
        a->uv[2 * q] = uvt[4 * q];
        a->uv[2 * q + 1] = uvt[4 * q + 1];
        a->t[q] = uvt[4 * q + 2];
        memcpy(a->point + 3 * q, point + 4 * q, 3 * sizeof(float));
        memcpy(a->normal + 3 * q, normal + 4 * q, 3 * sizeof(float));
    }
    free(uvt);
    free(point);
    free(normal);
    if (status == SC_OK && img)
        status = sc_gl_target_read_image(gl, t, SCG_FRAG_OUT_COLOUR, img, err);
    if (!aov || status != SC_OK)
        sc_aov_free(a);
    return status;
}
