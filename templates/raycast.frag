{{HEADER}}
#version 450 core

// Inputs from the vertex stage; every location is an entry of the
// shader/runtime contract (gen/shader_contract.h).
{{INPUTS}}
{{VARYING_CENTRE}}
{{VARYING_BASE_COLOUR}}

// Explicit locations: SPIR-V for OpenGL refuses default-block uniforms
// without them.
{{UNIFORM_VIEW_PROJECTION}}
{{UNIFORMS}}

{{TEXTURES}}

{{OUTPUTS}}

{{GLOBALS}}
{{INTERSECT_FUNCTION}}

{{FUNCTIONS}}
void main()
{
    {{PREPARE}}
    {{RESULTS}}
    {{CALL}}
    {{ON_MISS}}

    // Depth of the hit, not of the hull: hulls overlap where surfaces do not.
    // The projection is the camera's moved to the origin (hull.vert). The
    // depth range is the default [0, 1] (gl_DepthRange is not in SPIR-V).
    vec4 clip = sc_view_projection * vec4(point - sc_ray_origin, 1.0);
    {{DEPTH}}
    {{WRITE_OUTPUTS}}
}
