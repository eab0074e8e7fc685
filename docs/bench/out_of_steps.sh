#!/bin/sh
# Rays out of steps, per shipped scene and preset: how many ran past max_steps, how many were left
# unresolved, and how many pixels differ from the same preset with a budget of 20000 steps because of
# them. Renders SIZE (480x270), one sample a pixel, at each scene's own view; the EXRs are kept in
# WORKDIR and reused. Prints the table of docs/bench/out-of-steps.md.
# Usage: sh docs/bench/out_of_steps.sh FATHOM WORKDIR TAG [scene,scene,...] [SIZE]
#   FATHOM's tree (FATHOM/../..) is where it runs and where scenes/NAME.json gives each view's field of
#   view; TAG "old" reads a tree from before the tail march (a ray at exactly max_steps ran out).
# Reads the EXRs' Z and steps channels with a small OpenImageIO program it builds with g++ (g++,
# pkg-config and libopenimageio-dev: the README's install line); the rest is awk.
set -eu
[ $# -ge 3 ] || { echo "usage: sh docs/bench/out_of_steps.sh FATHOM WORKDIR TAG [scene,scene,...] [SIZE]" >&2; exit 2; }
bin=$(readlink -f "$1")
mkdir -p "$2"
work=$(cd "$2" && pwd)
tag=$3
scenes=$(echo "${4:-csg,himalaya,jacksboro,mandelbox,mandelbulb,menger,noise,spray,dem}" | tr ',' ' ')
size=${5:-480x270}
w=${size%x*} h=${size#*x}
tree=$(cd "$(dirname "$bin")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM

# exr_dump FILE: "W H", then one line a pixel, row by row: "HIT Z STEPS" (HIT 1 where Z is finite;
# Z 0 where it is not)
cat >"$tmp/exr_dump.cpp" <<'CPP'
#include <OpenImageIO/imageio.h>
#include <cmath>
#include <cstdio>
#include <vector>
using namespace OIIO;
int main(int argc, char **argv)
{
    if (argc != 2)
        return 2;
    auto in = ImageInput::open(argv[1]);
    if (!in) {
        fprintf(stderr, "exr_dump: %s\n", geterror().c_str());
        return 1;
    }
    const ImageSpec &s = in->spec();
    int z = s.channelindex("Z"), st = s.channelindex("steps");
    if (z < 0 || st < 0) {
        fprintf(stderr, "exr_dump: %s has no Z or no steps channel (--aov depth,steps)\n", argv[1]);
        return 1;
    }
    size_t n = (size_t)s.width * (size_t)s.height, c = (size_t)s.nchannels;
    std::vector<float> px(n * c);
    if (!in->read_image(0, 0, 0, s.nchannels, TypeDesc::FLOAT, px.data())) {
        fprintf(stderr, "exr_dump: %s\n", in->geterror().c_str());
        return 1;
    }
    printf("%d %d\n", s.width, s.height);
    for (size_t i = 0; i < n; i++) {
        float zv = px[i * c + (size_t)z];
        bool hit = std::isfinite(zv);
        printf("%d %.9g %.9g\n", hit ? 1 : 0, hit ? (double)zv : 0.0, (double)px[i * c + (size_t)st]);
    }
    return 0;
}
CPP
# shellcheck disable=SC2046 # pkg-config's flags are words
g++ -O2 -o "$tmp/exr_dump" "$tmp/exr_dump.cpp" $(pkg-config --cflags --libs OpenImageIO) ||
    { echo "out_of_steps.sh: could not build the EXR reader (needs g++, pkg-config, libopenimageio-dev)" >&2; exit 1; }

# render SCENE PRESET KIND [fathom options...]: WORKDIR/TAG-SCENE-PRESET-KIND-SIZE.exr (kept: reused if
# there), dumped to $tmp/KIND
render() {
    sc=$1 pr=$2 kind=$3
    shift 3
    exr="$work/$tag-$sc-$pr-$kind-$size.exr"
    if [ ! -e "$exr" ]; then
        (cd "$tree" && "$bin" --scene "$sc" --quality "$pr" --spp 1 --size "$size" --aov depth,steps --quiet \
            --output "$exr" "$@") >"$tmp/log" 2>&1 || { cat "$tmp/log" >&2; exit 1; }
    fi
    "$tmp/exr_dump" "$exr" >"$tmp/$kind"
}
# define SCENE PRESET NAME: the value of "#define NAME V" in the variant the scene compiles
define() {
    (cd "$tree" && "$bin" --scene "$1" --quality "$2" --print-variant) >"$tmp/variant" 2>&1 ||
        { cat "$tmp/variant" >&2; exit 1; }
    awk -v name="$3" '$1 == "#define" && $2 == name { print $3; found = 1; exit } END { if (!found) exit 1 }' "$tmp/variant" ||
        { echo "out_of_steps.sh: no #define $3 in $1's $2 variant" >&2; exit 1; }
}
# fov SCENE: the vertical field of view of scenes/SCENE.json's camera (or scenes/fractals/'s) [50]
fov() {
    for f in "$tree/scenes/$1.json" "$tree/scenes/fractals/$1.json"; do
        [ -r "$f" ] || continue
        tr -d '\n' <"$f" | sed -n 's/.*"camera"[[:space:]]*:[[:space:]]*{[^}]*"fov"[[:space:]]*:[[:space:]]*\([0-9.eE+-]*\).*/\1/p'
        return
    done
}

if [ "$tag" = old ]; then unresolved="drawn as their best guess"; else unresolved="flagged, drawn as a miss"; fi
echo "| scene | preset | ran past max_steps | left unresolved ($unresolved) | surface where the reference misses |" \
    "miss, unflagged, where it hits | depth off by more than the tail's 4 thresholds | of these columns, on a" \
    "silhouette |"
echo "|---|---|---|---|---|---|---|---|"
for sc in $scenes; do
    fv=$(fov "$sc")
    for pr in draft interactive final; do
        render "$sc" "$pr" test
        render "$sc" "$pr" ref --set quality.max_steps=20000
        budget=$(define "$sc" "$pr" MAX_STEPS)
        hit_k=$(define "$sc" "$pr" HIT_K)
        awk -v sc="$sc" -v pr="$pr" -v budget="$budget" -v hit_k="$hit_k" -v fov="$fv" -v W0="$w" -v H="$h" -v old="$([ "$tag" = old ] && echo 1 || echo 0)" '
            function abs(x) { return x < 0 ? -x : x }
            function max(a, b) { return a > b ? a : b }
            FNR == 1 { f++; if (f == 1) { W = $1; HH = $2 } else if ($1 != W || $2 != HH) bad = 1; next }
            f == 1 { i = FNR - 2; ht[i] = $1 + 0; zt[i] = $2 + 0; st[i] = $3 + 0; next }
            { i = FNR - 2; hr[i] = $1 + 0; zr[i] = $2 + 0 }
            END {
                if (f != 2 || bad || HH != H || W != W0) { print "out_of_steps.sh: the images are not " W0 "x" H > "/dev/stderr"; exit 1 }
                if (fov + 0 == 0) fov = 50
                pi = atan2(0, -1)
                pixel_angle = 2 * sin(fov * pi / 360) / cos(fov * pi / 360) / HH
                k = max(0.01, 4 * hit_k * pixel_angle)
                n = W * HH
                for (y = 0; y < HH; y++)
                    for (x = 0; x < W; x++) {
                        i = y * W + x
                        s = st[i]
                        out = s > budget + 0 || s < 0 || (s == budget + 0 && old)
                        # the silhouette of the reference: a 4-neighbour (across the borders, as np.roll) that
                        # misses where this pixel hits, or lies 5 % away
                        e = 0
                        for (d = 0; d < 4 && !e; d++) {
                            j = d == 0 ? y * W + (x + 1) % W : d == 1 ? y * W + (x + W - 1) % W : \
                                d == 2 ? ((y + 1) % HH) * W + x : ((y + HH - 1) % HH) * W + x
                            if (hr[j] != hr[i]) e = 1
                            else if (hr[i] && abs(zr[j] - zr[i]) > 0.05 * max(zr[i], 1e-30)) e = 1
                        }
                        if (!out) continue
                        ran++
                        if (s < 0) flagged++
                        fh = ht[i] && !hr[i]
                        fm = !ht[i] && hr[i] && s >= 0
                        deep = ht[i] && hr[i] && abs(zt[i] - zr[i]) > k * zr[i]
                        false_hit += fh; false_miss += fm; deeper += deep
                        if ((fh || fm || deep) && e) edge++
                    }
                printf "| %s | %s | %d | %d | %d | %d | %d | %d |\n", sc, pr, ran, flagged, false_hit, false_miss, deeper, edge
            }' "$tmp/test" "$tmp/ref"
    done
done
