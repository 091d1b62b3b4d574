#!/bin/sh
# The e-stop: while strand plays, the chain opens for 20 ms (gpio-sim's pull
# on the active-low e-stop line) and closes again. strand stops at the
# first tick after the edge, stays stopped (exit 6: a momentary opening is
# latched), and no trigger pulse follows; the journal ends before the stop.
# vm-timeout: 60
. /tests/lib.sh

PERIOD_US=4000                      # gpio_rig.yaml: 250 ticks a second
MAX_LATE_US=$(max_late_us)

attempt() {
	gpio_rig_chip
	bg gpiomon -b -F '%e %s %n' "$SIM_CHIP" 8 >/tmp/edges
	wait_for 5 line_held 8 gpiomon || fail "gpiomon never holds the wire (line 8)"

	strand play /scenes/gpio_rig.yaml --journal /tmp/journal --quiet >/tmp/play.out 2>&1 &
	play=$!
	# ten pulses (twenty edges), then the chain opens for 20 ms
	wait_for 20 lines_at_least 20 /tmp/edges || fail "no 10 frames before the e-stop"
	sim_pull 2 down
	sleep 0.02
	sim_pull 2 up
	wait "$play"
	rc=$?
	cat /tmp/play.out
	[ $rc = 6 ] || fail "strand play exited $rc, want 6 (e-stop)"
	stop=$(grep "e-stop: input 'estop'" /tmp/play.out | head -n 1)
	[ -n "$stop" ] || fail "no e-stop line from strand play"
	# "... acted on N us after the edge": the first tick after it
	us=$(echo "$stop" | sed -n 's/.*acted on \([0-9.]*\) us after the edge.*/\1/p')
	[ -n "$us" ] || fail "the e-stop line does not say when it was acted on: $stop"
	awk -v us="$us" -v b=$((PERIOD_US + MAX_LATE_US)) 'BEGIN { exit !(us >= 0 && us <= b) }' ||
		fail "acted on $us us after the edge: more than a tick ($PERIOD_US us) + $MAX_LATE_US us"

	# Nothing fired after the stop: the scene's 76 frames were not all
	# played, the journal ends before the stop, and the wire saw a whole
	# pulse for each frame of the journal and no more.
	strand journal /tmp/journal >/tmp/journal.csv || fail "strand journal failed"
	frames=$(($(wc -l </tmp/journal.csv) - 1))
	[ "$frames" -lt 76 ] || fail "all $frames frames fired despite the e-stop"
	stop_tick=$(echo "$stop" | sed -n 's/.* at tick \([0-9]*\).*/\1/p')
	last_tick=$(tail -n 1 /tmp/journal.csv | cut -d, -f3)
	[ -n "$stop_tick" ] && [ "$last_tick" -le "$stop_tick" ] ||
		fail "the journal's last frame (tick $last_tick) is after the stop (tick $stop_tick)"
	[ "$(sim_value 0)" = 0 ] || fail "the trigger line is left asserted"
	wait_for 2 lines_at_least $((2 * frames)) /tmp/edges
	sleep 0.2
	edges=$(wc -l </tmp/edges)
	if [ "$edges" != $((2 * frames)) ]; then
		cut -d, -f1,3,5,6,7 /tmp/journal.csv | tail -n 4
		tail -n 6 /tmp/edges
		WHY="$edges edges on the wire, $frames frames in the journal"
		return 1
	fi
}

twice attempt || fail "$WHY"
pass "stopped $us us after the chain opened (tick $stop_tick), latched (exit 6)," \
	"$frames frames fired and journaled, none after"
