#!/bin/sh
# big_scene.sh OUT.obj [PATCHES] — the large real work the envelope of
# docs/limits.md must admit: PATCHES (default 100,000) bicubic Bézier
# patches of 16 control points each (1.6 M control points, about 28 MB), a
# 400-wide sheet of gently curved patches, each with its own vertices.
# `make check-big` reads it with `splinecast info` and checks the count.
out=${1:?usage: big_scene.sh OUT.obj [PATCHES]}
n=${2:-100000}
awk -v n="$n" 'BEGIN {
    print "# " n " bicubic patches (tests/big_scene.sh)"
    print "cstype bezier"
    print "deg 3 3"
    for (p = 0; p < n; p++) {
        x0 = p % 400; y0 = int(p / 400)
        for (j = 0; j < 4; j++)
            for (i = 0; i < 4; i++)
                printf "v %d %d %d\n", 3 * x0 + i, 3 * y0 + j, (i % 3 && j % 3) ? 1 : 0
        print "surf 0 1 0 1 -16 -15 -14 -13 -12 -11 -10 -9 -8 -7 -6 -5 -4 -3 -2 -1"
        print "parm u 0 1"
        print "parm v 0 1"
        print "end"
    }
}' > "$out.tmp" && mv "$out.tmp" "$out"
