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
 * Every pass costs the rasterisation of every hull it draws, however few
 * fragments pass its tests (on llvmpipe a layer of the teapot's 35,536
 * triangles that runs almost no intersection costs half of the first
 * layer), so the hulls are culled on the GPU, by a compute program that
 * copies the indices of the hulls it keeps into a compact list, one region
 * and one indirect draw command per program:
 *
 *  - the hulls are peeled in batches, front to back by their boxes'
 *    distance (batch_hulls, doubling: 32, 64, 128, ...; the best hits carry
 *    over from batch to batch, so a hull of a later batch is intersected
 *    where its entry lies in front of the hit so far); after each batch a
 *    compute program takes the farthest best hit of every tile of
 *    PEEL_TILE x PEEL_TILE pixels, and a hull of a later batch whose box's
 *    nearest corner lies behind it in every tile its screen rectangle
 *    touches is not drawn at all (seed 000's culling, on the GPU);
 *  - within a batch, from the second layer on, the pre-pass marks the
 *    tiles where anything passed (an r32ui image), and only the hulls whose
 *    screen rectangle touches such a tile are drawn by the layer's
 *    intersection and the next pre-pass (a pixel pending after layer k had
 *    a candidate in layer k, so no hull it needs is left out).
 *
 * Up to SC_PEEL_MAX_LAYERS layers are issued a batch, each conditional on
 * the query of the one before, so nothing is read back to the CPU between
 * them (a query whose answer is already there, as llvmpipe's is after its
 * conditional rendering waited for it, and says nothing passed, ends the
 * batch); one more pre-pass counts the fragments still pending after the
 * last layer (sc_peel_finish reads the queries once the frame has been
 * waited for). A resolve pass then writes gl_FragDepth from the best
 * hits, for whatever composes with the frame. */
#include "gl_render_private.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "peer_private.h"
#include "shader_contract.h"

/* Texture units past the patch data's (shader_contract.h), image units
 * past the best hits', and the culling's storage buffers past the
 * counters'. */
enum { UNIT_PREVIOUS_ENTRY = 5, UNIT_BEST = 6, IMAGE_PENDING = 1, IMAGE_TILE_FAR = 2 };
enum { BUFFER_SLOTS = 1, BUFFER_SOURCE = 2, BUFFER_LIST = 3, BUFFER_COMMANDS = 4 };
enum { PEEL_TILE = 16, CULL_ALL = 0, CULL_FAR = 1, CULL_PENDING = 2 };

/* One hull of the frame for the culling program (std430). */
typedef struct peel_slot {
    int32_t rect[4];          /* tiles x0, y0, x1, y1 (inclusive) */
    uint32_t first, count;    /* its indices in the frame's index list */
    uint32_t command;         /* its program's draw command */
    float near;               /* window depth of its box's nearest corner */
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

/* The culling: one invocation per hull of the batch. sc_cull: 0 keeps
 * every hull, 1 those not behind the farthest best hit of every tile they
 * touch, 2 those touching a tile with work. */
static const char *cull_source =
    "#version 450 core\n"
    "layout(local_size_x = 64) in;\n"
    "struct slot { ivec4 rect; uint first, count, command; float near; };\n"
    "struct command { uint count, instances, first, base_vertex, base_instance; };\n"
    "layout(std430, binding = 1) readonly buffer sc_slots { slot slots[]; };\n"
    "layout(std430, binding = 2) readonly buffer sc_source { uint source[]; };\n"
    "layout(std430, binding = 3) writeonly buffer sc_list { uint list[]; };\n"
    "layout(std430, binding = 4) buffer sc_commands { command commands[]; };\n"
    "layout(r32ui, binding = 1) uniform readonly uimage2D sc_pending;\n"
    "layout(r32f, binding = 2) uniform readonly image2D sc_tile_far;\n"
    "layout(location = 0) uniform ivec3 sc_batch;   // first slot, slots, mode\n"
    "void main()\n"
    "{\n"
    "    int i = int(gl_GlobalInvocationID.x);\n"
    "    if (i >= sc_batch.y)\n"
    "        return;\n"
    "    slot s = slots[sc_batch.x + i];\n"
    "    bool keep = sc_batch.z == 0;\n"
    "    for (int y = s.rect.y; y <= s.rect.w && !keep; y++)\n"
    "        for (int x = s.rect.x; x <= s.rect.z && !keep; x++)\n"
    "            keep = sc_batch.z == 1 ? s.near <= imageLoad(sc_tile_far, ivec2(x, y)).r\n"
    "                                   : imageLoad(sc_pending, ivec2(x, y)).r != 0u;\n"
    "    if (!keep)\n"
    "        return;\n"
    "    uint to = commands[s.command].first + atomicAdd(commands[s.command].count, s.count);\n"
    "    for (uint j = 0u; j < s.count; j++)\n"
    "        list[to + j] = source[s.first + j];\n"
    "}\n";

/* The farthest best hit of each tile (1.0 where a pixel has none). */
static const char *tile_far_source =
    "#version 450 core\n"
    "layout(local_size_x = 8, local_size_y = 8) in;\n"
    "layout(binding = 6) uniform sampler2D sc_best;\n"
    "layout(r32f, binding = 2) uniform writeonly image2D sc_tile_far;\n"
    "void main()\n"
    "{\n"
    "    ivec2 tile = ivec2(gl_GlobalInvocationID.xy), size = textureSize(sc_best, 0);\n"
    "    if (any(greaterThanEqual(tile * 16, size)))\n"
    "        return;\n"
    "    ivec2 end = min(tile * 16 + 16, size);\n"
    "    float far = 0.0;\n"
    "    for (int y = tile.y * 16; y < end.y; y++)\n"
    "        for (int x = tile.x * 16; x < end.x; x++)\n"
    "            far = max(far, texelFetch(sc_best, ivec2(x, y), 0).r);\n"
    "    imageStore(sc_tile_far, tile, vec4(far));\n"
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

static GLuint texture_2d(const sc_gl *gl, GLenum format, int w, int h)
{
    GLuint tex;
    gl->CreateTextures(GL_TEXTURE_2D, 1, &tex);
    gl->TextureStorage2D(tex, 1, format, w, h);
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
    GLuint *tex[3] = {&r->peel_best, &r->peel_pending_tiles, &r->peel_tile_far};
    for (int i = 0; i < 3; i++) {
        if (*tex[i])
            gl->DeleteTextures(1, tex[i]);
        *tex[i] = 0;
    }
}

void sc_peel_destroy(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    release_targets(r);
    if (r->peel_queries[0])
        gl->DeleteQueries(SC_PEEL_QUERIES, r->peel_queries);
    GLuint *programs[5] = {&r->peel_program, &r->resolve_program, &r->cull_program,
                           &r->tile_far_program, &r->composite_program};
    for (int i = 0; i < 5; i++)
        if (*programs[i])
            gl->DeleteProgram(*programs[i]);
    if (r->peel_vao)
        gl->DeleteVertexArrays(1, &r->peel_vao);
    if (r->peel_buffers[0])
        gl->DeleteBuffers(5, r->peel_buffers);
    free(r->peel_slots);
    free(r->peel_commands);
}

/* Programs, queries, the culling's buffers for the renderer's hulls and
 * the targets at the renderer's target size. */
static int peel_resources(sc_renderer *r, sc_error *err)
{
    const sc_gl *gl = r->gl;
    if (!r->peel_program) {
        char vertex[1024];
        prepass_vertex_source(vertex, sizeof vertex);
        const char *pre[4] = {vertex, NULL, NULL, prepass_fragment_source};
        const char *resolve[4] = {sc_fullscreen_vertex_glsl, NULL, NULL, resolve_fragment_source};
        if (sc_peer_link(gl, pre, &r->peel_program, err) != SC_OK ||
            sc_peer_link(gl, resolve, &r->resolve_program, err) != SC_OK ||
            sc_peer_link_compute(gl, cull_source, &r->cull_program, err) != SC_OK ||
            sc_peer_link_compute(gl, tile_far_source, &r->tile_far_program, err) != SC_OK)
            return SC_FAIL;
        gl->GenQueries(SC_PEEL_QUERIES, r->peel_queries);
        if (!r->peel_vao)
            gl->CreateVertexArrays(1, &r->peel_vao);
    }
    /* The slots; two compact lists and their commands, taking turns. */
    size_t nindices = (size_t)(r->hulls.nindices ? r->hulls.nindices : 1);
    size_t nslots = (size_t)(r->hulls.count ? r->hulls.count : 1);
    size_t ncommands = (size_t)(r->ngroups ? r->ngroups : 1);
    if (r->peel_capacity != nindices + nslots) {
        if (r->peel_buffers[0])
            gl->DeleteBuffers(5, r->peel_buffers);
        gl->CreateBuffers(5, r->peel_buffers);
        gl->NamedBufferData(r->peel_buffers[0], (GLsizeiptr)(nslots * sizeof(peel_slot)), NULL,
                            GL_STREAM_DRAW);
        for (int i = 0; i < 2; i++) {
            gl->NamedBufferData(r->peel_buffers[1 + i], (GLsizeiptr)(nindices * 4), NULL,
                                GL_DYNAMIC_COPY);
            gl->NamedBufferData(r->peel_buffers[3 + i],
                                (GLsizeiptr)(ncommands * sizeof(peel_command)), NULL,
                                GL_DYNAMIC_COPY);
        }
        r->peel_slots = sc_realloc(r->peel_slots, nslots, sizeof(peel_slot));
        r->peel_commands = sc_realloc(r->peel_commands, ncommands, sizeof(peel_command));
        r->peel_capacity = nindices + nslots;
    }
    const sc_gl_target *t = &r->target;
    if (r->peel_best && r->peel_w == t->width && r->peel_h == t->height &&
        r->peel_depth == t->depth)
        return SC_OK;
    release_targets(r);
    int tw = (t->width + PEEL_TILE - 1) / PEEL_TILE, th = (t->height + PEEL_TILE - 1) / PEEL_TILE;
    r->peel_best = texture_2d(gl, GL_R32F, t->width, t->height);
    r->peel_pending_tiles = texture_2d(gl, GL_R32UI, tw, th);
    r->peel_tile_far = texture_2d(gl, GL_R32F, tw, th);
    for (int i = 0; i < 2; i++) {
        r->peel_entry[i] = texture_2d(gl, GL_R32F, t->width, t->height);
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
 * widened by a pixel, and the window depth of its box's nearest corner;
 * the whole screen and 0 when a corner lies at or behind the eye. */
static void hull_tiles(const sc_renderer *r, const float vp[16], int k, peel_slot *slot)
{
    const sc_subpatch *s = &r->hulls.subpatches[k];
    int w = r->target.width, h = r->target.height;
    int tw = (w + PEEL_TILE - 1) / PEEL_TILE, th = (h + PEEL_TILE - 1) / PEEL_TILE;
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, near = INFINITY;
    for (int c = 0; c < 8; c++) {
        double d[3] = {(c & 1 ? s->hi[0] : s->lo[0]) - r->camera.eye[0],
                       (c & 2 ? s->hi[1] : s->lo[1]) - r->camera.eye[1],
                       (c & 4 ? s->hi[2] : s->lo[2]) - r->camera.eye[2]};
        double clip[4];
        for (int row = 0; row < 4; row++)
            clip[row] = vp[row] * d[0] + vp[4 + row] * d[1] + vp[8 + row] * d[2] + vp[12 + row];
        if (!(clip[3] > 1e-9)) {
            slot->rect[0] = slot->rect[1] = 0;
            slot->rect[2] = tw - 1;
            slot->rect[3] = th - 1;
            slot->near = 0;
            return;
        }
        double x = (0.5 * clip[0] / clip[3] + 0.5) * w, y = (0.5 * clip[1] / clip[3] + 0.5) * h;
        x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
        near = fmin(near, 0.5 * clip[2] / clip[3] + 0.5);
    }
    slot->rect[0] = (int32_t)fmin(fmax(floor(x0 - 1), 0), w - 1) / PEEL_TILE;
    slot->rect[1] = (int32_t)fmin(fmax(floor(y0 - 1), 0), h - 1) / PEEL_TILE;
    slot->rect[2] = (int32_t)fmin(fmax(ceil(x1 + 1), 0), w - 1) / PEEL_TILE;
    slot->rect[3] = (int32_t)fmin(fmax(ceil(y1 + 1), 0), h - 1) / PEEL_TILE;
    /* A margin for the float depths the programs compute. */
    slot->near = (float)(near - 1e-6);
}

/* The hulls of slots [first, first + count) that `mode` keeps, into compact
 * list `list` (0 or 1) and its commands. */
static void cull(sc_renderer *r, int first, int count, int mode, int list, int ncommands,
                 GLuint *current)
{
    const sc_gl *gl = r->gl;
    gl->NamedBufferSubData(r->peel_buffers[3 + list], 0,
                           (GLsizeiptr)((size_t)ncommands * sizeof(peel_command)),
                           r->peel_commands);
    gl->MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_LIST, r->peel_buffers[1 + list]);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_COMMANDS, r->peel_buffers[3 + list]);
    gl->UseProgram(r->cull_program);
    *current = r->cull_program;
    gl->ProgramUniform3i(r->cull_program, 0, first, count, mode);
    gl->DispatchCompute((GLuint)(count + 63) / 64, 1, 1);
    gl->MemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT);
}

/* Draws compact list `list`: the pre-pass (every program's command with
 * the pre-pass program) or the intersection (each with its program). */
static void draw_list(sc_renderer *r, int list, int ncommands, int prepass, GLuint *current)
{
    const sc_gl *gl = r->gl;
    gl->VertexArrayElementBuffer(r->vertex_array, r->peel_buffers[1 + list]);
    gl->BindBuffer(GL_DRAW_INDIRECT_BUFFER, r->peel_buffers[3 + list]);
    if (prepass) {
        gl->MultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT, NULL, ncommands, 0);
        r->draw_calls++;
    }
    for (int g = 0; !prepass && g < ncommands; g++) {
        GLuint program = sc_program_gl_name(r->programs, sc_render_group_program(r, g, 0));
        if (program != *current) {
            gl->UseProgram(program);
            *current = program;
            r->program_switches++;
        }
        gl->DrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                 (const void *)((size_t)g * sizeof(peel_command)));
        r->draw_calls++;
    }
    gl->BindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gl->VertexArrayElementBuffer(r->vertex_array, r->index_buffer);
}

/* The layers of one batch (slots [first, first + count)); batch b's
 * queries. The best hits and the depth of earlier batches stay. */
static void peel_batch(sc_renderer *r, int b, int first, int count, GLuint *current)
{
    const sc_gl *gl = r->gl;
    const sc_gl_target *t = &r->target;
    static const float zero = 0, one = 1;
    static const GLuint none = 0;
    GLuint *queries = r->peel_queries + b * (SC_PEEL_MAX_LAYERS + 1);
    int ncommands = r->ngroups;
    /* The batch's hulls, less those behind the hits of the batches before. */
    int list = 0;
    cull(r, first, count, b ? CULL_FAR : CULL_ALL, list, ncommands, current);
    /* Layer 0's entries: nothing is in front of the first layer. */
    gl->ClearTexImage(r->peel_entry[0], 0, GL_RED, GL_FLOAT, &zero);
    for (int k = 1; k <= SC_PEEL_MAX_LAYERS; k++) {
        int cur = k & 1;
        int last = k == SC_PEEL_MAX_LAYERS;
        /* The pre-pass of layer k: only where layer k-1 found candidates. */
        if (k > 1)
            gl->BeginConditionalRender(queries[k - 2], GL_QUERY_WAIT);
        gl->BindFramebuffer(GL_FRAMEBUFFER, r->peel_fb[cur]);
        gl->DepthFunc(GL_LESS);
        gl->DepthMask(GL_TRUE);   /* before the clear, which it masks */
        gl->ClearNamedFramebufferfv(r->peel_fb[cur], GL_COLOR, 0, &one);
        gl->ClearNamedFramebufferfv(r->peel_fb[cur], GL_DEPTH, 0, &one);
        gl->ClearTexImage(r->peel_pending_tiles, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &none);
        gl->UseProgram(r->peel_program);
        *current = r->peel_program;
        gl->BindTextureUnit(UNIT_PREVIOUS_ENTRY, r->peel_entry[cur ^ 1]);
        gl->BeginQuery(GL_ANY_SAMPLES_PASSED, queries[k - 1]);
        draw_list(r, list, ncommands, 1, current);
        gl->EndQuery(GL_ANY_SAMPLES_PASSED);
        if (k > 1)
            gl->EndConditionalRender();
        /* From the second layer on, the hulls that touch a tile with work. */
        if (k > 1) {
            list ^= 1;
            cull(r, first, count, CULL_PENDING, list, ncommands, current);
        }
        /* The intersection of layer k, where the pre-pass passed anything. */
        gl->BeginConditionalRender(queries[k - 1], GL_QUERY_WAIT);
        gl->BindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
        gl->DepthFunc(GL_EQUAL);
        gl->DepthMask(GL_FALSE);
        draw_list(r, list, ncommands, 0, current);
        gl->EndConditionalRender();
        /* The next pre-pass reads the best hits as a texture. */
        gl->MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        r->peel_issued[b] = k;
        /* Where the query's answer is there already (llvmpipe has it: its
         * conditional rendering waits for it on the CPU), a layer that
         * found nothing ends the batch, rather than issuing empty
         * conditional layers, each a wait there; never waited for here. */
        GLuint available = 0, found = 1;
        gl->GetQueryObjectuiv(queries[k - 1], GL_QUERY_RESULT_AVAILABLE, &available);
        if (available)
            gl->GetQueryObjectuiv(queries[k - 1], GL_QUERY_RESULT, &found);
        if (!found)
            return;
        if (last) {
            /* One more pre-pass counts what the layers left undone. */
            gl->BeginConditionalRender(queries[k - 1], GL_QUERY_WAIT);
            gl->BindFramebuffer(GL_FRAMEBUFFER, r->peel_fb[cur ^ 1]);
            gl->DepthFunc(GL_LESS);
            gl->DepthMask(GL_TRUE);
            gl->ClearNamedFramebufferfv(r->peel_fb[cur ^ 1], GL_DEPTH, 0, &one);
            gl->UseProgram(r->peel_program);
            *current = r->peel_program;
            gl->BindTextureUnit(UNIT_PREVIOUS_ENTRY, r->peel_entry[cur]);
            gl->BeginQuery(GL_SAMPLES_PASSED, queries[k]);
            draw_list(r, list, ncommands, 1, current);
            gl->EndQuery(GL_SAMPLES_PASSED);
            gl->EndConditionalRender();
            r->peel_issued[b] = k + 1;
        }
    }
}

int sc_peel_draw(sc_renderer *r, int n, const float vp[16], const float raster_eye[3],
                 GLuint *current, sc_error *err)
{
    const sc_gl *gl = r->gl;
    r->peel_batches = 0;
    if (!n)   /* nothing in view: nothing drawn (the depth is cleared) */
        return SC_OK;
    if (peel_resources(r, err) != SC_OK)
        return SC_FAIL;
    /* The frame's index list in the order of the hulls (front to back);
     * each program's region of a compact list as long as all its hulls'
     * indices; a slot per hull. */
    int nidx = 0;
    peel_command *commands = r->peel_commands;
    for (int g = 0; g < r->ngroups; g++)
        commands[g] = (peel_command){.instances = 1};
    for (int i = 0; i < n; i++) {
        int k = r->items[i].hull, from = nidx;
        const sc_subpatch *s = &r->hulls.subpatches[k];
        memcpy(r->frame_indices + nidx, r->hulls.indices + s->first_index,
               (size_t)s->index_count * sizeof(uint32_t));
        nidx += s->index_count;
        peel_slot *slot = (peel_slot *)r->peel_slots + i;
        hull_tiles(r, vp, k, slot);
        slot->first = (uint32_t)from;
        slot->count = (uint32_t)(nidx - from);
        slot->command = (uint32_t)r->hull_group[k];
        commands[r->hull_group[k]].count += slot->count;
    }
    for (int g = 0, base = 0; g < r->ngroups; g++) {
        int size = (int)commands[g].count;
        commands[g].count = 0;
        commands[g].first = (uint32_t)base;
        base += size;
    }
    gl->NamedBufferSubData(r->index_buffer, 0, (GLsizeiptr)nidx * 4, r->frame_indices);
    gl->NamedBufferSubData(r->peel_buffers[0], 0, (GLsizeiptr)((size_t)n * sizeof(peel_slot)),
                           r->peel_slots);
    gl->ProgramUniformMatrix4fv(r->peel_program, SCG_LOC_VIEW_PROJECTION, 1, GL_FALSE, vp);
    gl->ProgramUniform3fv(r->peel_program, SCG_LOC_RASTER_EYE, 1, raster_eye);

    static const float one = 1;
    gl->ClearTexImage(r->peel_best, 0, GL_RED, GL_FLOAT, &one);
    gl->BindTextureUnit(UNIT_BEST, r->peel_best);
    gl->BindImageTexture(SCG_IMAGE_BEST_DEPTH, r->peel_best, 0, GL_FALSE, 0, GL_READ_WRITE,
                         GL_R32F);
    gl->BindImageTexture(IMAGE_PENDING, r->peel_pending_tiles, 0, GL_FALSE, 0, GL_READ_WRITE,
                         GL_R32UI);
    gl->BindImageTexture(IMAGE_TILE_FAR, r->peel_tile_far, 0, GL_FALSE, 0, GL_READ_WRITE,
                         GL_R32F);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_SLOTS, r->peel_buffers[0]);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, BUFFER_SOURCE, r->index_buffer);
    gl->CullFace(GL_BACK);
    /* Batches front to back, batch_hulls doubling; after each but the last
     * the farthest best hit per tile, for culling the later ones. */
    int tw = (r->target.width + PEEL_TILE - 1) / PEEL_TILE;
    int th = (r->target.height + PEEL_TILE - 1) / PEEL_TILE;
    for (int first = 0, size = r->desc.batch_hulls; first < n; first += size, size *= 2) {
        if (r->peel_batches == SC_PEEL_MAX_BATCHES - 1 || size > n - first)
            size = n - first;   /* the last batch takes the rest */
        r->peel_issued[r->peel_batches] = 0;
        peel_batch(r, r->peel_batches++, first, size, current);
        if (first + size < n) {
            gl->UseProgram(r->tile_far_program);
            *current = r->tile_far_program;
            gl->DispatchCompute((GLuint)(tw + 7) / 8, (GLuint)(th + 7) / 8, 1);
        }
    }
    for (int b = BUFFER_SLOTS; b <= BUFFER_COMMANDS; b++)
        gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)b, 0);
    /* The depth of the best hits, for whatever composes with the frame. */
    const sc_gl_target *t = &r->target;
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
    for (GLuint unit = SCG_IMAGE_BEST_DEPTH; unit <= IMAGE_TILE_FAR; unit++)
        gl->BindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    gl->BindTextureUnit(UNIT_PREVIOUS_ENTRY, 0);
    gl->BindTextureUnit(UNIT_BEST, 0);
    return sc_gl_check(gl, "depth peeling", err);
}

void sc_peel_finish(sc_renderer *r)
{
    const sc_gl *gl = r->gl;
    r->peel_layers = 0;
    r->peel_pending = 0;
    for (int b = 0; b < r->peel_batches; b++) {
        GLuint *queries = r->peel_queries + b * (SC_PEEL_MAX_LAYERS + 1);
        for (int k = 0; k < r->peel_issued[b] && k < SC_PEEL_MAX_LAYERS; k++) {
            GLuint any = 0;
            gl->GetQueryObjectuiv(queries[k], GL_QUERY_RESULT, &any);
            r->peel_layers += any != 0;
        }
        GLuint pending = 0;
        if (r->peel_issued[b] > SC_PEEL_MAX_LAYERS)
            gl->GetQueryObjectuiv(queries[SC_PEEL_MAX_LAYERS], GL_QUERY_RESULT, &pending);
        r->peel_pending += pending;
    }
}

/* The composition into an application's framebuffer: the target's colour
 * (sRGB, read back to linear light, as the programs write it) and depth
 * where it holds a hit. */
static const char *composite_fragment_source =
    "#version 450 core\n"
    "layout(binding = 5) uniform sampler2D sc_frame_depth;\n"
    "layout(binding = 6) uniform sampler2D sc_frame_colour;\n"
    "layout(location = 0) uniform ivec2 sc_origin;\n"
    "layout(location = 0) out vec4 sc_colour;\n"
    "void main()\n"
    "{\n"
    "    ivec2 px = ivec2(gl_FragCoord.xy) - sc_origin;\n"
    "    float depth = texelFetch(sc_frame_depth, px, 0).r;\n"
    "    if (depth >= 1.0)\n"
    "        discard;\n"
    "    sc_colour = texelFetch(sc_frame_colour, px, 0);\n"
    "    gl_FragDepth = depth;\n"
    "}\n";

int sc_peel_composite(sc_renderer *r, const int viewport[4], sc_error *err)
{
    const sc_gl *gl = r->gl;
    if (!r->composite_program) {
        const char *sources[4] = {sc_fullscreen_vertex_glsl, NULL, NULL, composite_fragment_source};
        if (sc_peer_link(gl, sources, &r->composite_program, err) != SC_OK)
            return SC_FAIL;
    }
    gl->UseProgram(r->composite_program);
    gl->ProgramUniform2i(r->composite_program, 0, viewport[0], viewport[1]);
    gl->BindTextureUnit(UNIT_PREVIOUS_ENTRY, r->target.depth);
    gl->BindTextureUnit(UNIT_BEST, r->target.colour[SCG_FRAG_OUT_COLOUR]);
    gl->Disable(GL_CULL_FACE);
    if (!r->peel_vao)   /* nothing was in view: the peeling made none */
        gl->CreateVertexArrays(1, &r->peel_vao);
    gl->BindVertexArray(r->peel_vao);
    gl->DrawArrays(GL_TRIANGLES, 0, 3);
    r->draw_calls++;
    return sc_gl_check(gl, "composing the frame into the application's framebuffer", err);
}
