#!/bin/sh
# Large CSG scenes: compile time, peak memory and frame time at 10 / 100 / 1,000 / 10,000 primitives,
# drawn from the primitive list (top level of "objects") and, for comparison, compiled as code (the same
# primitives inside a union moved by zero, which is not plain; at most 256 compile as code).
# Usage: docs/csg-scale/run.sh FATHOM [OUT_DIR]   (writes OUT_DIR/csg-scale.csv and prints a table)
# Compile: one 32x18 image with Mesa's shader cache off (parse + compile + upload + one tiny frame).
# Frame: fathom bench --frame-times at 320x180, median of 3 after a warm-up.
set -eu
fathom=$1
out=${2:-$(dirname "$0")}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

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

csv="$out/csg-scale.csv"
echo "primitives,path,compile_s,peak_rss_mb,interactive_ms,final_ms" >"$csv"
for case in "10 code" "31 code" "100 list" "100 code" "250 code" "1000 list" "10000 list"; do
    set -- $case
    n=$1 mode=$2
    scene "$n" "$mode" >"$tmp/s.json"
    /usr/bin/time -f "%e %M" -o "$tmp/time" env MESA_SHADER_CACHE_DISABLE=true "$fathom" --scene "$tmp/s.json" \
        --output "$tmp/o.png" --size 32x18 --spp 1 --quiet
    read -r secs kb <"$tmp/time"
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size 320x180 --runs 3 >"$tmp/bench" 2>&1
    inter=$(awk '$1 == "interactive" {print $2}' "$tmp/bench")
    final=$(awk '$1 == "final" {print $2}' "$tmp/bench")
    [ "$n" -ge 32 ] || mode=code # below 32 bounded primitives every scene is code
    echo "$n,$mode,$secs,$((kb / 1024)),$inter,$final" | tee -a "$csv"
done
