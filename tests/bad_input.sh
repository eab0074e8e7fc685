#!/bin/sh
# Bad input: each case must give one clear line on stderr (what, where, what to do), a non-zero exit
# code, no output file, and no crash. Usage: bad_input.sh FATHOM SOURCE_DIR
fathom=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

# expect NAME EXIT_CODE NEEDLE [MAX_LINES] -- COMMAND...
expect() {
    name=$1 code=$2 needle=$3 lines=$4
    shift 5
    rm -f "$tmp/out.png" "$tmp/out.exr"
    "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    got=$?
    why=""
    [ "$got" -eq "$code" ] || why="exit code $got, expected $code"
    grep -qF -- "$needle" "$tmp/stderr" || why="$why; stderr lacks '$needle'"
    n=$(wc -l <"$tmp/stderr")
    [ "$n" -le "$lines" ] || why="$why; $n lines on stderr (at most $lines)"
    ls "$tmp"/out.* "$tmp"/.out.* >/dev/null 2>&1 && why="$why; a (partial) output file was left"
    if [ -z "$why" ]; then
        passed=$((passed + 1))
        echo "ok   $name: $(head -n 1 "$tmp/stderr")"
    else
        failed=$((failed + 1))
        echo "FAIL $name: $why"
        sed 's/^/     | /' "$tmp/stderr"
    fi
}

out="--output $tmp/out.png --size 33x21 --spp 1 --quiet"

expect unknown-scene 1 "unknown scene 'nosuch' (known: csg" 1 -- "$fathom" --scene nosuch $out
expect missing-file 1 "scene file '$tmp/missing.json' not found" 1 -- "$fathom" --scene "$tmp/missing.json" $out

printf '{\n  "program": "csg",\n  "materials": { "a": { "roughness": 0.5 }\n  "objects": []\n}\n' >"$tmp/bad.json"
expect malformed-json 1 "$tmp/bad.json:4:" 1 -- "$fathom" --scene "$tmp/bad.json" $out

printf '{"program": "csg", "materials": {"a": {"texture": "no/such.png"}},\n "objects": [{"shape": "sphere", "material": "a"}]}\n' >"$tmp/tex.json"
expect missing-texture 1 "materials.a.texture: file '$tmp/no/such.png' not found" 1 -- "$fathom" --scene "$tmp/tex.json" $out

expect bad-size 2 "bad --size '0x-3'" 1 -- "$fathom" --size 0x-3 --output "$tmp/out.png"
expect bad-spp 2 "bad --spp '-1'" 1 -- "$fathom" --spp -1 --output "$tmp/out.png"
expect bad-fov 2 "bad --fov '400'" 1 -- "$fathom" --fov 400 --output "$tmp/out.png"
expect bad-extension 2 "must end in .png or .exr" 1 -- "$fathom" --output "$tmp/out.jpg"
expect unknown-option 2 "unknown option '--colour'" 1 -- "$fathom" --colour red
expect unknown-set-key 1 "materials.glass.iro: unknown key 'iro'" 1 -- "$fathom" --set materials.glass.iro=1.3 $out
expect bad-set-value 1 "materials.glass.ior: expected a number from 1 to 4 (from --set)" 1 -- "$fathom" --set materials.glass.ior=9 $out
expect unwritable-output 1 "folder '$tmp/no/such/dir' does not exist" 1 -- "$fathom" --output "$tmp/no/such/dir/out.png" --size 33x21 --quiet

# a shader that does not compile: a copy of the data folder with one broken line
mkdir -p "$tmp/data"
cp -r "$src/shaders" "$src/scenes" "$src/textures" "$src/terrains" "$tmp/data/"
line=$(grep -n "const vec2 k = vec2(1.0, -1.0);" "$tmp/data/shaders/common/march.glsl" | cut -d: -f1)
sed -i "${line}s/.*/    const vec2 k = undeclared_thing;/" "$tmp/data/shaders/common/march.glsl"
expect shader-error 1 "common/march.glsl:$line:" 40 -- env FATHOM_DATA_DIR="$tmp/data" "$fathom" $out

expect no-display 1 "no display to open a window on" 1 -- env -u DISPLAY -u WAYLAND_DISPLAY "$fathom" --frames 1

echo "bad_input: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
