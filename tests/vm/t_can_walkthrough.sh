#!/bin/sh
# README's "Turn one CiA 402 servo", as written there: a virtual CAN bus,
# strand-simdrive as node 5, strand check and strand play of
# examples/canopen_turntable.yaml; the run finishes, the drive took a SYNC
# for every tick, and it is left switched off and pre-operational.
# vm-timeout: 90
. /tests/lib.sh

ip link add dev vcan0 type vcan || fail "ip link add"
ip link set up vcan0 || fail "ip link set up"
# the README's candump, with a receive buffer of 4 MB and its drop count
# (-d): a stalled emulated CPU can leave candump behind the bus (a run
# under load: 3830 of 4014 SYNCs seen with the default buffer); the
# observer must not lose what it counts
bg candump -ta -r 4000000 -d vcan0 >/tmp/bus.log
wait_for 5 grep -q '^ *vcan0 .* raw$' /proc/net/can/rcvlist_all || fail "candump never listens"
strand-simdrive --can vcan0 --node 5 >/tmp/drive.out 2>&1 &
drive=$!
wait_for 5 grep -q listening /tmp/drive.out || fail "strand-simdrive: $(cat /tmp/drive.out)"

strand check /examples/canopen_turntable.yaml || fail "strand check"
strand play /examples/canopen_turntable.yaml --journal /tmp/journal >/tmp/play.out 2>&1
rc=$?
cat /tmp/play.out
[ $rc = 0 ] || fail "strand play exited $rc"
kill "$drive"
wait "$drive"
cat /tmp/drive.out
echo "the start-up on the bus:"
head -n 48 /tmp/bus.log
echo "..."
start=$(grep -n ' 000 *\[2\]  01 05' /tmp/bus.log | cut -d: -f1)
sed -n "$((start - 4)),$((start + 14))p" /tmp/bus.log
echo "... and the end:"
tail -n 8 /tmp/bus.log
ticks=$(sed -n 's/.*frames fired [0-9]*, ticks \([0-9]*\).*/\1/p' /tmp/play.out)
syncs=$(sed -n 's/.*; \([0-9]*\) SYNCs,.*/\1/p' /tmp/drive.out)
grep -q "node 5: ready to switch on, NMT 0x7f" /tmp/drive.out ||
	fail "the drive is not left switched off and pre-operational: $(tail -n 1 /tmp/drive.out)"
# every SYNC on the bus reached the drive: the loop's, one per tick, and
# the start-up's cycles until the drive said it was enabled (as many as
# the drive took to answer: more on a loaded machine) and the stop's
grep DROPCOUNT /tmp/bus.log && fail "candump dropped frames: $(grep DROPCOUNT /tmp/bus.log | tail -n 1)"
onbus=$(grep -c ' 080  *\[0\]' /tmp/bus.log)
[ "$syncs" -ge "$ticks" ] && [ "$syncs" = "$onbus" ] ||
	fail "the drive took $syncs SYNCs of the $onbus on the bus, for $ticks ticks"
pass "193 frames, $ticks ticks, the drive took all $syncs SYNCs on the bus" \
	"($((syncs - ticks)) of the start-up and the stop) and was left off"
