#!/bin/sh
# demo.sh — the main job on the embedded default scene (Newell's 32-patch
# teapot), with the time of each step. Run by `make demo` after the build.
set -e
CLI=${1:-build/splinecast}
OUT=${2:-build/demo}
mkdir -p "$OUT"
step() {
    name=$1; shift
    t0=$(date +%s.%N)
    "$@"
    t1=$(date +%s.%N)
    awk -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "demo: %s took %.2f s\n", n, b - a }' >&2
}
echo "demo: the embedded 32-patch teapot" >&2
step "info" "$CLI" info teapot
step "CPU reference (512x512)" "$CLI" ref teapot -o "$OUT/teapot.png" --size 512x512 --stats
echo "demo: wrote $OUT/teapot.png and $OUT/teapot.aov" >&2
step "GPU ray casting (512x512) and its accuracy against the reference" \
    "$CLI" render teapot -o "$OUT/teapot-gpu.png" --size 512x512 --ref
echo "demo: wrote $OUT/teapot-gpu.png and $OUT/teapot-gpu.aov" >&2
