#!/bin/sh
# bench-count.sh SCENE_COUNT SCENE... - instructions per node per tick of
# each scene, the core's and the double twin's, counted by callgrind
# (bench/scene_count.c: only scene_count_play() is counted, the ticks
# bench/scene_bench.c times), and their ratio. Prints COUNT lines.
set -eu
[ $# -ge 2 ] || { echo "usage: bench-count.sh SCENE_COUNT SCENE..." >&2; exit 2; }
prog=$1
shift
for s in "$@"; do
	for side in fixed double; do
		out=$(valgrind --tool=callgrind --callgrind-out-file=/dev/null \
			--toggle-collect=scene_count_play "$prog" "$s" "$side" 2>&1) || {
			echo "bench-count: $s $side failed:" >&2
			echo "$out" | tail -n 5 >&2
			exit 1
		}
		units=$(echo "$out" | awk '/^COUNT/ { print $5 }')
		ir=$(echo "$out" | awk '/Collected :/ { print $4 }')
		echo "$ir $units" | awk '{ printf "%.0f\n", $1 / $2 }' >"${TMPDIR:-/tmp}/count.$$.$side"
		echo "COUNT ${s}_$side $(cat "${TMPDIR:-/tmp}/count.$$.$side") instructions/node/tick"
	done
	awk -v s="$s" 'NR == FNR { f = $1; next }
		{ printf "COUNT %s_ratio_fixed_over_double %.3f x\n", s, f / $1 }' \
		"${TMPDIR:-/tmp}/count.$$.fixed" "${TMPDIR:-/tmp}/count.$$.double"
	rm -f "${TMPDIR:-/tmp}/count.$$.fixed" "${TMPDIR:-/tmp}/count.$$.double"
done
