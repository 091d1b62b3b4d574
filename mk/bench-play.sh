#!/bin/sh
# bench-play.sh STRAND SCENE OUTDIR [SLEEP_TICK] - the loop's wake-up latency
# on the wall clock against cyclictest's, same period (1 ms), same priority,
# same length, one after the other in this run; then the CPU time per tick
# of the scene on the simulated rig, and (SLEEP_TICK, bench/sleep_tick.c)
# of a thread that only sleeps to the same ticks. Prints BENCH lines.
#
# BENCH_PLAY_STRESS=N loads the machine with N stress-ng CPU workers for
# the whole run (Debian's stress-ng), the loaded half of a comparison.
set -eu
[ $# -eq 3 ] || [ $# -eq 4 ] || {
	echo "usage: bench-play.sh STRAND SCENE OUTDIR [SLEEP_TICK]" >&2
	exit 2
}
play=$1
scene=$2
out=$3
sleeper=${4:-}
secs=${BENCH_PLAY_SECONDS:-30}
prio=${BENCH_PLAY_PRIORITY:-80}
stress=${BENCH_PLAY_STRESS:-0}
mkdir -p "$out"
stress_pid=
trap '[ -z "$stress_pid" ] || kill "$stress_pid" 2>/dev/null || true' EXIT
if [ "$stress" -gt 0 ]; then
	command -v stress-ng >/dev/null || {
		echo "bench-play: BENCH_PLAY_STRESS needs stress-ng (Debian's stress-ng)" >&2
		exit 1
	}
	stress-ng --cpu "$stress" --quiet --timeout $((2 * secs + 60)) >"$out/stress.log" 2>&1 &
	stress_pid=$!
	sleep 1
	kill -0 "$stress_pid" 2>/dev/null || {
		echo "bench-play: stress-ng did not start:" >&2
		cat "$out/stress.log" >&2
		exit 1
	}
	echo "bench-play: stress-ng --cpu $stress loading the machine meanwhile"
fi

# percentiles from "us count" histogram lines, truncated microseconds
pct() {
	awk -v q="$2" '
		/^[0-9]+[ \t]+[0-9]+/ { c[$1 + 0] += $2; n += $2; if ($1 + 0 > top) top = $1 + 0 }
		END {
			want = q * n; if (want < 1) want = 1
			for (i = 0; i <= top; i++) { s += c[i]; if (s >= want - 1e-9) { print i; exit } }
		}' "$1"
}

# The two take turns, in rounds of $chunk s each (1 by default), so that what the host
# and the other processes do meanwhile falls on both alike: on a shared machine 3 s rounds
# let a burst of load land on one side often enough to move a pooled p99 by 40%.
chunk=${BENCH_PLAY_CHUNK:-1}
rounds=$(((secs + chunk - 1) / chunk))
: >"$out/strand.hist"
: >"$out/cyclictest.hist"
: >"$out/rounds.p0.5"
: >"$out/rounds.p0.99"
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
	# this round's percentiles of both, for the ratios of neighbours below
	for q in 0.5 0.99; do
		echo "$(pct "$out/strand.round" "$q") $(pct "$out/cyclictest.round" "$q")" \
			>>"$out/rounds.p$q"
	done
	r=$((r + 1))
done
policy=SCHED_FIFO
if grep -q "real-time priority" "$out/strand.err" || [ "$prio" -eq 0 ]; then
	policy=SCHED_OTHER
fi
echo "bench-play: $((rounds * chunk)) s at 1 kHz each in $rounds alternating rounds, priority $prio ($policy); strand: $scene on the simulated rig"

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
# The median over the rounds of each round's ratio: neighbours share the
# machine's state of the moment (other processes, the host), so their ratio
# is steadier than the ratio of the pooled percentiles when the load moves.
for q in 0.5 0.99; do
	name=$(echo "$q" | awk '{ printf "p%g", $1 * 100 }')
	m=$(awk '$2 > 0 { print $1 / $2 }' "$out/rounds.p$q" | sort -g | awk '
		{ v[NR] = $1 }
		END {
			if (!NR) print "inf"
			else if (NR % 2) printf "%.3f", v[(NR + 1) / 2]
			else printf "%.3f", (v[NR / 2] + v[NR / 2 + 1]) / 2
		}')
	echo "BENCH play_vs_cyclictest_${name}_median_of_rounds $m x"
	# and its 95% confidence interval without assuming a distribution: the
	# order statistics k and n + 1 - k of the sorted ratios, k = n/2 -
	# 1.96 sqrt(n)/2 (the sign test's; rounds 22 and 39 of 60). A claim
	# that strand's p99 is within 1.1x of cyclictest's holds when the
	# interval's top is at or under 1.1, and is refuted when its bottom is
	# above it; between the two, the run did not tell.
	ci=$(awk '$2 > 0 { print $1 / $2 }' "$out/rounds.p$q" | sort -g | awk '
		{ v[NR] = $1 }
		END {
			k = int(NR / 2 - 1.96 * sqrt(NR) / 2)
			if (k < 1) print "inf inf"
			else printf "%.3f %.3f", v[k], v[NR + 1 - k]
		}')
	echo "BENCH play_vs_cyclictest_${name}_median_of_rounds_ci95 $ci x"
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
# the same 5000 ticks of nothing but the sleep and the wake-up: the kernel's
# share of the line above
if [ -n "$sleeper" ]; then
	"$sleeper" 5000 "$prio" >"$out/sleep.txt"
	grep '^BENCH' "$out/sleep.txt"
	awk '/^BENCH sleep_cpu/ { s = $3 } END { print s }' "$out/sleep.txt" >"$out/sleep.ns"
	awk '/cpu .* ns per tick/ { print $2 }' "$out/cpu-wall.txt" | awk -v s="$(cat "$out/sleep.ns")" \
		'{ printf "BENCH play_cpu_per_tick_wall_over_sleep %d ns\n", $1 - s }'
fi
