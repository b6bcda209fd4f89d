{{HEADER}}
#version 450 core

// One vertex of a sub-patch's convex hull relative to its record's centre
// (object space: transforms are baked into the patch data), with the record
// it belongs to.
{{ATTRIB_HULL_POSITION}}
{{ATTRIB_HULL_UV}}
{{ATTRIB_HULL_DOMAIN}}
{{ATTRIB_HULL_RECORD}}
// The same vertex relative to one origin for the whole scene, for the
// rasteriser alone: hulls of different records meet there bit for bit.
{{ATTRIB_HULL_RASTER_POSITION}}

// The view-projection of the camera moved to the origin, and the eye as a
// float and the rest of its double value: nothing here holds a coordinate
// whose float precision depends on where the model sits.
{{UNIFORM_VIEW_PROJECTION}}
{{UNIFORM_EYE}}
{{UNIFORM_EYE_LOW}}
// The eye relative to the scene's origin.
{{UNIFORM_RASTER_EYE}}

{{TEXTURE_RECORDS}}
{{COLOUR_TEXTURE}}
{{VIEW_START_DECLARATIONS}}

// The fragment stage's inputs (gpu_layout.h): the ray as origin and
// direction relative to the record's centre, where float precision does not
// depend on where the model sits.
{{VARYING_RAY_ORIGIN}}
{{VARYING_RAY_DIR}}
{{VARYING_UV0}}
{{VARYING_DOMAIN}}
{{VARYING_RECORD}}
{{VARYING_CENTRE}}
{{VARYING_BASE_COLOUR}}

// Depth peeling draws the hulls again with another program and tests their
// depth for equality: gl_Position must come out bit for bit the same.
invariant gl_Position;

void main()
{
    sc_centre = texelFetch(sc_records, {{RECORD_TEXELS}} * sc_hull_record + 3).xyz;
    // Both are floats: the difference rounds only relative to the eye's
    // distance from the centre, and sc_eye_low adds what the float eye lacks.
    sc_ray_origin = (sc_eye - sc_centre) + sc_eye_low;
    // Not normalised: interpolated, it reaches the fragment's hull point at t = 1.
    sc_ray_dir = sc_hull_position - sc_ray_origin;
    sc_domain = sc_hull_domain;
    sc_record = sc_hull_record;
    {{UV_START}}
    {{COLOUR}}
    gl_Position = sc_view_projection * vec4(sc_hull_raster_position - sc_raster_eye, 1.0);
}
