#!/bin/sh
# make_scale_scenes.sh OUT_DIR [NX NY [SPANS]] — the scenes of the scale
# benchmark (docs/speed.md, "Scale"), too large to keep in the tree:
#   OUT_DIR/teapot_grid.bpt: NX × NY copies (default 56 × 56: 100,352
#     patches, 1.6 M control points, about 25 MB) of the 32-patch teapot
#     of this folder (teapot32.bpt), 8 units apart in x and 6 in y, in the
#     order of the copies (x fastest);
#   OUT_DIR/bspline_sheet.obj: one bicubic B-spline surface of SPANS × SPANS
#     spans (default 316: 99,856 spans, (SPANS + 3)² control points) over
#     [0, SPANS]², a gentle swell z = 0.3 sin(x / 3) cos(y / 5) sampled at
#     the control points, uniform clamped knots.
# The output is deterministic (awk, %.8g: every teapot coordinate plus an
# offset below 10⁴ is printed exactly), so a test can make a small grid and
# know what it holds.
set -eu
out=${1:?usage: make_scale_scenes.sh OUT_DIR [NX NY [SPANS]]}
nx=${2:-56}
ny=${3:-56}
spans=${4:-316}
here=$(dirname "$0")
mkdir -p "$out"
# .bpt: the patch count, then per patch its degrees and points, u fastest.
awk -v nx="$nx" -v ny="$ny" '
NR == 1 { npatches = $1; next }
{ for (i = 1; i <= NF; i++) token[ntokens++] = $i }
END {
    printf "%d\n", npatches * nx * ny
    for (j = 0; j < ny; j++)
        for (i = 0; i < nx; i++) {
            dx = 8 * i; dy = 6 * j; t = 0
            for (p = 0; p < npatches; p++) {
                du = token[t++]; dv = token[t++]
                printf "%d %d\n", du, dv
                for (k = 0; k < (du + 1) * (dv + 1); k++) {
                    printf "%.8g %.8g %.8g\n", token[t] + dx, token[t + 1] + dy, token[t + 2]
                    t += 3
                }
            }
        }
}' "$here/teapot32.bpt" > "$out/teapot_grid.bpt.tmp"
mv "$out/teapot_grid.bpt.tmp" "$out/teapot_grid.bpt"
awk -v n="$spans" 'BEGIN {
    m = n + 3   # control points per direction
    printf "# one bicubic B-spline surface of %d x %d spans (examples/scenes/make_scale_scenes.sh)\n", n, n
    for (j = 0; j < m; j++)
        for (i = 0; i < m; i++) {
            # Greville abscissae of the clamped uniform knots: the control
            # points lie over the parameters they most influence.
            x = (i < 3 ? i * (i + 1) / 6 : i > n ? n - (m - 1 - i) * (m - i) / 6 : i - 1)
            y = (j < 3 ? j * (j + 1) / 6 : j > n ? n - (m - 1 - j) * (m - j) / 6 : j - 1)
            printf "v %.8g %.8g %.8g\n", x, y, 0.3 * sin(x / 3) * cos(y / 5)
        }
    print "cstype bspline\ndeg 3 3"
    printf "surf 0 %d 0 %d", n, n
    for (k = 1; k <= m * m; k++) printf " %d", k
    printf "\n"
    for (d = 0; d < 2; d++) {
        printf "parm %s 0 0 0", d ? "v" : "u"
        for (k = 0; k <= n; k++) printf " %d", k
        printf " %d %d %d\n", n, n, n
    }
    print "end"
}' > "$out/bspline_sheet.obj.tmp"
mv "$out/bspline_sheet.obj.tmp" "$out/bspline_sheet.obj"
