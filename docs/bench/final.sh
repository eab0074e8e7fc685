#!/bin/sh
# Writes OUT/final.md: each scene's final-preset shot at SIZE as a user's process takes it (start, load,
# compile, every sample, the PNG written), every pixel sampled (quality.tolerance=0, as before adaptive
# sampling) against adaptive sampling at the preset's tolerance, in turn run after run
# (`fathom bench --final-frame`): times, samples a pixel, and how far the adaptive image is from the
# every-pixel one.
# Usage: sh docs/bench/final.sh FATHOM OUT [RUNS] [SIZE] [SCENE...]
#   [3 runs, 1920x1080, the nine scenes of issue 40]; OUT/final.md at 1920x1080, OUT/final-SIZE.md else
#   e.g. sh docs/bench/final.sh build/fathom docs/bench 3
# A failed run stops the script and leaves the table as it was.
set -eu
fathom=$1
out=$2
runs=${3:-3}
size=${4:-1920x1080}
shift 2
[ $# -gt 0 ] && shift
[ $# -gt 0 ] && shift
scenes=${*:-mandelbulb dem menger spray jacksboro himalaya csg mandelbox noise}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
mkdir -p "$out"
{
    echo "# The final preset's whole shot: every pixel sampled against adaptive sampling"
    echo
    echo "\`sh docs/bench/final.sh FATHOM docs/bench $runs $size\` on $(uname -m), $(nproc) cores, $("$fathom" --version)"
    echo "(llvmpipe where no GPU). Each row is \`fathom bench --final-frame --scene S --size $size --runs $runs\`:"
    echo "the shot \`fathom --scene S --quality final --size $size --output F.png\` timed as a whole process"
    echo "(seconds, the median of $runs runs [its 95 % interval]), the two variants in turn run after run after"
    echo "a warm-up of each. *Every pixel*: quality.tolerance=0, each pixel takes the preset's 16 samples (what"
    echo "every shot did before adaptive sampling). *Adaptive*: every pixel takes 2 samples, then more while"
    echo "the standard error of a mean in its 3×3 block, as displayed, is above the tolerance (0.008), while a"
    echo "ray of its samples passed a surface by within the pixel's footprint (then every sample), or until"
    echo "it has the samples an edge in its block needs (displayed contrast / 2.5 tolerances)."
    echo "Samples: a pixel's, on average. Difference: the adaptive PNG against the every-pixel PNG, in 8-bit"
    echo "levels (RMSE over the channels, the worst pixel, the 99.99th percentile of the pixels, and the share"
    echo "of pixels more than 2 levels off)."
    echo
    echo "| scene | size | every pixel s | adaptive s | speed-up | samples a pixel | RMSE levels | worst | 99.99 % | % > 2 levels |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
} >"$tmp/md"
for scene in $scenes; do
    "$fathom" bench --final-frame --scene "$scene" --size "$size" --runs "$runs" --quiet >>"$tmp/md"
done
name=final.md
[ "$size" = 1920x1080 ] || name=final-$size.md
mv "$tmp/md" "$out/$name"
