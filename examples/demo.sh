#!/bin/sh
# demo.sh — the main job on the embedded default scene, with the time of
# each step. Run by `make demo` after the build.
set -e
CLI=${1:-build/splinecast}
step() {
    name=$1; shift
    t0=$(date +%s.%N)
    "$@"
    t1=$(date +%s.%N)
    awk -v n="$name" -v a="$t0" -v b="$t1" 'BEGIN { printf "demo: %s took %.2f s\n", n, b - a }' >&2
}
echo "demo: the embedded 32-patch teapot" >&2
step "info" "$CLI" info teapot
