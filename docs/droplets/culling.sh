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
awk -v n="$n" 'BEGIN { srand(11); print "x,y,z,r"; r = 0.012 * sqrt(1000 / n)
    for (i = 0; i < n; i++) printf "%.5f,%.5f,%.5f,%.4e\n", rand() - 0.5, 0.5 + rand(), rand() - 0.5, r * (0.5 + rand()) }' \
    >"$tmp/drops.csv"
cat >"$tmp/s.json" <<JSON
{"program": "csg", "camera": {"position": [0.2, 1.0, 2.4], "look_at": [0, 1.0, 0], "fov": 40},
 "environment": {"color": [0.6, 0.7, 0.9], "intensity": 1},
 "lights": [{"type": "directional", "direction": [0.4, 0.8, 0.45], "intensity": 2.5, "shadow": "hard"}],
 "materials": {"ground": {"base_color": [0.5, 0.45, 0.4], "roughness": 0.8},
               "wall": {"base_color": [0.7, 0.2, 0.15], "roughness": 0.5}},
 "objects": [{"shape": "plane", "normal": [0, 1, 0], "material": "ground"},
             {"shape": "box", "size": [1.3, 1.4, 0.05], "position": [0.05, 1.0, 0.9], "material": "wall"}],
 "droplets": {"file": "drops.csv"}}
JSON
for cull in 1 0; do
    printf 'droplet_cull=%s: ' "$cull"
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size 640x360 --runs 5 --set quality.droplet_cull=$cull 2>&1 |
        awk '$1 == "interactive" || $1 == "final" {printf "%s %s ms  ", $1, $2} END {print ""}'
done
