{{HEADER}}
#version 450 core

// One vertex of a sub-patch's convex hull relative to its record's centre
// (object space: transforms are baked into the patch data), with the record
// it belongs to.
layout(location = 0) in vec3 sc_hull_position;
{{UV_ATTRIBUTE}}
layout(location = 2) in vec4 sc_hull_domain;
layout(location = 3) in int sc_hull_record;
// The same vertex relative to one origin for the whole scene, for the
// rasteriser alone: hulls of different records meet there bit for bit.
layout(location = 4) in vec3 sc_hull_raster_position;

// The view-projection of the camera moved to the origin, and the eye as a
// float and the rest of its double value: nothing here holds a coordinate
// whose float precision depends on where the model sits.
layout(location = 16) uniform mat4 sc_view_projection;
layout(location = 17) uniform vec3 sc_eye;
layout(location = 18) uniform vec3 sc_eye_low;
// The eye relative to the scene's origin.
layout(location = 19) uniform vec3 sc_raster_eye;

layout(binding = 2) uniform samplerBuffer sc_records;
{{COLOUR_TEXTURE}}

// The fragment stage's inputs (gpu_layout.h): the ray as origin and
// direction relative to the record's centre, where float precision does not
// depend on where the model sits.
layout(location = 0) flat out vec3 sc_ray_origin;
layout(location = 1) out vec3 sc_ray_dir;
{{UV_OUTPUT}}
layout(location = 3) flat out vec4 sc_domain;
layout(location = 4) flat out int sc_record;
layout(location = 8) flat out vec3 sc_centre;
{{COLOUR_OUTPUT}}

void main()
{
    sc_centre = texelFetch(sc_records, {{RECORD_TEXELS}} * sc_hull_record + 3).xyz;
    // Both are floats: the difference rounds only relative to the eye's
    // distance from the centre, and sc_eye_low adds what the float eye lacks.
    sc_ray_origin = (sc_eye - sc_centre) + sc_eye_low;
    // Not normalised: interpolated, it reaches the fragment's hull point at t = 1.
    sc_ray_dir = sc_hull_position - sc_ray_origin;
    {{UV_START}}
    sc_domain = sc_hull_domain;
    sc_record = sc_hull_record;
    {{COLOUR}}
    gl_Position = sc_view_projection * vec4(sc_hull_raster_position - sc_raster_eye, 1.0);
}
