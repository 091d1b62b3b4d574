#!/bin/sh
# bench-ab.sh OTHER_LIB SCENES PAIRS -- LINK_COMMAND... - this build's core against another
# build's in one process (bench/scene_ab.c): copies OTHER_LIB (another tree's libmotion.a) with
# every symbol prefixed ab_, links scene_ab with it by LINK_COMMAND (the linker and this build's
# objects; `-o` and the copy are added here), and runs it for each scene, PAIRS pairs of plays
# each, under $BENCH_PREFIX. One AB line a scene.
#
#   sh mk/bench-ab.sh /tmp/old/libmotion.a "arm joints1000" 150 -- cc build/bench/... -lm
set -eu
if [ $# -lt 5 ] || [ "$4" != "--" ]; then
	echo "usage: bench-ab.sh OTHER_LIB SCENES PAIRS -- LINK_COMMAND..." >&2
	exit 2
fi
lib=$1 scenes=$2 pairs=$3
shift 4
if [ ! -f "$lib" ]; then
	echo "bench-ab: no $lib (build the other tree first: make BUILD=DIR DIR/libmotion.a)" >&2
	exit 2
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# every symbol, defined or not: the core's own calls stay inside the copy,
# and its one call out (memcpy) lands on scene_ab.c's ab_memcpy
objcopy --prefix-symbols=ab_ "$lib" "$out/other.a"
"$@" "$out/other.a" -o "$out/scene_ab"
for s in $scenes; do
	${BENCH_PREFIX:-} "$out/scene_ab" "$s" "$pairs"
done
