#!/bin/sh
# The window's flight on every shipped scene: fathom bench --interactive at 1280x720, 30 fps target.
# Usage: docs/interactive/run.sh FATHOM [OUT_DIR]   (writes OUT_DIR/interactive.csv)
set -eu
fathom=$1
out=${2:-$(dirname "$0")}
csv="$out/interactive.csv"
echo "scene,window_w,window_h,target_fps,median_ms,p95_ms,inside_w,inside_h,rmse_mean,rmse_worst,first_full_ms,spp,spp_ms,adaptive_fraction,adaptive_ms,adaptive_rmse_vs_spp,one_spp_rmse_vs_spp,depth_aware_rmse_mean,depth_aware_rmse_worst,reprojected_rmse_mean,reprojected_rmse_worst" >"$csv"
for s in $("$fathom" --list-scenes | awk '{print $1}'); do
    "$fathom" bench --interactive --scene "$s" --size 1280x720 --quiet | tee /dev/stderr | sed -n 's/^csv,//p' >>"$csv"
done
