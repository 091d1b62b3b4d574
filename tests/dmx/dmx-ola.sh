#!/bin/sh
# SPDX-License-Identifier: MIT
# dmx-ola.sh STRAND WORKDIR - strand's DMX against real peers: Debian's olad
# (its E1.31 and Art-Net inputs, read back through ola-python) and tshark's
# sACN and Art-Net dissectors, in a network namespace of its own.
#
# olad never sees the machine's network: OLA 0.10's E1.31 plugin joins its
# multicast groups on the first interface that is not loopback, and its
# other network plugins bind there too (../VM.md's "DMX peers"). So this
# script re-runs itself under `unshare --net`, where the only interfaces
# are lo and a veth pair it makes (198.18.0.1 and .2, RFC 2544's benchmark
# range), refuses to go on if any other is there, runs olad as its own
# user with every plugin but E1.31 and Art-Net disabled, without its web
# server or DNS-SD, and runs strand there too. strand sends sACN to the
# universe's multicast group out of 198.18.0.2 and Art-Net to olad's
# 198.18.0.1, the destinations tests/dmx/lights.yaml names.
#
# Checks (tests/dmx/dmx_check.py): every frame olad hands its client equals
# `strand export --at ticks` for the tick in its tick slots (within half a
# count), none missing between the first and last frame; tshark decodes
# every packet as sACN or ArtDmx, not malformed, sequence numbers forward,
# the last three sACN packets marked stream terminated, and every packet
# strand sent addressed to a destination the scene names.
set -eu
[ $# -eq 2 ] || { echo "usage: dmx-ola.sh STRAND WORKDIR" >&2; exit 2; }
strand=$(realpath "$1")
work=$2
here=$(dirname "$(realpath "$0")")
if [ "${DMX_IN_NS:-}" != 1 ]; then
	mkdir -p "$work"
	work=$(realpath "$work")
	exec env DMX_IN_NS=1 timeout 120 unshare --net --fork sh "$0" "$strand" "$work"
fi
cd "$work"
rm -f frames.txt ready cap.pcap journal.j export.csv play.txt olad.log tshark.log
fail() { echo "dmx-ola: $*" >&2; exit 1; }

# ---- the namespace: lo and a veth pair, nothing else ----
ip link set lo up
ip link add dmx0 type veth peer name dmx1
ip addr add 198.18.0.1/24 dev dmx0
ip addr add 198.18.0.2/24 dev dmx1
ip link set dmx0 up
ip link set dmx1 up
# strand's multicast leaves dmx1 from 198.18.0.2 and comes back in on dmx0:
# a source address of this namespace's own, which Linux drops as a martian
# unless told to accept it (the namespace's own settings)
sysctl -q -w net.ipv4.conf.all.accept_local=1 net.ipv4.conf.dmx0.accept_local=1 \
	net.ipv4.conf.all.rp_filter=0 net.ipv4.conf.dmx0.rp_filter=0
# (ask netlink, not /sys/class/net: sysfs shows the namespace that mounted it)
for i in $(ip -o link show | awk -F': ' '{ sub(/@.*/, "", $2); print $2 }'); do
	case $i in
	lo | dmx0 | dmx1) ;;
	*) fail "interface $i in the test's namespace: refusing to start olad" ;;
	esac
done

# ---- olad: its own config, E1.31 and Art-Net only, on dmx0 ----
conf=$work/ola
rm -rf "$conf"
mkdir -p "$conf"
for p in artnet dummy e131 espnet ftdidmx gpio karate kinet milinst opendmx \
	openpixelcontrol osc pathport renard sandnet shownet spi stageprofi uartdmx usbdmx \
	usbpro dmx4linux nanoleaf; do
	echo "enabled = false" >"$conf/ola-$p.conf"
done
printf 'enabled = true\nip = 198.18.0.1\ninput_ports = 1\noutput_ports = 0\n%s\n' \
	'ignore_preview = true' >"$conf/ola-e131.conf"
printf 'enabled = true\nip = 198.18.0.1\nuse_limited_broadcast = false\n' >"$conf/ola-artnet.conf"
chown -R olad "$conf"
rpc=9011
setpriv --reuid olad --regid nogroup --clear-groups olad --config-dir "$conf" --no-http \
	--no-register-with-dns-sd --rpc-port $rpc -l ${OLA_LOG:-2} >olad.log 2>&1 &
olad=$!
tshark=""
reader=""
stop() {
	kill $olad 2>/dev/null || true
	[ -z "$tshark" ] || kill $tshark 2>/dev/null || true
	[ -z "$reader" ] || kill $reader 2>/dev/null || true
	wait 2>/dev/null || true
}
trap stop EXIT
n=0
until /usr/bin/python3 -c "import socket; socket.create_connection(('127.0.0.1', $rpc), 1)" \
	2>/dev/null; do
	n=$((n + 1))
	[ $n -lt 100 ] || fail "olad did not listen on port $rpc (olad.log: $(tail -n 3 olad.log))"
	kill -0 $olad 2>/dev/null || fail "olad ended: $(tail -n 5 olad.log)"
	sleep 0.1
done

# ---- tshark on both interfaces strand's packets cross ----
tshark -q -f 'udp' -i dmx1 -i lo -w cap.pcap >tshark.log 2>&1 &
tshark=$!
n=0
until grep -q "Capturing on" tshark.log 2>/dev/null; do
	n=$((n + 1))
	[ $n -lt 150 ] || fail "tshark did not start: $(cat tshark.log)"
	sleep 0.1
done

# ---- olad's client, then strand ----
/usr/bin/python3 "$here/ola_reader.py" $rpc frames.txt ready 1.0 30 &
reader=$!
n=0
until [ -e ready ]; do
	n=$((n + 1))
	[ $n -lt 100 ] || fail "olad's client did not register"
	kill -0 $reader 2>/dev/null || fail "olad's client ended (olad.log: $(tail -n 3 olad.log))"
	sleep 0.1
done
"$strand" play "$here/lights.yaml" --journal journal.j --priority 0 >play.txt 2>&1 ||
	fail "strand play: $(cat play.txt)"
wait $reader || fail "olad's client failed"
reader=""
sleep 0.3
kill -INT $tshark
wait $tshark || true
tshark=""
"$strand" journal journal.j >journal.csv
"$strand" export "$here/lights.yaml" --at ticks >export.csv
/usr/bin/python3 "$here/dmx_check.py" "$here/lights.yaml" frames.txt journal.csv export.csv \
	play.txt cap.pcap
