#!/bin/sh
# Files fathom writes and the files a stranger leaves where fathom writes (issue 50): a planted frames'
# folder or frame, a full disk under every writer the libraries cannot vouch for, a flight that asks for
# more points than memory, the temporaries of killed runs, terminal control bytes and oversized files.
# Each case failed on the code before its fix. Usage: trust_files.sh FATHOM SRC
fathom=$1
src=$2
. "$src/tests/lib/trust_lib.sh"
dem=$src/terrains/himalaya.tif
flight=$src/docs/flight/csg.json
small="--fps 2 --size 32x18 --spp 1 --quiet"
mkdir "$tmp/w" && cd "$tmp/w" || exit 1

# ---- 3. the frames' folder is fathom's, and so is every frame in it ------------------------------------
mkdir elsewhere && ln -s elsewhere v.mp4.frames
run "$fathom" render --path "$flight" $small --output v.mp4
check "frames-folder-link: refused, nothing written through it" \
    '[ $code -ne 0 ] && grep -q "is a link" "$tmp/stderr" && [ -z "$(ls -A elsewhere)" ] && [ ! -e v.mp4 ]'
rm v.mp4.frames
run "$fathom" render --path "$flight" $small --frames 0-0 --output p.mp4 # frame 0 rendered, the rest not yet
# a frame planted where frame 1 goes, a copy of a real frame of fathom's (it decodes, it carries a shot)
cp p.mp4.frames/00000.png p.mp4.frames/00001.png
run "$fathom" render --path "$flight" $small --output p.mp4
check "planted-frame: rendered again, not taken" \
    '[ $code -eq 0 ] && [ -s p.mp4 ] && ! grep -q "00001.png is there, skipped" "$tmp/stderr" && ! cmp -s p.mp4.frames/00000.png p.mp4.frames/00001.png'
cp p.mp4.frames/00000.png p.mp4.frames/00002.png # planted after the render, before a later assembly
run "$fathom" render --path "$flight" $small --output p.mp4
check "frame-changed-after-render: rendered again (not fathom's by the manifest)" \
    '[ $code -eq 0 ] && ! cmp -s p.mp4.frames/00000.png p.mp4.frames/00002.png'

# ---- 5. a full disk under the writers whose library cannot tell ----------------------------------------
mkdir -p "$tmp/small"
if mount -t tmpfs -o size=256k fathomfull "$tmp/small" 2>/dev/null; then
    dd if=/dev/zero of="$tmp/small/fill" bs=4k 2>/dev/null # until the disk is full
    run "$fathom" viewshed --dem "$dem" --observer 86.9,28 --output "$tmp/small/v.tif"
    check "full-disk-viewshed: fails, no file" '[ $code -ne 0 ] && grep -q "cannot write" "$tmp/stderr" && [ "$(ls -A "$tmp/small")" = fill ]'
    run "$fathom" mesh --scene torus --resolution 16 --output "$tmp/small/m.3mf" --quiet
    check "full-disk-3mf: fails, no file" '[ $code -ne 0 ] && grep -q "cannot write" "$tmp/stderr" && [ "$(ls -A "$tmp/small")" = fill ]'
    run "$fathom" track --dem "$dem" --path "$src/docs/flight/himalaya-day.json" --output "$tmp/small/t.kml"
    check "full-disk-kml: fails, no file" '[ $code -ne 0 ] && [ "$(ls -A "$tmp/small")" = fill ]'
    umount "$tmp/small"
else
    echo "skip full-disk: cannot mount a tmpfs here (not root)"
fi

# ---- 6. a flight asking for more points than a track holds --------------------------------------------
printf '{"keys":[{"time":-86400,"position":[0,110000,0],"look_at":[1000,20000,0]},' >twoday.json
printf '{"time":86400,"position":[1000,110000,0],"look_at":[2000,20000,0]}]}\n' >>twoday.json
run timeout 60 "$fathom" track --dem "$dem" --path twoday.json --fps 1000 --output t.gpx
check "track-two-days-at-1000-fps: refused at once, no crash" \
    '[ $code -eq 1 ] && grep -q "lower --fps" "$tmp/stderr" && [ ! -e t.gpx ]'

# ---- 9. every writer removes what a killed run of any writer left ---------------------------------------
dead=$(sh -c 'echo $$') # a process that has ended: its temporaries are stale
for out in m.3mf t.kml t.gpx v.tif s.png f.mp4; do
    base=${out%.*} ext=${out##*.}
    touch ".$out.tmp$dead-0.$ext" ".$out.tmp$dead.$ext"
    case $ext in
        3mf) run "$fathom" mesh --scene torus --resolution 8 --output "$out" --quiet ;;
        kml | gpx) run "$fathom" track --dem "$dem" --path "$src/docs/flight/himalaya-day.json" --output "$out" ;;
        tif) run "$fathom" viewshed --dem "$dem" --observer 86.9,28 --output "$out" ;;
        png) run "$fathom" --output "$out" --size 16x9 --spp 1 --quiet ;;
        mp4) run "$fathom" render --path "$flight" $small --output "$out" ;;
    esac
    check "stale-temporaries-$ext: removed by the next $ext writer" \
        '[ $code -eq 0 ] && [ -s "$out" ] && [ -z "$(ls -A | grep "^\.$base.*\.tmp")" ]'
done
touch ".other.png.tmp$$-0.png" # a live writer's (this shell's): kept
run "$fathom" --output s.png --size 16x9 --spp 1 --quiet
check "live-temporary: kept" '[ -e ".other.png.tmp$$-0.png" ]'
# a user's own files that only look like temporaries, beside the output: not fathom's to remove
touch ".notes.tmp$dead.md" ".s.png.tmp$dead.txt" ".s.png.tmp$dead-x.png" ".s.png.tmp$dead.pn"
run "$fathom" --output s.png --size 16x9 --spp 1 --quiet
check "user-files-like-temporaries: kept" \
    '[ $code -eq 0 ] && [ -e ".notes.tmp$dead.md" ] && [ -e ".s.png.tmp$dead.txt" ] && [ -e ".s.png.tmp$dead-x.png" ] && [ -e ".s.png.tmp$dead.pn" ]'

# ---- 4. no formula or fragment takes fathom down: bounds on what the compiler sees, loops that never end ---
formula() { # formula FILE BODY-EXPRESSION [DEFINES...]: a formula whose distance adds the expression
    f=$1 body=$2
    shift 2
    { printf '// @formula hostile\n// @iterations 1 [1, 1]\n// @bound 2\n#include "fractal/common.glsl"\n'
      for d in "$@"; do printf '%s\n' "$d"; done
      printf 'real formulaDE(real3 p, out float trap)\n{\n    trap = 0.0;\n    float a = float(p.x);\n'
      printf '    %s\n    return real(length(vec3(p)) - 1.0 + %s);\n}\n' "${loop:-}" "$body"; } >"$f"
}
chain=$(i=1; while [ $i -le 30 ]; do printf '#define M%d M%d M%d\n' $i $((i - 1)) $((i - 1)); i=$((i + 1)); done)
formula bomb.glsl "0.0 M30" "#define M0 +0.0" "$chain"
nest() { i=0; while [ $i -lt "$1" ]; do printf '%s' "$2"; i=$((i + 1)); done; }
formula fbomb.glsl "$(nest 40 'F(')0.0$(nest 40 ')')" "#define F(x) (x+x)"
formula rescan.glsl "$(nest 20 'A(')1.0$(nest 20 ')')" "#define B(x) x x x x" "#define A B"
formula deep.glsl "$(nest 3000 '(' | fold -w 60)0.0$(nest 3000 ')' | fold -w 60)"
formula longline.glsl "$(i=0; while [ $i -lt 3000 ]; do printf '0.0+'; i=$((i + 1)); done)0.0"
loop='for (int i = 0; i >= 0; i += 0) { a = a * 1.0001 + 1.0; if (a < -1e30) break; }' formula loop.glsl "min(a, 0.0)"
# each under 8 GB of address space: a bomb that got through would take the machine's memory, not CI's run
# (not under AddressSanitizer, whose shadow memory is terabytes of address space)
limit='ulimit -v 8000000;'
sh -c "$limit"' exec "$@"' sh "$fathom" --version >/dev/null 2>&1 || limit=''
for f in bomb fbomb rescan deep longline loop; do
    run sh -c "$limit"' exec "$@"' sh timeout 60 "$fathom" --formula $f.glsl --output $f.png --size 16x9 --spp 1 --quiet
    check "formula-$f: one line, exit 1, no image" '[ $code -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && [ ! -e $f.png ]'
done
for f in bomb loop; do # check-formula: the same refusal, or the loop flagged; never a hang
    run sh -c "$limit"' exec "$@"' sh timeout 120 "$fathom" check-formula $f.glsl
    check "check-formula-$f: fails, no hang" '[ $code -eq 1 ]'
done
# the same bomb in a fragment (Fragmentarium's translation keeps its macros)
{ printf '#include "DE-Raytracer.frag"\n#define M0 +0.0\n%s\n' "$chain"
  printf 'float DE(vec3 p) { return length(p) - 1.0 M30; }\n'; } >bomb.frag
run sh -c "$limit"' exec "$@"' sh timeout 60 "$fathom" --scene bomb.frag --output bombf.png --size 16x9 --spp 1 --quiet
check "fragment-bomb: one line, exit 1, no image" '[ $code -eq 1 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && [ ! -e bombf.png ]'

# ---- 7. no control byte from a file reaches the terminal; a track's name any bytes, its KML still XML ---
# a fragment whose #info, slider comment and preset name carry C1 controls (CSI clear, OSC title) in UTF-8
awk 'NR == 1 { print "#info \302\2332J\302\2350;TITLE\302\234 a C1 clear"; next }
     /^#preset Rolled/ { print "#preset \302\2350;EVIL\302\234Rolled"; next } { print }' \
    "$src/docs/fragments/mandelbox.frag" >c1.frag
{ "$fathom" --scene c1.frag --view nosuch --output c1.png --size 16x9 --spp 1
  "$fathom" --scene c1.frag --output c1.png --size 16x9 --spp 1 --quiet
  "$fathom" --scene c1.frag --print-variant
  "$fathom" --set "$(printf 'camera.roll=\033]0;T\007')" --output c1.png --size 16x9; } >"$tmp/stdout" 2>&1
check "control-bytes: none printed (the preset's name shown escaped)" \
    '! LC_ALL=C grep -q "$(printf "[\033\007]")" "$tmp/stdout" && ! LC_ALL=C grep -q "$(printf "\302[\200-\237]")" "$tmp/stdout" &&
     grep -q "u009d0;EVIL" "$tmp/stdout"'
name=$(printf 'bad\377\302\233name')
cp "$src/docs/flight/himalaya-day.json" "$name.json"
run "$fathom" track --dem "$dem" --path "$name.json" --output n.kml
check "kml-invalid-utf8-name: the file is UTF-8 XML" '[ $code -eq 0 ] && iconv -f UTF-8 -t UTF-8 n.kml >/dev/null 2>&1'

# ---- 8. an oversized fragment or formula is refused by its size, not read first (a sparse 2 GB file) ------
truncate -s 2G big.frag && truncate -s 2G big.glsl
for f in big.frag big.glsl; do
    case $f in *.frag) how="--scene" ;; *) how="--formula" ;; esac
    if [ -x /usr/bin/time ]; then # GNU time: the peak resident memory (KB) last on stderr
        run /usr/bin/time -f "%M" "$fathom" $how $f --output big.png --size 16x9 --spp 1 --quiet
        kb=$(tail -n 1 "$tmp/stderr")
    else
        run "$fathom" $how $f --output big.png --size 16x9 --spp 1 --quiet
        kb=0
    fi
    check "oversized-$f: refused at once (peak ${kb} KB)" '[ $code -ne 0 ] && grep -q "larger than" "$tmp/stderr" && [ "$kb" -lt 200000 ]'
done
rm -f big.frag big.glsl

# ---- 10. small: a hexadecimal count, an option given twice, an Include two folders up ---------------------
run "$fathom" mesh --scene torus --resolution 0x10 --output hex.ply
check "resolution-0x10: refused, not read as 16" '[ $code -eq 2 ] && grep -q "bad --resolution" "$tmp/stderr" && [ ! -e hex.ply ]'
run "$fathom" viewshed --dem "$dem" --observer 86.9,28 --radius 5000 --radius=6000 --output twice.tif
check "viewshed-option-twice: refused" '[ $code -eq 2 ] && grep -q "given twice" "$tmp/stderr" && [ ! -e twice.tif ]'
run "$fathom" track --dem "$dem" --dem "$dem" --path "$src/docs/flight/himalaya-day.json" --output twice.gpx
check "track-option-twice: refused" '[ $code -eq 2 ] && grep -q "given twice" "$tmp/stderr" && [ ! -e twice.gpx ]'
mkdir -p up/Include up/a/b
printf 'float DE(vec3 p) { return length(p) - 1.0; }\n' >up/Include/Planted.frag
printf '#include "DE-Raytracer.frag"\n#include "Planted.frag"\n' >up/a/b/x.frag
run "$fathom" --scene up/a/b/x.frag --output inc.png --size 16x9 --spp 1 --quiet
check "include-two-folders-up: not the collection's" '[ $code -ne 0 ] && grep -q "Planted.frag" "$tmp/stderr" && [ ! -e inc.png ]'
mv up/Include up/a/Include # one up: Fragmentarium's Examples/GROUP/X.frag beside Examples/Include
run "$fathom" --scene up/a/b/x.frag --output inc.png --size 16x9 --spp 1 --quiet
check "include-one-folder-up: the collection's, used" '[ $code -eq 0 ] && [ -s inc.png ]'
if [ "$(id -u)" = 0 ] && id nobody >/dev/null 2>&1; then
    chown -R nobody up/a/Include && rm -f inc.png
    run "$fathom" --scene up/a/b/x.frag --output inc.png --size 16x9 --spp 1 --quiet
    check "include-of-another-user: not used" '[ $code -ne 0 ] && [ ! -e inc.png ]'
fi

finish trust_files
