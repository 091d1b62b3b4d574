#!/bin/sh
# run.sh STRAND STRAND-SIMDRIVE [--bench] - several boards, one scene, for real: three
# `strand play --node` in network namespaces joined by a bridge, ptp4l
# between them (lib.sh), each board driving its part of tests/boards/lock3.yaml
# on simulated devices (board b, in one case, a Modbus drive served by
# strand-simdrive in its namespace). `make check-boards`.
#
#   lockstep    the three play the scene together (exit 0): every frame in
#               each journal, the due times of one frame on the three boards
#               within 20 us of each other (one machine's clock: the start
#               protocol's own error), the times the triggers went out
#               (mono_ns) within 2 ms at the median; BENCH lines of the skew
#   digest      board c's scene differs by one comment: all three refuse
#               (exit 7), naming board c
#   ptp         board c's ptp4l hears no master (LISTENING): all refuse,
#               naming board c and its port state
#   clocks      board c's clock 5 ms off (STRAND_LOCKSTEP_CLOCK_SKEW_NS):
#               all refuse, naming board c and the offset
#   past        board c's clock 10 s ahead, with a max_offset_us that lets
#               it pass: the start instant is past on it; all refuse
#   killed      board c killed (-9) while they play: a and b stop under
#               control within lost_ms and a tick or so (exit 7), naming it
#   estop       board b's e-stop (SIGUSR1 presses the simulated button):
#               b exits 6, a and c stop at once (exit 6) naming board b's
#               e-stop, a few ms later (BENCH)
#   fault       board b's Modbus drive trips (strand-simdrive
#               --trip-after): b stops with its device fault (exit 7), a and
#               c under control (exit 7) naming board b and the fault
#
# --bench (make bench-boards): the lockstep case alone, over 10 s (250
# frames on each board), for its BENCH lines.
#
# Needs root, ip netns, veth, a bridge and linuxptp; where one is missing,
# one SKIP line says which (never under CI).
set -u
STRAND=$(readlink -f "$1")
SIMDRIVE=$(readlink -f "$2")
BENCH=${3:-}
# the tests' boards: ordinary threads on a shared machine; the benchmark's:
# the loop's SCHED_FIFO and locked memory, as on a board
PLAY_RT="--priority 0 --no-mlock"
[ "$BENCH" = --bench ] && PLAY_RT=""

HERE=$(cd "$(dirname "$0")" && pwd)
SCENE=$HERE/lock3.yaml
PLAY_ENV=
FAILED=0
CASE=setup
. "$HERE/lib.sh"

skip() {
	if [ -n "${CI:-}" ]; then
		echo "FAIL check-boards cannot run under CI: $*"
		exit 1
	fi
	echo "SKIP check-boards: $*"
	exit 0
}
[ "$(id -u)" = 0 ] || skip "needs root (network namespaces)"
for p in ip ptp4l pmc; do
	command -v $p >/dev/null 2>&1 || skip "no $p (iproute2, linuxptp)"
done
trap net_down EXIT INT TERM
net_up 2>"$T.err" || skip "network namespaces, veth or a bridge refused: $(cat "$T.err")"
rm -f "$T.err"
ptp_up
ptp_wait 15 || { fail "ptp4l did not settle"; exit 1; }

# ---- lockstep: the skew between the boards' triggers --------------------------
# lockstep SCENE FRAMES: the three play SCENE (FRAMES frames) together
lockstep() {
	CASE=lockstep
	for b in $BOARDS; do play "$b" "$1"; done
	wait_all
	if [ "$RC_a$RC_b$RC_c" != 000 ]; then
		fail "exit codes a $RC_a, b $RC_b, c $RC_c, want 0"
		return
	fi
	for b in $BOARDS; do "$STRAND" journal "$T/$b.journal" >"$T/$b.csv"; done
	# per frame: the spread of due_ns and of mono_ns over the three boards
	awk -F, 'FNR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; f++; next }
		{ k = $c["frame"]; d[k, f] = $c["due_ns"]; m[k, f] = $c["mono_ns"]; n[k]++ }
		END {
			for (k in n) {
				if (n[k] != 3) { print "frame " k " in " n[k] " journals"; bad = 1; continue }
				dl = dh = d[k, 1]; ml = mh = m[k, 1]
				for (j = 2; j <= 3; j++) {
					if (d[k, j] < dl) dl = d[k, j]; if (d[k, j] > dh) dh = d[k, j]
					if (m[k, j] < ml) ml = m[k, j]; if (m[k, j] > mh) mh = m[k, j]
				}
				print (dh - dl) / 1000, (mh - ml) / 1000
			}
			exit bad
		}' "$T/a.csv" "$T/b.csv" "$T/c.csv" >"$T/skew" || {
		fail "$(grep frame "$T/skew" | head -n 1)"
		return
	}
	frames=$(wc -l <"$T/skew")
	# quantiles COLUMN NAME DIGITS: p50, p99, max of a column as BENCH lines
	quantiles() {
		sort -n -k"$1,$1" "$T/skew" | awk -v c="$1" -v name="$2" -v dg="$3" '
			{ v[NR] = $c }
			function q(p,    k) { k = int(NR * p) + 1; if (k > NR) k = NR; return v[k] }
			END {
				printf "BENCH %s_p50_us %.*f\n", name, dg, q(0.5)
				printf "BENCH %s_p99_us %.*f\n", name, dg, q(0.99)
				printf "BENCH %s_max_us %.*f\n", name, dg, v[NR]
			}'
	}
	{ quantiles 1 lockstep_due_skew 3; quantiles 2 lockstep_trigger_skew 1; } >"$T/bench"
	cat "$T/bench"
	due_max=$(sed -n 's/^BENCH lockstep_due_skew_max_us //p' "$T/bench")
	trig_p50=$(sed -n 's/^BENCH lockstep_trigger_skew_p50_us //p' "$T/bench")
	if [ "$frames" != "$2" ]; then
		fail "$frames frames in all three journals, want $2"
	elif awk -v d="$due_max" -v t="$trig_p50" 'BEGIN { exit !(d > 20 || t > 2000) }'; then
		fail "due times up to $due_max us apart (bound 20), triggers $trig_p50 us at the median (bound 2000)"
	else
		pass "$2 frames on three boards: due within $due_max us, triggers p50 $trig_p50 us apart;" \
			"$(grep -o 'the clocks within [^;]*' "$T/a.out")"
	fi
}

if [ "$BENCH" = --bench ]; then
	sed 's/^  frames: \[0, 25\]/  frames: [0, 250]/; s/{frame: 25,/{frame: 250,/' "$SCENE" >"$T/long.yaml"
	echo "bench-boards: three boards in network namespaces, ptp4l software timestamps," \
		"1 kHz, 250 frames each, SCHED_FIFO 80; skew = the spread of one frame's time over" \
		"the boards"
	ptp_settle 10 || { fail "ptp4l did not settle"; exit 1; }
	lockstep "$T/long.yaml" 251
	[ $FAILED = 0 ] || exit 1
	exit 0
fi
ptp_settle 10 || { fail "ptp4l did not settle"; exit 1; }
lockstep "$SCENE" 26

# ---- the refusals ------------------------------------------------------------------
# refused WHAT: all three exit 7, each saying WHAT (the refusal's words)
refused() {
	wait_all
	if [ "$RC_a$RC_b$RC_c" != 777 ]; then
		fail "exit codes a $RC_a, b $RC_b, c $RC_c, want 7 (refused)"
		return
	fi
	# a follower that had confirmed the start before another refused
	# stops at its tick 0 for it: the same words, without the prefix
	for b in $BOARDS; do
		said "$b" "$1" || { fail "board $b does not say '$1'"; return; }
	done
	pass "all three refused: $(grep -o 'lockstep refused: .*' "$T/a.out" | head -n 1)"
}

CASE=digest
ptp_settle 10 || fail "ptp4l did not settle"
sed 's/^# lock3.yaml - three boards/# lock3.yaml (changed) - three boards/' "$SCENE" >"$T/other.yaml"
play a "$SCENE"
play b "$SCENE"
play c "$T/other.yaml"
refused "board 'c' loaded another scene than board 'a'"

CASE=ptp
ptp_settle 10 || fail "ptp4l did not settle"
# a ptp4l of c's own on a link with no one at the other end, slaveOnly:
# it listens for a master that never comes
in_ns c ip link add "x$$" type veth peer name "y$$"
in_ns c ip link set "x$$" up
in_ns c ip link set "y$$" up
ptp_conf c 1 | sed "s|ptp4l-c|ptp4l-lone|" >"$T/ptp4l-lone.cfg"
ip netns exec "$(ns c)" ptp4l -f "$T/ptp4l-lone.cfg" -i "x$$" >"$T/ptp4l-lone.log" 2>&1 &
lone=$!
sleep 0.3
play a "$SCENE"
play b "$SCENE"
ip netns exec "$(ns c)" "$STRAND" play "$SCENE" --node c --ptp-socket "$T/ptp4l-lone" \
	--ptp-free-running --journal "$T/c.journal" >"$T/c.out" 2>&1 &
PID_c=$!
refused "board 'c': PTP is not locked: ptp4l's port is LISTENING"
kill "$lone" 2>/dev/null

CASE=clocks
ptp_settle 10 || fail "ptp4l did not settle"
play a "$SCENE"
play b "$SCENE"
PLAY_ENV=STRAND_LOCKSTEP_CLOCK_SKEW_NS=5000000
play c "$SCENE"
PLAY_ENV=
refused "the clocks of board 'c' and board 'a' disagree by"

CASE=past
ptp_settle 10 || fail "ptp4l did not settle"
sed 's/^lockstep: {start_ms: 300,/lockstep: {start_ms: 300, max_offset_us: 60000000,/' "$SCENE" >"$T/wide.yaml"
play a "$T/wide.yaml"
play b "$T/wide.yaml"
PLAY_ENV=STRAND_LOCKSTEP_CLOCK_SKEW_NS=10000000000
play c "$T/wide.yaml"
PLAY_ENV=
refused "board 'c': the start instant is already past on its clock"

# ---- faults that cross boards -------------------------------------------------------
# started: until the three play (their status: the journal has frames)
started() {
	for b in $BOARDS; do
		[ -s "$T/$b.journal" ] && "$STRAND" journal "$T/$b.journal" 2>/dev/null |
			grep -q ',fired,' || return 1
	done
}
wait_started() {
	_i=0
	while ! started; do
		_i=$((_i + 1))
		[ $_i -lt 200 ] || return 1
		sleep 0.05
	done
}
# begin: the three play SCENE; 0 once each has fired a frame, else 1 (the
# case failed, the boards waited for). When they refused because ptp4l's
# offset was off for a moment (ptp_settle), that is said and they start once
# more; a second refusal fails.
begin() {
	for _try in 1 2; do
		ptp_settle 10 || { fail "ptp4l did not settle"; return 1; }
		for b in $BOARDS; do rm -f "$T/$b.journal"; play "$b" "$SCENE"; done
		wait_started && return 0
		wait_all
		[ $_try = 1 ] && said a "PTP is not locked: ptp4l's offset" || break
		echo "boards $CASE: first start refused: $(grep -o 'lockstep refused: .*' "$T/a.out" | head -n 1); once more"
	done
	fail "the boards never began"
	return 1
}

CASE=killed
if begin; then
	kill -9 "$PID_c"
	wait_all
	if [ "$RC_a$RC_b" != 77 ]; then
		fail "exit codes a $RC_a, b $RC_b, want 7"
	elif ! said a "board 'c' lost: no heartbeat for" || ! said b "board 'c' lost"; then
		fail "a or b does not name board c lost"
	else
		pass "a and b stopped under control: $(grep -o "board 'c' lost[^;]*" "$T/a.out" | head -n 1)"
	fi
fi

CASE=estop
if begin; then
	kill -USR1 "$PID_b"
	wait_all
	if [ "$RC_a$RC_b$RC_c" != 666 ]; then
		fail "exit codes a $RC_a, b $RC_b, c $RC_c, want 6 (e-stop)"
	elif ! said a "board 'b': e-stop: input 'estop_b'" || ! said c "board 'b': e-stop"; then
		fail "a or c does not name board b's e-stop"
	elif ! said a "every drive disabled at once"; then
		fail "a did not disable its drives at once"
	else
		# when each stopped, on the one clock: its tick 0 plus its tick (1 kHz)
		at() {
			_k=$(sed -n "s/.*$2 at tick \([0-9]*\).*/\1/p" "$T/$1.out" | head -n 1)
			_t0=$(sed -n 's/.*tick 0 at \([0-9]*\) ns.*/\1/p' "$T/$1.out" | head -n 1)
			echo $((_t0 + _k * 1000000))
		}
		tb=$(at b "input 'estop_b' ([^)]*)")
		ta=$(at a "disabled at once")
		tc=$(at c "disabled at once")
		da=$(echo "$ta $tb" | awk '{ printf "%.0f", ($1 - $2) / 1e6 }')
		dc=$(echo "$tc $tb" | awk '{ printf "%.0f", ($1 - $2) / 1e6 }')
		echo "BENCH lockstep_estop_crossed_ms $da $dc"
		pass "b e-stopped; a stopped at once $da ms later, c $dc ms later (ticks of 1 ms)"
	fi
fi

CASE=fault
cat "$SCENE" >"$T/fault.yaml"
# board b's drive: a Modbus unit in its namespace, served by strand-simdrive
sed -i 's|  - {name: drive_b, driver: sim}|  - {name: drive_b, driver: modbus, modbus: {tcp: {host: 127.0.0.1, port: 15020}, unit: 1, update_hz: 250, read_every: 20, axes: [{register: 0, type: int32}], status: {register: 10, fault_mask: 1}}}|' "$T/fault.yaml"
ip netns exec "$(ns b)" "$SIMDRIVE" "$T/fault.yaml" --device drive_b --trip-after 150 --quiet \
	>"$T/simdrive.out" 2>&1 &
sim=$!
sleep 0.3
ptp_settle 10 || fail "ptp4l did not settle"
for b in $BOARDS; do rm -f "$T/$b.journal"; play "$b" "$T/fault.yaml"; done
wait_all
kill "$sim" 2>/dev/null
if [ "$RC_a$RC_b$RC_c" != 777 ]; then
	fail "exit codes a $RC_a, b $RC_b, c $RC_c, want 7 (device fault)"
elif ! said b "device fault: device 'drive_b'" || ! said a "board 'b': device fault: device 'drive_b'" ||
	! said c "board 'b': device fault"; then
	fail "the fault is not named on every board"
else
	pass "b's drive tripped; a and c stopped under control: $(grep -o "board 'b': device fault[^;]*" "$T/a.out" | head -n 1)"
fi

[ $FAILED = 0 ] || exit 1
