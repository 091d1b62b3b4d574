#!/bin/sh
# soak.sh STRAND - every example played for 24 hours of virtual time on the
# simulated rig (looping where the scene is shorter), each as one run of
# strand play: it must end as the duration says (exit 0, "duration
# reached"), having fired every frame of every pass. One BENCH line each
# for its frames, ticks and wall time, then the totals.
set -eu
strand=$1
dir=${TMPDIR:-/tmp}/strand-soak.$$
mkdir -p "$dir"
trap 'rm -rf "$dir"' EXIT
scenes=0 frames=0 ticks=0
start=$(date +%s.%N)
for ex in examples/*.yaml; do
	name=$(basename "$ex" .yaml)
	t0=$(date +%s.%N)
	rc=0
	"$strand" play "$ex" --sim --clock virtual --no-mlock --loop --duration 86400 \
		--journal "$dir/$name.journal" >"$dir/$name.out" 2>&1 || rc=$?
	t1=$(date +%s.%N)
	if [ $rc != 0 ] || ! grep -q 'duration reached' "$dir/$name.out"; then
		cat "$dir/$name.out"
		echo "FAIL soak $name: exit $rc"
		exit 1
	fi
	f=$(sed -n 's/.*frames fired \([0-9]*\), ticks \([0-9]*\).*/\1/p' "$dir/$name.out")
	k=$(sed -n 's/.*frames fired [0-9]*, ticks \([0-9]*\).*/\1/p' "$dir/$name.out")
	rows=$("$strand" journal "$dir/$name.journal" | tail -n +2 | wc -l)
	[ "$rows" = "$f" ] || { echo "FAIL soak $name: $rows journal rows, $f frames fired"; exit 1; }
	wall=$(echo "$t0 $t1" | awk '{ printf "%.1f", $2 - $1 }')
	echo "BENCH soak_${name}_frames $f"
	echo "BENCH soak_${name}_ticks $k"
	echo "BENCH soak_${name}_wall_s $wall"
	scenes=$((scenes + 1)) frames=$((frames + f)) ticks=$((ticks + k))
	rm -f "$dir/$name.journal"
done
end=$(date +%s.%N)
echo "BENCH soak_scenes $scenes"
echo "BENCH soak_frames $frames"
echo "BENCH soak_ticks $ticks"
echo "BENCH soak_wall_s $(echo "$start $end" | awk '{ printf "%.1f", $2 - $1 }')"
echo "PASS soak: $scenes examples, 24 h of virtual time each, every frame journaled"
