#!/bin/sh
# The camera trigger seen from outside: strand plays /scenes/gpio_rig.yaml
# on a gpio-sim chip while gpiomon watches the trigger line through the
# test wire (output 0 -> input 8). Every rising edge is a frame of the
# journal, in order, no earlier than its tick was due and no later than the
# loop's own reading of the clock after the commit; every pulse is the
# scene's 8 ms wide; no edge is later than the bound below (edges.awk).
# vm-timeout: 60
. /tests/lib.sh

# The bound on an edge's lateness and a pulse's width error under qemu's
# software emulation (TCG): a tick is 4 ms; a board does far better
# (README "GPIO").
MAX_LATE_US=${MAX_LATE_US:-2000}

gpio_rig_chip
bg gpiomon -b -F '%e %s %n' "$SIM_CHIP" 8 >/tmp/edges
wait_for 5 line_held 8 gpiomon || fail "gpiomon never holds the wire (line 8)"

strand play /scenes/gpio_rig.yaml --journal /tmp/journal --quiet >/tmp/play.out 2>&1
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
[ $rc = 0 ] || fail "$(grep '^edges:' /tmp/cmp.out | tail -n 1)"
pass "$frames frames, $frames pulses seen by gpiomon, in order and on time:" \
	"edge late p99 $(sed -n 's/^BENCH gpio_edge_late_p99 //p' /tmp/cmp.out)," \
	"max $(sed -n 's/^BENCH gpio_edge_late_max //p' /tmp/cmp.out) (bound $MAX_LATE_US us)"
