#!/bin/sh
# Step mode paced by the camera: strand plays three frames with
# --mode step while this script plays the camera on the cam-ready input
# (active high: pulled up = ready). While the camera is not ready, no
# frame fires however long it waits; each ready edge lets exactly one more
# frame through.
# vm-timeout: 60
. /tests/lib.sh

gpio_rig_chip
sed 's|^inputs:.*|&\n  - {name: ready, device: io, line: cam-ready, role: camera_ready}|' \
	/scenes/gpio_rig.yaml >/tmp/step.yaml
grep -q "role: camera_ready" /tmp/step.yaml || fail "could not make the step scene"
bg gpiomon -b -F '%e %s %n' "$SIM_CHIP" 8 >/tmp/edges
wait_for 5 line_held 8 gpiomon || fail "gpiomon never holds the wire (line 8)"

sim_pull 3 down                     # the camera is busy
strand play /tmp/step.yaml --mode step --frames 10,20,30 --timeout 30 --journal /tmp/journal \
	--quiet >/tmp/play.out 2>&1 &
play=$!
for k in 1 2 3; do
	# not ready: nothing may fire, however long the rig has settled
	sleep 1
	n=$(pulses /tmp/edges)
	[ "$n" = $((k - 1)) ] || fail "frame $k: $n pulses while the camera was busy, want $((k - 1))"
	sim_pull 3 up                   # ready: one frame
	wait_for 10 pulses_at_least /tmp/edges "$k" || fail "frame $k never fired after ready"
	sim_pull 3 down                 # exposing, then reading out
	sleep 0.3
	n=$(pulses /tmp/edges)
	[ "$n" = "$k" ] || fail "frame $k: $n pulses after one ready edge, want $k"
done
sim_pull 3 up
wait "$play"
rc=$?
cat /tmp/play.out
[ $rc = 0 ] || fail "strand play exited $rc"
strand journal /tmp/journal | cut -d, -f1 | tail -n +2 | tr '\n' ' ' >/tmp/frames
[ "$(cat /tmp/frames)" = "10 20 30 " ] || fail "journal frames: $(cat /tmp/frames), want 10 20 30"
pass "3 frames, each only after the camera's ready edge; none while it was busy"
