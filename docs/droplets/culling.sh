#!/bin/sh
# What culling saves where it matters: 1,000,000 droplets (as in run.sh) behind a wall that hides
# about 80 % of the view. Frame times (bench --frame-times, 640x360, median of 5, on the backend
# fathom's auto takes) with the grid walk stopping at the wall (droplet_cull=1, the default) and
# walking on behind it (0; the same image). Prints one line each; writes no file.
# Usage: docs/droplets/culling.sh FATHOM [N] [SIZE] [RUNS]   (defaults: 1000000 640x360 5)
set -eu
fathom=$1
n=${2:-1000000}
size=${3:-640x360}
runs=${4:-5}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
. "$(dirname "$0")/scene.sh"
droplet_scene "$tmp" "$n" "1.3, 1.4, 0.05" "0.05, 1.0, 0.9"
for cull in 1 0; do
    "$fathom" bench --frame-times --scene "$tmp/s.json" --size "$size" --runs "$runs" --set quality.droplet_cull=$cull \
        >"$tmp/bench" 2>&1 || { cat "$tmp/bench" >&2; exit 1; }
    # the backend auto takes: fragment ms is the 2nd field, compute ms the 4th
    line=$(awk '/: ms per frame/ { c = ($NF == "compute") ? 4 : 2 }
        c && ($1 == "interactive" || $1 == "final") { printf "%s%s %s ms", (k ? "  " : ""), $1, $c; k++ } END { if (k != 2) exit 1 }' "$tmp/bench") ||
        { cat "$tmp/bench" >&2; echo "culling.sh: no interactive or final row" >&2; exit 1; }
    echo "droplet_cull=$cull: $line"
done
