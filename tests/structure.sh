#!/bin/sh
# structure.sh — the layout rules that the compiler's include paths cannot
# enforce (docs/README.md, "Layers"):
#   1. no call cycle between source files: the "uses a symbol of" graph of
#      the library's and the command line's object files, read with nm, has
#      no loop (tsort finds one);
#   2. at most two source files over 900 lines, and each of them says at its
#      top why it is long.
# Usage: structure.sh BUILD_DIR (run from the project root). Prints what is
# wrong and exits 1, or prints nothing and exits 0.
build=${1:-build}
status=0

objects=$(find "$build/gen" "$build/runtime" "$build/examples/splinecast" -name '*.o' | sort)
[ -n "$objects" ] || { echo "structure: no object files under $build" >&2; exit 1; }
edges=$(mktemp)
trap 'rm -f "$edges"' EXIT
# "object symbol" for every global definition, then "user object" for every
# undefined reference, joined on the symbol.
nm -A -g --defined-only $objects 2>/dev/null |
  awk '{ split($1, p, ":"); if (NF >= 3) print p[1], $3 }' | sort -k2 > "$edges.def"
nm -A -u $objects 2>/dev/null |
  awk '{ split($1, p, ":"); print p[1], $NF }' | sort -k2 > "$edges.use"
join -1 2 -2 2 "$edges.use" "$edges.def" |
  awk '$2 != $3 { print $2, $3 }' | sed "s|$build/||g; s|\.o\b||g" | sort -u > "$edges"
rm -f "$edges.def" "$edges.use"
if ! tsort "$edges" > /dev/null 2> "$edges.err"; then
    echo "structure: a call cycle between files:"
    sed 's/^tsort: /  /' "$edges.err"
    status=1
fi
rm -f "$edges.err"

long=$(find gen runtime examples tests -name '*.[ch]' -exec wc -l {} + | awk '$2 != "total" && $1 > 900 { print $2 }')
count=$(echo "$long" | grep -c . || true)
if [ "$count" -gt 2 ]; then
    echo "structure: $count source files over 900 lines (at most 2):" $long
    status=1
fi
for f in $long; do
    if ! head -n 15 "$f" | grep -qi 'long'; then
        echo "structure: $f has over 900 lines and its opening comment does not say why it is long"
        status=1
    fi
done
exit $status
