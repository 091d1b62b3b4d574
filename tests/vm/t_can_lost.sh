#!/bin/sh
# A drive killed mid-run (kill -9: its process and its heartbeat gone):
# strand stops with a heartbeat fault naming its node, the two others get
# the quick stop (controlword 0x0002) and brake on their own ramps to switch
# on disabled, then pre-operational - all read from candump's record.
# vm-timeout: 90
. /tests/lib.sh
. /tests/can.sh

MAX_LATE_US=$(max_late_us)
can_up 1 2 3

bg strand play /scenes/can_rig.yaml --journal /tmp/journal >/tmp/play.out 2>&1
play=$!
# well into the run: 300 SYNCs (1.2 s)
wait_playing 300 "$play" /tmp/play.out
kill -9 "$DRIVE_2"
wait "$play"
rc=$?
cat /tmp/play.out
[ $rc = 7 ] || fail "strand play exited $rc, want 7 (device fault)"
grep -q "device fault: device 'bus' channel 2 (tilt.angle): heartbeat lost" /tmp/play.out ||
	fail "no heartbeat fault of node 2: $(grep 'strand play:' /tmp/play.out)"
for p in $DRIVE_1 $DRIVE_3; do kill "$p"; done
sleep 0.2
cat /tmp/drive1.out /tmp/drive3.out

# From the bus: node 2's last heartbeat; after it, within the heartbeat
# timeout (2.5 x 50 ms) and the VM's lateness, RPDOs with the quick stop and
# one SYNC to carry them; then the others' statuswords quick stop active,
# then switch on disabled; then NMT pre-operational for nodes 1 and 3.
awk -v max_late_us="$MAX_LATE_US" '
	function us(s, p) { gsub(/[()]/, "", s); split(s, p, "."); return p[1] * 1e6 + p[2] }
	$3 == "702" { hb = us($1); hb_at = NR }
	$3 ~ /^20[1-3]$/ && $5 == "02" && $6 == "00" && !qs[$3] && hb_at { qs[$3] = NR; t[$3] = us($1) }
	$3 == "080" && qs["203"] && !sync_after { sync_after = NR }
	$3 ~ /^18[13]$/ && qs["201"] {
		st = ("0x" $5) + 0
		if (and(st, 111) == 7) seen_qs[$3] = 1  # quick stop active (while it brakes)
		if (and(st, 79) == 64) disabled[$3] = 1 # switch on disabled
	}
	$3 == "000" && $5 == "80" { preop[$6] = 1 }
	END {
		if (!hb_at) { print "lost: no heartbeat of node 2"; exit 1 }
		for (n = 1; n <= 3; n++)
			if (!qs["20" n]) { print "lost: no quick stop RPDO for node " n; exit 1 }
		dt = t["201"] - hb
		printf "lost: quick stop %.1f ms after node 2'"'"'s last heartbeat\n", dt / 1000
		if (dt > 125000 + max_late_us + 25000) { print "lost: too late"; exit 1 }
		if (!sync_after) { print "lost: no SYNC after the quick stop"; exit 1 }
		# a drive that stands still when the quick stop comes is at rest at
		# once, and may report switch on disabled in its next TPDO without
		# one saying quick stop active
		if (!disabled["181"] || !disabled["183"]) {
			print "lost: nodes 1 and 3 not switched off after the quick stop"; exit 1
		}
		printf "lost: braking seen in TPDOs: node 1 %s, node 3 %s\n", \
		       seen_qs["181"] ? "yes" : "no (at rest)", seen_qs["183"] ? "yes" : "no (at rest)"
		if (!preop["01"] || !preop["03"]) { print "lost: no pre-operational"; exit 1 }
		print "lost: nodes 1 and 3: quick stop active, then switch on disabled, then pre-operational"
	}' /tmp/bus.log >/tmp/lost.out
rc=$?
cat /tmp/lost.out
[ $rc = 0 ] || fail "$(tail -n 1 /tmp/lost.out)"
pass "node 2 killed: heartbeat fault, exit 7; $(sed -n 's/^lost: \(quick stop .*\)/\1/p' /tmp/lost.out);" \
	"the others quick-stopped and switched off"
