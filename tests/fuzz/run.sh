#!/bin/sh
# Fuzzes the scene parser (TARGET scene, the default), the droplet-file reader and its grid and BVH
# (TARGET droplets), or the camera-path, shot-record, tile-record and formula-declaration readers
# (TARGET readers) with libFuzzer (clang, ASan + UBSan) for MINUTES minutes [5].
# Seeds: every shipped scene (scenes: the keys and names of the format in scene.dict), or the head of
# scenes/spray.csv and a ParaView-style file (droplets.dict).
# Findings (crash-*, leak-*, timeout-*) land in build-fuzz/findings-TARGET; the corpus grows in
# build-fuzz/corpus-TARGET.
# Usage: tests/fuzz/run.sh [MINUTES] [scene|droplets|readers]   (needs: apt-get install clang)
# FUZZ_BUILD=DIR uses a folder already configured with -DFATHOM_FUZZ=ON (tests/tree/build_types.sh), and
# FUZZ_SECONDS=N runs N seconds instead of MINUTES (a smoke run).
set -eu
minutes=${1:-5}
target=${2:-scene}
src=$(cd "$(dirname "$0")/../.." && pwd)
build="${FUZZ_BUILD:-$src/build-fuzz}"
seconds=${FUZZ_SECONDS:-$((minutes * 60))}
[ -n "${FUZZ_BUILD:-}" ] || CC=clang CXX=clang++ cmake -S "$src" -B "$build" -DFATHOM_FUZZ=ON -DBUILD_TESTING=OFF >/dev/null
cmake --build "$build" -j 2 --target "fuzz_$target" >/dev/null
mkdir -p "$build/corpus-$target" "$build/findings-$target"
if [ "$target" = scene ]; then
    cp "$src"/scenes/*.json "$build/corpus-$target/"
elif [ "$target" = readers ]; then
    # the first byte picks the reader: 0 a camera path, 1 a shot record, 2 a tile record, 3 a formula, 4 a fragment
    for f in "$src"/docs/flight/*.json; do { printf '\000'; cat "$f"; } >"$build/corpus-$target/path-$(basename "$f")"; done
    printf '\001{"scene":"/x/scenes/csg.json","sets":["a.b=1"],"camera":{"position":[0,1,5],"yaw":0,"pitch":0,"fov_y":0.8},"size":[64,36]}' >"$build/corpus-$target/shot"
    printf '\0022 4 640 360 180 7' >"$build/corpus-$target/tile"
    for f in "$src"/shaders/fractal/*.glsl; do { printf '\003'; cat "$f"; } >"$build/corpus-$target/formula-$(basename "$f")"; done
    for f in "$src"/tests/frag/*.frag "$src"/docs/fragments/*.frag; do { printf '\004'; cat "$f"; } >"$build/corpus-$target/frag-$(basename "$f")"; done
    export FATHOM_DATA_DIR="$src" # a fragment's includes: fathom's set
else
    head -n 40 "$src/scenes/spray.csv" >"$build/corpus-$target/spray.csv"
    printf '"Points:0","Points:1","Points:2","diameter"\n0.5,1.5,-2,0.002\n' >"$build/corpus-$target/paraview.csv"
fi
cd "$build/findings-$target"
dict="$src/tests/fuzz/$target.dict"
[ -f "$dict" ] || dict="$src/tests/fuzz/scene.dict"
status=0
"$build/fuzz_$target" "$build/corpus-$target" -dict="$dict" -max_total_time="$seconds" \
    -max_len=16384 -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 >"$build/fuzz-$target.log" 2>&1 || status=$?
tail -n 25 "$build/fuzz-$target.log"
exit $status
