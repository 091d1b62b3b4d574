#!/bin/sh
# can-run.sh PKG... - exit 0 when `make test-vm` can run on this machine;
# else print why not, on one line, and exit 1 (mk/vm.mk: check-vm).
#
# The guest is amd64 and runs the host's own binaries, so the host must be
# amd64 too. The packages PKG... are installed by mk/deps.sh, which needs
# root; a user other than root can run the VM once they are there.
arch=$(dpkg --print-architecture 2>/dev/null || uname -m)
case $arch in
amd64 | x86_64) ;;
*) echo "the VM runs this host's binaries on an amd64 kernel; this host is $arch"; exit 1 ;;
esac
[ "$(id -u)" -eq 0 ] && exit 0
missing=""
for p in "$@"; do
	dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
		missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "not root, and packages are missing: sudo apt-get install -y$missing"
exit 1
