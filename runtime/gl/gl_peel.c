/* gl_peel.c — depth peeling of the hulls' entries (SC_TERMINATION_PEEL):
 * each covered pixel runs the intersection for its hulls in the order in
 * which its ray enters them, and stops once its hit lies in front of every
 * hull entry left, all decided on the GPU.
 *
 * Layer k is two passes over the frame's hulls (front faces):
 *
 *  1. the pre-pass, a tiny program that writes no gl_FragDepth (so the
 *     depth test runs before it, also on llvmpipe): depth test LESS with
 *     writes, and the fragment's depth to an R32F target, discarding
 *     entries at or in front of layer k-1's entry at the pixel (that layer's
 *     target, read as a texture: the two targets take turns) and entries at
 *     or behind the best hit so far (a pixel whose hit lies in front of
 *     every hull entry left is done). An occlusion query counts what
 *     passed;
 *  2. the intersection, under glBeginConditionalRender on that query: the
 *     keys' ert4 programs (gen: no gl_FragDepth, early fragment tests) with
 *     the depth test EQUAL and depth writes off, so only the fragment of
 *     the hull this layer enters runs; it keeps its hit when nearer than
 *     the best so far (the image sc_best_depth), and writes the outputs.
 *
 * Both vertex programs compute gl_Position from the same expression,
 * declared invariant (templates/hull.vert and the pre-pass's below), so the
 * depths meet bit for bit.
 *
 * Most pixels are done after the first layer or two, but drawing every hull
 * costs a pass its rasterisation whatever the tests reject (on llvmpipe,
 * 8 ms a pass for the teapot's 35,536 triangles at 256 x 256). So from the
 * second layer on the hulls are culled on the GPU: the pre-pass marks the
 * tiles of PEEL_TILE x PEEL_TILE pixels where anything passed (an r32ui
 * image), and a compute program copies the indices of the hulls whose
 * screen rectangle (from their bounding box, on the CPU) touches such a
 * tile into a compact index list, one region and one indirect draw command
 * per draw call; the layer's intersection pass and the next pre-pass draw
 * that list. A pixel left pending by layer k had a candidate in layer k, so
 * no hull it needs is culled.
 *
 * Up to SC_PEEL_MAX_LAYERS layers are issued, each
 * conditional on the query of the one before, so nothing is read back to
 * the CPU between them; one more pre-pass counts the fragments still
 * pending after the last layer (sc_peel_finish reads it when the frame has
 * been waited for). A resolve pass then writes gl_FragDepth from the best
 * hits, for whatever composes with the frame. */
#include "gl_render_private.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "peer_private.h"
#include "shader_contract.h"

/* Texture units past the patch data's (shader_contract.h), the image unit
 * past the best hits', and the culling's storage buffers past the
 * counters'. */
enum { UNIT_PREVIOUS_ENTRY = 5, UNIT_BEST = 6, IMAGE_PENDING = 1 };
enum { BUFFER_SLOTS = 1, BUFFER_SOURCE = 2, BUFFER_LIST = 3, BUFFER_COMMANDS = 4 };
enum { PEEL_TILE = 16 };

/* One hull of the frame for the culling program (std430). */
typedef struct peel_slot {
    int32_t rect[4];          /* tiles x0, y0, x1, y1 (inclusive) */
    uint32_t first, count;    /* its indices in the frame's index list */
    uint32_t command, pad;    /* its draw call */
} peel_slot;

/* glDrawElementsIndirect's command. */
typedef struct peel_command {
    uint32_t count, instances, first, base_vertex, base_instance;
} peel_command;

/* The pre-pass: the hull's raster position as hull.vert computes it. */
static void prepass_vertex_source(char *buf, size_t size)
{
    const scg_slot_info *pos =
        scg_contract_find(scg_attribs, SCG_ATTRIB_ENTRIES, SCG_ATTRIB_HULL_RASTER_POSITION);
    const scg_slot_info *vp =
        scg_contract_find(scg_uniforms, SCG_UNIFORM_ENTRIES, SCG_LOC_VIEW_PROJECTION);
    const scg_slot_info *eye =
        scg_contract_find(scg_uniforms, SCG_UNIFORM_ENTRIES, SCG_LOC_RASTER_EYE);
    snprintf(buf, size,
             "#version 450 core\n"
             "layout(location = %d) in vec3 %s;\n"
             "layout(location = %d) uniform mat4 %s;\n"
             "layout(location = %d) uniform vec3 %s;\n"
             "// The same expression as the intersection's vertex programs, invariant in\n"
             "// both: the layer's depths must meet bit for bit in the equality test.\n"
             "invariant gl_Position;\n"
             "void main()\n"
             "{\n"
             "    gl_Position = %s * vec4(%s - %s, 1.0);\n"
             "}\n",
             pos->location, pos->name, vp->location, vp->name, eye->location, eye->name,
             vp->name, pos->name, eye->name);
}

static const char *prepass_fragment_source =
    "#version 450 core\n"
    "layout(binding = 5) uniform sampler2D sc_previous_entry;\n"
    "layout(binding = 6) uniform sampler2D sc_best;\n"
    "layout(r32ui, binding = 1) uniform writeonly uimage2D sc_pending;\n"
    "layout(location = 0) out float sc_entry;\n"
    "void main()\n"
    "{\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy);\n"
    "    float z = gl_FragCoord.z;\n"
    "    // Entered by an earlier layer, or behind the best hit so far.\n"
    "    if (z <= texelFetch(sc_previous_entry, px, 0).r || z >= texelFetch(sc_best, px, 0).r)\n"
    "        discard;\n"
    "    sc_entry = z;\n"
    "    // Its tile has work in this layer (a fragment the depth test rejects\n"
    "    // later is a candidate all the same).\n"
    "    imageStore(sc_pending, px / 16, uvec4(1u));\n"
    "}\n";

/* The culling: one invocation per hull of the frame. */
static const char *cull_source =
    "#version 450 core\n"
    "layout(local_size_x = 64) in;\n"
    "struct slot { ivec4 rect; uint first, count, command, pad; };\n"
    "struct command { uint count, instances, first, base_vertex, base_instance; };\n"
    "layout(std430, binding = 1) readonly buffer sc_slots { slot slots[]; };\n"
    "layout(std430, binding = 2) readonly buffer sc_source { uint source[]; };\n"
    "layout(std430, binding = 3) writeonly buffer sc_list { uint list[]; };\n"
    "layout(std430, binding = 4) buffer sc_commands { command commands[]; };\n"
    "layout(r32ui, binding = 1) uniform readonly uimage2D sc_pending;\n"
    "layout(location = 0) uniform int sc_slot_count;\n"
    "void main()\n"
    "{\n"
    "    int i = int(gl_GlobalInvocationID.x);\n"
    "    if (i >= sc_slot_count)\n"
    "        return;\n"
    "    ivec4 r = slots[i].rect;\n"
    "    bool pending = false;\n"
    "    for (int y = r.y; y <= r.w && !pending; y++)\n"
    "        for (int x = r.x; x <= r.z && !pending; x++)\n"
    "            pending = imageLoad(sc_pending, ivec2(x, y)).r != 0u;\n"
    "    if (!pending)\n"
    "        return;\n"
    "    uint n = slots[i].count, c = slots[i].command, from = slots[i].first;\n"
    "    uint to = commands[c].first + atomicAdd(commands[c].count, n);\n"
    "    for (uint j = 0u; j < n; j++)\n"
    "        list[to + j] = source[from + j];\n"
    "}\n";

static int link_compute(const sc_gl *gl, const char *source, GLuint *program, sc_error *err)
{
    GLuint shader = gl->CreateShader(GL_COMPUTE_SHADER);
    gl->ShaderSource(shader, 1, &source, NULL);
    gl->CompileShader(shader);
    GLuint prog = gl->CreateProgram();
    gl->AttachShader(prog, shader);
    gl->LinkProgram(prog);
    gl->DeleteShader(shader);
    GLint ok = 0;
    gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        gl->GetProgramInfoLog(prog, sizeof log, NULL, log);
        gl->DeleteProgram(prog);
        return sc_fail(err, NULL, 0, "depth peeling: the culling program does not link: %s", log);
    }
    *program = prog;
    return SC_OK;
}

static const char *resolve_vertex_source =
    "#version 450 core\n"
    "// One triangle that covers the viewport.\n"
    "void main()\n"
    "{\n"
    "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
    "    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n"
    "}\n";

static const char *resolve_fragment_source =
    "#version 450 core\n"
    "layout(binding = 6) uniform sampler2D sc_best;\n"
    "void main()\n"
    "{\n"
    "    float depth = texelFetch(sc_best, ivec2(gl_FragCoord.xy), 0).r;\n"
    "    if (depth >= 1.0)\n"
    "        discard;\n"
    "    gl_FragDepth = depth;\n"
    "}\n";

static GLuint r32f_texture(const sc_gl *gl, int w, int h)
{
    GLuint tex;
    gl->CreateTextures(GL_TEXTURE_2D, 1, &tex);
    gl->TextureStorage2D(tex, 1, GL_R32F, w, h);
    gl->TextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

static void release_targets(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    for (int i = 0; i < 2; i++) {
        if (r->peel_fb[i])
            gl->DeleteFramebuffers(1, &r->peel_fb[i]);
        if (r->peel_entry[i])
            gl->DeleteTextures(1, &r->peel_entry[i]);
        r->peel_fb[i] = r->peel_entry[i] = 0;
    }
    if (r->peel_best)
        gl->DeleteTextures(1, &r->peel_best);
    if (r->peel_pending_tiles)
        gl->DeleteTextures(1, &r->peel_pending_tiles);
    r->peel_best = r->peel_pending_tiles = 0;
}

void sc_peel_destroy(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    release_targets(r);
    if (r->peel_queries[0])
        gl->DeleteQueries(SC_PEEL_MAX_LAYERS + 2, r->peel_queries);
    if (r->peel_program)
        gl->DeleteProgram(r->peel_program);
    if (r->resolve_program)
        gl->DeleteProgram(r->resolve_program);
    if (r->peel_vao)
        gl->DeleteVertexArrays(1, &r->peel_vao);
    if (r->cull_program)
        gl->DeleteProgram(r->cull_program);
    gl->DeleteBuffers(5, r->peel_buffers);
    free(r->peel_slots);
    free(r->peel_commands);
}

/* Programs, queries and the targets at the renderer's target size. */
static int peel_resources(sc_renderer *r, sc_error *err)
{
    const sc_gl *gl = r->gl;
    if (!r->peel_program) {
        char vertex[1024];
        prepass_vertex_source(vertex, sizeof vertex);
        const char *pre[4] = {vertex, NULL, NULL, prepass_fragment_source};
        const char *resolve[4] = {resolve_vertex_source, NULL, NULL, resolve_fragment_source};
        if (sc_peer_link(gl, pre, &r->peel_program, err) != SC_OK ||
            sc_peer_link(gl, resolve, &r->resolve_program, err) != SC_OK ||
            link_compute(gl, cull_source, &r->cull_program, err) != SC_OK)
            return SC_FAIL;
        gl->GenQueries(SC_PEEL_MAX_LAYERS + 2, r->peel_queries);
        gl->CreateVertexArrays(1, &r->peel_vao);
    }
    /* The culling's buffers, for the renderer's hulls: the slots, the two
     * compact lists and their commands (taking turns), sized for every
     * hull and every draw call. */
    size_t nindices = (size_t)(r->hulls.nindices ? r->hulls.nindices : 1);
    size_t nslots = (size_t)(r->hulls.count ? r->hulls.count : 1);
    if (r->peel_capacity != nindices + nslots) {
        if (r->peel_buffers[0])
            gl->DeleteBuffers(5, r->peel_buffers);
        gl->CreateBuffers(5, r->peel_buffers);
        gl->NamedBufferData(r->peel_buffers[0], (GLsizeiptr)(nslots * sizeof(peel_slot)), NULL,
                            GL_STREAM_DRAW);
        for (int i = 0; i < 2; i++) {
            gl->NamedBufferData(r->peel_buffers[1 + i], (GLsizeiptr)(nindices * 4), NULL,
                                GL_DYNAMIC_COPY);
            gl->NamedBufferData(r->peel_buffers[3 + i], (GLsizeiptr)(nslots * sizeof(peel_command)),
                                NULL, GL_DYNAMIC_COPY);
        }
        r->peel_slots = sc_realloc(r->peel_slots, nslots, sizeof(peel_slot));
        r->peel_commands = sc_realloc(r->peel_commands, nslots, sizeof(peel_command));
        r->peel_capacity = nindices + nslots;
    }
    const sc_gl_target *t = &r->target;
    if (r->peel_best && r->peel_w == t->width && r->peel_h == t->height &&
        r->peel_depth == t->depth)
        return SC_OK;
    release_targets(r);
    r->peel_best = r32f_texture(gl, t->width, t->height);
    gl->CreateTextures(GL_TEXTURE_2D, 1, &r->peel_pending_tiles);
    gl->TextureStorage2D(r->peel_pending_tiles, 1, GL_R32UI, (t->width + PEEL_TILE - 1) / PEEL_TILE,
                         (t->height + PEEL_TILE - 1) / PEEL_TILE);
    for (int i = 0; i < 2; i++) {
        r->peel_entry[i] = r32f_texture(gl, t->width, t->height);
        gl->CreateFramebuffers(1, &r->peel_fb[i]);
        gl->NamedFramebufferTexture(r->peel_fb[i], GL_COLOR_ATTACHMENT0, r->peel_entry[i], 0);
        gl->NamedFramebufferTexture(r->peel_fb[i], GL_DEPTH_ATTACHMENT, t->depth, 0);
        GLenum status = gl->CheckNamedFramebufferStatus(r->peel_fb[i], GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            return sc_fail(err, NULL, 0, "depth peeling: its framebuffer is incomplete (0x%x)",
                           (unsigned)status);
    }
    r->peel_w = t->width;
    r->peel_h = t->height;
    r->peel_depth = t->depth;
    return sc_gl_check(gl, "making the depth peeling targets", err);
}

/* Hull k's screen rectangle in tiles (vp: the camera at the origin),
 * widened by a pixel; the whole screen when a corner lies at or behind
 * the eye. */
static void hull_tiles(const sc_renderer *r, const float vp[16], int k, int32_t rect[4])
{
    const sc_subpatch *s = &r->hulls.subpatches[k];
    int w = r->target.width, h = r->target.height;
    int tw = (w + PEEL_TILE - 1) / PEEL_TILE, th = (h + PEEL_TILE - 1) / PEEL_TILE;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int c = 0; c < 8; c++) {
        double d[3] = {(c & 1 ? s->hi[0] : s->lo[0]) - r->camera.eye[0],
                       (c & 2 ? s->hi[1] : s->lo[1]) - r->camera.eye[1],
                       (c & 4 ? s->hi[2] : s->lo[2]) - r->camera.eye[2]};
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = vp[row] * d[0] + vp[4 + row] * d[1] + vp[8 + row] * d[2] + vp[12 + row];
        if (!(clip[3] > 1e-9)) {
            rect[0] = rect[1] = 0;
            rect[2] = tw - 1;
            rect[3] = th - 1;
            return;
        }
        double x = (0.5 * clip[0] / clip[3] + 0.5) * w, y = (0.5 * clip[1] / clip[3] + 0.5) * h;
        x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
    }
    rect[0] = (int32_t)fmin(fmax(floor(x0 - 1), 0), w - 1) / PEEL_TILE;
    rect[1] = (int32_t)fmin(fmax(floor(y0 - 1), 0), h - 1) / PEEL_TILE;
    rect[2] = (int32_t)fmin(fmax(ceil(x1 + 1), 0), w - 1) / PEEL_TILE;
    rect[3] = (int32_t)fmin(fmax(ceil(y1 + 1), 0), h - 1) / PEEL_TILE;
}

/* Draws the pre-pass (program: the pre-pass's, runs: NULL) or the
 * intersection (the runs' programs) from the frame's list (list 0) or a
 * compact list (1 + which). */
static void draw_list(sc_renderer *r, int list, int nruns, int nidx, int prepass, GLuint *current)
{
    const sc_gl *gl = r->gl;
    if (!list) {
        if (prepass) {
            if (nidx)
                gl->DrawElements(GL_TRIANGLES, nidx, GL_UNSIGNED_INT, NULL);
            r->draw_calls++;
        } else {
            sc_render_draw_runs(r, nruns, current);
        }
        return;
    }
    gl->VertexArrayElementBuffer(r->vertex_array, r->peel_buffers[list]);
    gl->BindBuffer(GL_DRAW_INDIRECT_BUFFER, r->peel_buffers[2 + list]);
    if (prepass) {
        gl->MultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, NULL, nruns, 0);
        r->draw_calls++;
    }
    for (int i = 0; !prepass && i < nruns; i++) {
        const draw_run *run = &r->runs[i];
        GLuint program = sc_program_gl_name(r->programs, r->groups[run->group].program);
        if (program != *current) {
            gl->UseProgram(program);
            *current = program;
            r->program_switches++;
        }
        gl->DrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                 (const void *)((size_t)i * sizeof(peel_command)));
        r->draw_calls++;
    }
    gl->BindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gl->VertexArrayElementBuffer(r->vertex_array, r->index_buffer);
}

int sc_peel_draw(sc_renderer *r, int n, const float vp[16], const float raster_eye[3],
                 GLuint *current, sc_error *err)
{
    const sc_gl *gl = r->gl;
    r->peel_issued = 0;
    if (!n)   /* nothing in view: nothing drawn (the depth is cleared) */
        return SC_OK;
    if (peel_resources(r, err) != SC_OK)
        return SC_FAIL;
    /* Every hull once, by program (one draw call per program in the
     * intersection passes; the pre-pass draws them all in one). */
    int nruns = 0, nidx = 0;
    for (int i = 0; i < n; i++) {
        int run = nruns ? nruns - 1 : 0, first = nidx;
        sc_render_append_hull(r, &nruns, &nidx, r->items[i].hull, 0);
        if (nruns - 1 != run)
            run = nruns - 1;
        peel_slot *slot = (peel_slot *)r->peel_slots + i;
        hull_tiles(r, vp, r->items[i].hull, slot->rect);
        slot->first = (uint32_t)first;
        slot->count = (uint32_t)(nidx - first);
        slot->command = (uint32_t)run;
        slot->pad = 0;
    }
    for (int i = 0; i < nruns; i++)
        ((peel_command *)r->peel_commands)[i] = (peel_command){.count = 0, .instances = 1,
                                             .first = (uint32_t)r->runs[i].first};
    if (nidx)
        gl->NamedBufferSubData(r->index_buffer, 0, (GLsizeiptr)nidx * 4, r->frame_indices);
    if (n)
        gl->NamedBufferSubData(r->peel_buffers[0], 0, (GLsizeiptr)((size_t)n * sizeof(peel_slot)),
                               r->peel_slots);
    gl->ProgramUniformMatrix4fv(r->peel_program, SCG_LOC_VIEW_PROJECTION, 1, GL_FALSE, vp);
    gl->ProgramUniform3fv(r->peel_program, SCG_LOC_RASTER_EYE, 1, raster_eye);
    gl->ProgramUniform1i(r->cull_program, 0, n);

    static const float zero = 0, one = 1;
    static const GLuint none = 0;
    gl->ClearTexImage(r->peel_best, 0, GL_RED, GL_FLOAT, &one);
    /* Layer 0's entries: nothing is in front of the first layer. */
    gl->ClearTexImage(r->peel_entry[0], 0, GL_RED, GL_FLOAT, &zero);
    gl->BindTextureUnit(UNIT_BEST, r->peel_best);
    gl->BindImageTexture(SCG_IMAGE_BEST_DEPTH, r->peel_best, 0, GL_FALSE, 0, GL_READ_WRITE,
                         GL_R32F);
    gl->BindImageTexture(IMAGE_PENDING, r->peel_pending_tiles, 0, GL_FALSE, 0, GL_READ_WRITE,
                         GL_R32UI);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_SLOTS, r->peel_buffers[0]);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_SOURCE, r->index_buffer);
    gl->CullFace(GL_BACK);
    const sc_gl_target *t = &r->target;
    r->peel_issued = 0;
    /* The list layer k draws: the frame's for the first two pre-passes and
     * the first intersection, then the compact one the culling made. */
    int list = 0;
    for (int k = 1; k <= SC_PEEL_MAX_LAYERS + 1; k++) {
        int cur = k & 1;
        /* The pre-pass of layer k: only where layer k-1 found candidates. */
        if (k > 1)
            gl->BeginConditionalRender(r->peel_queries[k - 1], GL_QUERY_WAIT);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->peel_fb[cur]);
        gl->DepthFunc(GL_LESS);
        gl->DepthMask(GL_TRUE);   /* before the clear, which it masks */
        gl->ClearNamedFramebufferfv(r->peel_fb[cur], GL_COLOR, 0, &one);
        gl->ClearNamedFramebufferfv(r->peel_fb[cur], GL_DEPTH, 0, &one);
        if (k > 1)
            gl->ClearTexImage(r->peel_pending_tiles, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
        gl->UseProgram(r->peel_program);
        *current = r->peel_program;
        gl->BindTextureUnit(UNIT_PREVIOUS_ENTRY, r->peel_entry[cur ^ 1]);
        /* The pass past the last layer counts what is left undone. */
        GLenum query = k > SC_PEEL_MAX_LAYERS ? GL_SAMPLES_PASSED : GL_ANY_SAMPLES_PASSED;
        gl->BeginQuery(query, r->peel_queries[k]);
        draw_list(r, list, nruns, nidx, 1, current);
        gl->EndQuery(query);
        if (k > 1)
            gl->EndConditionalRender();
        if (k > SC_PEEL_MAX_LAYERS)
            break;
        /* From the second layer on, the hulls that touch a tile with work. */
        if (k > 1) {
            list = 1 + (k & 1);
            gl->NamedBufferSubData(r->peel_buffers[2 + list], 0,
                                   (GLsizeiptr)((size_t)nruns * sizeof(peel_command)),
                                   r->peel_commands);
            gl->MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_LIST, r->peel_buffers[list]);
            gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_COMMANDS,
                               r->peel_buffers[2 + list]);
            gl->UseProgram(r->cull_program);
            *current = r->cull_program;
            gl->DispatchCompute((GLuint)(n + 63) / 64, 1, 1);
            gl->MemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT);
        }
        /* The intersection of layer k, where the pre-pass passed anything. */
        gl->BeginConditionalRender(r->peel_queries[k], GL_QUERY_WAIT);
        gl->BindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
        gl->DepthFunc(GL_EQUAL);
        gl->DepthMask(GL_FALSE);
        draw_list(r, list, nruns, nidx, 0, current);
        gl->EndConditionalRender();
        /* The next pre-pass reads the best hits as a texture. */
        gl->MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        r->peel_issued = k;
    }
    for (int b = BUFFER_SLOTS; b <= BUFFER_COMMANDS; b++)
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)b, 0);
    /* The depth of the best hits, for whatever composes with the frame. */
    gl->BindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    gl->DepthMask(GL_TRUE);
    gl->ClearNamedFramebufferfv(t->framebuffer, GL_DEPTH, 0, &one);
    gl->DepthFunc(GL_ALWAYS);
    gl->ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl->UseProgram(r->resolve_program);
    *current = r->resolve_program;
    gl->BindVertexArray(r->peel_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    gl->BindVertexArray(r->vertex_array);
    gl->ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->DepthFunc(GL_LESS);
    gl->BindImageTexture(SCG_IMAGE_BEST_DEPTH, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    gl->BindImageTexture(IMAGE_PENDING, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    gl->BindTextureUnit(UNIT_PREVIOUS_ENTRY, 0);
    gl->BindTextureUnit(UNIT_BEST, 0);
    return sc_gl_check(gl, "depth peeling", err);
}

void sc_peel_finish(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    r->peel_layers = 0;
    r->peel_pending = 0;
    if (!r->peel_issued)
        return;
    for (int k = 1; k <= r->peel_issued; k++) {
        GLuint any = 0;
        gl->GetQueryObjectuiv(r->peel_queries[k], GL_QUERY_RESULT, &any);
        r->peel_layers += any != 0;
    }
    GLuint pending = 0;
    gl->GetQueryObjectuiv(r->peel_queries[SC_PEEL_MAX_LAYERS + 1], GL_QUERY_RESULT, &pending);
    r->peel_pending = pending;
}
