#!/bin/sh
# Every fathom command the README shows in a ```sh block (after the two set-up commands) runs and
# succeeds, at a tiny size, and its usage block is what --help prints: the README is exactly what the
# program accepts. Sizes become 32x18,
# spp 1, bench runs 1; window commands get --frames 1 under xvfb-run (skipped without it).
# Usage: readme_examples.sh FATHOM SOURCE_DIR
fathom=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/build"
ln -s "$fathom" "$tmp/build/fathom"
for d in scenes terrains textures shaders docs; do ln -s "$src/$d" "$tmp/$d"; done
passed=0 failed=0
awk '/^```sh/ {f = 1; next} /^```/ {f = 0} f && !/^apt-get/' "$src/README.md" | sed 's/[[:space:]]*#.*$//' |
    grep -v '^[[:space:]]*$' >"$tmp/commands"
while IFS= read -r line; do
    cmd=$(echo "$line" | sed -E 's/--size [0-9]+x[0-9]+/--size 32x18/; s/--spp [0-9]+/--spp 1/')
    case "$cmd" in
    build/fathom\ check-formula*) ;; # a report: it takes no size, frames or output
    build/fathom\ bench*) cmd="$cmd --runs 1 --quiet"; echo "$cmd" | grep -q -- --size || cmd="$cmd --size 32x18" ;;
    build/fathom*--output* | build/fathom*--print-variant* | build/fathom*--list-scenes* | build/fathom*--help*)
        echo "$cmd" | grep -q -- --size || cmd="$cmd --size 32x18"
        echo "$cmd" | grep -q -- --output && cmd="$cmd --quiet --spp 1" ;;
    build/fathom*)
        if command -v xvfb-run >/dev/null; then cmd="xvfb-run -a $cmd --frames 1 --size 64x36"; else
            echo "skip (no xvfb-run): $line"; continue; fi ;;
    esac
    if (cd "$tmp" && sh -c "$cmd" >"$tmp/out" 2>&1); then
        passed=$((passed + 1)); echo "ok   $line"
    else
        failed=$((failed + 1)); echo "FAIL $line"; echo "     ran: $cmd"; sed 's/^/     | /' "$tmp/out" | tail -5
    fi
done <"$tmp/commands"
# the usage block is exactly what --help prints
awk '/^usage: fathom \[options\]/ {f = 1} f && /^```/ {exit} f' "$src/README.md" >"$tmp/usage.readme"
"$fathom" --help >"$tmp/usage.help"
if diff "$tmp/usage.help" "$tmp/usage.readme" >"$tmp/usage.diff"; then
    passed=$((passed + 1)); echo "ok   the README's usage block is fathom --help"
else
    failed=$((failed + 1)); echo "FAIL the README's usage block differs from fathom --help:"; head -20 "$tmp/usage.diff"
fi
# words about the program that are checked, not trusted: the key table's scenes are the first nine
# of --list-scenes, and the formula list is --list-formulas
listed=$("$fathom" --list-scenes | head -n 9 | tr '\n' ',' | sed 's/,$//; s/,/, /g')
if grep -qF "the first nine scenes of \`--list-scenes\`: $listed |" "$src/README.md"; then
    passed=$((passed + 1)); echo "ok   the key table's scenes are --list-scenes' first nine ($listed)"
else
    failed=$((failed + 1)); echo "FAIL the key table's scene list is not --list-scenes' first nine: $listed"
fi
formulas=$("$fathom" --list-formulas | tr '\n' ',' | sed 's/,$//; s/,/, /g')
if tr '\n' ' ' <"$src/README.md" | sed 's/  */ /g' | grep -qF "Shipped formulas (\`--list-formulas\`): $formulas;"; then
    passed=$((passed + 1)); echo "ok   the README's formula list is --list-formulas"
else
    failed=$((failed + 1)); echo "FAIL the README's formula list is not --list-formulas: $formulas"
fi
# the --print-variant sample is the start of what it prints (the scene's folder left out)
awk '/^\$ build\/fathom --scene csg --print-variant$/ {f = 1; next} f && /^(\.\.\.|```)$/ {exit} f' "$src/README.md" \
    >"$tmp/variant.readme"
n=$(wc -l <"$tmp/variant.readme")
"$fathom" --scene csg --print-variant | sed 's#(/.*/scenes/#(scenes/#' | head -n "$n" >"$tmp/variant.out"
if [ "$n" -gt 2 ] && diff "$tmp/variant.out" "$tmp/variant.readme" >"$tmp/variant.diff"; then
    passed=$((passed + 1)); echo "ok   the README's --print-variant sample is what it prints"
else
    failed=$((failed + 1)); echo "FAIL the README's --print-variant sample differs:"; head -10 "$tmp/variant.diff"
fi
echo "readme_examples: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
