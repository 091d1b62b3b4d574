#!/bin/sh
# build-gpio-sim.sh KDIR OUTDIR KBUILD - gpio-sim.ko for the kernel unpacked in
# KDIR (tests/vm/fetch-kernel.sh), built out of tree in OUTDIR.
#
# One change to the kernel's own source: irq_sim.c hands a simulated
# interrupt on with handle_simple_irq(irq_to_desc(irqnum)), and irq_to_desc()
# is not exported to modules. generic_handle_irq(irqnum) looks the
# descriptor up itself and calls its flow handler, which irq_sim sets to
# handle_simple_irq: the same path, through exported symbols only.
set -eu
[ $# -eq 3 ] || { echo "usage: build-gpio-sim.sh KDIR OUTDIR KBUILD" >&2; exit 2; }
kdir=$(cd "$1" && pwd)
out=$2
kbuild=$3
headers=$(echo "$kdir"/usr/src/linux-headers-*-amd64)
[ -f "$headers/Makefile" ] || { echo "build-gpio-sim: no headers in $kdir" >&2; exit 1; }

rm -rf "$out"
mkdir -p "$out"
out=$(cd "$out" && pwd)
cp "$kdir/src/gpio-sim.c" "$out/gpio-sim-main.c"
cp "$kdir/src/gpiolib.h" "$kdir/src/irq_sim.c" "$out/"
cp "$kbuild" "$out/Kbuild"
old='handle_simple_irq(irq_to_desc(irqnum));'
new='generic_handle_irq(irqnum);'
grep -qF "$old" "$out/irq_sim.c" || {
	echo "build-gpio-sim: $kdir/src/irq_sim.c has no '$old' to replace" >&2
	exit 1
}
sed -i "s/handle_simple_irq(irq_to_desc(irqnum));/$new/" "$out/irq_sim.c"

if ! make -C "$headers" M="$out" modules >"$out/build.log" 2>&1; then
	cat "$out/build.log" >&2
	echo "build-gpio-sim: module build failed (log: $out/build.log)" >&2
	exit 1
fi
[ -f "$out/gpio-sim.ko" ]
echo "build-gpio-sim: $out/gpio-sim.ko for $(basename "$headers")" >&2
