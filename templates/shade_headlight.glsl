// Headlight diffuse: the light sits at the eye, so the normal that faces the
// viewer is the one that is lit.
vec3 sc_shade_headlight(vec3 base_colour, vec3 facing_normal, vec3 to_eye)
{
    const float ambient = 0.15;
    return base_colour * (ambient + (1.0 - ambient) * max(dot(facing_normal, to_eye), 0.0));
}
