# can.sh - sourced by the CAN tests in the VM (tests/vm/t_can_*.sh), after
# lib.sh: vcan0 as a classic CAN bus, candump recording it, strand-simdrive
# drives on it.

# can_up NODE...: vcan0 up (MTU 16, as a classic controller), candump -ta
# recording into /tmp/bus.log, one strand-simdrive per node-ID (its output in
# /tmp/driveN.out, its pid in DRIVE_N), each listening before the next.
can_up() {
	ip link add dev vcan0 type vcan || fail "ip link add vcan0 type vcan"
	ip link set vcan0 mtu 16 || fail "ip link set vcan0 mtu 16"
	ip link set up vcan0 || fail "ip link set up vcan0"
	# the observer first: a raw socket sees only what is sent after it is bound
	bg candump -ta -r 4000000 vcan0 >/tmp/bus.log
	wait_for 5 grep -q '^ *vcan0 .* raw$' /proc/net/can/rcvlist_all ||
		fail "candump never listens on vcan0"
	for _n in "$@"; do
		bg strand-simdrive --can vcan0 --node "$_n" --initial $((_n * 100)) \
			--sync-log /tmp/sync"$_n".log >/tmp/drive"$_n".out 2>&1
		eval "DRIVE_$_n=$!"
		wait_for 5 grep -q listening /tmp/drive"$_n".out ||
			fail "strand-simdrive node $_n: $(cat /tmp/drive"$_n".out)"
	done
}

# syncs_at_least N: candump has recorded N SYNCs (for wait_for)
syncs_at_least() { [ "$(grep -c ' 080 ' /tmp/bus.log)" -ge "$1" ]; }

# wait_playing N PID OUT: wait up to 30 s for N SYNCs on the bus while
# strand play (PID, its output in OUT) runs; fail at once, with its output,
# when it has ended before them.
wait_playing() {
	_end=$(($(uptime_ms) + 30000))
	while ! syncs_at_least "$1"; do
		kill -0 "$2" 2>/dev/null || {
			wait "$2"
			_rc=$?
			cat "$3"
			fail "strand play ended (exit $_rc) after $(grep -c ' 080 ' /tmp/bus.log) SYNCs:" \
				"$(grep 'strand play:' "$3" | tail -n 1)"
		}
		[ "$(uptime_ms)" -lt $_end ] ||
			fail "only $(grep -c ' 080 ' /tmp/bus.log) SYNCs in 30 s"
		sleep 0.02
	done
}
