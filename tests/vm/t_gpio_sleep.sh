#!/bin/sh
# What strand reads in sysfs to tell a GPIO chip that sleeps
# (hal/gpio/gpio_chip.c), on this kernel: /sys/bus/gpio/devices/gpiochipN
# resolves to the chip's device, under the device that provides it, whose
# `subsystem` link names its bus. gpio-sim's chip hangs off a platform
# device: it does not sleep, and strand plays a trigger and an e-stop on it
# without a word about that. Its start line names every thread as the plan
# has it (firmware/play/rt.h): strand-rt and the input event thread
# strand-gpio-io at SCHED_FIFO 80. (No chip that sleeps can be made here:
# Debian's amd64 kernel builds no I2C or SPI GPIO expander driver;
# tests/hal/test_gpio.c and tests/play/test_play_gpio.c cover one over a
# sysfs tree laid out the same way.)
# vm-timeout: 60
. /tests/lib.sh

gpio_rig_chip
dev=$(readlink -f "/sys/bus/gpio/devices/$SIM_CHIP") || fail "no /sys/bus/gpio/devices/$SIM_CHIP"
[ "$dev" = "/sys/devices/platform/$SIM_DEV/$SIM_CHIP" ] ||
	fail "/sys/bus/gpio/devices/$SIM_CHIP is $dev, want /sys/devices/platform/$SIM_DEV/$SIM_CHIP"
bus=$(basename "$(readlink "/sys/devices/platform/$SIM_DEV/subsystem")")
[ "$bus" = platform ] || fail "$SIM_DEV is on bus '$bus', want platform"

strand play /scenes/gpio_rig.yaml --duration 1 --no-journal --quiet >/tmp/play.out 2>&1
rc=$?
cat /tmp/play.out
[ $rc = 0 ] || fail "strand play exited $rc: $(tail -n 1 /tmp/play.out)"
if grep -q 'is on the [a-z0-9_]* bus' /tmp/play.out; then
	fail "strand takes gpio-sim's chip for one that sleeps: $(grep 'is on the' /tmp/play.out)"
fi
threads=$(grep '^strand: threads: ' /tmp/play.out) || fail "no 'strand: threads:' line at start"
echo "$threads" | grep -q 'strand-rt SCHED_FIFO 80' || fail "strand-rt is not SCHED_FIFO 80: $threads"
echo "$threads" | grep -q 'strand-gpio-io SCHED_FIFO 80' ||
	fail "the input event thread is not SCHED_FIFO 80: $threads"
pass "$SIM_CHIP is $dev, on the platform bus: not taken for a chip that sleeps; $threads"
