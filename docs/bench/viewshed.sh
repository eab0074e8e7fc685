#!/bin/sh
# Writes OUT/viewshed.md: the exact viewshed's time on generated DEMs, side by side with GDAL's own
# (`fathom bench --viewshed`), and where GDAL's answer differs from the exact one.
# Usage: sh docs/bench/viewshed.sh FATHOM OUT [RUNS] [SIDES]
#   [5 runs, sides 512,1024,2048,4096]   e.g. sh docs/bench/viewshed.sh build/fathom docs/bench 5
# A failed run stops the script and leaves OUT/viewshed.md as it was.
set -eu
fathom=$1
out=$2
runs=${3:-5}
sides=${4:-512,1024,2048,4096}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$out"
{
    echo "# The exact viewshed against GDAL's"
    echo
    echo "\`sh docs/bench/viewshed.sh FATHOM docs/bench $runs $sides\` on $(uname -m), $(nproc) cores, $("$fathom" --version)."
    echo "Each DEM is the bench's generated N × N Int16 GeoTIFF (30 m texels in UTM, hills of wavelengths 3.75-60 km,"
    echo "0-3,000 m); the observer stands at its centre, 1.7 m above the ground (a person) or 100 m (a mast);"
    echo "refraction 0.13 with Earth curvature. *fathom exact*: \`fathom viewshed\`'s computation (every texel's line"
    echo "of sight against the bilinear surface, the max-mip descent; the DEM already in memory), every core."
    echo "*GDAL*: \`GDALViewshedGenerate\` (gdal_viewshed's algorithm, edge mode, curvature coefficient 0.87), one"
    echo "core. Seconds: the median of $runs runs [its 95 % interval], the two in turn. The last two columns: the"
    echo "share of all texels where GDAL's answer differs from the exact one, each way."
    echo
    "$fathom" bench --viewshed --knob side="$sides" --runs "$runs" --quiet
} >"$tmp/md"
mv "$tmp/md" "$out/viewshed.md"
