#!/bin/sh
# check-cross.sh NAME=COMMAND... - run each digest program (all at once, they
# are single-threaded) and require one DIGEST line from all of them. On a
# disagreement, runs them again with -v and shows the digest of each
# workload, to find the one that differs.
set -eu
[ $# -ge 2 ] || { echo "usage: check-cross.sh NAME=COMMAND NAME=COMMAND..." >&2; exit 2; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
i=0
for arg in "$@"; do
	i=$((i + 1))
	# shellcheck disable=SC2086 # COMMAND is a runner and a program
	(
		rc=0
		start=$(date +%s)
		${arg#*=} >"$dir/$i.out" 2>"$dir/$i.err" || rc=$?
		echo $rc >"$dir/$i.rc"
		echo $(($(date +%s) - start)) >"$dir/$i.time"
	) &
done
wait
status=0
first=""
i=0
for arg in "$@"; do
	i=$((i + 1))
	name=${arg%%=*}
	digest=$(sed -n 's/^DIGEST \([0-9a-f]\{16\}\)$/\1/p' "$dir/$i.out")
	if [ "$(cat "$dir/$i.rc")" != 0 ] || [ -z "$digest" ]; then
		echo "check-cross: $name (${arg#*=}) failed, exit $(cat "$dir/$i.rc"):" >&2
		cat "$dir/$i.out" "$dir/$i.err" | tail -n 20 | sed 's/^/  /' >&2
		status=1
		continue
	fi
	printf 'DIGEST %s  %-11s %3s s  %s\n' "$digest" "$name" "$(cat "$dir/$i.time")" "${arg#*=}"
	[ -n "$first" ] || first=$digest
	[ "$digest" = "$first" ] || status=2
done
if [ $status -eq 2 ]; then
	echo "check-cross: the targets disagree; digest of each workload:" >&2
	for arg in "$@"; do
		echo "  ${arg%%=*}:" >&2
		# shellcheck disable=SC2086
		${arg#*=} -v 2>&1 | sed 's/^/    /' >&2 || true
	done
fi
[ $status -eq 0 ] || exit 1
echo "CROSS ok: $# builds agree, DIGEST $first"
