{{HEADER}}
#version 450 core

// The rectangle of pixels whose candidate lists the fragment stage runs.
{{UNIFORM_LIST_QUAD}}

void main()
{
    // Four vertices, a triangle strip: (x0, y0), (x1, y0), (x0, y1), (x1, y1).
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    gl_Position = vec4(mix(sc_list_quad.xy, sc_list_quad.zw, corner), 0.0, 1.0);
}
