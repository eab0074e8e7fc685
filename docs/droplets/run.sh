#!/bin/sh
# Droplets at scale: build time, memory and frame time for 1k, 10k, 100k and 1M droplets.
# Usage: docs/droplets/run.sh FATHOM [OUT_DIR] [COUNTS]   (writes OUT_DIR/droplets.csv, prints a table)
# Scene: N droplets uniform in a 1 m cube above a ground plane, radii ∝ N^(−1/2) so the droplets cover
# about the same part of the screen at every N (N · π r² fixed); an opaque box hides the cube's left
# third (what culling skips); a sun with hard shadows. 640x360.
# Build: reading the CSV and building the grid (fathom's own clock); memory: peak resident set of a
# 64x36 shot (/usr/bin/time). Frames: fathom bench --frame-times, 1 sample per pixel, median of 5:
# the interactive and final presets, culling off (quality.droplet_cull=0), level of detail off
# (quality.droplet_lod=0: every droplet traced), and the BVH instead of the grid (droplets.structure=bvh).
set -eu
fathom=$1
out=${2:-$(dirname "$0")}
counts=${3:-"1000 10000 100000 1000000"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

. "$(dirname "$0")/scene.sh"

bench() { # LABEL SET... : prints "interactive_ms final_ms"
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size 640x360 --runs 5 "$@" >"$tmp/bench" 2>&1 ||
        { cat "$tmp/bench"; exit 1; }
    awk '$1 == "interactive" {i = $2} $1 == "final" {f = $2} END {print i, f}' "$tmp/bench"
}

csv="$out/droplets.csv"
echo "droplets,read_s,grid_s,cells,listings,gpu_mb,peak_rss_mb,interactive_ms,final_ms,interactive_nocull_ms,final_nocull_ms,interactive_nolod_ms,final_nolod_ms,bvh_build_s,interactive_bvh_ms,final_bvh_ms" >"$csv"
for n in $counts; do
    droplet_scene "$tmp" "$n" "0.4, 1.4, 0.1" "-0.45, 0.9, 0.8"
    /usr/bin/time -f "%M" -o "$tmp/time" "$fathom" --scene "$tmp/s.json" --output "$tmp/o.png" --size 64x36 --spp 1 --quiet
    kb=$(cat "$tmp/time")
    set -- $(bench)
    inter=$1 final=$2
    build=$(awk '$1 == "droplets" {gsub(/[(),]/, " "); print $4, $7, $9, $11, $13}' "$tmp/bench")
    set -- $build
    read_s=$1 grid_s=$2 cells=$3 listings=$4 mb=$5
    set -- $(bench --set quality.droplet_cull=0)
    nocull_i=$1 nocull_f=$2
    set -- $(bench --set quality.droplet_lod=0)
    nolod_i=$1 nolod_f=$2
    set -- $(bench --set droplets.structure=bvh)
    bvh_i=$1 bvh_f=$2
    bvh_s=$(awk '$1 == "droplets" {gsub(/[(),]/, " "); print $7}' "$tmp/bench")
    echo "$n,$read_s,$grid_s,$cells,$listings,$mb,$((kb / 1024)),$inter,$final,$nocull_i,$nocull_f,$nolod_i,$nolod_f,$bvh_s,$bvh_i,$bvh_f" | tee -a "$csv"
done
