#!/bin/sh
# check-rt.sh OBJDUMP TRUSTED OBJ|ARCHIVE... - the real-time boundary, checked on
# the objects as modpost checks the kernel's sections: every reference made
# from the section .text.strand_rt (the functions tagged STRAND_RT,
# hal/rt.h) must go to
#   - code in .text.strand_rt itself, of this object or another one;
#   - a function of TRUSTED (an archive or object, or "-" for none): the
#     motion core, which `make check-freestanding` proves allocation- and
#     libc-free; and a copy of a static inline function of a HEADER of it
#     (-H), which the compiler may keep in the calling object (-O0,
#     -fno-inline, -Os) under the header's own name;
#   - data of any kind (tables, state, strings: reading and writing memory
#     is what rt code does);
#   - a name outside the project that an allow line of mk/check-rt.list
#     matches (each says why it is safe in the loop).
# Anything else fails the check, naming the object, the rt function and
# what it references: a deny line's category (an allocator, stdio, a lock, a
# call that may sleep), a function of the project that is not STRAND_RT, or
# a name on neither list. A call through a function pointer leaves no
# reference: that is why every [rt] operation of an ops table is tagged.
#
# Every OBJ is read, tagged or not, so that a call into another object is
# judged by where its target is. The relocations are read with objdump -r:
# a call to a static function of another section may be written as the
# section's symbol plus an offset (x86_64: R_X86_64_PC32 .text+0x2c, the
# target 4 bytes on), which is mapped back to the function through the
# symbol table; one that cannot be mapped is refused, not guessed.
# Fails, too, when no OBJ has a function in .text.strand_rt (the tag
# defined away, the wrong objects) and when a function is named strand_rt
# (-ffunction-sections would put it in the section; hal/rt.h).
# Prints the allowed names it saw and the motion functions called.
set -eu
usage="usage: check-rt.sh [-H HEADER]... OBJDUMP TRUSTED|- OBJ|ARCHIVE..."
hdrs=
while [ $# -gt 0 ] && [ "$1" = -H ]; do
	[ $# -ge 2 ] || { echo "$usage" >&2; exit 2; }
	hdrs="$hdrs $2"
	shift 2
done
[ $# -ge 3 ] || { echo "$usage" >&2; exit 2; }
objdump=$1
trusted=$2
shift 2
list=$(dirname "$0")/check-rt.list
[ -r "$list" ] || { echo "check-rt: cannot read $list" >&2; exit 2; }

# Three streams, one after the other, for one awk: the lists, the trusted
# symbols, the objects' symbols and relocations (objdump fails on a missing
# object, and so does the check).
tmp=${TMPDIR:-/tmp}/check-rt.$$
trap 'rm -f "$tmp"' EXIT
{
	echo "@@list"
	sed -e 's/#.*//' -e '/^[[:space:]]*$/d' "$list"
	echo "@@trusted"
	[ "$trusted" = - ] || "$objdump" -t "$trusted"
	echo "@@inlines"
	# shellcheck disable=SC2086
	[ -z "$hdrs" ] || sed -n \
		's/^static inline[^(]*[ *]\([A-Za-z_][A-Za-z0-9_]*\)(.*/\1/p' $hdrs
	echo "@@objects"
	# one at a time: an archive's members are named "ARCHIVE(MEMBER)", and
	# objdump says where an archive starts, not where it ends
	for o in "$@"; do
		"$objdump" -t -r "$o"
		echo "@@objects"
	done
} >"$tmp"

status=0
report=$(awk -v rtsec=.text.strand_rt '
	function hex(s,    i, n) {
		s = tolower(s)
		sub(/^0x/, "", s)
		n = 0
		for (i = 1; i <= length(s); i++)
			n = n * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1
		return n
	}
	# objdump -t: "VALUE FLAGS SECTION<TAB>SIZE NAME", FLAGS 7 columns wide
	function sym(line,    rest, a, n) {
		s_val = $1
		rest = substr(line, length($1) + 2)
		s_flags = substr(rest, 1, 7)
		rest = substr(rest, 9)
		n = index(rest, "\t")
		s_sec = substr(rest, 1, n - 1)
		rest = substr(rest, n + 1)
		n = split(rest, a, " ")
		s_size = a[1]
		s_name = a[n] # after .hidden or .protected, if any
	}
	# The function of OBJ whose bytes in section SEC hold offset OFF, or "".
	function fn_at(obj, sec, off,    k, i) {
		k = obj SUBSEP sec
		for (i = 1; i <= nfn[k]; i++)
			if (off >= fnv[k, i] && off < fnv[k, i] + fns[k, i])
				return fnn[k, i]
		return ""
	}
	# The function GCC made a copy of: foo for foo.constprop.0, foo.isra.1
	function clone_of(n) {
		sub(/\.(constprop|isra|part)\.[0-9]+$/, "", n)
		return n
	}
	# Is the untagged NAME referenced from OBJ on a ref line?
	function excused(obj, name,    j, o) {
		for (j = 1; j <= nref; j++) {
			o = ref_obj[j]
			if (name == ref_name[j] && (obj == o || substr(obj, length(obj) - length(o)) == "/" o)) {
				ref_used[j] = 1
				return 1
			}
		}
		return 0
	}
	function bad(obj, fn, what) {
		if ((obj, fn, what) in said)
			return
		said[obj, fn, what] = 1
		print "bad " obj ": " fn " references " what
	}
	$0 == "@@list" { part = "list"; next }
	$0 == "@@trusted" { part = "trusted"; next }
	$0 == "@@inlines" { part = "inlines"; next }
	part == "inlines" && $0 !~ /^@@/ { trust_inline[$1] = 1; next }
	$0 == "@@objects" { part = "objects"; arch = ""; next }
	part == "list" {
		if ($1 == "ref") {
			# ref OBJECT NAME WHY: rt code of the object (a path
			# suffix) may reference the untagged NAME
			nref++
			ref_obj[nref] = $2; ref_name[nref] = $3
			next
		}
		kind = $1; re = $2
		why = $0; sub(/^[^ ]+ +[^ ]+ */, "", why)
		nlist++
		l_kind[nlist] = kind; l_re[nlist] = "^(" re ")$"; l_why[nlist] = why
		next
	}
	/^In archive / { arch = $3; sub(/:$/, "", arch); next }
	/:[ \t]+file format / {
		obj = $1; sub(/:$/, "", obj)
		if (part == "objects") {
			if (arch != "") obj = arch "(" obj ")"
			nobj++
			objs[nobj] = obj
		}
		mode = ""
		next
	}
	/^SYMBOL TABLE:/ { mode = "sym"; next }
	/^RELOCATION RECORDS FOR \[/ {
		mode = "rel"
		relsec = $0; sub(/^RELOCATION RECORDS FOR \[/, "", relsec); sub(/\]:$/, "", relsec)
		next
	}
	mode == "sym" && NF >= 4 {
		sym($0)
		if (s_sec == "*UND*" || s_sec == "*ABS*")
			next
		global = substr(s_flags, 1, 1) ~ /[gu]/ || substr(s_flags, 2, 1) == "w"
		isfn = substr(s_flags, 7, 1) == "F"
		if (part == "trusted") {
			if (global && isfn)
				trust[s_name] = 1
			next
		}
		k = obj SUBSEP s_name
		sec[k] = s_sec
		if (substr(s_flags, 6, 1) == "d" && s_name == s_sec)
			secsym[k] = 1
		if (global) {
			gsec[s_name] = s_sec
			gobj[s_name] = obj
		}
		if (isfn) {
			ks = obj SUBSEP s_sec
			nfn[ks]++
			fnv[ks, nfn[ks]] = hex(s_val)
			fns[ks, nfn[ks]] = hex(s_size)
			fnn[ks, nfn[ks]] = s_name
			if (s_sec == rtsec) {
				nrt++
				if (!(obj in rtobj)) { rtobj[obj] = 1; nrtobj++ }
			}
			if (s_name == "strand_rt")
				print "bad " obj ": a function named strand_rt (-ffunction-sections would put it in " rtsec ")"
		}
		next
	}
	mode == "rel" && relsec == rtsec && $1 ~ /^[0-9a-fA-F]+$/ && NF >= 3 {
		nrel++
		r_obj[nrel] = obj; r_off[nrel] = hex($1); r_type[nrel] = $2; r_val[nrel] = $3
		next
	}
	END {
		for (i = 1; i <= nrel; i++) {
			obj = r_obj[i]
			fn = fn_at(obj, rtsec, r_off[i])
			if (fn == "")
				fn = rtsec "+0x" sprintf("%x", r_off[i])
			v = r_val[i]; add = 0
			if (match(v, /[+-]0x[0-9a-fA-F]+$/)) {
				add = hex(substr(v, RSTART + 1))
				if (substr(v, RSTART, 1) == "-")
					add = -add
				v = substr(v, 1, RSTART - 1)
			}
			k = obj SUBSEP v
			if (k in sec) {
				# defined in this object: code of another section is
				# an untagged function, anything else data
				s = sec[k]
				if (s == rtsec || s !~ /^\.text/)
					continue
				name = v
				if (k in secsym) {
					# PC-relative on x86_64: the field is 4 bytes
					# before the end of the instruction
					bias = r_type[i] ~ /^R_(X86_64|386)_(PC32|PLT32)$/ ? 4 : 0
					name = fn_at(obj, s, add + bias)
					if (name == "")
						name = fn_at(obj, s, add)
					if (name == "") {
						bad(obj, fn, s "+0x" sprintf("%x", add + bias) ", code that is no function of the symbol table (cannot tell which)")
						continue
					}
				}
				if (clone_of(name) in trust_inline)
					trusted_seen[clone_of(name)] = 1
				else if (!excused(obj, name))
					bad(obj, fn, name ", a function of the project that is not STRAND_RT (" s " of this object)")
				continue
			}
			if (v in gsec) {
				s = gsec[v]
				if (s == rtsec || s !~ /^\.text/)
					continue
				if (!excused(obj, v))
					bad(obj, fn, v ", a function of the project that is not STRAND_RT (" s " of " gobj[v] ")")
				continue
			}
			if (v in trust) {
				trusted_seen[v] = 1
				continue
			}
			for (j = 1; j <= nlist; j++)
				if (v ~ l_re[j])
					break
			if (j > nlist)
				bad(obj, fn, v ", which is not on the allow-list (mk/check-rt.list)")
			else if (l_kind[j] == "deny")
				bad(obj, fn, v " (" l_why[j] ")")
			else
				allowed_seen[v] = 1
		}
		# a ref line whose object was checked and that excused nothing
		# is stale: the reference it was for has gone
		for (j = 1; j <= nref; j++) {
			if (ref_used[j])
				continue
			for (i = 1; i <= nobj; i++) {
				o = ref_obj[j]
				if (objs[i] == o || substr(objs[i], length(objs[i]) - length(o)) == "/" o) {
					print "bad " objs[i] ": the ref line for " ref_name[j] " in mk/check-rt.list excuses nothing: remove it"
					break
				}
			}
		}
		if (!nrt)
			print "bad no function in " rtsec " in " nobj " object(s): is STRAND_RT defined away, or are these the wrong objects?"
		for (v in allowed_seen) print "allowed " v
		for (v in trusted_seen) print "trusted " v
		printf "count %d %d %d\n", nobj, nrt, nrtobj
	}' "$tmp")
printf '%s\n' "$report" | sed -n 's/^bad /check-rt: /p' >&2
printf '%s\n' "$report" | grep -q '^bad' && status=1
allowed=$(printf '%s\n' "$report" | sed -n 's/^allowed //p' | sort | tr "\n" " " | sed "s/ $//")
ntrusted=$(printf '%s\n' "$report" | grep -c '^trusted ' || true)
# shellcheck disable=SC2046 # three numbers, split on purpose
set -- $(printf '%s\n' "$report" | sed -n 's/^count //p')
echo "check-rt: $1 object(s), $2 rt function(s) in $3 of them; allowed outside the project: ${allowed:-none}; motion functions called: $ntrusted"
exit $status
