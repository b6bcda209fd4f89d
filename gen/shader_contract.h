/* shader_contract.h — every name, location, binding, type and format that
 * the generated programs and the GL runtime must agree on, in one place:
 * vertex attributes, uniforms, varyings, texture units and fragment outputs.
 * The emitter declares them in GLSL from these tables (the templates only
 * say where each declaration goes), the runtime binds, sets and allocates
 * from the same tables, and tests/test_contract.c checks that the generated
 * GLSL declares nothing else. What the textures hold, texel by texel, is
 * gpu_layout.h's; docs/gpu-layout.md says it in prose.
 *
 * Each table is an X-macro, X(ID, …), so that the runtime can expand GL
 * tokens (GL_##FORMAT) that the compiler, which sees no GL header, never
 * spells. The location constants (SCG_ATTRIB_*, SCG_VARYING_*, SCG_LOC_*,
 * SCG_UNIT_*, SCG_FRAG_OUT_*) and the info arrays below are made from them. */
#ifndef SCG_SHADER_CONTRACT_H
#define SCG_SHADER_CONTRACT_H

/* Vertex attributes of a hull vertex (templates/hull.vert; the runtime's
 * gpu_vertex): X(ID, location, GLSL name, GLSL type, components, component
 * type for glVertexArrayAttrib*Format: FLOAT or INT, the latter read with
 * the I variant). */
#define SCG_ATTRIBS(X)                                                               \
    /* the vertex relative to its record's centre (transforms baked) */              \
    X(HULL_POSITION, 0, "sc_hull_position", "vec3", 3, FLOAT)                        \
    /* its control-point parameters (`cp` and `view` keys only) */                   \
    X(HULL_UV, 1, "sc_hull_uv", "vec2", 2, FLOAT)                                    \
    /* the sub-patch domain (u0, u1, v0, v1) */                                      \
    X(HULL_DOMAIN, 2, "sc_hull_domain", "vec4", 4, FLOAT)                            \
    /* the record index */                                                           \
    X(HULL_RECORD, 3, "sc_hull_record", "int", 1, INT)                               \
    /* the vertex relative to the scene's origin, for gl_Position only */            \
    X(HULL_RASTER_POSITION, 4, "sc_hull_raster_position", "vec3", 3, FLOAT)

/* Vertex-stage outputs = fragment-stage inputs: X(ID, location, GLSL name,
 * GLSL type, FLAT or SMOOTH). The first five are the IR's inputs
 * (scg_input_slot, gpu_layout.h, says what they mean); the rest belong to
 * the skeletons. */
#define SCG_VARYINGS(X)                                                              \
    X(RAY_ORIGIN, 0, "sc_ray_origin", "vec3", FLAT)                                  \
    X(RAY_DIR, 1, "sc_ray_dir", "vec3", SMOOTH)                                      \
    X(UV0, 2, "sc_uv0", "vec2", SMOOTH)                                              \
    X(DOMAIN, 3, "sc_domain", "vec4", FLAT)                                          \
    X(RECORD, 4, "sc_record", "int", FLAT)                                           \
    /* the record's centre (record texel +3) */                                      \
    X(CENTRE, 8, "sc_centre", "vec3", FLAT)                                          \
    /* the surface's colour (keys with `shade`) */                                   \
    X(BASE_COLOUR, 9, "sc_base_colour", "vec3", FLAT)

/* Uniforms of the default block (SPIR-V for OpenGL wants explicit
 * locations): X(ID, location, GLSL name, GLSL type). FOOTPRINT is the IR's
 * (scg_uniform_slot); the rest the skeletons'. */
#define SCG_UNIFORMS(X)                                                              \
    /* 2·tan(fovy/2) / image height: one pixel at unit distance */                   \
    X(FOOTPRINT, 0, "sc_footprint", "float")                                         \
    /* both stages: the camera's view-projection moved to the origin */              \
    X(VIEW_PROJECTION, 16, "sc_view_projection", "mat4")                             \
    /* vertex stage: the eye as a float, the rest of its double value, and */        \
    /* the eye relative to the scene's origin */                                     \
    X(EYE, 17, "sc_eye", "vec3")                                                     \
    X(EYE_LOW, 18, "sc_eye_low", "vec3")                                             \
    X(RASTER_EYE, 19, "sc_raster_eye", "vec3")                                      \
    /* ert5 fragment stage: window position (x, y, 1) to a world direction */        \
    /* of the pixel's ray (locations 20-22) */                                       \
    X(PIXEL_TO_RAY, 20, "sc_pixel_to_ray", "mat3")                                   \
    /* ert5 fragment stage: the drawn rectangle's first pixel (x, y), its */         \
    /* width, and its first entry in sc_list_heads */                                \
    X(LIST_CELLS, 23, "sc_list_cells", "ivec4")                                      \
    /* ert5 vertex stage: the draw's first tile in sc_list_tiles, the */             \
    /* target's width and height, and the tiles' side, in pixels */                  \
    X(LIST_TILE, 24, "sc_list_tile", "ivec4")

/* Textures, bound to the texture unit equal to their binding: X(ID, unit,
 * GLSL name, sampler type, components of a texel read). POINTS, KNOTS and
 * RECORDS are the IR's patch data (scg_texture, gpu_layout.h), on
 * consecutive units from SCG_UNIT_POINTS. */
#define SCG_TEXTURES(X)                                                              \
    X(POINTS, 0, "sc_points", "samplerBuffer", 4)                                    \
    X(KNOTS, 1, "sc_knots", "samplerBuffer", 1)                                      \
    X(RECORDS, 2, "sc_records", "samplerBuffer", 4)                                  \
    /* linear RGB per surface id (keys with `shade`) */                              \
    X(COLOURS, 3, "sc_colours", "samplerBuffer", 4)                                  \
    /* per tile of SCG_NEAREST_TILE² pixels, the largest distance along the */       \
    /* unit ray to the nearest surfaces drawn so far (ert1/ert2 keys) */             \
    X(NEAREST_T, 4, "sc_nearest_t", "sampler2D", 1)                                 \
    /* ert5 keys (runtime/gl/gl_lists.c): per pixel of the drawn rectangle */        \
    /* (row by row, from LIST_CELLS.w) its first entry in sc_list_items, the */      \
    /* next pixel's first ending it */                                               \
    X(LIST_HEADS, 8, "sc_list_heads", "usamplerBuffer", 1)                           \
    /* the candidates: slots of sc_list_hulls, nearest box first per pixel */        \
    X(LIST_ITEMS, 9, "sc_list_items", "usamplerBuffer", 1)                           \
    /* per slot two texels: the sub-patch domain (u0, u1, v0, v1); the */            \
    /* record index and the distance from the eye to the hull's box */               \
    X(LIST_HULLS, 10, "sc_list_hulls", "samplerBuffer", 4)                           \
    /* ert5 vertex stage: per tile of pixels that hold candidates, its first */      \
    /* pixel, x | y << 16 */                                                         \
    X(LIST_TILES, 11, "sc_list_tiles", "usamplerBuffer", 1)

/* Shader storage: the fragment programs that write the AOVs count, in one
 * std430 block at binding SCG_BUFFER_COUNTERS, the intersections they run
 * (fragments past the early-termination test), with an atomic add on the
 * GPU: the figure `rays_per_covered_pixel` divides it by the pixels that
 * hit a surface. Programs without the AOVs (shaded frames) count nothing. */
#define SCG_BUFFER_COUNTERS 0
#define SCG_COUNTERS_BLOCK "sc_counters"
#define SCG_COUNTER_INTERSECTIONS "sc_intersections"

/* Image units: depth peeling (ert4 keys; runtime/gl/gl_peel.c) keeps, per
 * pixel, the window depth of the nearest hit the layers drawn so far found
 * (r32f, 1.0 where none): a layer's program keeps its hit only when it is
 * nearer, and writes it there; the runtime's passes read it. */
#define SCG_IMAGE_BEST_DEPTH 0
#define SCG_BEST_DEPTH_NAME "sc_best_depth"

/* Fragment outputs = the render target's colour attachments, declared when
 * the key asks for their output: X(ID, location, GLSL name, GLSL type, the
 * key's output (SCG_OUTPUT_<it>), GL internal format (GL_<it>), the value
 * written where the hull view draws a miss (NULL: the template writes it),
 * the clear value: BACKGROUND (the renderer's background colour),
 * VALUE(r, g, b, a), or NONE: not cleared, because every reader reads it
 * only where the surface id marks a hit, which writes it). */
#define SCG_FRAG_OUTS(X)                                                             \
    /* headlight diffuse, linear RGB */                                              \
    X(COLOUR, 0, "sc_colour", "vec4", SHADE, SRGB8_ALPHA8, "vec4(0.0)", BACKGROUND)  \
    /* surface id, -1 for none */                                                    \
    X(SURFACE, 1, "sc_aov_surface", "int", AOV, R32I, "-1", VALUE(-1, -1, -1, -1))   \
    /* u, v, t along the unit ray in world units (far away when cleared, as */       \
    /* the nearest distance so far), iterations */                                   \
    X(UVT, 2, "sc_aov_uvt", "vec4", AOV, RGBA32F, "vec4(0.0)", VALUE(0, 0, 3.0e38f, 0)) \
    /* world hit point, 1 */                                                         \
    X(POINT, 3, "sc_aov_point", "vec4", AOV, RGBA32F, "vec4(0.0)", NONE)             \
    /* world unit normal facing the viewer, 0 */                                     \
    X(NORMAL, 4, "sc_aov_normal", "vec4", AOV, RGBA32F, "vec4(0.0)", NONE)            \
    /* debug views: iterations, (u, v), the hulls */                                 \
    X(ITERS, 5, "sc_view_iters", "vec4", ITERS, RGBA8, "vec4(0.0)", VALUE(0, 0, 0, 0)) \
    X(UV, 6, "sc_view_uv", "vec4", UVVIEW, RGBA8, "vec4(0.0)", VALUE(0, 0, 0, 0))    \
    X(HULL, 7, "sc_view_hull", "vec4", HULLVIEW, SRGB8_ALPHA8, NULL, BACKGROUND)

/* The location (binding, unit) of each entry, by name. */
enum {
#define SCG_A_(ID, location, ...) SCG_ATTRIB_##ID = location,
    SCG_ATTRIBS(SCG_A_)
#undef SCG_A_
};
enum {
#define SCG_V_(ID, location, ...) SCG_VARYING_##ID = location,
    SCG_VARYINGS(SCG_V_)
#undef SCG_V_
};
enum {
#define SCG_U_(ID, location, ...) SCG_LOC_##ID = location,
    SCG_UNIFORMS(SCG_U_)
#undef SCG_U_
};
enum {
#define SCG_T_(ID, unit, ...) SCG_UNIT_##ID = unit,
    SCG_TEXTURES(SCG_T_)
#undef SCG_T_
};
enum {
#define SCG_F_(ID, location, ...) SCG_FRAG_OUT_##ID = location,
    SCG_FRAG_OUTS(SCG_F_)
#undef SCG_F_
};

/* The number of entries of each table. */
#define SCG_CONTRACT_ONE_(...) +1
enum {
    SCG_ATTRIB_ENTRIES = 0 SCG_ATTRIBS(SCG_CONTRACT_ONE_),
    SCG_VARYING_ENTRIES = 0 SCG_VARYINGS(SCG_CONTRACT_ONE_),
    SCG_UNIFORM_ENTRIES = 0 SCG_UNIFORMS(SCG_CONTRACT_ONE_),
    SCG_TEXTURE_ENTRIES = 0 SCG_TEXTURES(SCG_CONTRACT_ONE_),
    SCG_FRAG_OUT_ENTRIES = 0 SCG_FRAG_OUTS(SCG_CONTRACT_ONE_),
};

/* One declaration: a table entry, or one of the IR's slots (gpu_layout.h). */
typedef struct scg_slot_info {
    const char *name;      /* GLSL identifier, e.g. "sc_ray_dir" */
    const char *glsl_type; /* "vec3", "int", "samplerBuffer", … */
    int flat;              /* varyings: 1 when `flat` interpolation */
    int components;        /* textures: of a texel read (4 or 1); attributes:
                              count; IR results: width; others 0 */
    int location;          /* location, or binding = texture unit; -1: none */
} scg_slot_info;

/* The tables in order, SCG_*_ENTRIES each. */
extern const scg_slot_info scg_attribs[];
extern const scg_slot_info scg_varyings[];
extern const scg_slot_info scg_uniforms[];
extern const scg_slot_info scg_textures[];

typedef struct scg_frag_out_info {
    const char *name;      /* "sc_colour", … */
    const char *glsl_type;
    int location;          /* = colour attachment */
    unsigned key_output;   /* the SCG_OUTPUT_* bit that declares it */
    const char *miss;      /* GLSL value on a hull-view miss; NULL: none */
    int clear_background;  /* cleared to the background colour, else to clear */
    int not_cleared;       /* left as the last frame wrote it (NONE) */
    float clear[4];
} scg_frag_out_info;

extern const scg_frag_out_info scg_frag_outs[];

/* The entry of a table with this location (binding), or NULL. */
const scg_slot_info *scg_contract_find(const scg_slot_info *table, int entries, int location);

#endif
