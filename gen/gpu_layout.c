/* gpu_layout.c — the declarations of the IR's slots (gpu_layout.h): its
 * textures, inputs and uniforms are entries of the shader contract
 * (shader_contract.h), found by their location; its results are the
 * intersection function's parameters. */
#include "gpu_layout.h"

static const scg_slot_info *texture_entry(int unit)
{
    return scg_contract_find(scg_textures, SCG_TEXTURE_ENTRIES, unit);
}

const scg_slot_info *scg_texture_info(scg_texture tex)
{
    static const int units[SCG_TEXTURE_COUNT] = {
        [SCG_TEX_POINTS] = SCG_UNIT_POINTS,
        [SCG_TEX_KNOTS] = SCG_UNIT_KNOTS,
        [SCG_TEX_RECORDS] = SCG_UNIT_RECORDS,
    };
    return (unsigned)tex < SCG_TEXTURE_COUNT ? texture_entry(units[tex]) : 0;
}

const scg_slot_info *scg_input_info(scg_input_slot slot)
{
    static const int locations[SCG_INPUT_COUNT] = {
        [SCG_IN_RAY_ORIGIN] = SCG_VARYING_RAY_ORIGIN,
        [SCG_IN_RAY_DIR] = SCG_VARYING_RAY_DIR,
        [SCG_IN_UV0] = SCG_VARYING_UV0,
        [SCG_IN_DOMAIN] = SCG_VARYING_DOMAIN,
        [SCG_IN_RECORD] = SCG_VARYING_RECORD,
        [SCG_IN_T_LIMIT] = -1,
    };
    /* Set by the fragment program's main() from sc_nearest_t. */
    static const scg_slot_info t_limit = {"sc_t_limit", "float", 0, 0, -1};
    if ((unsigned)slot >= SCG_INPUT_COUNT)
        return 0;
    if (slot == SCG_IN_T_LIMIT)
        return &t_limit;
    return scg_contract_find(scg_varyings, SCG_VARYING_ENTRIES, locations[slot]);
}

const scg_slot_info *scg_uniform_info(scg_uniform_slot slot)
{
    static const int locations[SCG_UNIFORM_COUNT] = {[SCG_UNI_FOOTPRINT] = SCG_LOC_FOOTPRINT};
    return (unsigned)slot < SCG_UNIFORM_COUNT
               ? scg_contract_find(scg_uniforms, SCG_UNIFORM_ENTRIES, locations[slot])
               : 0;
}

static const scg_slot_info outputs[SCG_OUTPUT_COUNT] = {
    [SCG_OUT_HIT] = {"hit", "bool", 0, 1, -1},
    [SCG_OUT_UV] = {"uv", "vec2", 0, 2, -1},
    [SCG_OUT_T] = {"t", "float", 0, 1, -1},
    [SCG_OUT_POINT] = {"point", "vec3", 0, 3, -1},
    [SCG_OUT_NORMAL] = {"normal", "vec3", 0, 3, -1},
    [SCG_OUT_ITERS] = {"iters", "int", 0, 1, -1},
    [SCG_OUT_SURFACE] = {"surface", "int", 0, 1, -1},
    [SCG_OUT_START] = {"start_uv", "vec2", 0, 2, -1},
};

const scg_slot_info *scg_output_info(scg_output_slot slot)
{
    return (unsigned)slot < SCG_OUTPUT_COUNT ? &outputs[slot] : 0;
}
