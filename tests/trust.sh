#!/bin/sh
# Trust boundaries: a preset, shot, formula or module from a stranger is data, never code. Each case
# fails on the code before the fix (the closing note of issue 34 lists them). Usage: trust.sh FATHOM SRC
fathom=$1
src=$2
tmp=$(mktemp -d)
trap 'umount "$tmp/small" 2>/dev/null; chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok   $1"; }
bad() { failed=$((failed + 1)); echo "FAIL $1"; [ -s "$tmp/stderr" ] && sed 's/^/     | /' "$tmp/stderr"; }
# check NAME CONDITION: CONDITION is a shell test run after the case
check() { if eval "$2"; then ok "$1"; else bad "$1"; fi; }
run() { "$@" >"$tmp/stdout" 2>"$tmp/stderr"; code=$?; }
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
# a bad --knob value is refused before anything renders, and a refused run leaves no folder
run "$fathom" bench --scene csg --size 16x9 --runs 1 --knob "step_factor=0.5,0.6,0.7,0.8,9" --out refused --quiet
check "bench-bad-knob-value: refused at once, no folder left" \
    '[ $code -ne 0 ] && grep -q "step_factor" "$tmp/stderr" && [ ! -e refused ] && [ ! -s "$tmp/stdout" ]'
# a full disk: no partial plot, CSV or report, and the folder the run made is gone
mkdir -p "$tmp/small"
if mount -t tmpfs -o size=96k fathomtrust "$tmp/small" 2>/dev/null; then
    run "$fathom" bench --scene csg --size 64x36 --runs 1 --knob resolution_scale=0.5 --quiet --out "$tmp/small/full"
    check "bench-full-disk: fails with the disk named" '[ $code -ne 0 ] && grep -q "cannot write" "$tmp/stderr"'
    check "bench-full-disk: nothing left" '[ -z "$(ls -A "$tmp/small")" ]'
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
for inc in "$tmp/work/token.txt" ../token.txt link.glsl 'sub/../../token.glsl'; do
    printf '// @formula reads a file\n#include "%s"\nfloat formulaDE(vec3 p, out float trap) { trap = 0.0; return length(p) - 1.0; }\n' "$inc" >fm/evil.glsl
    run "$fathom" --formula fm/evil.glsl $png
    check "formula-include '$inc': refused, the file's text not shown" \
        '[ $code -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && ! grep -q FAKESECRET "$tmp/stderr" && [ ! -e o.png ]'
done
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

echo "trust: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
