#!/bin/sh
# fetch-kernel.sh ABI VERSION DIR - Debian's kernel ABI-amd64 at VERSION
# (image, headers, kbuild and source packages), downloaded with apt-get and
# unpacked with dpkg -x into DIR; nothing is installed. Leaves in DIR:
#   vmlinux               the uncompressed kernel (boots ~3 s faster under
#                         TCG than vmlinuz: CONFIG_PVH lets qemu jump in)
#   lib/modules/ABI-amd64 the modules, and modules -> that folder
#   usr/src/linux-headers-ABI-amd64, usr/lib/linux-kbuild-*: to build modules
#   src/                  gpio-sim.c, gpiolib.h and irq_sim.c from linux-source
#   .done                 written last: "ABI VERSION" of what DIR holds
#
# ABI and VERSION are a pin, not a requirement: Debian's mirror keeps only
# the kernel linux-image-amd64 depends on now, so a pin goes stale with each
# point release. When the pinned version cannot be downloaded, the current
# one is taken instead and a NOTE says so (move the pin in mk/vm.mk to
# silence it); the tests still run, on a kernel of the same series.
set -eu
[ $# -eq 3 ] || { echo "usage: fetch-kernel.sh ABI VERSION DIR" >&2; exit 2; }
abi=$1
ver=$2
dir=$3
rm -rf "$dir"
mkdir -p "$dir/dl"
dir=$(cd "$dir" && pwd)

# fetch ABI VERSION: download the five packages of that kernel into dl/.
fetch() {
	series=$(echo "$2" | cut -d. -f1,2)   # 6.1.192-2 -> 6.1
	rm -f "$dir"/dl/*.deb
	# As root, apt's download sandbox user cannot write to the cache: run
	# the download as root, which is who asked for it.
	(cd "$dir/dl" && for p in "linux-image-$1-amd64" "linux-headers-$1-amd64" \
		"linux-headers-$1-common" "linux-kbuild-$series" "linux-source-$series"; do
		echo "$p=$2"; done |
		xargs apt-get -q -o APT::Sandbox::User=root download >"$dir/dl/apt.log" 2>&1)
}
# current: "ABI VERSION" of the kernel linux-image-amd64 depends on now.
current() {
	apt-cache show linux-image-amd64 2>/dev/null |
		sed -n 's/^Depends: linux-image-\([^ ]*\)-amd64 (= \(.*\))$/\1 \2/p' |
		head -n 1
}
if ! fetch "$abi" "$ver"; then
	apt-get -q update >/dev/null 2>&1 || true
	if ! fetch "$abi" "$ver"; then
		pinned="$abi $ver"
		now=$(current)
		if [ -z "$now" ] || [ "$now" = "$pinned" ] || ! fetch $now; then
			cat "$dir/dl/apt.log" >&2
			echo "fetch-kernel: Debian kernel $abi-amd64 $ver cannot be downloaded," \
				"nor the current one (${now:-unknown}): is the Debian mirror reachable?" >&2
			exit 1
		fi
		abi=${now% *}
		ver=${now#* }
		echo "fetch-kernel: NOTE the pinned kernel $pinned is gone from the mirror;" \
			"using the current one, $abi $ver (move VM_KERNEL_ABI and" \
			"VM_KERNEL_VERSION in mk/vm.mk to it)" >&2
	fi
fi
flavour=$abi-amd64
series=$(echo "$ver" | cut -d. -f1,2)

echo "fetch-kernel: unpacking Debian kernel $flavour $ver into $dir" >&2
for deb in "$dir"/dl/*.deb; do
	case $deb in
	*linux-source-*) dpkg-deb --fsys-tarfile "$deb" |
		tar -x -C "$dir" "./usr/src/linux-source-$series.tar.xz" ;;
	*) dpkg -x "$deb" "$dir" ;;
	esac
done

# The headers' Makefile includes the common tree by its absolute path under
# /usr/src; point it at the unpacked one.
mk=$dir/usr/src/linux-headers-$flavour/Makefile
sed -i "s|^include /usr/src/|include $dir/usr/src/|" "$mk"
grep -q "^include $dir/usr/src/linux-headers-$abi-common/Makefile" "$mk" || {
	echo "fetch-kernel: unexpected $mk:" >&2
	cat "$mk" >&2
	exit 1
}

# The three gpio-sim sources; the rest of the source tree is not needed.
mkdir -p "$dir/src"
tar -xJf "$dir/usr/src/linux-source-$series.tar.xz" -C "$dir/src" --strip-components=3 \
	"linux-source-$series/drivers/gpio/gpio-sim.c" \
	"linux-source-$series/drivers/gpio/gpiolib.h"
tar -xJf "$dir/usr/src/linux-source-$series.tar.xz" -C "$dir/src" --strip-components=3 \
	"linux-source-$series/kernel/irq/irq_sim.c"
rm -f "$dir/usr/src/linux-source-$series.tar.xz"

# vmlinux: the XZ stream inside vmlinuz, found by its magic FD 37 7A 58 5A 00.
vmlinuz=$dir/boot/vmlinuz-$flavour
off=$(LC_ALL=C grep -obUaP '\xfd7zXZ\x00' "$vmlinuz" | head -n 1 | cut -d: -f1)
[ -n "$off" ] || { echo "fetch-kernel: no XZ stream in $vmlinuz" >&2; exit 1; }
tail -c +$((off + 1)) "$vmlinuz" | xz -dc --single-stream >"$dir/vmlinux"
case $(od -An -tx1 -N4 "$dir/vmlinux" | tr -d ' ') in
7f454c46) ;;
*) echo "fetch-kernel: what came out of $vmlinuz is not an ELF kernel" >&2; exit 1 ;;
esac

ln -s "lib/modules/$flavour" "$dir/modules"
rm -rf "$dir/dl"
echo "$abi $ver" >"$dir/.done"
