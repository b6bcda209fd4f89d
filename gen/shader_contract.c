/* shader_contract.c — the contract's tables (shader_contract.h) as arrays,
 * for the emitter, the runtime and the tests to walk. */
#include "shader_contract.h"

#include <stddef.h>

#include "key.h"

enum { SCG_SMOOTH = 0, SCG_FLAT = 1 };

const scg_slot_info scg_attribs[] = {
#define X(ID, location, name, type, components, component_type) \
    {name, type, 0, components, location},
    SCG_ATTRIBS(X)
#undef X
};

const scg_slot_info scg_varyings[] = {
#define X(ID, location, name, type, interpolation) \
    {name, type, SCG_##interpolation, 0, location},
    SCG_VARYINGS(X)
#undef X
};

const scg_slot_info scg_uniforms[] = {
#define X(ID, location, name, type) {name, type, 0, 0, location},
    SCG_UNIFORMS(X)
#undef X
};

const scg_slot_info scg_textures[] = {
#define X(ID, unit, name, type, components) {name, type, 0, components, unit},
    SCG_TEXTURES(X)
#undef X
};

/* The three forms of a clear value, as the fields after key_output and miss. */
#define SCG_CLEAR_BACKGROUND 1, 0, {0, 0, 0, 0}
#define SCG_CLEAR_VALUE(r, g, b, a) 0, 0, {r, g, b, a}
#define SCG_CLEAR_NONE 0, 1, {0, 0, 0, 0}

const scg_frag_out_info scg_frag_outs[] = {
#define X(ID, location, name, type, output, format, miss, clear) \
    {name, type, location, SCG_OUTPUT_##output, miss, SCG_CLEAR_##clear},
    SCG_FRAG_OUTS(X)
#undef X
};

const scg_slot_info *scg_contract_find(const scg_slot_info *table, int entries, int location)
{
    for (int i = 0; i < entries; i++)
        if (table[i].location == location)
            return &table[i];
    return NULL;
}
