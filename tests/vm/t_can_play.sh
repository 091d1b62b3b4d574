#!/bin/sh
# strand drives three CiA 402 drives on vcan0, each a strand-simdrive
# process, while candump records the bus as an independent observer; the
# record is checked against the run's journal and the scene's export
# (can.awk): the NMT/SDO/402 start-up of every node, one SYNC per tick with
# its period and jitter, every RPDO target equal to the exported setpoint of
# its tick, the drives left pre-operational.
# vm-timeout: 120
. /tests/lib.sh
. /tests/can.sh

MAX_LATE_US=$(max_late_us)
# make bench-canopen: the scene five times over (20 s)
PASSES=$(vm_arg bench_passes)

can_up 1 2 3

strand check /scenes/can_rig.yaml || fail "strand check refuses the scene"
strand play /scenes/can_rig.yaml ${PASSES:+--loop --passes $PASSES} --journal /tmp/journal \
	>/tmp/play.out 2>&1
rc=$?
cat /tmp/play.out
[ $rc = 0 ] || fail "strand play exited $rc: $(grep 'strand play:' /tmp/play.out)"
ticks=$(sed -n 's/.*frames fired [0-9]*, ticks \([0-9]*\).*/\1/p' /tmp/play.out)
# strand's count of the SYNCs of its start-up and of its run (the summary)
n='\([0-9]*\)'
startup=$(sed -n "s/.*canopen 'bus': [0-9]* SYNCs: $n of the start-up, $n of the run.*/\1 \2/p" \
	/tmp/play.out)
[ "${startup#* }" = "$ticks" ] ||
	fail "strand counts SYNCs (start-up, run) '$startup', for $ticks ticks"
startup=${startup% *}
# A gap between SYNCs may be as long as the loop was late (the emulated CPU
# stalls now and then: strand's summary says by how much) plus what
# candump's timestamps can be off by in this VM (25 ms seen): never more.
late=$(sed -n 's/.*latest tick start \([0-9]*\).*/\1/p' /tmp/play.out)
bound=$(( ${late:-0} + 25000 ))
[ "$bound" -gt "$MAX_LATE_US" ] || bound=$MAX_LATE_US
strand journal /tmp/journal >/tmp/journal.csv || fail "strand journal"
strand export /scenes/can_rig.yaml --at ticks >/tmp/export.csv || fail "strand export"

# the drives say what they saw; the bus goes quiet
for p in $BG_PIDS; do kill "$p" 2>/dev/null; done
sleep 0.2
cat /tmp/drive1.out /tmp/drive2.out /tmp/drive3.out
echo "bus: $(wc -l </tmp/bus.log) frames recorded"

awk -f /tests/can.awk -v nodes="1 2 3" -v cols="pan.angle tilt.angle spin.rpm" \
	-v cpu="1000 1000 100" -v hz=250 -v fps=25 -v ticks="$ticks" -v startup="$startup" \
	-v max_late_us="$bound" \
	-v synclog=/tmp/sync1.log \
	/tmp/journal.csv /tmp/export.csv /tmp/bus.log >/tmp/can.out
rc=$?
cat /tmp/can.out
if [ $rc != 0 ]; then
	head -n 40 /tmp/bus.log
	fail "$(grep '^can: FAIL' /tmp/can.out)"
fi
pass "$ticks ticks: start-up, one SYNC per tick (jitter p99 as a drive received them" \
	"$(sed -n 's/^BENCH can_sync_drive_jitter_p99_us //p' /tmp/can.out) us), every target" \
	"equal to export's"
