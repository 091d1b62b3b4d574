#!/bin/sh
# mkinitramfs.sh INIT OUT - the test VM's initramfs (newc cpio, gzip) in OUT,
# and OUT.tests, the names of the test scripts in it, in the order they run.
#
# From the environment, lists separated by blanks:
#   VM_MODULES  .ko files, copied to /lib/modules/ and loaded in this order
#   VM_MODULE_PARAMS  NAME.ko:PARAM=VALUE, for insmod
#   VM_BINS     programs, copied to /bin/, each with the shared libraries ldd
#               lists for it at the same paths (so the guest's loader finds
#               them without an ld.so.cache)
#   VM_FILES    DEST=SRC pairs, copied as they are
#   VM_TESTS    test scripts, copied to /tests/ and run in this order
#   VM_AGAIN    NAME@VARIANT: the test NAME run once more after them, with
#               /VARIANT/bin first on PATH (a second build of strand there)
# The rest is busybox (static), one symlink per applet.
set -eu
[ $# -eq 2 ] || { echo "usage: mkinitramfs.sh INIT OUT" >&2; exit 2; }
init=$1
out=$2
root=$out.root
rm -rf "$root"
mkdir -p "$root"/bin "$root"/sbin "$root"/lib/modules "$root"/tests "$root"/proc "$root"/sys \
	"$root"/dev "$root"/tmp "$root"/run "$root"/etc

# busybox: a symlink per applet, but none for busybox itself (a link to
# itself fails to exec with ELOOP).
cp /bin/busybox "$root/bin/busybox"
for a in $(/bin/busybox --list); do
	[ "$a" = busybox ] || ln -sf busybox "$root/bin/$a"
done
cp "$init" "$root/init"
chmod 755 "$root/init"

: >"$root/lib/modules/load.order"
for m in ${VM_MODULES:-}; do
	[ -f "$m" ] || { echo "mkinitramfs: no module $m" >&2; exit 1; }
	cp "$m" "$root/lib/modules/"
	name=$(basename "$m")
	params=""
	for p in ${VM_MODULE_PARAMS:-}; do
		[ "${p%%:*}" = "$name" ] && params="$params ${p#*:}"
	done
	echo "$name$params" >>"$root/lib/modules/load.order"
done

# A library at the path ldd names; /lib64 and /lib are symlinks into /usr on
# the host (merged /usr), plain directories in the guest.
copy_lib() {
	[ -e "$root$1" ] && return 0
	mkdir -p "$root$(dirname "$1")"
	cp -L "$1" "$root$1"
}
for b in ${VM_BINS:-}; do
	[ -x "$b" ] || { echo "mkinitramfs: no program $b" >&2; exit 1; }
	cp "$b" "$root/bin/"
	# "libx.so => /path (0x...)", "/lib64/ld-linux-x86-64.so.2 (0x...)"
	for l in $(ldd "$b" 2>/dev/null | sed -n 's|.*=> \(/[^ ]*\) .*|\1|p; s|^[[:space:]]*\(/[^ ]*\) .*|\1|p'); do
		copy_lib "$l"
	done
done

for f in ${VM_FILES:-}; do
	dest=${f%%=*}
	src=${f#*=}
	[ -e "$src" ] || { echo "mkinitramfs: no file $src" >&2; exit 1; }
	mkdir -p "$root$(dirname "$dest")"
	cp -R "$src" "$root$dest"
done

: >"$out.tests.new"
for t in ${VM_TESTS:-}; do
	cp "$t" "$root/tests/"
	basename "$t" .sh >>"$out.tests.new"
done
for a in ${VM_AGAIN:-}; do
	[ -f "$root/tests/${a%@*}.sh" ] || { echo "mkinitramfs: VM_AGAIN $a: no such test" >&2; exit 1; }
	echo "$a" >>"$out.tests.new"
done
cp "$out.tests.new" "$root/tests/list"

(cd "$root" && find . | LC_ALL=C sort | cpio -o -H newc -R 0:0 --quiet) | gzip -6 >"$out.new"
mv "$out.tests.new" "$out.tests"
mv "$out.new" "$out"
echo "mkinitramfs: $out, $(($(wc -c <"$out") / 1024)) KiB, $(wc -l <"$out.tests") test scripts" >&2
