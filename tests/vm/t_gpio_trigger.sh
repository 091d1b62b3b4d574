#!/bin/sh
# The camera trigger seen from outside: strand plays /scenes/gpio_rig.yaml
# on a gpio-sim chip while gpiomon watches the trigger line through the
# test wire (output 0 -> input 8). Every rising edge is a frame of the
# journal, in order, no earlier than its tick was due and no later than the
# loop's own reading of the clock after the commit; every pulse is the
# scene's 8 ms wide; no edge is later than the bound below (edges.awk).
# vm-timeout: 120
. /tests/lib.sh

# The bound on an edge's lateness and a pulse's width error under qemu's
# software emulation (TCG), where the guest's CPU is a host thread that the
# host preempts: measured medians of 0.3 ms, worst cases of 5.6 ms in 76
# frames (README "GPIO"); a board does far better. A tick is 4 ms.
MAX_LATE_US=$(vm_arg max_late_us)
MAX_LATE_US=${MAX_LATE_US:-10000}
# make bench-gpio: the scene ten times over (760 frames, 30 s)
PASSES=$(vm_arg bench_passes)

gpio_rig_chip
bg gpiomon -b -F '%e %s %n' "$SIM_CHIP" 8 >/tmp/edges
wait_for 5 line_held 8 gpiomon || fail "gpiomon never holds the wire (line 8)"

strand play /scenes/gpio_rig.yaml ${PASSES:+--loop --passes $PASSES} --journal /tmp/journal \
	--quiet >/tmp/play.out 2>&1
rc=$?
cat /tmp/play.out
[ $rc = 0 ] || fail "strand play exited $rc: $(tail -n 1 /tmp/play.out)"
strand journal /tmp/journal >/tmp/journal.csv || fail "strand journal failed"
frames=$(($(wc -l </tmp/journal.csv) - 1))
# the last pulse falls 8 ms after the last frame: wait for gpiomon to see it
wait_for 5 edges_at_least /tmp/edges 0 "$frames" ||
	note "only $(edge_count /tmp/edges 0) falling edges for $frames frames"
awk -f /tests/edges.awk -v width_ns=8000000 -v max_late_us="$MAX_LATE_US" \
	/tmp/journal.csv /tmp/edges >/tmp/cmp.out
rc=$?
cat /tmp/cmp.out
if [ $rc != 0 ]; then
	echo "journal (frame,tick,due_ns,mono_ns) and edges (event s ns):"
	cut -d, -f1,3,6,7 /tmp/journal.csv | head -n 6
	head -n 10 /tmp/edges
fi
[ $rc = 0 ] || fail "$(grep '^edges:' /tmp/cmp.out | tail -n 1)"
pass "$frames frames, $frames pulses seen by gpiomon, in order and on time:" \
	"edge late p99 $(sed -n 's/^BENCH gpio_edge_late_p99 //p' /tmp/cmp.out)," \
	"max $(sed -n 's/^BENCH gpio_edge_late_max //p' /tmp/cmp.out) (bound $MAX_LATE_US us)"
