#!/bin/sh
# Every shipped scene at every preset (and the Himalaya with water, two ways) must compile the variant recorded
# in tests/golden/variants.txt:
# refactors keep behaviour, and a change to what a scene compiles is made on purpose.
# Usage: variant_golden.sh FATHOM SOURCE_DIR [--update]   (--update rewrites the golden file)
fathom=$1
src=$2
golden=$src/tests/golden/variants.txt
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
for f in "$src"/scenes/*.json "$src"/scenes/fractals/*.json; do
    s=$(basename "$f" .json)
    for p in draft interactive final reference; do
        echo "== $s $p"
        # the scene's path differs between checkouts: drop it
        "$fathom" --scene "$s" --quality "$p" --print-variant | sed 's/ ([^)]*): program/: program/' || exit 1
    done
done >"$tmp"
# water compiles only where a scene has it: a level, and lakes a texel at a time (terrain.water)
for w in 1500 fill; do
    echo "== himalaya terrain.water=$w interactive"
    "$fathom" --scene himalaya --set terrain.water=$w --print-variant | sed 's/ ([^)]*): program/: program/' || exit 1
done >>"$tmp"
if [ "$3" = "--update" ]; then
    cp "$tmp" "$golden" && echo "variant_golden: wrote $golden"
    exit 0
fi
if diff -u "$golden" "$tmp"; then
    echo "variant_golden: $(grep -c '^== ' "$tmp") passed, 0 failed"
else
    echo "variant_golden: the preambles differ from $golden (above); if that change is on purpose, run"
    echo "  sh tests/gpu/variant_golden.sh build/fathom . --update"
    echo "variant_golden: 0 passed, 1 failed"
    exit 1
fi
