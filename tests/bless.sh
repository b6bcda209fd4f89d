#!/bin/sh
# Re-blesses the golden GLSL files: regenerates tests/golden/ (the programs
# of the keys in tests/golden/keys.txt, their vertex programs and the
# manifest) with the given splinecast command. Usage: tests/bless.sh [CLI]
set -e
cli=${1:-build/splinecast}
root=$(cd "$(dirname "$0")/.." && pwd)
keys=$(grep -v '^#' "$root/tests/golden/keys.txt")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$cli" gen --key $keys -o "$tmp" >/dev/null
rm -f "$root"/tests/golden/*.frag "$root"/tests/golden/*.vert "$root"/tests/golden/manifest.tsv
cp "$tmp"/* "$root/tests/golden/"
echo "blessed $(ls "$tmp" | wc -l) files in tests/golden"
