#!/bin/sh
# The window's flight on every shipped scene: fathom bench --interactive at 1280x720, 30 fps target.
# Usage: docs/interactive/run.sh FATHOM [OUT_DIR] [SIZE] [SCENES]
#   writes OUT_DIR/interactive.csv [the folder of this script: docs/interactive] once every scene
#   was measured (a failed run leaves the old file as it was); each run's report goes to stderr.
#   SIZE [1280x720]; SCENES, space-separated [every scene fathom --list-scenes lists].
set -eu
fathom=$1
out=${2:-$(dirname "$0")}
size=${3:-1280x720}
scenes=${4:-}
[ -d "$out" ] || { echo "run.sh: no folder '$out'" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out/.interactive.csv.$$"' EXIT
trap 'exit 130' INT TERM
[ -n "$scenes" ] || scenes=$("$fathom" --list-scenes | awk '{print $1}')
[ -n "$scenes" ] || { echo "run.sh: fathom --list-scenes listed no scene" >&2; exit 1; }
csv="$tmp/interactive.csv"
echo "scene,window_w,window_h,target_fps,median_ms,p95_ms,inside_w,inside_h,rmse_mean,rmse_worst,first_full_ms,spp,spp_ms,adaptive_fraction,adaptive_ms,adaptive_rmse_vs_spp,one_spp_rmse_vs_spp,depth_aware_rmse_mean,depth_aware_rmse_worst,reprojected_rmse_mean,reprojected_rmse_worst" >"$csv"
for s in $scenes; do
    "$fathom" bench --interactive --scene "$s" --size "$size" --quiet >"$tmp/bench" 2>&1 ||
        { cat "$tmp/bench" >&2; echo "run.sh: fathom bench --interactive failed on $s" >&2; exit 1; }
    cat "$tmp/bench" >&2
    grep -q '^csv,' "$tmp/bench" || { echo "run.sh: no csv line for $s" >&2; exit 1; }
    sed -n 's/^csv,//p' "$tmp/bench" >>"$csv"
done
# into place in one rename (a copy beside it first: $tmp may be another file system)
cp "$csv" "$out/.interactive.csv.$$"
mv -f "$out/.interactive.csv.$$" "$out/interactive.csv"
echo "wrote $out/interactive.csv" >&2
