#!/bin/sh
# check-includes.sh FILE... - the motion core's line of the layer table
# (mk/layers.txt) applied to FILEs: a file of the core may include only the
# headers beside it ("name.h") and <stdint.h>, <stddef.h>, <stdbool.h>.
# `mk/layers.sh check` applies every line of the table to every folder;
# this is its one-folder form, for the freestanding self-test.
set -eu
[ $# -ge 1 ] || { echo "usage: check-includes.sh FILE..." >&2; exit 2; }
here=$(dirname "$0")
args=
for f in "$@"; do
	[ -r "$f" ] || { echo "check-includes: cannot read $f" >&2; exit 2; }
	args="$args motion=$f"
done
# shellcheck disable=SC2086 # one word per file
exec sh "$here/layers.sh" check "$here/layers.txt" ". firmware" $args
