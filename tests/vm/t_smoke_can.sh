#!/bin/sh
# The harness's CAN side works: vcan0 up, frames sent with cansend reach a
# candump that was listening before the first one (a CAN_RAW socket sees
# only frames sent after it is bound: the test waits for candump's receiver
# to show in /proc/net/can/rcvlist_all instead of sleeping).
# vm-timeout: 30
. /tests/lib.sh

ip link add dev vcan0 type vcan || fail "ip link add vcan0 type vcan"
ip link set up vcan0 || fail "ip link set up vcan0"
ip link show vcan0 | grep -q "mtu 72" || fail "vcan0 is not CAN FD (mtu 72): $(ip link show vcan0)"

bg candump -n 3 -ta vcan0 >/tmp/candump.out
dump=$!
wait_for 5 grep -q '^ *vcan0 .* raw$' /proc/net/can/rcvlist_all || fail "candump never listens on vcan0"
cansend vcan0 080# || fail "cansend SYNC"
cansend vcan0 601#2F60600008000000 || fail "cansend SDO"
cansend vcan0 '181##1.11223344' || fail "cansend CAN FD"
wait_for 5 lines_are 3 /tmp/candump.out || fail "candump saw $(wc -l </tmp/candump.out) frames, want 3"
wait "$dump"
cat /tmp/candump.out
awk 'NR == 1 && !($3 == "080" && $4 == "[0]") { exit 1 }
     NR == 2 && !($3 == "601" && $4 == "[8]" && $5 == "2F" && $12 == "00") { exit 1 }
     NR == 3 && !($3 == "181" && $4 == "[04]" && $5 == "11") { exit 1 }' /tmp/candump.out ||
	fail "frames in candump differ from those sent"
ip link del vcan0
pass "vcan0: SYNC, an SDO and a CAN FD frame through cansend and candump, in order"
