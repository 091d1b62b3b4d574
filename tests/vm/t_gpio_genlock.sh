#!/bin/sh
# Genlock for real: one strand plays /scenes/genlock_gen.yaml and its camera
# trigger (25 pulses a second, 20 ms wide) is the sync generator; through the
# test wire (output 0 -> input 8) another strand chases it with
# --chase gpio:CHIP:8 (the kernel's edge timestamps) on a simulated rig,
# frames 0 to 50. Each frame the chaser fired must be due on a pulse of
# the generator (the generator's journal: the clock right after its edge
# went out): the median within 2 ms, every one within a tick plus the
# emulation's bound (max_late_us); the chaser locked, cued once and
# finished (exit 0). Under TCG a host busy with other work can stall the
# emulated CPU for tens of ms, both strands with it (a CI run saw 111
# overruns of the chaser's 710 ticks and the generator's rate 3,574 ppm
# off): a failed attempt is said and run once more (lib.sh's twice); two in
# a row fail.
# vm-timeout: 60
. /tests/lib.sh

MAX_LATE_US=$(max_late_us)

attempt() {
	gpio_rig_chip
	bg strand play /scenes/genlock_gen.yaml --journal /tmp/gen.journal --quiet
	gen=$!
	wait_for 5 line_held 0 strand || fail "the generator never holds its trigger line"
	strand play /scenes/gpio_rig.yaml --sim --chase "gpio:$SIM_CHIP:8" --to 50 \
		--journal /tmp/chase.journal >/tmp/chase.out 2>&1
	rc=$?
	cat /tmp/chase.out
	# the generator stops (a controlled stop, then its journal closed)
	# before its journal is read
	kill "$gen"
	wait "$gen"
	cleanup
	overruns=$(grep -o 'overruns [0-9]*' /tmp/chase.out)
	if [ $rc != 0 ]; then
		WHY="the chaser exited $rc: $(tail -n 1 /tmp/chase.out)"
		return 1
	fi
	strand journal /tmp/gen.journal >/tmp/gen.csv || fail "strand journal (generator) failed"
	strand journal /tmp/chase.journal >/tmp/chase.csv || fail "strand journal (chaser) failed"
	# due_ns of the chaser (column 7: it has source_tc) against the nearest
	# mono_ns of the generator (column 7 too: it has not)
	awk -F, -v bound="$MAX_LATE_US" '
		NR == FNR { if (FNR > 1 && $5 == "fired") g[ng++] = $7; next }
		FNR > 1 && $6 == "fired" {
			best = -1
			for (i = 0; i < ng; i++) { d = $7 - g[i]; if (d < 0) d = -d; if (best < 0 || d < best) best = d }
			e[n++] = best / 1000
		}
		END {
			if (n < 40) { print "genlock: only " n " frames"; exit 1 }
			for (i = 0; i < n; i++) for (j = i + 1; j < n; j++) if (e[j] < e[i]) { t = e[i]; e[i] = e[j]; e[j] = t }
			p50 = e[int(n / 2)]; p99 = e[int(n * 0.99)]; mx = e[n - 1]
			printf "BENCH genlock_phase_p50_us %.1f\nBENCH genlock_phase_p99_us %.1f\nBENCH genlock_phase_max_us %.1f\n", p50, p99, mx
			printf "genlock: %d frames, |due - pulse| p50 %.1f us, p99 %.1f us, max %.1f us\n", n, p50, p99, mx
			if (p50 > 2000 || mx > bound + 4000) exit 1
		}' /tmp/gen.csv /tmp/chase.csv >/tmp/cmp.out
	rc=$?
	cat /tmp/cmp.out
	if [ $rc != 0 ]; then
		WHY="$(tail -n 1 /tmp/cmp.out) (chaser's $overruns)"
		return 1
	fi
	grep -q "cued 1 time" /tmp/chase.out || {
		WHY="the chaser did not cue once: $(grep chase /tmp/chase.out | tr '\n' ' ')"
		return 1
	}
}

twice attempt || fail "$WHY"
pass "$(tail -n 1 /tmp/cmp.out); $(grep -o 'locked [^,]*' /tmp/chase.out)"
