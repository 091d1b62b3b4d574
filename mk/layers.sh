#!/bin/sh
# layers.sh - the layer table (mk/layers.txt) applied.
#
#   layers.sh check TABLE ROOTS [FOLDER=FILE...]
#       Every quoted and angle include of every .c and .h in every folder of
#       TABLE, checked against what the table lets that folder see. With
#       FOLDER=FILE arguments, only those files, each checked as if it were
#       in FOLDER (the self-tests put a file where it does not belong).
#       Fails, printing FILE:LINE and the edge, on an include the table does
#       not allow, a bare name that is not a sibling, a header that does not
#       exist, a folder with sources that the table does not list, and a
#       table that is not a DAG.
#   layers.sh views TABLE ROOTS OUT
#       For each folder F of TABLE, OUT/F/ (F with '/' as '-': hal-gpio) holds links to the headers of
#       every folder F reaches through the table (its transitive closure)
#       and nothing else: compiled with -iquote OUT/F, a file of F that
#       includes a header from above it does not compile.
#
# ROOTS: the directories a folder's name is looked up in, first match
# first ("." then "firmware": scene is firmware/scene, hal/gpio is
# hal/gpio). A folder's headers are its *.h, not its sub-folders'.
set -eu
[ $# -ge 3 ] || { echo "usage: layers.sh check|views TABLE ROOTS [...]" >&2; exit 2; }
cmd=$1
table=$2
roots=$3
shift 3
[ -r "$table" ] || { echo "layers: cannot read $table" >&2; exit 2; }

# the table without comments: "FOLDER ENTRY..." per line
rows=$(sed -e 's/#.*//' -e '/^[[:space:]]*$/d' "$table")

# dir_of NAME: the directory a folder name stands for, or nothing
dir_of() {
	for r in $roots; do
		if [ -d "$r/$1" ]; then
			if [ "$r" = . ]; then echo "$1"; else echo "$r/$1"; fi
			return
		fi
	done
}

# closure: "FOLDER REACHED..." per line, or a cycle on stderr (exit 1)
closure() {
	printf '%s\n' "$rows" | awk '
	{
		f = $1; folders[++n] = f
		for (i = 2; i <= NF; i++) {
			e = $i
			if (e ~ /^</) continue
			if (e ~ /\.h$/) sub(/\/[^\/]*$/, "", e)
			edge[f] = edge[f] " " e
		}
	}
	function visit(f, path,    k, es, m) {
		if (state[f] == 2) return
		if (state[f] == 1) { print "layers: the table has a cycle: " path " " f > "/dev/stderr"; bad = 1; return }
		state[f] = 1
		m = split(edge[f], es, " ")
		for (k = 1; k <= m; k++) {
			visit(es[k], path " " f)
			reach[f] = reach[f] " " es[k] reach[es[k]]
		}
		state[f] = 2
	}
	END {
		for (i = 1; i <= n; i++) visit(folders[i], "")
		if (bad) exit 1
		for (i = 1; i <= n; i++) {
			f = folders[i]; m = split(reach[f], es, " "); delete seen; line = f
			for (k = 1; k <= m; k++) if (!(es[k] in seen)) { seen[es[k]] = 1; line = line " " es[k] }
			print line
		}
	}'
}

case $cmd in
views)
	[ $# -eq 1 ] || { echo "usage: layers.sh views TABLE ROOTS OUT" >&2; exit 2; }
	out=$1
	reach=$(closure)
	rm -rf "$out"
	printf '%s\n' "$reach" | while read -r f seen; do
		v=$out/$(printf '%s' "$f" | tr / -)
		mkdir -p "$v"
		for g in $seen; do
			d=$(dir_of "$g")
			[ -n "$d" ] || { echo "layers: $table: no folder '$g'" >&2; exit 1; }
			mkdir -p "$v/$g"
			for h in "$d"/*.h; do
				[ -e "$h" ] || continue
				ln -s "$(cd "$(dirname "$h")" && pwd)/$(basename "$h")" "$v/$g/"
			done
		done
	done
	echo "layers: views of $(printf '%s\n' "$reach" | wc -l | tr -d ' ') folders in $out"
	;;
check)
	closure >/dev/null
	if [ $# -gt 0 ]; then
		list=$(for a in "$@"; do echo "${a%%=*} ${a#*=}"; done)
	else
		list=$(printf '%s\n' "$rows" | while read -r f rest; do
			d=$(dir_of "$f")
			[ -n "$d" ] || { echo "layers: $table: no folder '$f'" >&2; exit 1; }
			for s in "$d"/*.c "$d"/*.h; do [ -e "$s" ] && echo "$f $s"; done
		done)
		# every folder with sources is in the table
		# (under ".", only the trees the table's folders are in)
		tops=$(printf '%s\n' "$rows" | while read -r f rest; do
			[ -d "./$f" ] && echo "${f%%/*}"
		done | sort -u)
		for r in $roots; do
			if [ "$r" = . ]; then
				for t in $tops; do find "$t" -type d; done
			elif [ -d "$r" ]; then
				find "$r" -mindepth 1 -type d
			fi
		done | sort -u | while read -r d; do
			[ -n "$(find "$d" -maxdepth 1 -name '*.[ch]')" ] || continue
			name=$d
			for r in $roots; do
				[ "$r" != . ] && case $d in "$r"/*) name=${d#"$r"/} ;; esac
			done
			printf '%s\n' "$rows" | awk -v n="$name" '$1 == n { ok = 1 } END { exit !ok }' ||
				echo "missing $d"
		done >"${TMPDIR:-/tmp}/layers.$$"
		if [ -s "${TMPDIR:-/tmp}/layers.$$" ]; then
			sed 's/^missing \(.*\)/layers: \1 has sources but no line in the table/' \
				"${TMPDIR:-/tmp}/layers.$$" >&2
			rm -f "${TMPDIR:-/tmp}/layers.$$"
			exit 1
		fi
		rm -f "${TMPDIR:-/tmp}/layers.$$"
	fi
	# "FOLDER FILE LINENO INCLUDE" for every include, then judged by awk
	bad=$(printf '%s\n' "$list" | while read -r f file; do
		grep -n '^[[:space:]]*#[[:space:]]*include' "$file" | while IFS= read -r l; do
			inc=$(printf '%s\n' "${l#*:}" | sed -n \
				's/^[[:space:]]*#[[:space:]]*include[[:space:]]*\([<"][^>"]*[>"]\).*$/\1/p')
			printf '%s %s %s %s\n' "$f" "$file" "${l%%:*}" "${inc:-?}"
		done
	done | while read -r f file line inc; do
		case $inc in
		'<'*) ;;
		'"'*'"')
			name=${inc#\"}
			name=${name%\"}
			case $name in
			*/*)
				d=$(dir_of "${name%/*}")
				if [ -z "$d" ] || [ ! -f "$d/${name##*/}" ]; then
					echo "$file:$line: $inc: no such header"
					continue
				fi ;;
			*)
				[ -f "$(dirname "$file")/$name" ] ||
					echo "$file:$line: $inc: a bare name is a sibling, and there is none"
				continue ;;
			esac ;;
		*) echo "$file:$line: not a plain #include \"...\" or <...>"; continue ;;
		esac
		printf '%s\n' "$rows" | awk -v f="$f" -v inc="$inc" -v where="$file:$line" '
			$1 == f {
				found = 1
				for (i = 2; i <= NF; i++) {
					if (inc ~ /^</) { if ($i == "<*>" || $i == inc) ok = 1; continue }
					name = substr(inc, 2, length(inc) - 2)
					dir = name; sub(/\/[^\/]*$/, "", dir)
					if ($i == name || $i == dir || dir == f) ok = 1
				}
			}
			END {
				if (!found) print where ": folder " f " is not in the table"
				else if (!ok) print where ": " f " may not include " inc
			}'
	done)
	if [ -n "$bad" ]; then
		printf '%s\n' "$bad" | sed 's/^/layers: /' >&2
		echo "layers: $(printf '%s\n' "$bad" | wc -l | tr -d ' ') include(s) break $table" >&2
		exit 1
	fi
	n=$(printf '%s\n' "$list" | wc -l | tr -d ' ')
	echo "layers: $n file(s) include only what $table allows"
	;;
*)
	echo "usage: layers.sh check|views TABLE ROOTS [...]" >&2
	exit 2
	;;
esac
