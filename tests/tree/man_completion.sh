#!/bin/sh
# The man page (help2man from --help, built beside fathom) names every option --help does, and the
# bash completion completes options, subcommands, scene names and formula names from the program
# itself. Usage: man_completion.sh FATHOM SOURCE_DIR
fathom=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$2
passed=0 failed=0
check() { if eval "$2"; then passed=$((passed + 1)); echo "ok   $1"; else failed=$((failed + 1)); echo "FAIL $1"; fi; }
page=$(dirname "$fathom")/fathom.1
if command -v help2man >/dev/null; then
    check "the man page was built" '[ -s "$page" ]'
    missing=""
    for o in $("$fathom" --help | grep -oE -- '--[a-z][a-z-]+' | sort -u); do
        grep -qF -- "$(echo "$o" | sed 's/-/\\-/g')" "$page" || missing="$missing $o"
    done
    check "the man page names every option of --help (missing:$missing)" '[ -z "$missing" ]'
    check "the man page has a NAME and the guide in SEE ALSO" 'grep -q "terrain and fractal ray-marching explorer" "$page" && grep -q "docs/guide" "$page"'
else
    echo "skip the man page: no help2man"
fi
complete_words() { # complete_words WORD...: what the completion offers for the last word
    bash -c '. "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _fathom; printf "%s\n" "${COMPREPLY[@]}"' \
        sh "$src/completion/fathom.bash" "$@" | sort | tr '\n' ' '
}
check "--scene man completes to mandelbox mandelbulb" '[ "$(complete_words "$fathom" --scene man)" = "mandelbox mandelbulb " ]'
check "--ti completes to --tile" '[ "$(complete_words "$fathom" --ti)" = "--tile " ]'
check "check-formula quat completes to the two quaternion formulas" \
    '[ "$(complete_words "$fathom" check-formula quat)" = "quaternion_julia quaternion_mandelbrot " ]'
check "me completes to the subcommand mesh" '[ "$(complete_words "$fathom" me)" = "mesh " ]'
check "st completes to the subcommand stitch" '[ "$(complete_words "$fathom" st)" = "stitch " ]'
check "--quality f completes to final" '[ "$(complete_words "$fathom" --quality f)" = "final " ]'
echo "man_completion: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
