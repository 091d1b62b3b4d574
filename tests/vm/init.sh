#!/bin/sh
# /init of the test VM (tests/vm/mkinitramfs.sh puts it there): mount the
# pseudo file systems, load the modules, run each /tests/t_*.sh in the order
# of /tests/list, print one result line, hand the verdict to qemu through
# isa-debug-exit and power off. PID 1 never exits: that would panic.
#
# Lines for the host (tests/vm/run.sh), each alone on a line:
#   VMBOOT <uptime s>                   init started
#   VMTEST BEGIN <name>                 a test starts; its output follows
#   VMTEST PASS|FAIL <name>: <words>    its verdict (the script prints it)
#   VMTEST TIME <name> <s>              how long it took
#   VMRESULT PASS|FAIL <words>          the run's verdict, the last line
#
# A name NAME@VARIANT in the list is the test NAME run again with
# /VARIANT/bin first on PATH: the same script against a second build of
# strand (mk/gpiod2.mk: @gpiod2, libgpiod 2).
#
# Kernel command line: strand.only=t_a,t_b runs only those tests;
# strand.watchdog=S (default 240) fails the run after S seconds;
# strand.shell=1 gives a shell on the console instead.
export PATH=/bin:/sbin
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
exec </dev/console >/dev/console 2>&1
mount -t tmpfs tmpfs /tmp
mount -t tmpfs tmpfs /run
echo "VMBOOT $(cut -d' ' -f1 /proc/uptime)"

# arg NAME: the value of strand.NAME=, the last one given.
arg() {
	_v=
	for w in $(cat /proc/cmdline); do
		case $w in "strand.$1="*) _v=${w#*=} ;; esac
	done
	echo "$_v"
}

# isa-debug-exit at port 0xf4: qemu exits with (byte << 1) | 1.
finish() {
	echo "VMRESULT $1"
	case $1 in PASS*) b='\000' ;; *) b='\001' ;; esac
	sync
	printf "$b" | dd of=/dev/port bs=1 seek=244 count=1 2>/dev/null
	# Only without the device (a hand-run qemu): stop anyway.
	poweroff -f
	while :; do sleep 1; done
}

# one module a line: FILE [PARAM=VALUE...]
while read -r m params; do
	# shellcheck disable=SC2086 # the parameters are words
	insmod "/lib/modules/$m" $params || finish "FAIL insmod $m $params"
done </lib/modules/load.order
mount -t configfs configfs /sys/kernel/config || finish "FAIL mount configfs"

if [ "$(arg shell)" = 1 ]; then
	echo "VM shell: /tests holds the tests; exit powers off"
	setsid cttyhack sh
	finish "FAIL shell"
fi

# The in-guest watchdog: a hung test fails the run with a line saying so,
# well before the host's own timeout kills qemu.
wd_secs=$(arg watchdog)
(
	sleep "${wd_secs:=240}"
	echo "VMTEST FAIL $(cat /tmp/current 2>/dev/null): still running after the run's $wd_secs s"
	cat /tmp/current.out 2>/dev/null
	finish "FAIL watchdog after $wd_secs s"
) &
wd=$!

# Every process but init, the watchdog and its sleep: what a test left.
reap() {
	for p in /proc/[0-9]*; do
		pid=${p#/proc/}
		[ "$pid" = 1 ] || [ "$pid" = "$wd" ] && continue
		[ -s "$p/cmdline" ] || continue         # kernel thread
		pp=$(sed -n 's/^PPid:[[:space:]]*//p' "$p/status" 2>/dev/null)
		[ "$pp" = "$wd" ] && continue
		kill -KILL "$pid" 2>/dev/null
	done
}

# What a test set up in the kernel: gpio-sim chips and virtual CAN links,
# so that each test starts from the same machine.
tidy() {
	for c in /sys/kernel/config/gpio-sim/*; do
		[ -d "$c" ] || continue
		echo 0 >"$c/live"
		for b in "$c"/bank*; do
			for l in "$b"/line*; do
				[ -d "$l/hog" ] && rmdir "$l/hog"
				[ -d "$l" ] && rmdir "$l"
			done
			rmdir "$b"
		done
		rmdir "$c"
	done
	for l in /sys/class/net/vcan*; do
		[ -e "$l" ] && ip link del "${l##*/}"
	done
}

only=$(arg only | tr ',' ' ')
failed=0
ran=0
for name in $(cat /tests/list); do
	if [ -n "$only" ] && ! echo " $only " | grep -q " $name "; then
		continue
	fi
	t=/tests/${name%@*}.sh
	path=$PATH
	case $name in *@*) path=/${name#*@}/bin:$PATH ;; esac
	limit=$(sed -n 's/^# vm-timeout: *\([0-9]*\).*/\1/p' "$t")
	echo "$name" >/tmp/current
	echo "VMTEST BEGIN $name"
	t0=$(cut -d' ' -f1 /proc/uptime)
	# Output to a file rather than a pipe: a process the test left behind
	# cannot hold the run up by keeping a pipe open.
	(cd /tmp && PATH=$path VM_TEST=$name timeout -s KILL "${limit:-60}" sh "$t") \
		>/tmp/current.out 2>&1 </dev/null
	rc=$?
	t1=$(cut -d' ' -f1 /proc/uptime)
	reap
	tidy 2>>/tmp/current.out
	cat /tmp/current.out
	verdict=$(grep -E "^VMTEST (PASS|FAIL) $name:" /tmp/current.out | tail -n 1 | cut -d' ' -f2)
	if [ "$rc" = 137 ]; then
		echo "VMTEST FAIL $name: killed after its ${limit:-60} s"
		verdict=FAIL
	elif [ "$rc" != 0 ] && [ "$verdict" != FAIL ]; then
		echo "VMTEST FAIL $name: exited $rc without a FAIL line"
		verdict=FAIL
	elif [ "$rc" = 0 ] && [ "$verdict" != PASS ]; then
		echo "VMTEST FAIL $name: exited 0 without a PASS line"
		verdict=FAIL
	fi
	echo "VMTEST TIME $name $(echo "$t0 $t1" | awk '{ printf "%.2f", $2 - $1 }')"
	[ "$verdict" = PASS ] || failed=$((failed + 1))
	ran=$((ran + 1))
done
rm -f /tmp/current
kill "$wd" 2>/dev/null

if [ "$ran" = 0 ]; then
	finish "FAIL no test ran (only: ${only:-all})"
elif [ "$failed" = 0 ]; then
	finish "PASS $ran tests"
else
	finish "FAIL $failed of $ran tests"
fi
