// Normals face the viewer, so that no orientation convention of a file
// format can make two correct renders disagree.
vec3 to_eye = -normalize(sc_ray_dir);
vec3 facing_normal = dot(normal, to_eye) < 0.0 ? -normal : normal;
