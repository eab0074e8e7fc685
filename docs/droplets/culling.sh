#!/bin/sh
# What culling saves where it matters: 1,000,000 droplets (as in run.sh) behind a wall that hides
# about 80 % of the view. Frame times (bench --frame-times, 640x360, median of 5) with the grid walk
# stopping at the wall (droplet_cull=1, the default) and walking on behind it (0; the same image).
# Usage: docs/droplets/culling.sh FATHOM [N]
set -eu
fathom=$1
n=${2:-1000000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
. "$(dirname "$0")/scene.sh"
droplet_scene "$tmp" "$n" "1.3, 1.4, 0.05" "0.05, 1.0, 0.9"
for cull in 1 0; do
    printf 'droplet_cull=%s: ' "$cull"
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size 640x360 --runs 5 --set quality.droplet_cull=$cull 2>&1 |
        awk '$1 == "interactive" || $1 == "final" {printf "%s %s ms  ", $1, $2} END {print ""}'
done
