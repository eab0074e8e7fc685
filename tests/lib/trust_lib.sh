# Sourced by the trust suites (trust.sh, trust_gis.sh, trust_files.sh): a temporary folder removed on any
# exit (a tmpfs mounted at $tmp/small unmounted first, read-only folders made writable), and the cases'
# helpers. The suite sets extra_cleanup for what else its exit must end (a listener).
tmp=$(mktemp -d)
extra_cleanup=:
trap 'eval "$extra_cleanup"; umount "$tmp/small" 2>/dev/null; chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
trap 'exit 130' INT TERM
passed=0
failed=0
ok() { passed=$((passed + 1)); echo "ok   $1"; }
bad() { failed=$((failed + 1)); echo "FAIL $1"; [ -s "$tmp/stderr" ] && sed 's/^/     | /' "$tmp/stderr"; }
# check NAME CONDITION: CONDITION is a shell test run after the case
check() { if eval "$2"; then ok "$1"; else bad "$1"; fi; }
run() { "$@" >"$tmp/stdout" 2>"$tmp/stderr"; code=$?; }
# the closing line ctest's log and CI read: "NAME: N passed, N failed"
finish() { echo "$1: $passed passed, $failed failed"; [ "$failed" -eq 0 ]; }
