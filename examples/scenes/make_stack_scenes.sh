#!/bin/sh
# Writes the scenes of the early-ray-termination and draw-order benchmarks
# (docs/speed.md) into the folder given (default: this script's folder):
#   stack_N.obj, N = 2, 4, …, 128: N copies of one bicubic Bézier patch
#     over [-1, 1]², stacked 0.01 apart along -z (the bump, 0.03 high at the inner
#     control points, spans three layers), so that seen from +z
#     (camera 0,0,4.5 → 0,0,0, fovy 22.6) every patch covers most of the
#     view (seed 000, Table 3);
#   mixed_keys.obj: 24 patches, rotated about z and stacked 0.05 apart,
#     of six variant keys — bez2x2, bez3x3, rational bez3x3, bez2x3, bez4x4
#     and bez5x5 — interleaved in depth, so that front-to-back order and
#     grouping by program disagree everywhere.
# The output is deterministic (awk's %.6g), so the checked-in files can be
# regenerated and compared.
set -eu
out=${1:-$(dirname "$0")}
for n in 2 4 8 16 32 64 128; do
  awk -v n="$n" 'BEGIN {
    printf "# %d stacked bicubic patches (examples/scenes/make_stack_scenes.sh)\n", n
    print "mtllib examples.mtl"
    split("grey blue orange green red", colours, " ")
    for (k = 0; k < n; k++) {
      printf "g layer%d\nusemtl %s\n", k, colours[k % 5 + 1]
      for (j = 0; j <= 3; j++)
        for (i = 0; i <= 3; i++) {
          bump = (i == 1 || i == 2) && (j == 1 || j == 2) ? 0.03 : 0
          printf "v %.6g %.6g %.6g\n", -1 + 2 * i / 3, -1 + 2 * j / 3, -0.01 * k + bump
        }
      print "cstype bezier\ndeg 3 3"
      printf "surf 0 1 0 1"
      for (v = -16; v <= -1; v++) printf " %d", v
      print "\nparm u 0 1\nparm v 0 1\nend"
    }
  }' > "$out/stack_$n.obj"
done
awk 'function r(x) { return x < 1e-9 && x > -1e-9 ? 0 : x }
BEGIN {
  pi = 3.14159265358979
  print "# 24 overlapping patches of six variant keys, interleaved in depth"
  print "# (examples/scenes/make_stack_scenes.sh)"
  print "mtllib examples.mtl"
  split("2 3 3 2 4 5", du, " "); split("2 3 3 3 4 5", dv, " ")
  split("0 0 1 0 0 0", rational, " ")
  split("grey blue orange green red grey", colours, " ")
  for (k = 0; k < 24; k++) {
    key = k % 6 + 1; p = du[key]; q = dv[key]
    angle = k * 15 * pi / 180; c = cos(angle); s = sin(angle)
    printf "g layer%d\nusemtl %s\n", k, colours[key]
    for (j = 0; j <= q; j++)
      for (i = 0; i <= p; i++) {
        x = 1.2 * (-1 + 2 * i / p); y = 1.2 * (-1 + 2 * j / q)
        z = -0.05 * k + 0.02 * cos(pi * (i / p + 0.25 * k)) * cos(pi * j / q)
        w = rational[key] && i > 0 && i < p && j > 0 && j < q ? 1.5 : 1
        if (rational[key])
          printf "v %.6g %.6g %.6g %.6g\n", r(c * x - s * y), r(s * x + c * y), r(z), w
        else
          printf "v %.6g %.6g %.6g\n", r(c * x - s * y), r(s * x + c * y), r(z)
      }
    printf "cstype %sbezier\ndeg %d %d\nsurf 0 1 0 1", rational[key] ? "rat " : "", p, q
    for (v = -(p + 1) * (q + 1); v <= -1; v++) printf " %d", v
    print "\nparm u 0 1\nparm v 0 1\nend"
  }
}' > "$out/mixed_keys.obj"
