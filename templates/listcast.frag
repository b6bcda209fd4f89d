{{HEADER}}
#version 450 core

// What the intersection reads, set here for each candidate in turn (there
// is no hull, so no vertex stage computes them).
{{INPUTS}}
{{GLOBAL_CENTRE}}
{{GLOBAL_BASE_COLOUR}}

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
    // This pixel's candidates: the hulls whose projected outline holds its
    // centre, nearest box first (runtime/gl/gl_lists.c).
    ivec2 cell = ivec2(gl_FragCoord.xy) - sc_list_cells.xy;
    int head = sc_list_cells.w + cell.y * sc_list_cells.z + cell.x;
    int first = int(texelFetch(sc_list_heads, head).r);
    int end = int(texelFetch(sc_list_heads, head + 1).r);
    if (first == end)
        discard;
    vec3 pixel_ray = normalize(sc_pixel_to_ray * vec3(gl_FragCoord.xy, 1.0));
    {{RESULTS}}
    {{CANDIDATE_RESULTS}}
    // Distance along the unit ray of the nearest hit so far.
    float nearest = 3.0e38;
    vec3 hit_origin = vec3(0.0), hit_dir = vec3(0.0), hit_centre = vec3(0.0);
    int hit_record = 0;
    for (int i = first; i < end; i++) {
        int slot = int(texelFetch(sc_list_items, i).r);
        vec4 record_and_box = texelFetch(sc_list_hulls, 2 * slot + 1);
        // No point of this box, nor of any later one, lies nearer.
        if (record_and_box.y >= nearest)
            break;
        sc_record = int(record_and_box.x);
        sc_domain = texelFetch(sc_list_hulls, 2 * slot);
        sc_centre = texelFetch(sc_records, {{RECORD_TEXELS}} * sc_record + 3).xyz;
        // As hull.vert computes them: relative to the record's centre. The
        // direction's length is the centre's distance, as a hull point's
        // would be about: the tolerance scales with it.
        sc_ray_origin = (sc_eye - sc_centre) + sc_eye_low;
        float reach = max(length(sc_ray_origin), 1.0e-30);
        sc_ray_dir = pixel_ray * reach;
        sc_t_limit = nearest / reach;
        {{COUNT}}
        {{CALL}}
        if (candidate_hit) {
            nearest = candidate_t * reach;
            {{KEEP}}
            hit_origin = sc_ray_origin;
            hit_dir = sc_ray_dir;
            hit_centre = sc_centre;
            hit_record = sc_record;
        }
    }
    {{ON_MISS}}
    sc_ray_origin = hit_origin;
    sc_ray_dir = hit_dir;
    sc_centre = hit_centre;
    sc_record = hit_record;
    {{BASE_COLOUR}}

    // Depth of the hit. The projection is the camera's moved to the origin
    // (hull.vert). The depth range is the default [0, 1].
    vec4 clip = sc_view_projection * vec4(point - sc_ray_origin, 1.0);
    {{DEPTH}}
    {{WRITE_OUTPUTS}}
}
