// Iterations taken, blue (1) to red ({{MAX_ITERS}}).
float iteration_share = float(iters - 1) / {{MAX_ITERS_MINUS_ONE}};
sc_view_iters = vec4(iteration_share, 0.0, 1.0 - iteration_share, 1.0);
