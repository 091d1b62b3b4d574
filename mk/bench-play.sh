#!/bin/sh
# bench-play.sh STRAND SCENE OUTDIR - the loop's wake-up latency on the
# wall clock against cyclictest's, same period (1 ms), same priority, same
# length, one after the other in this run; then the CPU time per tick of the
# scene on the simulated rig. Prints BENCH lines.
set -eu
[ $# -eq 3 ] || { echo "usage: bench-play.sh STRAND SCENE OUTDIR" >&2; exit 2; }
play=$1
scene=$2
out=$3
secs=${BENCH_PLAY_SECONDS:-30}
prio=${BENCH_PLAY_PRIORITY:-80}
mkdir -p "$out"

# The two take turns, in rounds of $chunk s each (3 by default), so that what the host
# does meanwhile (this is a virtual machine) falls on both alike.
chunk=${BENCH_PLAY_CHUNK:-3}
rounds=$(((secs + chunk - 1) / chunk))
: >"$out/strand.hist"
: >"$out/cyclictest.hist"
r=0
while [ $r -lt $rounds ]; do
	# strand: the scene played again and again at its 1 kHz tick
	"$play" play "$scene" --sim --loop --duration "$chunk" --no-journal --priority "$prio" \
		--latency-hist "$out/strand.round" --quiet 2>"$out/strand.err" || {
		echo "bench-play: strand play failed:" >&2
		cat "$out/strand.err" >&2
		exit 1
	}
	cat "$out/strand.round" >>"$out/strand.hist"
	# cyclictest: one thread, 1000 us interval, the same priority, memory
	# locked, clock_nanosleep to an absolute time (its default, like strand)
	cyclictest -m -t1 -p "$prio" -i 1000 -l $((chunk * 1000)) -h 10000 -q \
		>"$out/cyclictest.round" 2>"$out/cyclictest.err" || {
		echo "bench-play: cyclictest failed:" >&2
		cat "$out/cyclictest.err" >&2
		exit 1
	}
	cat "$out/cyclictest.round" >>"$out/cyclictest.hist"
	r=$((r + 1))
done
policy=SCHED_FIFO
if grep -q "real-time priority" "$out/strand.err" || [ "$prio" -eq 0 ]; then
	policy=SCHED_OTHER
fi
echo "bench-play: $((rounds * chunk)) s at 1 kHz each in $rounds alternating rounds, priority $prio ($policy); strand: $scene on the simulated rig"

# percentiles from "us count" histogram lines, truncated microseconds
pct() {
	awk -v q="$2" '
		/^[0-9]+[ \t]+[0-9]+/ { c[$1 + 0] += $2; n += $2; if ($1 + 0 > top) top = $1 + 0 }
		END {
			want = q * n; if (want < 1) want = 1
			for (i = 0; i <= top; i++) { s += c[i]; if (s >= want - 1e-9) { print i; exit } }
		}' "$1"
}
maxof() {
	awk '/Max Latencies:/ { for (i = 4; i <= NF; i++) if ($i + 0 > m) m = $i + 0 } END { print m + 0 }' "$1"
}
ratio() {
	awk -v a="$1" -v b="$2" 'BEGIN { if (b > 0) printf "%.3f", a / b; else print "inf" }'
}
for q in 0.5 0.99 0.999; do
	name=$(echo "$q" | awk '{ printf "p%g", $1 * 100 }')
	s=$(pct "$out/strand.hist" "$q")
	c=$(pct "$out/cyclictest.hist" "$q")
	echo "BENCH play_latency_$name $s us"
	echo "BENCH cyclictest_latency_$name $c us"
	echo "BENCH play_vs_cyclictest_$name $(ratio "$s" "$c") x"
done
s=$(maxof "$out/strand.hist")
c=$(maxof "$out/cyclictest.hist")
echo "BENCH play_latency_max $s us"
echo "BENCH cyclictest_latency_max $c us"
echo "BENCH play_vs_cyclictest_max $(ratio "$s" "$c") x"
grep -h "overruns" "$out/strand.err" /dev/null | sed 's/^/bench-play: /' || true

# CPU per tick: the same scene on the virtual clock (the loop's own work:
# evaluation, limits, the simulated drives and camera), and on the wall
# clock (with the sleep and wake-up system calls)
"$play" play "$scene" --sim --clock virtual --loop --passes 20 --no-journal >"$out/cpu.txt"
awk '/cpu .* ns per tick/ { print "BENCH play_cpu_per_tick_virtual " $2 " ns" }' "$out/cpu.txt"
"$play" play "$scene" --sim --loop --duration 5 --no-journal --priority "$prio" >"$out/cpu-wall.txt"
awk '/cpu .* ns per tick/ { print "BENCH play_cpu_per_tick_wall " $2 " ns" }' "$out/cpu-wall.txt"
