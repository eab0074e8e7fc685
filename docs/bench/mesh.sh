#!/bin/sh
# Writes OUT/mesh.md: `fathom mesh` per scene and resolution — time (median of RUNS, min–max), the
# process's peak memory, the extractor's working memory, triangles, the topology check, shells, the
# vertices' distance to the field (in voxels), then the same mesh simplified to a tenth of its
# triangles within a voxel (meshoptimizer): triangles, deviation, the vertices' distance again.
# Usage: sh docs/bench/mesh.sh FATHOM OUT [RUNS] [SCENE:RES1,RES2,...[:X0,Y0,Z0,X1,Y1,Z1]]...
#   [3 runs; mandelbulb, menger and csg to 512, jacksboro (a DEM solid: RES vertices a side, 403
#   its own)]
#   e.g. sh docs/bench/mesh.sh build/fathom docs/bench 3
# The runs of a scene interleave (64, 128, ..., then again); a failed run stops the script and leaves
# OUT/mesh.md as it was.
set -eu
fathom=$1
out=$2
runs=${3:-3}
shift 2
[ $# -gt 0 ] && shift
specs=${*:-mandelbulb:64,128,256,512 menger:128,256,512 csg:128,256,512:-3.5,-0.3,-2,3.5,2,3 jacksboro:100,200,403}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$out"
export LC_ALL=C

# one mesh: the report's numbers as "time peak work triangles closed shells err_median_or_mean err_worst"
measure() { # SCENE RES BOX [TRIANGLES]
    box_option=
    [ -n "$3" ] && box_option="--box $3"
    simplify_option=
    [ -n "${4:-}" ] && simplify_option="--triangles $4"
    # shellcheck disable=SC2086 # each is an option and its value, or nothing
    "$fathom" mesh --scene "$1" --resolution "$2" $box_option $simplify_option --output "$tmp/m.ply" --quiet >"$tmp/report" ||
        { cat "$tmp/report" >&2; exit 1; }
    awk '
        /^grid:/ { for (i = 1; i <= NF; i++) if ($i == "memory") work = $(i + 1) }
        /^mesh:/ { tri = $2; closed = ($0 ~ /NOT closed/) ? "no" : "yes"
                   for (i = 1; i <= NF; i++) if ($i ~ /^shells?,$/) shells = $(i - 1) }
        /^error:/ { err = $4; for (i = 1; i <= NF; i++) if ($i == "(mean") { m = $(i + 1); sub(/\)/, "", m); mean = m } }
        /^simplified:/ { n = split($0, a, ": "); split(a[3], b, ","); stri = b[1]; sub(/ .*/, "", stri)
                         if ($0 ~ /more than asked/) stri = stri "+"; if ($0 ~ /kept whole/) stri = "kept-whole"
                         for (i = 1; i <= NF; i++) if ($i == "deviation") dev = $(i + 2); sub(/\(/, "", dev)
                         for (i = 4; i <= NF; i++) if ($i == "field" && $(i - 2) == "by") dev = $(i - 4) }
        /^wrote/ { for (i = 1; i <= NF; i++) { if ($i == "in") t = $(i + 1); if ($i == "memory") peak = $(i + 1) } }
        function v(x) { return x == "" ? "-" : x }
        END { print v(t), v(peak), v(work), v(tri), v(closed), v(shells), v(err), v(mean), v(stri), v(dev) }
   ' "$tmp/report"
}

{
    echo "# Meshes: time, memory, triangles and error by resolution"
    echo
    echo "\`sh docs/bench/mesh.sh FATHOM docs/bench $runs\` on $(uname -m), $(nproc) cores, $("$fathom" --version)"
    echo "(llvmpipe where no GPU: every sample is the scene's map() on the GL). Time: the median of $runs runs"
    echo "(min–max), scene load to file written. Peak: the process's resident high-water mark (the GL driver's"
    echo "included). Work: the extractor's own arrays (two sample layers, their crossings, two cell layers:"
    echo "grows with the square of the resolution); the mesh itself is the rest. Error: the vertices' distance to"
    echo "the level by the field, in voxels, worst and mean (a DEM's vertices are its texels: none). Simplified:"
    echo "the same mesh toward a tenth of its triangles within one voxel (a DEM: one texel) by meshoptimizer;"
    echo "its deviation in voxels as the field measures it at corners, edge midpoints and face centres (a DEM"
    echo "or a fractal, whose estimate is no distance: meshoptimizer's estimate); whether it is still closed and"
    echo "manifold (meshoptimizer's collapses promise"
    echo "no manifold: faces folded back to back are dropped, sheets that touch parted, holes closed, crossing"
    echo "faces untangled; a result still not closed, or past the tolerance, is tried again with a quarter more"
    echo "triangles: a + marks a count above the tenth asked)."
    echo
    echo "| scene | resolution | time s | peak MB | work MB | triangles | closed, manifold | shells | error worst | error mean | simplified | deviation | still closed |"
    echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$tmp/md"
for spec in $specs; do
    scene=${spec%%:*}
    rest=${spec#*:}
    resolutions=${rest%%:*}
    box=
    [ "$rest" != "$resolutions" ] && box=${rest#*:}
    run=1
    while [ "$run" -le "$runs" ]; do # interleaved: every resolution once, then again
        for res in $(echo "$resolutions" | tr ',' ' '); do
            measure "$scene" "$res" "$box" >"$tmp/$scene-$res-$run"
        done
        run=$((run + 1))
    done
    for res in $(echo "$resolutions" | tr ',' ' '); do
        tri=$(awk '{ print $4 }' "$tmp/$scene-$res-1")
        measure "$scene" "$res" "$box" $((tri / 10)) >"$tmp/$scene-$res-s"
        cat "$tmp/$scene-$res"-[0-9]* | sort -n -k 1 | awk -v scene="$scene" -v res="$res" -v s="$(cat "$tmp/$scene-$res-s")" '
            { t[NR] = $1; line = $0 }
            END { split(line, f, " "); split(s, g, " ")
                  med = t[int((NR + 1) / 2)]
                  printf "| %s | %s | %s (%s–%s) | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", scene, res, med, t[1],
                         t[NR], f[2], f[3], f[4], f[5], f[6], f[7], f[8], g[9], g[10], g[5] }' >>"$tmp/md"
    done
done
mv "$tmp/md" "$out/mesh.md.new.$$" && mv "$out/mesh.md.new.$$" "$out/mesh.md"
echo "wrote $out/mesh.md"
