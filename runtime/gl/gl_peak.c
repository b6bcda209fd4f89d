/* gl_peak.c — the machine's vec4 multiply-add rate in a fragment program:
 * the peak that `bench --peak` holds the intersection programs' achieved
 * rate against. One full-screen triangle over a float target; each
 * fragment runs `chains` independent chains of `length` dependent vec4
 * multiply-adds (written a * m + c: llvmpipe runs GLSL's fma() at half
 * that rate) (independent chains keep the pipeline full; dependence
 * keeps the compiler from removing them), with operands from uniforms so
 * that nothing folds, and writes the chains' sum so that nothing is dead. */
#include "gl_peak.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "peer_private.h"

/* The chains unrolled: in a loop, llvmpipe masks every assignment with the
 * loop's execution mask and runs at a third of the rate. Unrolled, the body
 * must still fit the CPU's instruction cache: 2 chains of 256 do (docs/speed.md
 * has the rate by length). */
static char *fragment_source(int chains, int length)
{
    size_t size = 1024 + (size_t)chains * (size_t)(length + 2) * 48;
    char *s = malloc(size);
    if (!s)
        return NULL;
    int n = snprintf(s, size,
                     "#version 450 core\n"
                     "layout(location = 0) uniform vec4 sc_m;\n"
                     "layout(location = 1) uniform vec4 sc_c;\n"
                     "layout(location = 0) out vec4 sc_out;\n"
                     "void main()\n{\n");
    for (int k = 0; k < chains; k++)
        n += snprintf(s + n, size - (size_t)n,
                      "    vec4 a%d = gl_FragCoord.xyxy * 1e-3 + vec4(%d.0);\n", k, k);
    for (int i = 0; i < length; i++)
        for (int k = 0; k < chains; k++)
            n += snprintf(s + n, size - (size_t)n, "    a%d = a%d * sc_m + sc_c;\n", k, k);
    n += snprintf(s + n, size - (size_t)n, "    sc_out = a0");
    for (int k = 1; k < chains; k++)
        n += snprintf(s + n, size - (size_t)n, " + a%d", k);
    snprintf(s + n, size - (size_t)n, ";\n}\n");
    return s;
}

static int compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int sc_gl_measure_peak(const sc_gl *gl, sc_gl_peak *p, sc_error *err)
{
    char *fragment = fragment_source(p->chains, p->length);
    if (!fragment)
        return sc_fail(err, NULL, 0, "out of memory");
    const char *sources[4] = {sc_fullscreen_vertex_glsl, NULL, NULL, fragment};
    GLuint program = 0;
    int status = sc_peer_link(gl, sources, &program, err);
    free(fragment);
    if (status != SC_OK)
        return SC_FAIL;
    GLuint texture, framebuffer, vertex_array, query;
    gl->CreateTextures(GL_TEXTURE_2D, 1, &texture);
    gl->TextureStorage2D(texture, 1, GL_RGBA32F, p->width, p->height);
    gl->CreateFramebuffers(1, &framebuffer);
    gl->NamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    gl->CreateVertexArrays(1, &vertex_array);
    gl->GenQueries(1, &query);
    gl->BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl->Viewport(0, 0, p->width, p->height);
    gl->Disable(GL_DEPTH_TEST);
    gl->Disable(GL_CULL_FACE);
    gl->UseProgram(program);
    gl->BindVertexArray(vertex_array);
    /* A multiplier just under 1 keeps the chains finite. */
    gl->ProgramUniform4f(program, 0, 0.999f, 0.998f, 0.997f, 0.996f);
    gl->ProgramUniform4f(program, 1, 0.001f, 0.002f, 0.003f, 0.004f);
    double *gpu = calloc((size_t)p->frames, sizeof(double));
    double *wall = calloc((size_t)p->frames, sizeof(double));
    gl->DrawArrays(GL_TRIANGLES, 0, 3);   /* warm-up: compiles the variant */
    gl->Finish();
    int timed = 1;
    for (int f = 0; f < p->frames; f++) {
        double t0 = sc_now();
        gl->BeginQuery(GL_TIME_ELAPSED, query);
        gl->DrawArrays(GL_TRIANGLES, 0, 3);
        gl->EndQuery(GL_TIME_ELAPSED);
        gl->Finish();
        wall[f] = 1e3 * (sc_now() - t0);
        GLuint64 ns = 0;
        gl->GetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
        gpu[f] = 1e-6 * (double)ns;
        timed = timed && ns > 0;
    }
    qsort(gpu, (size_t)p->frames, sizeof(double), compare);
    qsort(wall, (size_t)p->frames, sizeof(double), compare);
    p->gpu_ms = timed ? gpu[p->frames / 2] : -1;
    p->wall_ms = wall[p->frames / 2];
        p->flops = (double)p->width * p->height * p->chains * p->length * 4 * 2;
    free(gpu);
    free(wall);
    gl->BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl->UseProgram(0);
    gl->BindVertexArray(0);
    gl->DeleteQueries(1, &query);
    gl->DeleteVertexArrays(1, &vertex_array);
    gl->DeleteFramebuffers(1, &framebuffer);
    gl->DeleteTextures(1, &texture);
    gl->DeleteProgram(program);
    return sc_gl_check(gl, "measuring the peak", err);
}
