#!/bin/sh
# An emergency injected into a drive mid-run (SIGUSR1: over-current, error
# code 0x2310): candump sees the EMCY frame with that code, strand stops
# with a device fault naming node 3, the code and its CiA 301 class, and
# the quick stop goes out after it.
# vm-timeout: 90
. /tests/lib.sh
. /tests/can.sh

can_up 1 2 3

bg strand play /scenes/can_rig.yaml --journal /tmp/journal >/tmp/play.out 2>&1
play=$!
wait_playing 300 "$play" /tmp/play.out
kill -USR1 "$DRIVE_3"
wait "$play"
rc=$?
cat /tmp/play.out
[ $rc = 7 ] || fail "strand play exited $rc, want 7 (device fault)"
msg=$(grep 'strand play: device fault' /tmp/play.out)
echo "$msg" | grep -q "channel 3 (spin.rpm): emergency 0x2310 (current, device output side)" ||
	fail "no emergency 0x2310 of node 3 in: $msg"
for p in $DRIVE_1 $DRIVE_2; do kill "$p"; done
sleep 0.2

# the EMCY on the bus: 0x83, code 0x2310 little-endian, error register
# generic + current (0x03); then the quick stop for node 1
awk '$3 == "083" && $4 == "[8]" && $5 == "10" && $6 == "23" && $7 == "03" { e = NR }
     e && $3 == "201" && $5 == "02" && $6 == "00" { q = NR; exit }
     END { if (!e) { print "emcy: no EMCY 0x2310 from node 3"; exit 1 }
	   if (!q) { print "emcy: no quick stop after it"; exit 1 }
	   print "emcy: EMCY 0x2310 (register 0x03) on the bus, then the quick stop" }' \
	/tmp/bus.log >/tmp/emcy.out
rc=$?
cat /tmp/emcy.out
[ $rc = 0 ] || fail "$(tail -n 1 /tmp/emcy.out)"
pass "node 3's emergency 0x2310 on the bus and in strand's fault: $msg"
