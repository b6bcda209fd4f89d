/* gl_deferred.c — deferred shading of terrains (seed 004, section VIII):
 * the intersection pass writes only the AOVs (surface id, the hit's domain
 * point (x, y) and distance, point, normal); this full-screen pass reads
 * back, per pixel, the domain point, finds the patch that holds it (its
 * square and triangle of the type-1 mesh: the patch id) and its
 * barycentric coordinates (s, t), evaluates the patch's exact normal from
 * its record by de Casteljau, and shades. The intersection programs then
 * carry no shading, and each pixel is shaded once however many prisms
 * were drawn over it. */
#include "gl_deferred.h"

#include <stdio.h>
#include <stdlib.h>

#include "peer_private.h"
#include "shader_contract.h"
#include "tri_bezier.h"

/* Texture units past the patch data's (shader_contract.h). */
enum { UNIT_SURFACE = 5, UNIT_UVT = 6 };
_Static_assert(SCG_RECORD_TEXELS == 4, "the fragment program's record stride");

/* The fragment program: a head, the de Casteljau steps unrolled (runtime
 * loops over an indexed array cost llvmpipe several times the whole
 * intersection), and a tail. */
static const char *fragment_head =
    "#version 450 core\n"
    "layout(binding = 0) uniform samplerBuffer sc_points;\n"
    "layout(binding = 2) uniform samplerBuffer sc_records;\n"
    "layout(binding = 5) uniform isampler2D sc_aov_surface;\n"
    "layout(binding = 6) uniform sampler2D sc_aov_uvt;\n"
    "layout(location = 0) uniform vec4 sc_grid;        // x0, y0, hx, hy\n"
    "layout(location = 1) uniform ivec3 sc_cells;      // nx, ny, first record\n"
    "layout(location = 2) uniform vec3 sc_eye;\n"
    "layout(location = 3) uniform vec3 sc_base_colour;\n"
    "layout(location = 0) out vec4 sc_colour;\n"
    "\n"
    "void main()\n"
    "{\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    if (texelFetch(sc_aov_surface, px, 0).r < 0)\n"
    "        discard;\n"
    "    // The patch id and (s, t) from the hit's domain point.\n"
    "    vec2 q = (texelFetch(sc_aov_uvt, px, 0).xy - sc_grid.xy) / sc_grid.zw;\n"
    "    ivec2 sq = clamp(ivec2(floor(q)), ivec2(0), sc_cells.xy - 1);\n"
    "    vec2 f = clamp(q - vec2(sq), 0.0, 1.0);\n"
    "    int up = f.y > f.x ? 1 : 0;\n"
    "    int patch_id = 2 * (sq.y * sc_cells.x + sq.x) + up;\n"
    "    vec3 l = up == 1 ? vec3(1.0 - f.y, f.x, f.y - f.x) : vec3(1.0 - f.x, f.x - f.y, f.y);\n"
    "    int rec = (sc_cells.z + patch_id) * 4;   // SCG_RECORD_TEXELS\n"
    "    int cp = int(texelFetch(sc_records, rec).x);\n"
    "    vec3 centre = texelFetch(sc_records, rec + 3).xyz;\n";

static const char *fragment_tail =
    "    vec3 point = l.x * p100 + l.y * p010 + l.z * p001 + centre;\n"
    "    vec3 n = normalize(cross(p010 - p100, p001 - p100));\n"
    "    vec3 to_eye = normalize(sc_eye - point);\n"
    "    if (dot(n, to_eye) < 0.0)\n"
    "        n = -n;\n"
    "    // The headlight of the forward programs (shade_headlight.glsl).\n"
    "    const float ambient = 0.15;\n"
    "    sc_colour = vec4(sc_base_colour * (ambient + (1.0 - ambient) * max(dot(n, to_eye), 0.0)),"
    " 1.0);\n"
    "}\n";

/* The fragment program's text (malloc'd): c<m>_<k> is coefficient k, in
 * sc_tri_index order, of the degree-m net. */
static char *fragment_source(void)
{
    size_t cap = 16384, len = 0;
    char *s = sc_alloc(cap, 1);
    len += (size_t)snprintf(s + len, cap - len, "%s", fragment_head);
    for (int k = 0; k < 15; k++)
        len += (size_t)snprintf(s + len, cap - len,
                                "    vec3 c4_%d = texelFetch(sc_points, cp + %d).xyz;\n", k, k);
    for (int m = 4; m > 1; m--)
        for (int i = m - 1; i >= 0; i--)
            for (int j = m - 1 - i; j >= 0; j--)
                len += (size_t)snprintf(s + len, cap - len,
                                        "    vec3 c%d_%d = l.x * c%d_%d + l.y * c%d_%d + "
                                        "l.z * c%d_%d;\n",
                                        m - 1, sc_tri_index(m - 1, i, j), m,
                                        sc_tri_index(m, i + 1, j), m, sc_tri_index(m, i, j + 1),
                                        m, sc_tri_index(m, i, j));
    len += (size_t)snprintf(s + len, cap - len,
                            "    vec3 p100 = c1_%d, p010 = c1_%d, p001 = c1_%d;\n%s",
                            sc_tri_index(1, 1, 0), sc_tri_index(1, 0, 1), sc_tri_index(1, 0, 0),
                            fragment_tail);
    return s;
}

int sc_deferred_shade(sc_renderer *r, const double eye[3], sc_error *err)
{
    const sc_gl *gl = r->gl;
    const sc_tri_mesh *m = r->scene->terrain;
    if (!m || m->degree != 4)
        return sc_fail(err, NULL, 0, "deferred shading is for quartic terrains");
    if (!r->deferred_program) {
        char *fragment = fragment_source();
        const char *sources[4] = {sc_fullscreen_vertex_glsl, NULL, NULL, fragment};
        int status = sc_peer_link(gl, sources, &r->deferred_program, err);
        free(fragment);
        if (status != SC_OK)
            return SC_FAIL;
    }
    GLuint program = r->deferred_program;
    const sc_gl_target *t = &r->target;
    gl->ProgramUniform4f(program, 0, (float)m->x0, (float)m->y0, (float)m->hx, (float)m->hy);
    gl->ProgramUniform3i(program, 1, m->nx, m->ny, sc_gpu_data_record(&r->data, 0, 0));
    gl->ProgramUniform3f(program, 2, (float)eye[0], (float)eye[1], (float)eye[2]);
    const float *c = r->scene->surfaces[0].color;
    gl->ProgramUniform3f(program, 3, c[0], c[1], c[2]);
    /* Only the colour is drawn: the AOVs it reads stay attached but are
     * not draw buffers, and depth is left alone. */
    const GLenum colour_only = GL_COLOR_ATTACHMENT0 + SCG_FRAG_OUT_COLOUR;
    gl->NamedFramebufferDrawBuffers(t->framebuffer, 1, &colour_only);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->DepthMask(GL_FALSE);
    sc_gpu_data_bind(gl, &r->data);
    gl->BindTextureUnit(UNIT_SURFACE, t->colour[SCG_FRAG_OUT_SURFACE]);
    gl->BindTextureUnit(UNIT_UVT, t->colour[SCG_FRAG_OUT_UVT]);
    gl->UseProgram(program);
    gl->BindVertexArray(r->vertex_array);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    r->draw_calls++;
    gl->BindTextureUnit(UNIT_SURFACE, 0);
    gl->BindTextureUnit(UNIT_UVT, 0);
    gl->DepthMask(GL_TRUE);
    GLenum all[SC_GL_TARGET_MAX_COLOURS];
    int count = 0;
    for (int i = 0; i < SC_GL_TARGET_MAX_COLOURS; i++)
        if (t->formats[i]) {
            for (; count < i; count++)
                all[count] = GL_NONE;
            all[count++] = GL_COLOR_ATTACHMENT0 + i;
        }
    gl->NamedFramebufferDrawBuffers(t->framebuffer, count, all);
    return sc_gl_check(gl, "deferred shading", err);
}
