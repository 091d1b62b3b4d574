#!/bin/sh
# unit.sh NPAR PROGRAM... -- PROGRAM... - `make unit`: the test programs
# before "--" NPAR at a time (the motion core's: all their time is CPU),
# then the rest one after the other (they run threads on the wall clock,
# servers, a loop at real-time priority: two at once on a small machine
# would time each other out). One line each (mk/unit-one.sh); exit 1 when
# any failed.
set -u
npar=$1
shift
par=""
while [ $# -gt 0 ] && [ "$1" != -- ]; do
	par="$par $1"
	shift
done
[ $# -gt 0 ] && shift
fail=0
if [ -n "$par" ]; then
	# shellcheck disable=SC2086 # the programs are words
	printf '%s\n' $par | xargs -P "$npar" -n 1 sh mk/unit-one.sh || fail=1
fi
for t in "$@"; do
	sh mk/unit-one.sh "$t" || fail=1
done
exit $fail
