#!/bin/sh
# The camera trigger seen from outside: strand plays /scenes/gpio_rig.yaml
# on a gpio-sim chip while gpiomon watches the trigger line through the
# test wire (output 0 -> input 8). Every rising edge is a frame of the
# journal, in order, no earlier than its tick was due and no later than the
# loop's own reading of the clock after the commit; every pulse is the
# scene's 20 ms wide, never narrower; no edge is later than max_late_us
# (lib.sh) after its tick was due (edges.awk). The
# rig-ready line is up for the whole run, pulses included.
# vm-timeout: 120
. /tests/lib.sh

MAX_LATE_US=$(max_late_us)
# make bench-gpio: the scene ten times over (760 frames, 30 s)
PASSES=$(vm_arg bench_passes)

attempt() {
	gpio_rig_chip
	bg gpiomon -b -F '%e %s %n' "$SIM_CHIP" 8 >/tmp/edges
	wait_for 5 line_held 8 gpiomon || fail "gpiomon never holds the wire (line 8)"
	bg gpiomon -b -F '%e %s %n' "$SIM_CHIP" 9 >/tmp/ready
	wait_for 5 line_held 9 gpiomon || fail "gpiomon never holds the rig-ready wire (line 9)"

	strand play /scenes/gpio_rig.yaml ${PASSES:+--loop --passes $PASSES} \
		--journal /tmp/journal --quiet >/tmp/play.out 2>&1
	rc=$?
	cat /tmp/play.out
	[ $rc = 0 ] || fail "strand play exited $rc: $(tail -n 1 /tmp/play.out)"
	strand journal /tmp/journal >/tmp/journal.csv || fail "strand journal failed"
	frames=$(($(wc -l </tmp/journal.csv) - 1))
	# the last pulse falls 20 ms after the last frame: wait for gpiomon
	wait_for 5 lines_are $((2 * frames)) /tmp/edges ||
		note "$(wc -l </tmp/edges) edges for $frames frames"
	awk -f /tests/edges.awk -v width_ns=20000000 -v max_late_us="$MAX_LATE_US" \
		/tmp/journal.csv /tmp/edges >/tmp/cmp.out
	rc=$?
	cat /tmp/cmp.out
	if [ $rc != 0 ]; then
		echo "journal (frame,tick,due_ns,mono_ns) and edges (event s ns):"
		cut -d, -f1,3,6,7 /tmp/journal.csv | head -n 6
		head -n 10 /tmp/edges
		WHY=$(grep '^edges:' /tmp/cmp.out | tail -n 1)
		return 1
	fi

	# The rig-ready line (1, wired to 9): up before the first pulse, down
	# after the last one, once.
	wait_for 5 lines_are 2 /tmp/ready || note "rig-ready: $(wc -l </tmp/ready) edges"
	cat /tmp/ready
	awk 'NR == FNR { t = $2 * 1e9 + $3; if (first == "") first = t; last = t; next }
	     FNR == 1 && !($2 * 1e9 + $3 < first) { exit 1 }
	     FNR == 2 && !($2 * 1e9 + $3 > last) { exit 1 }
	     END { if (FNR != 2) exit 1 }' /tmp/edges /tmp/ready || {
		WHY="rig-ready: $(tr '\n' ' ' </tmp/ready), want up before the first pulse and down after the last"
		return 1
	}
}

twice attempt || fail "$WHY"
pass "$frames frames, $frames pulses seen by gpiomon, in order and on time:" \
	"edge late p99 $(sed -n 's/^BENCH gpio_edge_late_p99 //p' /tmp/cmp.out)," \
	"max $(sed -n 's/^BENCH gpio_edge_late_max //p' /tmp/cmp.out) (bound $MAX_LATE_US us)"
