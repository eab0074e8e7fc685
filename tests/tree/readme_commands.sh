#!/bin/sh
# The README's test command must be the one .ci/run runs, and both README commands must be there.
# Usage: readme_commands.sh SOURCE_DIR
src=$1
ci=$(grep -E '^apt-get update && ' "$src/.ci/run")
readme_test=$(grep -E '^apt-get update && .*ctest --test-dir build' "$src/README.md")
readme_main=$(grep -E '^apt-get update && .*build/fathom' "$src/README.md")
passed=0 failed=0
check() {
    if [ "$2" = "$3" ] && [ -n "$2" ]; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL $1"; fi
}
check "README test command = .ci/run" "$ci" "$readme_test"
check "README main command present" "$(echo "$readme_main" | wc -l)" "1"
# The main command installs the same packages (minus the test-only ones).
pk() { echo "$1" | sed 's/.*--no-install-recommends //; s/ &&.*//' | tr ' ' '\n' | grep -vE '^(libcmocka-dev|xvfb|xauth|xdotool|clang|slurmctld|slurmd|slurm-client|munge)$' | sort; }
check "same packages" "$(pk "$readme_main")" "$(pk "$readme_test")"
echo "readme_commands: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
