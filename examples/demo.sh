#!/bin/sh
# demo.sh — the whole set-up and the main job on the embedded default scene
# (Newell's 32-patch teapot), with the time of each step: installing missing
# Debian packages, building, then info, the CPU reference and the GPU render.
# Run by `make demo` as `demo.sh CLI OUT MAKE...`: MAKE... is the make
# command for the deps and build steps (without it they are skipped).
# DEMO_SIZE sets the image size (default 512x512).
set -e
SIZE=${DEMO_SIZE:-512x512}
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
# info's per-surface lines are for scripts; the demo shows the summary.
info_summary() { "$CLI" info teapot | grep -v '^surface '; }
step "info (without its per-surface lines)" info_summary
step "CPU reference ($SIZE)" "$CLI" ref teapot -o "$OUT/teapot.png" --size "$SIZE" --stats
echo "demo: wrote $OUT/teapot.png and $OUT/teapot.aov" >&2
step "GPU ray casting ($SIZE) and its accuracy against the reference" \
    "$CLI" render teapot -o "$OUT/teapot-gpu.png" --size "$SIZE" --ref --aov "$OUT/teapot-gpu.aov"
echo "demo: wrote $OUT/teapot-gpu.png and $OUT/teapot-gpu.aov" >&2
