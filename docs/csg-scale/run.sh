#!/bin/sh
# Large CSG scenes: compile time, peak memory and frame time at 10 / 100 / 1,000 / 10,000 primitives,
# drawn from the primitive list (top level of "objects") and, for comparison, compiled as code (the same
# primitives inside a union moved by zero, which is not plain; at most 256 compile as code).
# Usage: docs/csg-scale/run.sh FATHOM [OUT_DIR] [CASES] [SIZE] [RUNS]
#   writes OUT_DIR/csg-scale.csv [the folder of this script: docs/csg-scale] once every case was
#   measured (a failed run leaves the old file as it was) and prints its rows as they come.
#   CASES: N:list or N:code, space-separated ["10:code 31:code 100:list 100:code 250:code 1000:list
#   10000:list"]; SIZE of the frames [320x180]; RUNS a median [3].
# Compile: one 32x18 image with Mesa's shader cache off (parse + compile + upload + one tiny frame), its
# wall time; peak memory: that process's peak resident set (VmHWM, read from /proc while it runs).
# Frame: fathom bench --frame-times at SIZE, median of RUNS after a warm-up, on the backend fathom's
# auto takes.
set -eu
fathom=$1
out=${2:-$(dirname "$0")}
cases=${3:-"10:code 31:code 100:list 100:code 250:code 1000:list 10000:list"}
size=${4:-320x180}
runs=${5:-3}
[ -d "$out" ] || { echo "run.sh: no folder '$out'" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out/.csg-scale.csv.$$"' EXIT
trap 'exit 130' INT TERM

. "$(dirname "$0")/../peak_kb.sh"

# N primitives of seven kinds, rotated, in a cube whose side grows as N^(1/3) (about the same density).
scene() { # N MODE(list|code) > file
    awk -v n="$1" -v mode="$2" 'BEGIN {
        srand(7); side = 1.5 * exp(log(n) / 3); cam = 2.2 * side
        printf "{\"program\": \"csg\", \"materials\": {\"a\": {\"base_color\": [0.8, 0.6, 0.4]}, \"b\": {\"base_color\": [0.3, 0.5, 0.8]}},"
        printf " \"lights\": [{\"type\": \"directional\", \"direction\": [-0.5, 0.7, 0.3], \"intensity\": 3, \"shadow\": \"soft\"}],"
        printf " \"camera\": {\"position\": [%g, %g, %g], \"look_at\": [0, 0, 0]}, \"objects\": [", 0.3 * cam, 0.6 * cam, cam
        if (mode == "code") printf "{\"op\": \"union\", \"position\": [0, 0, 0], \"children\": ["
        split("sphere box round_box torus cylinder capsule cone", kinds, " ")
        for (i = 0; i < n; i++) {
            k = kinds[i % 7 + 1]; s = 0.15 + 0.3 * rand()
            if (k == "sphere") shape = sprintf("\"radius\": %.3f", s)
            else if (k == "box") shape = sprintf("\"size\": [%.3f, %.3f, %.3f]", 2 * s, s, 1.5 * s)
            else if (k == "round_box") shape = sprintf("\"size\": [%.3f, %.3f, %.3f], \"radius\": %.3f", 2 * s, s, 1.5 * s, 0.2 * s)
            else if (k == "torus") shape = sprintf("\"major\": %.3f, \"minor\": %.3f", s, 0.3 * s)
            else if (k == "cone") shape = sprintf("\"radius_bottom\": %.3f, \"radius_top\": %.3f, \"height\": %.3f", s, 0.3 * s, 2 * s)
            else shape = sprintf("\"radius\": %.3f, \"height\": %.3f", 0.6 * s, 2 * s)
            printf "%s{\"shape\": \"%s\", %s, \"position\": [%.3f, %.3f, %.3f], \"rotation\": [%.1f, %.1f, %.1f], \"material\": \"%s\"}",
                (i ? ", " : ""), k, shape, side * (rand() - 0.5), side * (rand() - 0.5), side * (rand() - 0.5),
                360 * rand() - 180, 360 * rand() - 180, 360 * rand() - 180, (i % 2 ? "a" : "b")
        }
        if (mode == "code") printf "]}"
        printf "]}\n"
    }'
}

csv="$tmp/csg-scale.csv"
echo "primitives,path,compile_s,peak_rss_mb,interactive_ms,final_ms" >"$csv"
for case in $cases; do
    n=${case%%:*} mode=${case#*:}
    case "$n" in '' | *[!0-9]*) mode=bad ;; esac
    [ "$mode" = list ] || [ "$mode" = code ] || { echo "run.sh: bad case '$case' (N:list or N:code)" >&2; exit 1; }
    scene "$n" "$mode" >"$tmp/s.json"
    t0=$(date +%s.%N)
    kb=$(peak_kb env MESA_SHADER_CACHE_DISABLE=true "$fathom" --scene "$tmp/s.json" --output "$tmp/o.png" \
        --size 32x18 --spp 1 --quiet) || { echo "run.sh: the 32x18 image of $n primitives ($mode) failed" >&2; exit 1; }
    t1=$(date +%s.%N)
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size "$size" --runs "$runs" >"$tmp/bench" 2>&1 ||
        { cat "$tmp/bench" >&2; exit 1; }
    # the backend auto takes: fragment ms is the 2nd field, compute ms the 4th
    r=$(awk '/: ms per frame/ { c = ($NF == "compute") ? 4 : 2 } c && $1 == "interactive" { i = $c } c && $1 == "final" { f = $c }
        END { if (i == "" || f == "") exit 1; print i, f }' "$tmp/bench") ||
        { cat "$tmp/bench" >&2; echo "run.sh: no interactive or final row" >&2; exit 1; }
    inter=${r% *} final=${r#* }
    [ "$n" -ge 32 ] || mode=code # below 32 bounded primitives every scene is code
    echo "$n,$mode,$secs,$((kb / 1024)),$inter,$final" | tee -a "$csv"
done
# into place in one rename (a copy beside it first: $tmp may be another file system)
cp "$csv" "$out/.csg-scale.csv.$$"
mv -f "$out/.csg-scale.csv.$$" "$out/csg-scale.csv"
echo "wrote $out/csg-scale.csv"
