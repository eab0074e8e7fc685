#!/bin/sh
# Every command the README, the user guide (docs/guide/*.md) and docs/flights.md show in a ```sh block
# (after the README's two set-up commands) runs and succeeds, at a tiny size, and the words about the
# program that those pages quote are what it prints: the pages are exactly what the program accepts.
# Sizes become 32x18, spp 1, bench runs 1 (a sweep --quick), check-formula --quick, mesh resolutions 24;
# window commands get --frames 1 under xvfb-run (skipped without it). A command shown on several pages runs once (the first time it is shown), in the order
# of the pages below, all from one folder that links build/fathom, scenes, terrains, textures, shaders
# and docs, so a later command may open what an earlier one wrote.
# Usage: readme_examples.sh FATHOM SOURCE_DIR
fathom=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
work=$tmp/work # where the commands run; the script's own files stay in $tmp, out of their way
mkdir -p "$work/build"
ln -s "$fathom" "$work/build/fathom"
for d in scenes terrains textures shaders docs; do ln -s "$src/$d" "$work/$d"; done
passed=0 failed=0
ok() { passed=$((passed + 1)); echo "ok   $*"; }
fail() { failed=$((failed + 1)); echo "FAIL $*"; }

# the pages, by their path under SOURCE_DIR
pages=README.md
for f in "$src"/docs/guide/*.md; do [ -f "$f" ] && pages="$pages docs/guide/${f##*/}"; done
[ -f "$src/docs/flights.md" ] && pages="$pages docs/flights.md"

# PAGE<tab>COMMAND for every line of every ```sh block, comments and blank lines left out; then each
# command once, with every page that shows it
for p in $pages; do
    awk -v page="$p" '/^```sh/ {f = 1; next} /^```/ {f = 0} f && !/^apt-get/ {print page "\t" $0}' "$src/$p"
done | sed 's/[[:space:]]*#.*$//' | awk -F '\t' '
    $2 ~ /^[[:space:]]*$/ { next }
    !($2 in src) { order[n++] = $2 }
    { if (index(", " src[$2] ", ", ", " $1 ", ") == 0) src[$2] = (src[$2] == "" ? "" : src[$2] ", ") $1 }
    END { for (i = 0; i < n; i++) print src[order[i]] "\t" order[i] }' >"$tmp/commands"
tab=$(printf '\t')
while IFS="$tab" read -r from line; do
    cmd=$(echo "$line" | sed -E 's/--size [0-9]+x[0-9]+/--size 32x18/; s/--spp [0-9]+/--spp 1/; s/--runs [0-9]+/--runs 1/')
    case "$cmd" in
    build/fathom\ check-formula*) # a report: it takes no size, frames or output; the defaults only
        echo "$cmd" | grep -q -- --quick || cmd="$cmd --quick" ;;
    build/fathom\ viewshed* | build/fathom\ track* | build/fathom\ water*) ;; # GIS files: no size, spp or frames
    build/fathom\ mesh*) cmd=$(echo "$cmd" | sed -E 's/--resolution [0-9]+/--resolution 24/') # a mesh: no size or spp
        echo "$cmd" | grep -q -- --resolution || cmd="$cmd --resolution 24"
        cmd="$cmd --quiet" ;;
    build/fathom\ bench*) cmd="$cmd --quiet" # options are given once: only what the example lacks is added
        echo "$cmd" | grep -q -- --runs || cmd="$cmd --runs 1"
        echo "$cmd" | grep -q -- '--quick\|--full\|--frame-times\|--interactive\|--terrain-scale\|--final-frame\|--viewshed' ||
            cmd="$cmd --quick"
        echo "$cmd" | grep -q -- --size || cmd="$cmd --size 32x18" ;;
    build/fathom*--output* | build/fathom*--print-variant* | build/fathom*--list-scenes* | build/fathom*--help* | \
        build/fathom*--list-formulas*)
        echo "$cmd" | grep -q -- --size || cmd="$cmd --size 32x18"
        echo "$cmd" | grep -q -- --output && cmd="$cmd --quiet"
        echo "$cmd" | grep -q -- --output && ! echo "$cmd" | grep -q -- --spp && cmd="$cmd --spp 1" ;;
    build/fathom*)
        if command -v xvfb-run >/dev/null; then cmd="xvfb-run -a $cmd --frames 1 --size 64x36"; else
            echo "skip (no xvfb-run) $from: $line"; continue; fi ;;
    esac
    if (cd "$work" && sh -c "$cmd" >"$tmp/out" 2>&1); then
        ok "$from: $line"
    else
        fail "$from: $line"; echo "     ran: $cmd"; sed 's/^/     | /' "$tmp/out" | tail -5
    fi
done <"$tmp/commands"

# holding PATTERN (grep -E, per line): the pages with a line that matches it
holding() {
    for p in $pages; do grep -qE -- "$1" "$src/$p" && printf '%s ' "$p"; done
}
# the usage block is exactly what --help prints, and there is one copy of it
usage=$(holding '^usage: fathom \[options\]')
n=$(for p in $usage; do grep -cE '^usage: fathom \[options\]' "$src/$p"; done | awk '{s += $1} END {print s + 0}')
if [ "$n" -ne 1 ]; then
    fail "the usage block (usage: fathom [options]) should be on one page, once; found $n times: ${usage:-nowhere}"
else
    usage=${usage% }
    awk '/^usage: fathom \[options\]/ {f = 1} f && /^```/ {exit} f' "$src/$usage" >"$tmp/usage.page"
    "$fathom" --help >"$tmp/usage.help"
    if diff "$tmp/usage.help" "$tmp/usage.page" >"$tmp/usage.diff"; then
        ok "$usage: the usage block is fathom --help"
    else
        fail "$usage: the usage block differs from fathom --help:"; head -20 "$tmp/usage.diff"
    fi
fi
# words about the program that are checked, not trusted: the key table's scenes are the first nine
# of --list-scenes, and the formula list is --list-formulas (wherever a page quotes them)
listed=$("$fathom" --list-scenes | head -n 9 | awk '{print $1}' | tr '\n' ',' | sed 's/,$//; s/,/, /g')
where=$(holding 'the first nine scenes of `--list-scenes`:')
[ -n "$where" ] || fail "no page has the key table's 'the first nine scenes of \`--list-scenes\`: ...'"
for p in $where; do
    if grep -qF "the first nine scenes of \`--list-scenes\`: $listed |" "$src/$p"; then
        ok "$p: the key table's scenes are --list-scenes' first nine ($listed)"
    else
        fail "$p: the key table's scene list is not --list-scenes' first nine: $listed"
    fi
done
formulas=$("$fathom" --list-formulas | tr '\n' ',' | sed 's/,$//; s/,/, /g')
where=$(holding 'Shipped formulas \(`--list-formulas`\):')
[ -n "$where" ] || fail "no page has 'Shipped formulas (\`--list-formulas\`): ...'"
for p in $where; do
    if tr '\n' ' ' <"$src/$p" | sed 's/  */ /g' | grep -qF "Shipped formulas (\`--list-formulas\`): $formulas;"; then
        ok "$p: the formula list is --list-formulas"
    else
        fail "$p: the formula list is not --list-formulas: $formulas"
    fi
done
# the --print-variant sample is the start of what it prints (the scene's folder left out)
where=$(holding '^\$ build/fathom --scene csg --print-variant$')
[ -n "$where" ] || fail "no page has the '\$ build/fathom --scene csg --print-variant' sample"
for p in $where; do
    awk '/^\$ build\/fathom --scene csg --print-variant$/ {f = 1; next} f && /^(\.\.\.|```)$/ {exit} f' "$src/$p" \
        >"$tmp/variant.page"
    n=$(wc -l <"$tmp/variant.page")
    "$fathom" --scene csg --print-variant | sed 's#(/.*/scenes/#(scenes/#' | head -n "$n" >"$tmp/variant.out"
    if [ "$n" -gt 2 ] && diff "$tmp/variant.out" "$tmp/variant.page" >"$tmp/variant.diff"; then
        ok "$p: the --print-variant sample is what it prints"
    else
        fail "$p: the --print-variant sample differs:"; head -10 "$tmp/variant.diff"
    fi
done
# every path file a page shows (a ```json block with "keys") is one fathom renders: its first frame, tiny
for p in $pages; do
    awk '/^```json/ {f = 1; n++; next} /^```/ {f = 0} f { print > (dir "/block-" n ".json") }' dir="$tmp" n=0 "$src/$p"
    for b in "$tmp"/block-*.json; do
        [ -f "$b" ] || continue
        if grep -q '"keys"' "$b"; then
            if (cd "$work" && "$fathom" render --path "$b" --scene csg --frames 0-0 --output "$tmp/path_%04d.png" \
                --size 16x9 --quiet >"$tmp/out" 2>&1); then
                ok "$p: its path file example renders ($(grep -c '"time"' "$b") keys)"
            else
                fail "$p: its path file example is refused:"; sed 's/^/     | /' "$tmp/out" | tail -3
            fi
        fi
        rm -f "$b" "$tmp"/path_*.png
    done
done
echo "readme_examples: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
