#!/bin/sh
# unit-one.sh PROGRAM - run one test program into PROGRAM.log and say one
# line: PASS with its BOUND lines' count and its time, or FAIL with its
# log's tail (exit 1).
t=$1
t0=$(date +%s%N)
if ! "$t" >"$t.log" 2>&1; then
	echo "FAIL $t (log: $t.log)"
	tail -n 30 "$t.log"
	exit 1
fi
echo "PASS $(basename "$t")  $(grep -h '^BOUND' "$t.log" | wc -l) bounds checked," \
	"$(( ($(date +%s%N) - t0) / 1000000 )) ms"
