#!/bin/sh
# run-steps.sh MAKE LOGDIR STEP... - `make test`: run each step in a make of
# its own, keep going after a failure so that one run reports all of them,
# then print a summary ending in "N passed, N failed". Exits 1 if a step
# failed.
set -eu
[ $# -ge 3 ] || { echo "usage: run-steps.sh MAKE LOGDIR STEP..." >&2; exit 2; }
make=$1
logs=$2
shift 2
mkdir -p "$logs"
for step in "$@"; do
	echo "==== $step"
	start=$(date +%s)
	# shellcheck disable=SC2086 # MAKE may carry words
	{ rc=0; $make --no-print-directory "$step" 2>&1 || rc=$?; echo $rc >"$logs/$step.rc"; } |
		tee "$logs/$step.log"
	echo $(($(date +%s) - start)) >"$logs/$step.time"
done
echo "==== summary"
passed=0
failed=0
for step in "$@"; do
	if [ "$(cat "$logs/$step.rc")" = 0 ]; then
		verdict=PASS
		passed=$((passed + 1))
	else
		verdict=FAIL
		failed=$((failed + 1))
	fi
	printf '%s %-20s %4s s   (log: %s)\n' "$verdict" "$step" "$(cat "$logs/$step.time")" "$logs/$step.log"
	if [ $verdict = PASS ]; then
		grep -E '^(PASS|FAIL|SKIP|FREESTANDING|CROSS|CORTEX-M4|LAYERS|RT) ' "$logs/$step.log" || true
	else
		grep -v -e ", as expected" -e "^make\[" "$logs/$step.log" | tail -n 6
	fi | sed 's/^/    /'
done
echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
