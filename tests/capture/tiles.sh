#!/bin/sh
# Tiles: an image rendered as N tiles (--tile I/N) and stitched (fathom stitch) equals the image rendered
# at once, bit for bit (PNG: the same file; EXR with depth and normals: the same bytes but for the
# DateTime stamp in the header), also where adaptive sampling stops pixels (the final preset, in tiles and
# in bands); stitching refuses an incomplete or mixed set.
# Usage: tiles.sh FATHOM
fathom=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
shot="--scene csg --size 97x55 --spp 2 --quiet"
for ext in png exr; do
    aov=""
    [ $ext = exr ] && aov="--aov depth,normal"
    "$fathom" $shot $aov --output "$tmp/whole.$ext" || fail "the whole $ext"
    for i in 1 2 3 4 5; do
        "$fathom" $shot $aov --tile $i/5 --output "$tmp/poster.$ext" || fail "tile $i of the $ext"
    done
    # any order on the command line
    "$fathom" stitch --quiet --output "$tmp/stitched.$ext" "$tmp"/poster.tile-3-of-5.$ext "$tmp"/poster.tile-1-of-5.$ext \
        "$tmp"/poster.tile-5-of-5.$ext "$tmp"/poster.tile-2-of-5.$ext "$tmp"/poster.tile-4-of-5.$ext || fail "stitch $ext"
    if [ $ext = png ]; then
        cmp -s "$tmp/whole.png" "$tmp/stitched.png" || fail "the stitched PNG differs from the whole"
    else
        date=$(grep -a -b -o '[0-9]\{4\}:[0-9][0-9]:[0-9][0-9] [0-9][0-9]:[0-9][0-9]:[0-9][0-9]' "$tmp/whole.exr" | head -n 1 | cut -d: -f1)
        [ -n "$date" ] || fail "no DateTime in the EXR header"
        [ "$(stat -c %s "$tmp/whole.exr")" = "$(stat -c %s "$tmp/stitched.exr")" ] || fail "the stitched EXR's size differs"
        bad=$(cmp -l "$tmp/whole.exr" "$tmp/stitched.exr" | awk -v lo="$date" '$1 <= lo || $1 > lo + 19' | wc -l)
        [ "$bad" -eq 0 ] || fail "the stitched EXR differs from the whole in $bad bytes outside its DateTime"
    fi
done
# adaptive sampling (the final preset): a pixel's stop reads its 3x3 block, so tiles and bands carry
# margin rows; without them both differ from the whole image
final="--scene mandelbulb --size 97x55 --quality final --quiet"
"$fathom" $final --output "$tmp/final.png" || fail "the whole final shot"
"$fathom" $final --strip-rows 8 --output "$tmp/final-bands.png" || fail "the final shot in bands"
for i in 1 2 3 4 5; do
    "$fathom" $final --tile $i/5 --output "$tmp/fposter.png" || fail "final tile $i"
done
"$fathom" stitch --quiet --output "$tmp/final-tiles.png" "$tmp"/fposter.tile-*-of-5.png || fail "stitch the final tiles"
cmp -s "$tmp/final.png" "$tmp/final-bands.png" || fail "the final shot in 8-row bands differs from the whole"
cmp -s "$tmp/final.png" "$tmp/final-tiles.png" || fail "the final shot's stitched tiles differ from the whole"
# an incomplete set, a tile from another poster, a file that is not a tile
"$fathom" stitch --output "$tmp/x.png" "$tmp"/poster.tile-1-of-5.png "$tmp"/poster.tile-2-of-5.png 2>"$tmp/e1" &&
    fail "an incomplete set was stitched"
grep -q "2 of 5 tiles given: missing 3, 4, 5" "$tmp/e1" || fail "incomplete: $(cat "$tmp/e1")"
"$fathom" $shot --tile 1/2 --output "$tmp/other.png" || fail "tile 1/2"
"$fathom" stitch --output "$tmp/x.png" "$tmp"/poster.tile-*-of-5.png "$tmp/other.tile-1-of-2.png" 2>"$tmp/e2" &&
    fail "a mixed set was stitched"
grep -q "belongs to another poster" "$tmp/e2" || fail "mixed: $(cat "$tmp/e2")"
"$fathom" stitch --output "$tmp/x.png" "$tmp/whole.png" 2>"$tmp/e3" && fail "a plain image was stitched"
grep -q "is not a fathom tile" "$tmp/e3" || fail "not a tile: $(cat "$tmp/e3")"
[ -e "$tmp/x.png" ] && fail "a refused stitch left a file"
echo "tiles: 5 tiles stitched equal the whole image (PNG and EXR with AOVs); incomplete, mixed and foreign sets refused"
