#!/bin/sh
# build-gpio-sim.sh KDIR OUTDIR KBUILD PATCH - gpio-sim.ko for the kernel
# unpacked in KDIR (tests/vm/fetch-kernel.sh), built out of tree in OUTDIR.
#
# PATCH adds to gpio-sim a test wire from output lines to input lines
# (module parameter loopback=OUT,IN,...): see the patch.
#
# One change is needed to build at all: irq_sim.c hands a simulated
# interrupt on with handle_simple_irq(irq_to_desc(irqnum)), and irq_to_desc()
# is not exported to modules. generic_handle_irq(irqnum) looks the
# descriptor up itself and calls its flow handler, which irq_sim sets to
# handle_simple_irq: the same path, through exported symbols only.
set -eu
[ $# -eq 4 ] || { echo "usage: build-gpio-sim.sh KDIR OUTDIR KBUILD PATCH" >&2; exit 2; }
kdir=$(cd "$1" && pwd)
out=$2
kbuild=$3
patch=$(cd "$(dirname "$4")" && pwd)/$(basename "$4")
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
(cd "$out" && patch -p1 --quiet --no-backup-if-mismatch <"$patch") || {
	echo "build-gpio-sim: $patch does not apply to this kernel's gpio-sim.c" >&2
	exit 1
}

if ! make -C "$headers" M="$out" modules >"$out/build.log" 2>&1; then
	cat "$out/build.log" >&2
	echo "build-gpio-sim: module build failed (log: $out/build.log)" >&2
	exit 1
fi
[ -f "$out/gpio-sim.ko" ]
echo "build-gpio-sim: $out/gpio-sim.ko for $(basename "$headers")" >&2
