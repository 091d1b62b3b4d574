#!/bin/sh
# check-includes.sh FILE... - a file of the motion core may include only the
# headers beside it ("name.h") and <stdint.h>, <stddef.h>, <stdbool.h>.
# Anything else (libc, hal/, a path, a macro) is printed with its line and
# fails.
set -eu
[ $# -ge 1 ] || { echo "usage: check-includes.sh FILE..." >&2; exit 2; }
for f in "$@"; do
	[ -r "$f" ] || { echo "check-includes: cannot read $f" >&2; exit 2; }
done
bad=$(for f in "$@"; do
	dir=$(dirname "$f")
	# "lineno:text" of every include directive, however it is spaced
	grep -n '^[[:space:]]*#[[:space:]]*include' "$f" | while IFS= read -r line; do
		hdr=$(printf '%s\n' "${line#*:}" | sed -n \
			's/^[[:space:]]*#[[:space:]]*include[[:space:]]*\([<"][^>"]*[>"]\)[[:space:]]*\(\/[*/].*\)\{0,1\}$/\1/p')
		case $hdr in
		"<stdint.h>" | "<stddef.h>" | "<stdbool.h>")
			continue ;;
		\"*.h\")
			name=${hdr#\"}
			name=${name%\"}
			case $name in
			*/*) ;;
			*) [ -f "$dir/$name" ] && continue ;;
			esac ;;
		esac
		echo "check-includes: $f:${line%%:*}: not allowed in the core: ${line#*:}"
	done
done)
if [ -n "$bad" ]; then
	printf '%s\n' "$bad" >&2
	exit 1
fi
echo "check-includes: $# file(s) include only their own headers and <stdint.h> <stddef.h> <stdbool.h>"
