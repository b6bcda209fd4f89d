// A colour for each proxy hull, hashed from its record and the corner of its
// sub-patch domain, so that neighbouring hulls differ.
vec3 sc_hull_colour()
{
    vec3 id = vec3(sc_domain.xz, float(sc_record));
    float h = fract(sin(dot(id, vec3(12.9898, 78.233, 37.719))) * 43758.5453);
    return 0.55 + 0.45 * cos(6.2831853 * (h + vec3(0.0, 0.33, 0.67)));
}
