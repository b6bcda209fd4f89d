#!/bin/sh
# survey.sh — the real-file survey of issue 17's "large set of real files"
# (docs/step.md, docs/iges.md): runs `splinecast info` on every IGES and STEP
# file given (folders are searched), each with a 60 s cap, and prints one row
# per file and the share of the files holding surfaces that give surfaces > 0.
# A file holds surfaces when it has an IGES entity of type 108, 114, 118, 120,
# 122, 128, 140, 143, 144, 186 or 190–198, or a STEP ADVANCED_FACE or
# FACE_SURFACE. With SURVEY_RENDER=K every K-th file that gives surfaces is
# also rendered with --ref at 256 x 256 and its fail_pct printed.
# Usage: survey.sh SPLINECAST FILE_OR_DIR...
# Columns: file holds rc seconds surfaces projected dropped skipped [fail_pct]
# Exit status 1 when a file crashed, timed out, or a holding file gave no surfaces.
cli=$1
shift
[ -x "$cli" ] || { echo "survey: no splinecast at '$cli'" >&2; exit 2; }
render_every=${SURVEY_RENDER:-0}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

holds_iges() {
    # The D section: records whose column 73 is D, two per entity, the
    # type in columns 1-8 of the first. Files without line breaks are cut
    # into 80-column records first.
    fold -w 80 "$1" | tr -d '\r' | awk '
        substr($0, 73, 1) == "D" { if (n++ % 2 == 0) { t = substr($0, 1, 8) + 0;
            if (t == 108 || t == 114 || t == 118 || t == 120 || t == 122 || t == 128 ||
                t == 140 || t == 143 || t == 144 || t == 186 || (t >= 190 && t <= 198)) { found = 1; exit } } }
        END { exit found ? 0 : 1 }'
}
holds_step() { grep -q -i -E 'ADVANCED_FACE|FACE_SURFACE' "$1"; }

find "$@" -type f \( -iname '*.igs' -o -iname '*.iges' -o -iname '*.stp' -o -iname '*.step' \) |
    sort > "$tmp/files"
total=0; holding=0; drawn=0; bad=0; maxt=0; maxf=; rendered=0; k=0
printf '%-44s %-5s %3s %7s %8s %9s %7s %s\n' file holds rc seconds surfaces projected dropped skipped
while read -r f; do
    case "$f" in
    *.igs|*.IGS|*.iges|*.IGES) if holds_iges "$f"; then h=yes; else h=no; fi ;;
    *) if holds_step "$f"; then h=yes; else h=no; fi ;;
    esac
    t0=$(date +%s.%N)
    timeout -s KILL 60 "$cli" info "$f" > "$tmp/out" 2> "$tmp/err" < /dev/null
    rc=$?
    t1=$(date +%s.%N)
    secs=$(echo "$t1 - $t0" | bc)
    s=$(awk '$1 == "surfaces" { print $2 }' "$tmp/out"); s=${s:-0}
    p=$(awk '$1 == "projected_loops" { print $2 }' "$tmp/out"); p=${p:-0}
    d=$(awk '$1 == "dropped_loops" { print $2 }' "$tmp/out"); d=${d:-0}
    sk=$(awk '$1 == "skipped" { printf "%s%s:%s:%s", sep, $2, $3, $4; sep = "," }' "$tmp/out")
    total=$((total + 1))
    [ "$h" = yes ] && holding=$((holding + 1))
    [ "$h" = yes ] && [ "$s" -gt 0 ] && drawn=$((drawn + 1))
    # rc 0 or 1 is an answer (1: a file refused with its reason); a signal
    # or the 60 s cap is not.
    if [ $rc -gt 1 ] || { [ "$h" = yes ] && [ "$s" -eq 0 ]; }; then
        bad=$((bad + 1))
        sed 's/^/    /' "$tmp/err" | head -3
    fi
    if [ "$(echo "$secs > $maxt" | bc)" = 1 ]; then maxt=$secs; maxf=$f; fi
    fp=
    if [ "$render_every" -gt 0 ] && [ "$s" -gt 0 ]; then
        k=$((k + 1))
        if [ $((k % render_every)) -eq 0 ]; then
            fp=$("$cli" render "$f" -o "$tmp/r.png" --ref --frames 1 --size 256x256 2>/dev/null |
                 sed -n 's/.* fail_pct=\([^ ]*\).*/\1/p')
            fp=${fp:-error}
            rendered=$((rendered + 1))
        fi
    fi
    printf '%-44s %-5s %3d %7.2f %8d %9d %7d %s %s\n' "$(basename "$f")" $h $rc $secs $s $p $d "${sk:--}" "$fp"
done < "$tmp/files"
pct=$(echo "scale=1; 100 * $drawn / ($holding + ($holding == 0))" | bc)
echo "files $total holding_surfaces $holding with_surfaces $drawn pct $pct failures $bad slowest $maxt $(basename "$maxf")"
[ $bad -eq 0 ]
