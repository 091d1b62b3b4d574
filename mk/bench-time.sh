#!/bin/sh
# bench-time.sh ROUNDS REPS SCENES -- SCENE_COUNT... - the core against its double twin by the
# clock, one or more builds side by side: each round runs every build in turn, each from a fresh
# copy of its bench/scene_count, the core's side and then the twin's (the fastest of REPS plays
# each, `scene_count SCENE fixed|double REPS`), and at the end prints per build and scene the
# medians over the rounds of both sides and of their ratio (TIME lines).
#
# Why fresh copies: on this project's VM one copy of a program ran 5% slower than a byte-identical
# copy, run after run, interleaved with it, in two sets (a later set of six copies had no such
# copy); presumably where its pages sit in memory. A fresh copy each round spreads that luck over
# the rounds. The ratio is taken within one copy (both sides share it), the median across copies.
#
#   sh mk/bench-time.sh 9 40 "joints1000 random1000" -- build/bench/scene_count /tmp/old/scene_count
set -eu
[ $# -ge 5 ] && [ "$4" = "--" ] || {
	echo "usage: bench-time.sh ROUNDS REPS SCENES -- SCENE_COUNT..." >&2
	exit 2
}
rounds=$1 reps=$2 scenes=$3
shift 4
prefix=${BENCH_PREFIX:-}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
r=0
while [ "$r" -lt "$rounds" ]; do
	i=0
	for b in "$@"; do
		i=$((i + 1))
		cp "$b" "$out/run"
		for s in $scenes; do
			f=$($prefix "$out/run" "$s" fixed "$reps" | awk '/^TIME/ { print $4 }')
			d=$($prefix "$out/run" "$s" double "$reps" | awk '/^TIME/ { print $4 }')
			[ -n "$f" ] && [ -n "$d" ] || { echo "bench-time: $b $s failed" >&2; exit 1; }
			echo "$f $d" >>"$out/b$i.$s"
		done
		rm -f "$out/run"
	done
	r=$((r + 1))
done
med() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
i=0
for b in "$@"; do
	i=$((i + 1))
	for s in $scenes; do
		fm=$(awk '{ print $1 }' "$out/b$i.$s" | med)
		dm=$(awk '{ print $2 }' "$out/b$i.$s" | med)
		rm_=$(awk '{ printf "%.4f\n", $1 / $2 }' "$out/b$i.$s" | med)
		lo=$(awk '{ printf "%.3f\n", $1 / $2 }' "$out/b$i.$s" | sort -g | head -n 1)
		hi=$(awk '{ printf "%.3f\n", $1 / $2 }' "$out/b$i.$s" | sort -g | tail -n 1)
		echo "TIME build$i ${s} fixed $fm double $dm ns/node/tick ratio $rm_ (runs $lo to $hi, $rounds rounds) $b"
	done
done
