#!/bin/sh
# A line held by another process: strand play refuses to start, says which
# chip and line and who holds it, and drives nothing. The scene is
# gpio_rig.yaml with the device given by chip name and the lines by
# offset, the other way of naming them.
# vm-timeout: 30
. /tests/lib.sh

gpio_rig_chip
sed -e "s|{name: io, driver: gpio, ready: {line: rig-ready}}|{name: io, driver: gpio, chip: $SIM_CHIP}|" \
	-e 's|line: cam-trigger|line: 0|' -e 's|line: estop|line: 2|' \
	/scenes/gpio_rig.yaml >/tmp/offsets.yaml
grep -q "chip: $SIM_CHIP" /tmp/offsets.yaml && grep -q "line: 0" /tmp/offsets.yaml ||
	fail "could not make the offsets scene"

# First the same scene with the lines free: it plays (so that the refusal
# below is about the held line, nothing else).
strand play /tmp/offsets.yaml --to 5 --no-journal --quiet >/tmp/free.out 2>&1 ||
	fail "with the lines free, strand play failed: $(tail -n 1 /tmp/free.out)"

bg gpioset --mode=signal "$SIM_CHIP" 0=0
wait_for 5 line_held 0 gpioset || fail "gpioset never holds line 0"
strand play /tmp/offsets.yaml --to 5 --no-journal --quiet >/tmp/busy.out 2>&1
rc=$?
cat /tmp/busy.out
[ $rc = 7 ] || fail "strand play exited $rc on a line gpioset holds, want 7 (device)"
msg=$(grep -i "held" /tmp/busy.out | head -n 1)
for want in "'io'" "$SIM_CHIP" "line 0" "gpioset"; do
	echo "$msg" | grep -qF "$want" || fail "the message does not name $want: '$msg'"
done
pass "exit $rc: $msg"
