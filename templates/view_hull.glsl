// The surface seen through its hull, lit, in the hull's colour.
sc_view_hull = vec4(sc_shade_headlight(sc_hull_colour(), facing_normal, to_eye), 1.0);
