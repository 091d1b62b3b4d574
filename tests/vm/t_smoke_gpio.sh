#!/bin/sh
# The harness's GPIO side works: a gpio-sim chip made through configfs, lines
# found by name, an output read back through sysfs, an input driven through
# the pull attribute and seen by gpioget and by gpiomon as edge events with
# kernel timestamps, and EBUSY on a second request for a held line.
# vm-timeout: 30
. /tests/lib.sh

sim_chip smoke 8 2=smoke-in 5=smoke-out
gpiodetect | grep -q "^$SIM_CHIP \[$SIM_DEV" || fail "gpiodetect does not list $SIM_CHIP [$SIM_DEV]"
[ "$(gpiofind smoke-out)" = "$SIM_CHIP 5" ] || fail "gpiofind smoke-out: '$(gpiofind smoke-out)', want '$SIM_CHIP 5'"
gpiofind no-such-line >/dev/null 2>&1 && fail "gpiofind finds a line that is not there"

# Output: what gpioset drives is what the chip sees, while it holds the line.
[ "$(sim_value 5)" = 0 ] || fail "line 5 starts at $(sim_value 5), want 0"
bg gpioset --mode=signal "$SIM_CHIP" 5=1
hold=$!
wait_for 5 sim_value_is 5 1 || fail "gpioset 5=1: the chip sees $(sim_value 5)"

# A second request for the held line is refused with EBUSY.
if err=$(gpioget "$SIM_CHIP" 5 2>&1); then
	fail "gpioget on a line gpioset holds succeeded: $err"
fi
echo "$err" | grep -q "Device or resource busy" || fail "second request: '$err', want EBUSY"
kill "$hold"
wait "$hold" 2>/dev/null

# Input: the pull attribute is the outside world driving the line.
sim_pull 2 up
[ "$(gpioget "$SIM_CHIP" 2)" = 1 ] || fail "pull up: gpioget reads $(gpioget "$SIM_CHIP" 2)"
sim_pull 2 down
[ "$(gpioget "$SIM_CHIP" 2)" = 0 ] || fail "pull down: gpioget reads $(gpioget "$SIM_CHIP" 2)"

# Edge events: gpiomon holds the line (gpioinfo says so) before the edges.
bg gpiomon -b -n 2 -F '%e %o %s.%n' "$SIM_CHIP" 2 >/tmp/mon.out
mon=$!
wait_for 5 sh -c "gpioinfo $SIM_CHIP | grep -q '\"gpiomon\"'" || fail "gpiomon never holds line 2"
sim_pull 2 up
sim_pull 2 down
wait_for 5 lines_are 2 /tmp/mon.out || fail "gpiomon saw $(wc -l </tmp/mon.out) edges, want 2"
wait "$mon"
note "$(tr '\n' ' ' </tmp/mon.out)"
awk 'NR == 1 && !($1 == 1 && $2 == 2) { exit 1 }
     NR == 2 && !($1 == 0 && $2 == 2) { exit 1 }
     NR == 2 && !($3 > t) { exit 1 }
     { t = $3 }' /tmp/mon.out || fail "edges: $(tr '\n' ' ' </tmp/mon.out), want rising then falling on 2"

sim_chip_remove smoke

# The test wire of the patched gpio-sim (loopback=0,8,...): what an output
# drives on line 0, an input on line 8 sees, edges and all.
sim_chip wire 16
bg gpiomon -b -n 2 -F '%e %o %s.%n' "$SIM_CHIP" 8 >/tmp/wire.out
mon=$!
wait_for 5 sh -c "gpioinfo $SIM_CHIP | grep -q '\"gpiomon\"'" || fail "gpiomon never holds line 8"
gpioset --mode=time --usec=20000 "$SIM_CHIP" 0=1 || fail "gpioset 0=1"
gpioset "$SIM_CHIP" 0=0 || fail "gpioset 0=0"
wait_for 5 lines_are 2 /tmp/wire.out || fail "line 8 saw $(wc -l </tmp/wire.out) edges of line 0, want 2"
wait "$mon"
note "wire: $(tr '\n' ' ' </tmp/wire.out)"
awk 'NR == 1 && !($1 == 1 && $2 == 8) { exit 1 }
     NR == 2 && !($1 == 0 && $2 == 8) { exit 1 }
     NR == 2 && !($3 - t > 0.015) { exit 1 }
     { t = $3 }' /tmp/wire.out || fail "wire: $(tr '\n' ' ' </tmp/wire.out), want a 20 ms pulse on 8"
sim_chip_remove wire
pass "$SIM_CHIP: set/get/find, 2 edges in order, EBUSY on a held line, the 0->8 test wire"
