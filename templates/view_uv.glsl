// (u, v) as red and green, repeating every unit of the surface's domain.
sc_view_uv = vec4(fract(uv), 0.0, 1.0);
