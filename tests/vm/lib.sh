# lib.sh - sourced by the test scripts in the VM (tests/vm/t_*.sh). busybox sh.
#
# A test ends with pass WORDS or fail WORDS, which print its verdict line
# for /init and the host, and kill what it started in the background.
#
# gpio-sim, through configfs (the module is loaded and configfs mounted by
# /init): sim_chip NAME NLINES [OFFSET=LINENAME...] makes a live chip and
# sets SIM_CHIP (gpiochipN, for the gpiod tools and strand) and SIM_DEV
# (its platform device, for sim_pull and sim_value).

VM_TEST=${VM_TEST:-$(basename "$0" .sh)}
SIM_CFS=/sys/kernel/config/gpio-sim
BG_PIDS=""

note() { echo "$VM_TEST: $*"; }

cleanup() {
	for p in $BG_PIDS; do kill "$p" 2>/dev/null; done
	BG_PIDS=""
}

pass() {
	cleanup
	echo "VMTEST PASS $VM_TEST: $*"
	exit 0
}

fail() {
	cleanup
	echo "VMTEST FAIL $VM_TEST: $*"
	exit 1
}

# bg CMD...: start CMD in the background, killed by pass and fail; $! is it.
bg() {
	"$@" &
	BG_PIDS="$BG_PIDS $!"
}

# wait_for SECONDS CMD...: poll CMD every 20 ms until it succeeds; 1 when
# SECONDS have passed by the clock (not by a count of polls: on a loaded
# host one poll can take far longer than 20 ms).
wait_for() {
	_end=$(($(uptime_ms) + $1 * 1000))
	shift
	while ! "$@" 2>/dev/null; do
		[ "$(uptime_ms)" -lt $_end ] || return 1
		sleep 0.02
	done
}

# uptime_ms: milliseconds since boot, for coarse durations only (10 ms steps).
uptime_ms() { awk '{ printf "%d", $1 * 1000 }' /proc/uptime; }

sim_chip() {
	_name=$1
	_n=$2
	shift 2
	_d=$SIM_CFS/$_name
	mkdir "$_d" "$_d/bank0" || fail "gpio-sim: cannot make $_d"
	echo "$_n" >"$_d/bank0/num_lines"
	for _l in "$@"; do
		mkdir "$_d/bank0/line${_l%%=*}"
		echo "${_l#*=}" >"$_d/bank0/line${_l%%=*}/name"
	done
	echo 1 >"$_d/live" || fail "gpio-sim: $_name does not go live"
	SIM_CHIP=$(cat "$_d/bank0/chip_name")
	SIM_DEV=$(cat "$_d/dev_name")
	[ -c "/dev/$SIM_CHIP" ] || fail "gpio-sim: no /dev/$SIM_CHIP for $_name"
}

# sim_chip_remove NAME: take a chip down (lines must be released first).
sim_chip_remove() {
	_d=$SIM_CFS/$1
	echo 0 >"$_d/live"
	for _l in "$_d"/bank0/line*; do [ -d "$_l" ] && rmdir "$_l"; done
	rmdir "$_d/bank0" "$_d"
}

_sim_attr() { echo "/sys/devices/platform/$SIM_DEV/$SIM_CHIP/sim_gpio$1/$2"; }

# sim_pull OFFSET up|down: what the outside world drives onto an input line.
sim_pull() { echo "pull-$2" >"$(_sim_attr "$1" pull)"; }

# sim_value OFFSET: the level the chip sees on the line (0 or 1), for an
# output what the program drives.
sim_value() { cat "$(_sim_attr "$1" value)"; }

# sim_value_is OFFSET V: for wait_for, which evaluates its command each time.
sim_value_is() { [ "$(sim_value "$1")" = "$2" ]; }

# lines_are N FILE, lines_at_least N FILE: FILE has N lines, N or more
# (for wait_for).
lines_are() { [ "$(wc -l <"$2" 2>/dev/null)" = "$1" ]; }
lines_at_least() { [ "$(wc -l <"$2" 2>/dev/null)" -ge "$1" ]; }

# line_held OFFSET CONSUMER: gpioinfo shows CONSUMER holding the line of
# SIM_CHIP (for wait_for: a request is made before its events count).
line_held() {
	gpioinfo "$SIM_CHIP" | grep -E "^[[:space:]]+line[[:space:]]+$1:" | grep -q "\"$2\""
}

# gpio_rig_chip: the chip of /scenes/gpio_rig.yaml, every line named:
#   0 cam-trigger  strand's trigger output, wired to 8 (loopback=0,8)
#   1 rig-ready    an output, wired to 9 (loopback=1,9)
#   2 estop        the e-stop chain: pulled up, closed (active low)
#   3 cam-ready    the camera's ready output: pulled up, ready
#   8 cam-wire     what gpiomon watches to see the trigger
#   9 ready-wire
gpio_rig_chip() {
	sim_chip rig 16 0=cam-trigger 1=rig-ready 2=estop 3=cam-ready 8=cam-wire 9=ready-wire
	sim_pull 2 up
	sim_pull 3 up
}

# pulses FILE: pulses begun on a wire that starts low, from gpiomon's
# output (one line per edge); the edges' kinds are not trusted (twice).
pulses() { echo $((($(wc -l <"$1") + 1) / 2)); }
pulses_at_least() { [ "$(pulses "$1")" -ge "$2" ]; }

# vm_arg NAME: the value of strand.NAME= on the kernel command line (make
# test-vm VM_APPEND=strand.NAME=VALUE), empty when not given.
vm_arg() { sed -n "s/.*strand\.$1=\([^ ]*\).*/\1/p" /proc/cmdline; }

# max_late_us: how late the loop may act on its schedule in this VM, for
# the timing checks. Under qemu's software emulation (TCG) the guest's CPU
# is a host thread that the host preempts: medians of 0.3 ms, but stalls of
# 17 ms were seen; under KVM the guest runs on a real CPU. A board does far
# better than either (README "GPIO"). strand.max_late_us=N overrides.
max_late_us() {
	_m=$(vm_arg max_late_us)
	if [ -n "$_m" ]; then
		echo "$_m"
	elif [ "$(vm_arg accel)" = kvm ]; then
		echo 2000
	else
		echo 50000
	fi
}

# twice ATTEMPT: run the function ATTEMPT, which sets WHY and returns 1 on
# a failure; if it fails, say why and run it once more, from a fresh chip.
# For the tests whose observer is gpiomon: the kernel's v1 edge-event
# thread delivers one event per run, so when the emulated CPU stalls for
# longer than a pulse (a host busy with other work) two edges become one
# and gpiomon misses an edge that was there. Two failures in a row fail.
twice() {
	WHY=""
	"$1" && return 0
	note "first attempt: $WHY; once more"
	cleanup
	[ -d "$SIM_CFS/rig" ] && sim_chip_remove rig
	WHY=""
	"$1"
}

# A test run again against the libgpiod 2 build (NAME@gpiod2: init.sh puts
# /gpiod2/bin first on PATH): make sure that is the strand it runs.
case $VM_TEST in
*@gpiod2)
	strand --version | grep -q '(libgpiod 2\.' ||
		fail "not the libgpiod 2 build: $(strand --version 2>&1)"
	;;
esac
