// Hull view: where the ray misses the surface the hull's own face is drawn,
// dim and at its own depth, so the proxy's slack shows around the surface.
if (!hit) {
    gl_FragDepth = gl_FragCoord.z;
    sc_view_hull = vec4(0.08 * sc_hull_colour(), 1.0);
    {{CLEAR_OUTPUTS}}
    return;
}
