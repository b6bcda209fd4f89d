sc_aov_surface = surface;
// t along the unit ray from the eye, in world units.
sc_aov_uvt = vec4(uv, t * length(sc_ray_dir), float(iters));
sc_aov_point = vec4(point + sc_centre, 1.0);
sc_aov_normal = vec4(facing_normal, 0.0);
