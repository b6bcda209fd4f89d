/* gl_pack.h — a renderer's GPU data as a pack file's contents
 * (pack_file.h, docs/pack-format.md): made from a scene without GL at
 * build time, and drawn from at run time without the scene. */
#ifndef SC_GL_PACK_H
#define SC_GL_PACK_H

#include "gl_render.h"
#include "pack_file.h"

/* What sc_renderer_create would upload for the scene under desc (keys,
 * patch records and trim blocks, hull vertices and indices), in memory.
 * Needs no GL context. Terrains are refused. */
int sc_pack_build(const sc_scene *scene, const sc_render_desc *desc, sc_pack *out,
                  sc_error *err);

/* A renderer drawing the pack's data: its keys' programs from desc's cache
 * (or its own), the data uploaded as the pack holds it. The pack decides
 * keys, hulls and view; desc's draw order, batch size and memory budget
 * apply. The pack may be freed afterwards. */
int sc_renderer_create_packed(const sc_gl *gl, const sc_pack *pack, const sc_render_desc *desc,
                              sc_renderer **out, sc_error *err);

#endif
