#!/bin/sh
# check-objects.sh NM ALLOW_RE OBJ... - what a freestanding target lacks,
# checked on the objects of the motion core (the idea of Klipper's
# scripts/check-software-div.sh).
#
# Fails, naming the symbol and the object, when
#   - an object references a symbol that no object of the set defines and
#     that does not match ALLOW_RE (an extended regular expression): the core
#     would need libc, libm or a runtime helper the target does not have;
#   - an object defines a symbol in a writable data section (.data, .bss,
#     small data, common): the core keeps no mutable file-scope or
#     static-local state. Constant tables live in .rodata and are fine.
#     Build without -fpic, where a const table of pointers is writable data.
# Prints the allowed undefined symbols it saw, so the report lists them.
set -eu
[ $# -ge 3 ] || { echo "usage: check-objects.sh NM ALLOW_RE OBJ..." >&2; exit 2; }
nm=$1
allow=$2
shift 2
# -A -P: "object: name type [value size]"; nm fails on a missing object.
syms=$("$nm" -A -P "$@")
status=0
report=$(printf '%s\n' "$syms" | ALLOW="$allow" awk '
	{
		obj = $1; sub(/:$/, "", obj); name = $2; type = $3
		if (type ~ /^[Uvw]$/) {
			nref++
			ref_obj[nref] = obj
			ref_name[nref] = name
			next
		}
		if (type ~ /^[A-Z]$/)
			defined[name] = 1
		if (type ~ /^[bBdDgGsSC]$/) {
			print "bad " obj ": " name " is mutable state (nm type " type ", a writable data section)"
			bad = 1
		}
	}
	END {
		# libgcc and ARM EABI floating-point helpers, named in the message
		fp = "^__aeabi_([fd]|u?[il]2[fd])|^__(fix|float)|^__[a-z]+[sdtx]f[0-9]?$|^__[a-z]+[sdtx]f[sdtx]f?[0-9]$"
		for (i = 1; i <= nref; i++) {
			n = ref_name[i]
			if (n in defined)
				continue
			if (n ~ ENVIRON["ALLOW"]) {
				print "allowed " n
				continue
			}
			why = n ~ fp ? "a floating-point helper" : "not available freestanding"
			print "bad " ref_obj[i] ": undefined symbol " n " (" why ")"
			bad = 1
		}
		exit bad
	}') || status=$?
printf '%s\n' "$report" | sed -n 's/^bad /check-objects: /p' >&2
allowed=$(printf '%s\n' "$report" | sed -n 's/^allowed //p' | sort -u | tr "\n" " " | sed "s/ $//")
echo "check-objects: $# object(s), allowed undefined: ${allowed:-none}"
exit $status
