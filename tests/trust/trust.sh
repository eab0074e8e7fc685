#!/bin/sh
# Trust boundaries: a preset, shot, formula or module from a stranger is data, never code. Each case
# fails on the code before the fix (the closing note of issue 34 lists them). Usage: trust.sh FATHOM SRC
fathom=$1
src=$2
. "$src/tests/lib/trust_lib.sh"
quick="--size 16x9 --runs 1 --knob resolution_scale=0.5 --quiet"

# a preset that carries its own small scene, under the name NAME
cat >"$tmp/mini.json" <<'JSON'
{"program": "csg", "materials": {"a": {"base_color": [0.8, 0.3, 0.2]}},
 "objects": [{"shape": "sphere", "material": "a"}]}
JSON
preset() {
    printf '{"scene":"%s","scene_text":"%s","sets":[],"camera":{"position":[0,1.7,6.2],"yaw":0,"pitch":-0.17,"fov_y":0.87},"size":[32,18]}' \
        "$1" "$(tr -d '\n' <"$tmp/mini.json" | sed 's/"/\\"/g')"
}
mkdir "$tmp/work" && cd "$tmp/work" || exit 1

# ---- 1. no name reaches a shell: gnuplot runs without one, every string quoted ------------------
i=0
for name in '`touch PWNED`.json' "x';touch PWNED;'.json" '$(touch PWNED).json' 'a\nb.json'; do
    i=$((i + 1))
    preset "$name" >"p$i.fathom"
    run "$fathom" bench --scene "p$i.fathom" $quick --out "o$i"
    check "bench-scene-name-$i: exit 0, no command ran" '[ $code -eq 0 ] && [ ! -e PWNED ] && [ ! -e "$tmp/PWNED" ]'
    check "bench-scene-name-$i: 13 files in --out, plots included" \
        '[ "$(ls "o$i" | wc -l)" -eq 13 ] && [ -s "$(ls -d o$i/*-plot.png)" ] && [ -s "$(ls -d o$i/*-overview.png)" ]'
done
run "$fathom" bench --scene csg $quick --out "Bob's results" --name 'run`touch PWNED`'
check "bench-quote-in-out-and-backquote-in-name" '[ $code -eq 0 ] && [ ! -e PWNED ] && [ -s "Bob'"'"'s results/run_touch_PWNED_-plot.png" ]'

# ---- 2. every file the bench writes stays in --out, through a new temporary file -----------------
mkdir -p deep/er && cd deep/er || exit 1
preset '../../escape/x.json' >esc.fathom
run "$fathom" bench --scene esc.fathom $quick --out out
check "bench-path-in-scene-name: nothing outside --out" '[ $code -eq 0 ] && [ ! -e ../../escape ] && [ -s out/x-knobs.csv ]'
cd "$tmp/work" || exit 1
mkdir planted targets
for f in knobs.csv effects.csv plot.dat plot.gp plot.png overview.png summary.md report.html reference.png \
    diff-preset-draft.png; do
    echo keep >"targets/$f"
    ln -s "../targets/$f" "planted/csg-$f"
done
run "$fathom" bench --scene csg $quick --out planted
check "bench-planted-links: exit 0" '[ $code -eq 0 ]'
check "bench-planted-links: no target written through a link" '[ "$(cat targets/* | sort -u)" = keep ]'
check "bench-planted-links: the results are files" '[ -f planted/csg-knobs.csv ] && [ ! -L planted/csg-knobs.csv ]'
# a link planted at the name of the temporary file the bench will make (its PID is the shell's, which
# execs it): the temporary file is made new (O_EXCL | O_NOFOLLOW), never written through the link
mkdir templink && echo keep >targets/temp
run sh -c 'ln -s ../targets/temp "templink/.csg-knobs.csv.tmp$$-0.csv"; exec "$0" "$@"' "$fathom" bench --scene csg $quick --out templink
check "bench-planted-temp-link: not written through" '[ "$(cat targets/temp)" = keep ]'
# a gnuplot that exits 0 but leaves its images cut short (a full disk under it): the bench fails
mkdir fakebin && printf '#!/bin/sh\nprintf "\\211PNG" >plot.png; printf "\\211PNG" >overview.png\n' >fakebin/gnuplot
chmod +x fakebin/gnuplot
run env PATH="$tmp/work/fakebin:$PATH" "$fathom" bench --scene csg $quick --out cutplots
check "bench-gnuplot-image-cut-short: refused, not moved in" \
    '[ $code -eq 1 ] && grep -q "image is incomplete" "$tmp/stderr" && [ ! -e cutplots ]'
# a bad --knob value is refused before anything renders, and a refused run leaves no folder
run "$fathom" bench --scene csg --size 16x9 --runs 1 --knob "step_factor=0.5,0.6,0.7,0.8,9" --out refused --quiet
check "bench-bad-knob-value: refused at once, no folder left" \
    '[ $code -ne 0 ] && grep -q "step_factor" "$tmp/stderr" && [ ! -e refused ] && [ ! -s "$tmp/stdout" ]'
mkdir refused2 # into a folder that exists: had a value been rendered, its row would be on disk
run "$fathom" bench --scene csg --size 16x9 --runs 1 --knob "step_factor=0.5,0.6,0.7,0.8,9" --out refused2 --quiet
check "bench-bad-knob-value: nothing rendered before the refusal" '[ $code -ne 0 ] && [ -z "$(ls -A refused2)" ]'
# a full disk: no partial plot, CSV or report, and the folder the run made is gone
mkdir -p "$tmp/small"
if mount -t tmpfs -o size=96k fathomtrust "$tmp/small" 2>/dev/null; then
    run "$fathom" bench --scene csg --size 64x36 --runs 1 --knob resolution_scale=0.5 --quiet --out "$tmp/small/full"
    check "bench-full-disk: fails with the disk named" '[ $code -ne 0 ] && grep -q "cannot write" "$tmp/stderr"'
    check "bench-full-disk: nothing left" '[ -z "$(ls -A "$tmp/small")" ]'
    run "$fathom" --output "$tmp/small/full.png" --size 640x360 --spp 1 --quiet
    check "full-disk-png: the reason, not libpng's 'Write Error'" 'grep -q "No space left on device" "$tmp/stderr"'
    umount "$tmp/small"
else
    echo "skip bench-full-disk: cannot mount a tmpfs here"
fi

# ---- 3. modules only from beside the binary and <prefix>/lib/fathom, checked before dlopen -------
mkdir -p mods/bin
cp "$fathom" mods/bin/fathom
image="$(dirname "$fathom")/fathom_image.so"
exr="--output $tmp/work/o.exr --size 8x8 --spp 1 --quiet"
cp "$image" mods/fathom_image.so # the folder above the binary: never looked in
run mods/bin/fathom $exr
check "module-above-binary: not loaded" '[ $code -eq 1 ] && grep -q "is not beside" "$tmp/stderr" && [ ! -e o.exr ]'
cp "$image" mods/bin/fathom_image.so && chmod g+w mods/bin/fathom_image.so
run mods/bin/fathom $exr
check "module-group-writable: refused" '[ $code -eq 1 ] && grep -q "writable by its group or others" "$tmp/stderr"'
head -c 3000 "$image" >mods/bin/fathom_image.so && chmod 644 mods/bin/fathom_image.so
run mods/bin/fathom $exr
check "module-truncated: refused, no crash" '[ $code -eq 1 ] && grep -q "cut short" "$tmp/stderr"'
if [ "$(id -u)" = 0 ] && id nobody >/dev/null 2>&1; then # root can give the module to another user
    cp "$image" mods/bin/fathom_image.so && chmod 644 mods/bin/fathom_image.so && chown nobody mods/bin/fathom_image.so
    run mods/bin/fathom $exr
    check "module-owned-by-another-user: refused" '[ $code -eq 1 ] && grep -q "owned by another user" "$tmp/stderr"'
fi
rm mods/bin/fathom_image.so && mkfifo mods/bin/fathom_image.so
run timeout 20 mods/bin/fathom $exr
check "module-fifo: refused, no hang" '[ $code -eq 1 ] && grep -q "not a regular file" "$tmp/stderr"'
rm mods/bin/fathom_image.so && cp "$image" mods/bin/fathom_image.so && chmod 644 mods/bin/fathom_image.so
run mods/bin/fathom $exr
check "module-trusted: loaded" '[ $code -eq 0 ] && [ -s o.exr ]'
rm -f o.exr

# ---- 4. formulas live in a jail --------------------------------------------------------------
mkdir -p fm
echo 'ghp_FAKESECRET0123456789' >token.txt
ln -s "$tmp/work/token.txt" fm/link.glsl
png="--output $tmp/work/o.png --size 16x9 --spp 1 --quiet"
up=$(printf '../%.0s' 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16) # from the shader folder up to /, then down
for inc in "$tmp/work/token.txt" "$up${tmp#/}/work/token.txt" ../token.txt link.glsl 'sub/../../token.glsl'; do
    printf '// @formula reads a file\n#include "%s"\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - 1.0; }\n' "$inc" >fm/evil.glsl
    run "$fathom" --formula fm/evil.glsl $png
    check "formula-include '$inc': refused, the file's text not shown" \
        '[ $code -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && ! grep -q FAKESECRET "$tmp/stderr" && [ ! -e o.png ]'
done
# an absolute path to a .glsl file: refused by its form alone, whatever it is called
cp token.txt "$tmp/secret.glsl"
printf '// @formula reads a file\n#include "%s"\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - 1.0; }\n' "$tmp/secret.glsl" >fm/evil.glsl
run "$fathom" --formula fm/evil.glsl $png
check "formula-include-absolute-glsl: refused, the file's text not shown" \
    '[ $code -eq 1 ] && grep -q "an absolute path" "$tmp/stderr" && ! grep -q FAKESECRET "$tmp/stderr"'
printf '// @formula quote\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - 1.0; }\n' >'fm/a"b.glsl'
run "$fathom" --formula 'fm/a"b.glsl' $png
check "formula-quote-in-path: refused" '[ $code -eq 1 ] && grep -q "rename it" "$tmp/stderr"'
# bounded before the driver sees it: Mesa dies on 10,000 dependent statements
{ printf '// @formula long\nfloat formulaDE(vec3 p, out float trap) {\n trap = 0.0; float a0 = p.x;\n'
  i=1; while [ $i -lt 10000 ]; do printf ' float a%d = a%d * 1.0001;\n' $i $((i - 1)); i=$((i + 1)); done
  printf ' return length(p) - 1.0 + 0.0 * a9999;\n}\n'; } >fm/long.glsl
run "$fathom" --formula fm/long.glsl $png
check "formula-10000-statements: refused with one line, no crash" \
    '[ $code -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -q "shorten it" "$tmp/stderr"'
# the statement bound alone: 2,001 empty statements in 3 KB, under the byte bound (issue 58 item 17)
{ printf '// @formula semis\nfloat formulaDE(vec3 p, out float trap) {\n trap = 0.0;\n'
  i=0; while [ $i -lt 2001 ]; do printf ';'; i=$((i + 1)); done
  printf '\n return length(p) - 1.0;\n}\n'; } >fm/semis.glsl
run "$fathom" --formula fm/semis.glsl $png
check "formula-2001-statements-in-3-kb: refused by the statement bound" \
    '[ $code -eq 1 ] && grep -q "more than 2000 statements" "$tmp/stderr"'

# ---- 5. names mean one thing ---------------------------------------------------------------------
mkdir -p user
sed 's/length(p) - 1.0/length(p) - 0.2/' fm/evil.glsl | sed '2d' >user/mandelbox.glsl
run env FATHOM_FORMULAS="$tmp/work/user" "$fathom" --formula mandelbox --output "$tmp/work/shadow.png" --size 32x18 --spp 1 --quiet
run "$fathom" --formula mandelbox --output "$tmp/work/shipped.png" --size 32x18 --spp 1 --quiet
check "formula-shadowing: a user file never replaces the shipped one" 'cmp -s shadow.png shipped.png'
run env FATHOM_FORMULAS="$tmp/work/user" "$fathom" --list-formulas
check "formula-shadowing: listed once, the user file as ignored" \
    '[ "$(grep -c "^mandelbox$" "$tmp/stdout")" -eq 1 ] && grep -q "^note: .*/user/mandelbox.glsl is ignored" "$tmp/stdout"'
mkdir -p scenedir elsewhere
printf '// @formula ball\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - 1.0; }\n' >scenedir/ball.glsl
printf '{"program": "fractal", "fractal": {"formula": "ball.glsl"}}' >scenedir/ball.json
cd elsewhere && run "$fathom" --scene ../scenedir/ball.json $png && cd ..
check "formula-path-relative-to-scene: found from another folder" '[ $code -eq 0 ] && [ -s o.png ]'
rm -f o.png

# ---- 7. a shot carries the formulas that drew it ---------------------------------------------------
mkdir -p mine
printf '// @formula a ball of radius r\nuniform float uR; // @param 1 [0.1, 2] radius\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - uR; }\n' >mine/ball.glsl
run "$fathom" --formula mine/ball.glsl --output "$tmp/work/shot.png" --size 32x18 --spp 1 --quiet
cp mine/ball.glsl ball-kept.glsl
rm -rf mine # the formula is gone from this machine: the shot draws it from the text it carries
run env XDG_CACHE_HOME="$tmp/work/cache" "$fathom" --scene shot.png --output "$tmp/work/again.png" --spp 1 --quiet
check "shot-carries-a-user-formula: reopens without the file, and says so" \
    '[ $code -eq 0 ] && cmp -s "$(ls cache/fathom/formulas/*/ball.glsl)" ball-kept.glsl && grep -q "is not on this machine: drawn with the text the shot carries" "$tmp/stderr"'
mkdir -p mine && sed 's/length(p) - uR/length(p) - 0.5 * uR/' ball-kept.glsl >mine/ball.glsl
run env XDG_CACHE_HOME="$tmp/work/cache" "$fathom" --scene shot.png --output "$tmp/work/again2.png" --spp 1 --quiet
check "shot-formula-changed-since: said, and drawn as it was" \
    '[ $code -eq 0 ] && grep -q "changed since this shot was made: drawn with the text the shot carries" "$tmp/stderr" && cmp -s again.png again2.png'
run "$fathom" --scene mandelbox --output "$tmp/work/box.png" --size 32x18 --spp 1 --quiet
mkdir -p data && cp -r "$src/shaders" "$src/scenes" "$src/textures" data/ 2>/dev/null
sed -i 's/^\(uniform float uScale;.*@param \)[-0-9.]*/\1-1.7/' data/shaders/fractal/mandelbox.glsl
run env FATHOM_DATA_DIR="$tmp/work/data" "$fathom" --scene box.png --output "$tmp/work/box2.png" --spp 1 --quiet
check "shot-shipped-formula-changed: said" 'grep -q "note: formula fractal/mandelbox.glsl changed since this shot was made" "$tmp/stderr"'
rm -rf data cache

# ---- 8. the smaller ones --------------------------------------------------------------------------
formula_case() { # NAME NEEDLE TEXT...: the formula file TEXT is refused with NEEDLE in one line
    name=$1 needle=$2; shift 2
    printf "$@" >fm/case.glsl
    run "$fathom" --formula fm/case.glsl $png
    check "$name" '[ $code -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -qF -- "$needle" "$tmp/stderr"'
}
de='float formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - 1.0; }\n'
formula_case formula-default-past-float "expected DEFAULT [LO, HI]" "// @formula f\nuniform float uA; // @param 1e39 [0, 1e40] a\n$de"
formula_case formula-fractional-iterations "whole numbers from 1 to 1000" "// @formula f\n// @iterations 2.5 [1, 8]\n$de"
long=uA; i=0; while [ $i -lt 60 ]; do long="${long}bcde"; i=$((i + 1)); done
formula_case formula-long-uniform "uniform name is at most 47 characters" "// @formula f\nuniform float $long; // @param 1 [0, 2] a\n$de"
formula_case formula-escape-byte "a control character (0x1b)" "// @formula f \033[31mred\n$de"
formula_case formula-del-byte "a control character (0x7f)" "// @formula f del\177\n$de" # DEL too (issue 58 item 17)
printf '\357\273\277// @formula with a BOM and CRLF\r\nuniform float uA; // @param 1 [0, 2] a\r\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - uA; }\r\n' >fm/crlf.glsl
run "$fathom" --formula fm/crlf.glsl $png
check "formula-bom-and-crlf: read as the text it is" '[ $code -eq 0 ] && [ -s o.png ]'
rm -f o.png
run "$fathom" --help-formula fm/crlf.glsl
check "help-formula: no control byte reaches the terminal" '[ $code -eq 0 ] && ! grep -q "$(printf "\r")" "$tmp/stdout"'
run "$fathom" --formula mandelbulb --dem "$src/terrains/jacksboro.png" $png
check "formula-then-dem: a usage error (2), as dem-then-formula" '[ $code -eq 2 ]'
run "$fathom" check-formula mandelbulb --output "$tmp/work/o.png"
check "check-formula-output: refused, not ignored" '[ $code -eq 2 ] && grep -q "does not apply\|do not apply" "$tmp/stderr"'
run "$fathom" bench --scene csg --size 12000x12000 --quiet
check "bench-huge-size: refused up front, no assert" '[ $code -eq 2 ] && grep -q "at most 134217727 pixels" "$tmp/stderr"'
run env FATHOM_TERRAIN_TILE=4294967296 timeout 60 "$fathom" --scene jacksboro $png
check "terrain-tile-env-huge: refused, no endless loop" '[ $code -eq 1 ] && grep -q "FATHOM_TERRAIN_TILE" "$tmp/stderr"'
run "$fathom" stitch --output "$tmp/work/p.png"
check "stitch-message: one 'fathom:'" '[ "$(grep -o "fathom" "$tmp/stderr" | wc -l)" -le 2 ] && ! grep -q "fathom: fathom stitch" "$tmp/stderr"'
# a single shot killed mid-write leaves its temporary file; the next shot into that folder removes it
mkdir -p killed
"$fathom" --output "$tmp/work/killed/shot.exr" --size 640x360 --spp 64 --quiet --aov depth &
pid=$!
i=0
while [ $i -lt 3000 ] && ! ls -A killed | grep -q tmp; do sleep 0.01; i=$((i + 1)); done
kill -KILL $pid; wait $pid 2>/dev/null
run "$fathom" --output "$tmp/work/killed/next.png" --size 16x9 --spp 1 --quiet
check "killed-shot-temp: removed by the next shot" '[ $i -lt 3000 ] && [ -z "$(ls -A killed | grep tmp)" ] && [ -s killed/next.png ]'

# ---- 6. no silent truncation: every loop within fathom's budget, a pixel cut short flagged ---------
if "$fathom" --scene csg --output "$tmp/work/probe.png" --size 8x8 --spp 1 2>&1 | grep -q llvmpipe; then
    # a formula whose own loop runs 70,000 times an estimate: llvmpipe cuts it; was all sky, exit 0
    cat >fm/long_loop.glsl <<'GLSL'
// @formula a ball behind a loop longer than llvmpipe allows
// @bound 2
uniform int uCount; // @param 70000 [1, 100000] loop count
float formulaDE(vec3 p, out float trap) {
    trap = 0.0;
    float s = 0.0;
    for (int i = 0; i < uCount; i++)
        s += 1.0;
    return s >= float(uCount) - 0.5 ? length(p) - 1.0 : 1e9;
}
GLSL
    run "$fathom" --formula fm/long_loop.glsl --output "$tmp/work/o.png" --size 32x18 --spp 1
    check "loops-cut-by-the-driver: flagged and counted" 'grep -q "ran out of the loop budget" "$tmp/stderr"'
    run "$fathom" check-formula fm/long_loop.glsl
    check "loops-cut-by-the-driver: check-formula fails it" \
        '[ $code -ne 0 ] && grep -q "loops: an estimate runs at most .* @loops declares 2:" "$tmp/stdout"'
    # fathom's own budget: a formula that declares 9,000 loop iterations an estimate (it runs 3,000) spends
    # the budget by its declaration, so marches end unresolved before llvmpipe's limit would cut them
    sed 's|^// @bound 2|// @bound 2\n// @loops count * 3|; s|@param 70000|@param 3000|' fm/long_loop.glsl >fm/declared.glsl
    run "$fathom" --formula fm/declared.glsl --output "$tmp/work/o.png" --size 32x18 --spp 1
    check "loop-budget: spent by the declaration, flagged as out of the loop budget" \
        '[ $code -eq 0 ] && grep -q "ran out of the loop budget (63487" "$tmp/stderr"'
    run "$fathom" check-formula fm/declared.glsl
    check "loop-budget: check-formula passes a formula within its declaration" \
        '[ $code -eq 0 ] && grep -q "runs at most 300[0-9] loop iterations; @loops declares 9000$" "$tmp/stdout"'
    sed '/^\/\/ @loops/d' fm/declared.glsl >fm/undeclared.glsl
    run "$fathom" check-formula fm/undeclared.glsl
    check "loop-budget: check-formula fails 3,000 loops declared as 2 (and nothing else)" \
        '[ $code -ne 0 ] && grep -q "passes\|FAILS" "$tmp/stdout" && grep -q "@loops declares 2:" "$tmp/stdout" && grep -q "above 1.005 at 0$" "$tmp/stdout"'
    # the budget is spent by the declaration: 30 times the loops flags far more pixels than the truth
    sed 's|^// @loops count \* 3|// @loops count * 30|' fm/declared.glsl >fm/overdeclared.glsl
    run "$fathom" --formula fm/overdeclared.glsl --output "$tmp/work/o.png" --size 32x18 --spp 1
    over=$(sed -n 's/^note: \([0-9]*\) pixels.*loop budget.*/\1/p' "$tmp/stderr")
    run "$fathom" --formula fm/undeclared.glsl --output "$tmp/work/o.png" --size 32x18 --spp 1
    under=$(sed -n 's/^note: \([0-9]*\) pixels.*loop budget.*/\1/p' "$tmp/stderr")
    check "loop-budget: spent as declared ($over pixels at 30x, ${under:-0} at 2)" '[ "${over:-0}" -gt $((2 * ${under:-0} + 10)) ]'
    run "$fathom" check-formula menger --set fractal.iterations=7
    check "loop-budget: the shipped Menger sponge declares its loops" '[ $code -eq 0 ] && grep -q "@loops declares 29$" "$tmp/stdout"'
    rm -f o.png probe.png
else
    echo "skip loops: not llvmpipe (a GPU has no loop limiter to cut them)"
fi

finish trust
