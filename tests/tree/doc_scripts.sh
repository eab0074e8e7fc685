#!/bin/sh
# Every script under docs/ runs from the README's install line alone (no python3, no GNU time), on tiny
# sizes and one run each, into a temporary folder; each exits 0 and makes what its header says; a
# failing run leaves the file it would write as it was; and nothing under docs/ changes (the shipped
# CSVs and pages are never written by a test). docs/slurm/run.sh has its own test (slurm_farm).
# Usage: doc_scripts.sh FATHOM SOURCE_DIR
fathom=$(readlink -f "$1")
src=$(cd "$2" && pwd) || exit 1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
passed=0 failed=0 skipped=0
ok() { passed=$((passed + 1)); echo "ok   $1"; }
bad() {
    failed=$((failed + 1))
    echo "FAIL $1"
    [ -s "$tmp/stderr" ] && tail -n 15 "$tmp/stderr" | sed 's/^/     | /'
}
# check NAME CONDITION: CONDITION is a shell test run after the case
check() { if eval "$2"; then ok "$1"; else bad "$1"; fi; }
# run CMD...: CMD's output in $tmp/stdout and $tmp/stderr, its exit status in $code, its seconds in $secs
run() {
    t0=$(date +%s)
    "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    code=$?
    secs=$(($(date +%s) - t0))
}
# numbers LINE CELLS: LINE is a markdown row of CELLS cells, each but the first a number (or "N (N)")
numbers() { awk -F'|' -v n="$2" 'NF != n + 2 { exit 1 } { for (i = 2; i <= n + 1; i++) { v = $i; gsub(/^ +| +$/, "", v)
    if (v !~ /^[0-9]+(\.[0-9]+)?$/ && v !~ /^[0-9.]+ \([0-9.]+\)$/ && i > 2) exit 1 } }' <<EOF
$1
EOF
}
# csv_ok FILE COLUMNS ROWS: a header and ROWS rows, every line COLUMNS fields, no field empty
csv_ok() {
    [ -s "$1" ] && [ "$(wc -l <"$1")" -eq $(($3 + 1)) ] &&
        awk -F, -v n="$2" 'NF != n { exit 1 } { for (i = 1; i <= NF; i++) if ($i == "") exit 1 }' "$1"
}
# the state of docs/ (the guide aside: people, not scripts, edit it): every file's checksum, and git's view
snapshot() {
    (cd "$src" && find docs -path docs/guide -prune -o -type f -exec cksum {} + | LC_ALL=C sort -k 3)
    git -C "$src" status --porcelain -- docs ':(exclude)docs/guide' 2>/dev/null
}
snapshot >"$tmp/docs.before"
out="$tmp/out"
mkdir -p "$out"

# ---- what every script may use ------------------------------------------------------------------
scripts=$(cd "$src" && find docs \( -name '*.sh' -o -name '*.py' -o -name '*.sbatch' -o -name '*.pl' -o -name '*.rb' \) -type f | LC_ALL=C sort)
for s in $scripts; do
    case "$s" in
    *.py | *.pl | *.rb) bad "$s: a script the README's install line cannot run (port it to sh/awk)" ;;
    esac
    grep -n 'python\|/usr/bin/time\|time -v\|time -f\|\bbc\b' "$src/$s" >"$tmp/stderr"
    check "$s: no python, GNU time or bc" '[ ! -s "$tmp/stderr" ]'
    : >"$tmp/stderr"
    check "$s: a Usage line (or what sources it) in its header" \
        'sed -n "1,/^[^#]/p" "$src/$s" | grep -q "^# *Usage:\|^# Sourced by\|^#   sbatch "'
    case "$s" in
    docs/bench/final.sh | docs/bench/viewshed.sh | docs/bench/formulas.sh | docs/bench/index.sh | docs/bench/mesh.sh | docs/bench/out_of_steps.sh | docs/csg-scale/run.sh | \
        docs/droplets/run.sh | docs/droplets/culling.sh | docs/droplets/scene.sh | docs/interactive/run.sh | docs/peak_kb.sh | \
        docs/interactive/panel.sh | docs/slurm/run.sh | docs/slurm/flight.sbatch | docs/slurm/poster.sbatch) ;;
    *) bad "$s: no case below runs it (add one)" ;;
    esac
done

# ---- docs/bench/formulas.sh: the user's formulas (one new, one shadowing a shipped name) left out --
mkdir -p "$tmp/user-formulas" "$out/formulas"
cp "$src/docs/formulas/torus.glsl" "$tmp/user-formulas/"
cp "$src/shaders/fractal/menger.glsl" "$tmp/user-formulas/"
run env FATHOM_FORMULAS="$tmp/user-formulas" sh "$src/docs/bench/formulas.sh" "$fathom" 32x18 1 "$out/formulas" menger
md="$out/formulas/formulas.md"
check "formulas.sh exits 0 with a user formula folder ($secs s)" '[ $code -eq 0 ]'
check "formulas.sh: formulas.md names the machine, not a scene" \
    '[ -s "$md" ] && grep -q "^\`sh docs/bench/formulas.sh .*\` on .*(the [a-z]* backend)\.\$" "$md" && ! grep -qi "shot of\|start-up" "$md"'
row=$(grep '^| menger |' "$md" 2>/dev/null | head -n 1)
check "formulas.sh: menger's row, six numbers" 'numbers "$row" 6'
check "formulas.sh: no row for the user's torus" '[ -s "$md" ] && ! grep -q "^| torus " "$md"'
check "formulas.sh: float against double, a ratio" 'numbers "$(grep "^| menger |" "$md" 2>/dev/null | sed -n 2p)" 4'
# the last column is steps a pixel: the last field of final's row in bench --frame-times
"$fathom" bench --frame-times --scene menger --runs 1 --size 32x18 --quiet >"$tmp/bench" 2>&1
steps=$(awk '$1 == "final" { print $NF }' "$tmp/bench")
check "formulas.sh: steps a pixel ($(echo "$row" | awk -F'|' '{ gsub(/ /, "", $7); print $7 }')) are bench's ($steps)" \
    '[ -n "$steps" ] && [ "$(echo "$row" | awk -F"|" "{ gsub(/ /, \"\", \$7); print \$7 }")" = "$steps" ]'
echo keep >"$tmp/keep.md" && cp "$tmp/keep.md" "$out/formulas/formulas.md"
run sh "$src/docs/bench/formulas.sh" /bin/false 32x18 1 "$out/formulas" menger
check "formulas.sh: a failed run exits non-zero and leaves formulas.md" '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$md"'

# ---- docs/bench/final.sh: two small scenes, one run; a failed run keeps the page --------------------
mkdir -p "$out/final"
run sh "$src/docs/bench/final.sh" "$fathom" "$out/final" 1 64x36 torus csg
check "final.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "final.sh: a row a scene, times, samples a pixel, RMSE, worst, 99.99th percentile and share" \
    'grep -q "^| torus | 64x36 | [0-9.]* \[[0-9.]*-[0-9.]*\] | [0-9.]* \[[0-9.]*-[0-9.]*\] | [0-9.]* | [0-9.]* | [0-9.]* | [0-9]* | [0-9]* | [0-9.]* |$" "$out/final/final-64x36.md" &&
     grep -q "^| csg | 64x36 | " "$out/final/final-64x36.md" && [ ! -e "$out/final/final.md" ]'
check "final.sh: at 64x36 (2,304 pixels) the 99.99th percentile is the worst pixel" \
    'awk -F"|" '"'"'$2 ~ /csg/ { found = 1; if ($9 + 0 != $10 + 0 || $9 + 0 == 0) bad = 1 } END { exit !(found && !bad) }'"'"' "$out/final/final-64x36.md"'
echo keep >"$tmp/keep.md" && cp "$tmp/keep.md" "$out/final/final-64x36.md"
run sh "$src/docs/bench/final.sh" /bin/false "$out/final" 1 64x36 torus
check "final.sh: a failed run exits non-zero and leaves the table" '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$out/final/final-64x36.md"'

# ---- docs/bench/viewshed.sh: two small sides, one run; a failed run keeps the page ------------------
mkdir -p "$out/viewshed"
run sh "$src/docs/bench/viewshed.sh" "$fathom" "$out/viewshed" 1 64,100
check "viewshed.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "viewshed.sh: a row a side and eye height, exact and GDAL's times" \
    'grep -q "^| 64² | 1.7 | [0-9.]* \[[0-9.]*-[0-9.]*\] | [0-9]* | [0-9.]* | [0-9.]* | [0-9.]* \[" "$out/viewshed/viewshed.md" &&
     grep -q "^| 100² | 100.0 | " "$out/viewshed/viewshed.md"'
echo keep >"$tmp/keep.md" && cp "$tmp/keep.md" "$out/viewshed/viewshed.md"
run sh "$src/docs/bench/viewshed.sh" /bin/false "$out/viewshed" 1 64
check "viewshed.sh: a failed run exits non-zero and leaves viewshed.md" '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$out/viewshed/viewshed.md"'

# ---- docs/bench/mesh.sh: a torus, one run; a failed run keeps the page ----------------------------
mkdir -p "$out/mesh"
run sh "$src/docs/bench/mesh.sh" "$fathom" "$out/mesh" 1 torus:12:-1.5,-0.5,-1.5,1.5,0.5,1.5 jacksboro:20
check "mesh.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "mesh.sh: the torus closed, its error and a simplification" \
    'grep -q "^| torus | 12 | [0-9.]* ([0-9.]*–[0-9.]*) | [0-9]* | [0-9.]* | [0-9]* | yes | 1 | [0-9.]* | [0-9.]* | [0-9]*+\\{0,1\\} | [0-9.]* | yes |\$" "$out/mesh/mesh.md"'
check "mesh.sh: the DEM solid closed, no field error" 'grep -q "^| jacksboro | 20 | .* | yes | 1 | - | - | " "$out/mesh/mesh.md"'
cp "$tmp/keep.md" "$out/mesh/mesh.md"
run sh "$src/docs/bench/mesh.sh" /bin/false "$out/mesh" 1 torus:12
check "mesh.sh: a failed run exits non-zero and leaves mesh.md" '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$out/mesh/mesh.md"'

# ---- docs/bench/index.sh: the shipped README is what it makes of the shipped CSVs --------------
run sh "$src/docs/bench/index.sh" "$src/docs/bench" "$out/README.md"
check "index.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "index.sh: docs/bench/README.md is what it makes (else run sh docs/bench/index.sh)" \
    'cmp -s "$out/README.md" "$src/docs/bench/README.md"'
mkdir -p "$tmp/bench-dir"
cp "$src/docs/bench/menger-knobs.csv" "$src/docs/bench/menger-summary.md" "$tmp/bench-dir/" # no effects CSV
cp "$tmp/keep.md" "$tmp/bench-dir/README.md"
run sh "$src/docs/bench/index.sh" "$tmp/bench-dir"
check "index.sh: a run missing its effects CSV fails and leaves README.md" \
    '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$tmp/bench-dir/README.md"'

# ---- docs/bench/out_of_steps.sh --------------------------------------------------------------------
run sh "$src/docs/bench/out_of_steps.sh" "$fathom" "$out/oos" new menger 48x27
check "out_of_steps.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "out_of_steps.sh: a header and menger's three presets, each eight cells" \
    '[ "$(grep -c "^| menger | \(draft\|interactive\|final\) |" "$tmp/stdout")" -eq 3 ] &&
     [ -z "$(grep "^| menger |" "$tmp/stdout" | awk -F"|" "NF != 10 || \$4 !~ /^ [0-9]+ \$/")" ] &&
     grep -q "^| scene | preset | ran past max_steps |" "$tmp/stdout"'

# ---- docs/droplets/run.sh and culling.sh -----------------------------------------------------------
mkdir -p "$out/droplets"
run sh "$src/docs/droplets/run.sh" "$fathom" "$out/droplets" 1000 32x18 1
check "droplets/run.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "droplets/run.sh: droplets.csv, 16 columns, one row" 'csv_ok "$out/droplets/droplets.csv" 16 1'
check "droplets/run.sh: a peak memory in MB" \
    '[ "$(awk -F, "NR == 2 && \$7 ~ /^[0-9]+\$/ && \$7 > 10 { print 1 }" "$out/droplets/droplets.csv")" = 1 ]'
cp "$tmp/keep.md" "$out/droplets/droplets.csv"
run sh "$src/docs/droplets/run.sh" /bin/false "$out/droplets" 1000 32x18 1
check "droplets/run.sh: a failed run exits non-zero and leaves droplets.csv" \
    '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$out/droplets/droplets.csv"'
run sh "$src/docs/droplets/culling.sh" "$fathom" 1000 32x18 1
check "droplets/culling.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "droplets/culling.sh: both lines" \
    '[ "$(grep -c "^droplet_cull=[01]: interactive [0-9.]* ms  final [0-9.]* ms\$" "$tmp/stdout")" -eq 2 ]'
run sh "$src/docs/droplets/culling.sh" /bin/false 1000 32x18 1
check "droplets/culling.sh: fathom failing fails it" '[ $code -ne 0 ]'

# ---- docs/csg-scale/run.sh -------------------------------------------------------------------------
mkdir -p "$out/csg-scale"
run sh "$src/docs/csg-scale/run.sh" "$fathom" "$out/csg-scale" 100:list 32x18 1
check "csg-scale/run.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "csg-scale/run.sh: csg-scale.csv, 6 columns, one row" 'csv_ok "$out/csg-scale/csg-scale.csv" 6 1'
check "csg-scale/run.sh: compile seconds and peak memory" \
    '[ "$(awk -F, "NR == 2 && \$3 ~ /^[0-9]+\.[0-9][0-9]\$/ && \$4 ~ /^[0-9]+\$/ && \$4 > 10 { print 1 }" "$out/csg-scale/csg-scale.csv")" = 1 ]'
cp "$tmp/keep.md" "$out/csg-scale/csg-scale.csv"
run sh "$src/docs/csg-scale/run.sh" /bin/false "$out/csg-scale" 100:list 32x18 1
check "csg-scale/run.sh: a failed run exits non-zero and leaves csg-scale.csv" \
    '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$out/csg-scale/csg-scale.csv"'

# ---- docs/interactive/run.sh and panel.sh ----------------------------------------------------------
mkdir -p "$out/interactive"
run sh "$src/docs/interactive/run.sh" "$fathom" "$out/interactive" 64x36 menger
check "interactive/run.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
check "interactive/run.sh: interactive.csv, 21 columns, one row" 'csv_ok "$out/interactive/interactive.csv" 21 1'
cp "$tmp/keep.md" "$out/interactive/interactive.csv"
run sh "$src/docs/interactive/run.sh" "$fathom" "$out/interactive" 64x36 "menger no_such_scene"
check "interactive/run.sh: a failed run exits non-zero and leaves interactive.csv" \
    '[ $code -ne 0 ] && cmp -s "$tmp/keep.md" "$out/interactive/interactive.csv"'
run sh "$src/docs/interactive/panel.sh" "$fathom" 1 30 menger 320x180
if [ $code -eq 77 ]; then
    skipped=$((skipped + 1))
    echo "skip interactive/panel.sh: $(cat "$tmp/stderr")"
else
    check "interactive/panel.sh exits 0 ($secs s)" '[ $code -eq 0 ]'
    check "interactive/panel.sh: the panel open and closed" \
        '[ "$(grep -c "^| menger | \(open\|closed\) | [0-9]* | [0-9.]* ([0-9.]*) |" "$tmp/stdout")" -eq 2 ]'
fi

# ---- docs/slurm/flight.sbatch: one array task without Slurm ------------------------------------------
run env SLURM_ARRAY_TASK_ID=1 FATHOM="$fathom" sh "$src/docs/slurm/flight.sbatch" "$src/docs/flight/csg.json" \
    "$out/flight" 2 --size 16x9 --quiet
check "slurm/flight.sbatch: task 1 of 2 frames exits 0 ($secs s)" '[ $code -eq 0 ]'
check "slurm/flight.sbatch: it rendered frames 2 and 3, no other" \
    '[ "$(ls "$out/flight" | tr "\n" " ")" = "frame_0002.png frame_0003.png " ]'

# ---- docs/slurm/poster.sbatch: one tile without Slurm --------------------------------------------------
run env SLURM_ARRAY_TASK_ID=2 FATHOM="$fathom" sh "$src/docs/slurm/poster.sbatch" "$out/poster/p.png" 3 \
    --scene csg --size 16x9 --spp 1 --quiet
check "slurm/poster.sbatch: tile 2 of 3 exits 0 ($secs s)" '[ $code -eq 0 ]'
check "slurm/poster.sbatch: it wrote tile 2, no other" '[ "$(ls "$out/poster" | tr "\n" " ")" = "p.tile-2-of-3.png " ]'

# ---- nothing under docs/ changed -----------------------------------------------------------------
snapshot >"$tmp/docs.after"
diff "$tmp/docs.before" "$tmp/docs.after" >"$tmp/stderr"
check "nothing under docs/ changed" '[ ! -s "$tmp/stderr" ]'

[ "$skipped" -eq 0 ] || echo "($skipped skipped: what they need is not installed)"
echo "doc_scripts: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
