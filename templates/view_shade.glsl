sc_colour = vec4(sc_shade_headlight(sc_base_colour, facing_normal, to_eye), 1.0);
