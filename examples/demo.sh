#!/bin/sh
# demo.sh — the whole set-up and the main job on the embedded default scene
# (Newell's 32-patch teapot), with the time of each step: installing missing
# Debian packages, building, then info, the CPU reference and the GPU render.
# Run by `make demo` as `demo.sh CLI OUT MAKE...`: MAKE... is the make
# command for the deps and build steps (without it they are skipped).
set -e
CLI=${1:-build/splinecast}
OUT=${2:-build/demo}
[ $# -ge 2 ] && shift 2 || shift $#
step() {
    name=$1; shift
    t0=$(date +%s.%N)
    "$@"
    t1=$(date +%s.%N)
    awk -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "demo: %s took %.2f s\n", n, b - a }' >&2
}
if [ $# -gt 0 ]; then
    step "Debian packages (make deps)" "$@" deps
    step "build (make all)" "$@" all
fi
mkdir -p "$OUT"
echo "demo: the embedded 32-patch teapot" >&2
step "info" "$CLI" info teapot
step "CPU reference (512x512)" "$CLI" ref teapot -o "$OUT/teapot.png" --size 512x512 --stats
echo "demo: wrote $OUT/teapot.png and $OUT/teapot.aov" >&2
step "GPU ray casting (512x512) and its accuracy against the reference" \
    "$CLI" render teapot -o "$OUT/teapot-gpu.png" --size 512x512 --ref
echo "demo: wrote $OUT/teapot-gpu.png and $OUT/teapot-gpu.aov" >&2
