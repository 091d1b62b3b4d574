#!/bin/sh
# fetch-gpiod2.sh DIR - Debian 13's libgpiod-dev (libgpiod 2.x: its static
# library and headers) from Debian's archive, unpacked into DIR/root with
# dpkg -x; nothing is installed. apt-get runs on a state of its own under
# DIR (a sources list naming trixie, its own lists and cache), so the
# machine's apt sees none of it. Leaves in DIR:
#   root/usr/include/gpiod.h, root/usr/lib/<triplet>/libgpiod.a
#   .done   written last: the package's version
#
# libgpiod.a links statically against Debian 12's C library: the second
# strand mk/gpiod2.mk builds with it runs on this machine and in the VM.
# The archive keeps only trixie's current version, so none is pinned: any
# 2.x is taken, and the version said.
set -eu
[ $# -eq 1 ] || { echo "usage: fetch-gpiod2.sh DIR" >&2; exit 2; }
dir=$1
rm -rf "$dir"
mkdir -p "$dir/etc" "$dir/lists/partial" "$dir/cache/archives/partial" "$dir/dl"
dir=$(cd "$dir" && pwd)
mirror=http://deb.debian.org/debian
echo "deb [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] $mirror trixie main" \
	>"$dir/etc/sources.list"
# As root, apt's download sandbox user cannot write here: run as who asked.
set -- -q -o "Dir::Etc::SourceList=$dir/etc/sources.list" -o Dir::Etc::SourceParts=/nonexistent \
	-o Dir::Etc::Preferences=/nonexistent -o Dir::Etc::PreferencesParts=/nonexistent \
	-o "Dir::State::Lists=$dir/lists" -o "Dir::Cache=$dir/cache" -o APT::Sandbox::User=root
if ! apt-get "$@" update >"$dir/apt.log" 2>&1 || grep -q '^[EW]:' "$dir/apt.log"; then
	cat "$dir/apt.log" >&2
	echo "fetch-gpiod2: Debian 13's archive ($mirror trixie) cannot be read (apt-get update" \
		"above); the libgpiod 2 build and its VM tests need it" >&2
	exit 1
fi
if ! (cd "$dir/dl" && apt-get "$@" download libgpiod-dev/trixie) >>"$dir/apt.log" 2>&1; then
	cat "$dir/apt.log" >&2
	echo "fetch-gpiod2: libgpiod-dev cannot be downloaded from Debian 13's archive" >&2
	exit 1
fi
deb=$(ls "$dir"/dl/libgpiod-dev_*.deb)
ver=$(dpkg-deb -f "$deb" Version)
case $ver in
2.*) ;;
*) echo "fetch-gpiod2: Debian 13's libgpiod-dev is $ver, not 2.x" >&2; exit 1 ;;
esac
dpkg -x "$deb" "$dir/root"
lib=$(find "$dir/root" -name libgpiod.a | head -n 1)
[ -f "$dir/root/usr/include/gpiod.h" ] && [ -n "$lib" ] || {
	echo "fetch-gpiod2: $deb holds no gpiod.h or libgpiod.a" >&2
	exit 1
}
ln -sf "${lib#"$dir"/}" "$dir/libgpiod.a"
rm -rf "$dir/dl" "$dir/lists" "$dir/cache"
echo "fetch-gpiod2: libgpiod-dev $ver from Debian 13, unpacked into $dir/root" >&2
echo "$ver" >"$dir/.done"
