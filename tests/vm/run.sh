#!/bin/sh
# run.sh KERNEL INITRD OUTDIR - boot the test VM once, run its tests
# (tests/vm/init.sh), report each by name and exit 0 only when every test
# named in INITRD.tests passed.
#
# The run fails on any of: a test's FAIL line, a test with no verdict, no
# VMRESULT line (kernel panic: with panic=-1 and -no-reboot qemu exits 0),
# the in-guest watchdog, qemu's exit code not saying pass, or the outer
# timeout (a hang). The console goes to OUTDIR/console.log.
#
# Environment: VM_TIMEOUT (s, default 300), VM_ONLY (test names, blank
# separated), VM_VERBOSE=1 (console on stdout as it runs), VM_SHELL=1 (an
# interactive shell instead of the tests), VM_APPEND (more kernel arguments).
set -eu
[ $# -eq 3 ] || { echo "usage: run.sh KERNEL INITRD OUTDIR" >&2; exit 2; }
kernel=$1
initrd=$2
out=$3
timeout=${VM_TIMEOUT:-300}
log=$out/console.log
mkdir -p "$out"

# KVM only where it is the real thing (VM.md): /dev/kvm can also belong to a
# software hypervisor module under which Debian's kernel does not boot.
accel="-accel tcg"
accel_name=TCG
if [ -w /dev/kvm ] && { [ -d /sys/module/kvm_intel ] || [ -d /sys/module/kvm_amd ]; }; then
	accel="-accel kvm -cpu host"
	accel_name=KVM
fi

append="console=ttyS0 quiet panic=-1 strand.watchdog=$((timeout * 4 / 5))"
append="$append strand.accel=$(echo $accel_name | tr 'A-Z' 'a-z')"
if [ -n "${VM_ONLY:-}" ]; then
	append="$append strand.only=$(echo "$VM_ONLY" | tr -s ' ' ',')"
fi
append="$append ${VM_APPEND:-}"

# -smp 1: one CPU, as the small boards; 256 MB is plenty for a 5 MB initramfs.
# shellcheck disable=SC2086 # accel is two or three words
set -- qemu-system-x86_64 $accel -m 256M -smp 1 -display none -no-reboot -nic none \
	-device isa-debug-exit,iobase=0xf4,iosize=0x04 \
	-kernel "$kernel" -initrd "$initrd"

if [ -n "${VM_SHELL:-}" ]; then
	exec "$@" -serial mon:stdio -append "console=ttyS0 quiet panic=-1 strand.shell=1"
fi

echo "vm: booting $(basename "$kernel") ($accel_name) with $(wc -l <"$initrd.tests") test scripts," \
	"timeout $timeout s; console: $log"
start=$(date +%s.%N)
rc=0
if [ -n "${VM_VERBOSE:-}" ]; then
	{ timeout "$timeout" "$@" -serial stdio -monitor none -append "$append" </dev/null || rc=$?
	  echo "$rc" >"$out/qemu.rc"; } | tee "$log"
	rc=$(cat "$out/qemu.rc")
else
	timeout "$timeout" "$@" -serial stdio -monitor none -append "$append" </dev/null >"$log" 2>&1 ||
		rc=$?
fi
secs=$(echo "$start $(date +%s.%N)" | awk '{ printf "%.1f", $2 - $1 }')
# The serial console ends lines with CR LF.
tr -d '\r' <"$log" >"$log.txt"

# One line per test, in the order they ran; a test that should have run and
# did not say anything fails.
failed=0
passed=0
for name in $(cat "$initrd.tests"); do
	if [ -n "${VM_ONLY:-}" ] && ! echo " $VM_ONLY " | grep -q " $name "; then
		continue
	fi
	line=$(grep -E "^VMTEST (PASS|FAIL) $name:" "$log.txt" | tail -n 1 || true)
	t=$(sed -n "s/^VMTEST TIME $name //p" "$log.txt" | tail -n 1)
	case $line in
	"VMTEST PASS "*)
		echo "PASS vm $name (${t:-?} s):${line#*:}"
		passed=$((passed + 1))
		;;
	*)
		failed=$((failed + 1))
		if [ -n "$line" ]; then
			echo "FAIL vm $name (${t:-?} s):${line#*:}"
		else
			echo "FAIL vm $name: no verdict (kernel panic, hang or watchdog; see $log)"
		fi
		# its output, between its BEGIN and its verdict
		awk -v n="$name" '$0 == "VMTEST BEGIN " n { on = 1; next }
			on && /^VMTEST (PASS|FAIL|TIME) / { exit }
			on { print "    | " $0 }' "$log.txt" | tail -n 25
		;;
	esac
done

result=$(grep "^VMRESULT " "$log.txt" | tail -n 1 || true)
boot=$(sed -n 's/^VMBOOT //p' "$log.txt" | head -n 1)
case $rc in
1) qemu="qemu exit 1 (guest said pass)" ;;
3) qemu="qemu exit 3 (guest said fail)" ;;
124) qemu="qemu killed after $timeout s (hang)" ;;
0) qemu="qemu exit 0: the guest rebooted or panicked" ;;
*) qemu="qemu exit $rc" ;;
esac
echo "vm: ${result:-no VMRESULT line}; $qemu; /init at ${boot:-?} s, $secs s in all"
if [ -z "$result" ] || [ "$rc" != 1 ] || [ "${result#VMRESULT PASS}" = "$result" ] ||
	[ $failed -ne 0 ] || [ $passed -eq 0 ]; then
	[ -n "$result" ] || tail -n 20 "$log.txt" | sed 's/^/    | /'
	echo "vm: $passed passed, $failed failed: FAIL"
	exit 1
fi
echo "vm: $passed passed, 0 failed"
