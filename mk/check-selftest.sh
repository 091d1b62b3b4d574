#!/bin/sh
# check-selftest.sh OUTDIR EXPECT:FILE... - prove that the freestanding checks
# are not no-ops: each FILE goes through the same stages as the core
# (check-includes.sh, the compiler, check-objects.sh) and must be stopped
# by the stage EXPECT names, or pass all of them when EXPECT is "pass".
#   EXPECT: pass | includes | compiler | objects
# The compiler and the object check come from the environment: CC, CFLAGS
# (word-split), NM, ALLOW (the allowed undefined symbols, a regex).
set -eu
[ $# -ge 2 ] || { echo "usage: check-selftest.sh OUTDIR EXPECT:FILE..." >&2; exit 2; }
: "${CC:?}" "${CFLAGS:?}" "${NM:?}" "${ALLOW:?}"
out=$1
shift
mkdir -p "$out"
here=$(dirname "$0")
status=0
for arg in "$@"; do
	expect=${arg%%:*}
	src=${arg#*:}
	obj=$out/$(basename "$src" .c).o
	log=$out/$(basename "$src" .c).log
	rm -f "$obj"
	# the first stage that refuses the file (CFLAGS is a list of words)
	# shellcheck disable=SC2086
	if ! sh "$here/check-includes.sh" "$src" >"$log" 2>&1; then
		got=includes
	elif ! $CC $CFLAGS -c "$src" -o "$obj" >"$log" 2>&1; then
		got=compiler
	elif ! sh "$here/check-objects.sh" "$NM" "$ALLOW" "$obj" >"$log" 2>&1; then
		got=objects
	else
		got=pass
	fi
	why=$(grep -m1 -e 'error' -e '^check-' "$log" || true)
	if [ "$got" = "$expect" ]; then
		echo "check-selftest: $(basename "$src"): $got, as expected${why:+ ($why)}"
	else
		echo "check-selftest: $(basename "$src"): expected $expect, got $got; log:" >&2
		sed 's/^/  /' "$log" >&2
		status=1
	fi
done
exit $status
