#!/bin/sh
# Droplets at scale: build time, memory and frame time for 1k, 10k, 100k and 1M droplets.
# Usage: docs/droplets/run.sh FATHOM [OUT_DIR] [COUNTS] [SIZE] [RUNS]
#   writes OUT_DIR/droplets.csv [the folder of this script: docs/droplets] once every count was
#   measured (a failed run leaves the old file as it was) and prints its rows as they come.
#   COUNTS ["1000 10000 100000 1000000"], SIZE of the frames [640x360], RUNS a median [5].
# Scene: N droplets uniform in a 1 m cube above a ground plane, radii ∝ N^(−1/2) so the droplets cover
# about the same part of the screen at every N (N · π r² fixed); an opaque box hides the cube's left
# third (what culling skips); a sun with hard shadows.
# Build: reading the CSV and building the grid (fathom's own clock); memory: peak resident set of a
# 64x36 shot (VmHWM, read from /proc while it runs). Frames: fathom bench --frame-times, 1 sample per
# pixel, median of RUNS, on the backend fathom's auto takes: the interactive and final presets, culling
# off (quality.droplet_cull=0), level of detail off (quality.droplet_lod=0: every droplet traced), and
# the BVH instead of the grid (droplets.structure=bvh).
set -eu
fathom=$1
out=${2:-$(dirname "$0")}
counts=${3:-"1000 10000 100000 1000000"}
size=${4:-640x360}
runs=${5:-5}
[ -d "$out" ] || { echo "run.sh: no folder '$out'" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out/.droplets.csv.$$"' EXIT
trap 'exit 130' INT TERM

. "$(dirname "$0")/scene.sh"

. "$(dirname "$0")/../peak_kb.sh"

bench() { # SET... : prints "interactive_ms final_ms" (the backend auto takes: fragment ms is the 2nd
    # field, compute ms the 4th)
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size "$size" --runs "$runs" "$@" >"$tmp/bench" 2>&1 ||
        { cat "$tmp/bench" >&2; exit 1; }
    awk '/: ms per frame/ { c = ($NF == "compute") ? 4 : 2 } c && $1 == "interactive" { i = $c } c && $1 == "final" { f = $c }
        END { if (i == "" || f == "") exit 1; print i, f }' "$tmp/bench" ||
        { cat "$tmp/bench" >&2; echo "run.sh: no interactive or final row" >&2; exit 1; }
}

csv="$tmp/droplets.csv"
echo "droplets,read_s,grid_s,cells,listings,gpu_mb,peak_rss_mb,interactive_ms,final_ms,interactive_nocull_ms,final_nocull_ms,interactive_nolod_ms,final_nolod_ms,bvh_build_s,interactive_bvh_ms,final_bvh_ms" >"$csv"
for n in $counts; do
    droplet_scene "$tmp" "$n" "0.4, 1.4, 0.1" "-0.45, 0.9, 0.8"
    kb=$(peak_kb "$fathom" --scene "$tmp/s.json" --output "$tmp/o.png" --size 64x36 --spp 1 --quiet) ||
        { echo "run.sh: the 64x36 shot of $n droplets failed" >&2; exit 1; }
    r=$(bench)
    set -- $r
    inter=$1 final=$2
    build=$(awk '$1 == "droplets" {gsub(/[(),]/, " "); print $4, $7, $9, $11, $13}' "$tmp/bench")
    [ -n "$build" ] || { echo "run.sh: no droplets line in fathom bench's output" >&2; exit 1; }
    set -- $build
    read_s=$1 grid_s=$2 cells=$3 listings=$4 mb=$5
    r=$(bench --set quality.droplet_cull=0)
    set -- $r
    nocull_i=$1 nocull_f=$2
    r=$(bench --set quality.droplet_lod=0)
    set -- $r
    nolod_i=$1 nolod_f=$2
    r=$(bench --set droplets.structure=bvh)
    set -- $r
    bvh_i=$1 bvh_f=$2
    bvh_s=$(awk '$1 == "droplets" {gsub(/[(),]/, " "); print $7}' "$tmp/bench")
    echo "$n,$read_s,$grid_s,$cells,$listings,$mb,$((kb / 1024)),$inter,$final,$nocull_i,$nocull_f,$nolod_i,$nolod_f,$bvh_s,$bvh_i,$bvh_f" | tee -a "$csv"
done
# into place in one rename (a copy beside it first: $tmp may be another file system)
cp "$csv" "$out/.droplets.csv.$$"
mv -f "$out/.droplets.csv.$$" "$out/droplets.csv"
echo "wrote $out/droplets.csv"
