/* gpu_layout.c — the names and GLSL declarations of the GPU layout's
 * textures, inputs, uniforms and results (gpu_layout.h), so that the
 * emitter and the runtime spell them from one table. */
#include "gpu_layout.h"

static const scg_slot_info textures[SCG_TEXTURE_COUNT] = {
    [SCG_TEX_POINTS] = {"sc_points", "samplerBuffer", 0, 4},
    [SCG_TEX_KNOTS] = {"sc_knots", "samplerBuffer", 0, 1},
    [SCG_TEX_RECORDS] = {"sc_records", "samplerBuffer", 0, 4},
};

static const scg_slot_info inputs[SCG_INPUT_COUNT] = {
    [SCG_IN_RAY_ORIGIN] = {"sc_ray_origin", "vec3", 1, 3},
    [SCG_IN_RAY_DIR] = {"sc_ray_dir", "vec3", 0, 3},
    [SCG_IN_UV0] = {"sc_uv0", "vec2", 0, 2},
    [SCG_IN_DOMAIN] = {"sc_domain", "vec4", 1, 4},
    [SCG_IN_RECORD] = {"sc_record", "int", 1, 1},
    [SCG_IN_T_LIMIT] = {"sc_t_limit", "float", 0, 1},
};

static const scg_slot_info uniforms[SCG_UNIFORM_COUNT] = {
    [SCG_UNI_FOOTPRINT] = {"sc_footprint", "float", 0, 1},
};

static const scg_slot_info outputs[SCG_OUTPUT_COUNT] = {
    [SCG_OUT_HIT] = {"hit", "bool", 0, 1},
    [SCG_OUT_UV] = {"uv", "vec2", 0, 2},
    [SCG_OUT_T] = {"t", "float", 0, 1},
    [SCG_OUT_POINT] = {"point", "vec3", 0, 3},
    [SCG_OUT_NORMAL] = {"normal", "vec3", 0, 3},
    [SCG_OUT_ITERS] = {"iters", "int", 0, 1},
    [SCG_OUT_SURFACE] = {"surface", "int", 0, 1},
};

const scg_slot_info *scg_texture_info(scg_texture tex)
{
    return (unsigned)tex < SCG_TEXTURE_COUNT ? &textures[tex] : 0;
}
const scg_slot_info *scg_input_info(scg_input_slot slot)
{
    return (unsigned)slot < SCG_INPUT_COUNT ? &inputs[slot] : 0;
}
const scg_slot_info *scg_uniform_info(scg_uniform_slot slot)
{
    return (unsigned)slot < SCG_UNIFORM_COUNT ? &uniforms[slot] : 0;
}
const scg_slot_info *scg_output_info(scg_output_slot slot)
{
    return (unsigned)slot < SCG_OUTPUT_COUNT ? &outputs[slot] : 0;
}
