# edges.awk - the trigger line's edges as an outside observer saw them,
# against strand's journal, frame for frame.
#
#   awk -f edges.awk -v width_ns=W -v max_late_us=B JOURNAL.csv EDGES
#
# JOURNAL.csv is `strand journal` output; EDGES is gpiomon -F '%e %s %n' on
# the line wired to the trigger: "1 S N" a rising edge at S s N ns
# (CLOCK_MONOTONIC, the kernel's timestamp, taken in the interrupt
# handler), "0 S N" a falling one.
#
# Checks: as many rising edges as fired frames, and as many falling ones;
# the k-th rising edge is the k-th frame: it came no earlier than the tick
# was due (due_ns) and no later than the loop's own reading of the clock
# right after the commit (mono_ns); its falling edge no earlier than its
# own tick was due (width_ns after the rising edge's); no edge later than
# max_late_us after its due time.
# Prints the figures as BENCH lines (microseconds): how late the edges came
# after their ticks were due (the jitter of the trigger), how far the
# pulses' widths were off, and how long after the edge the journal's time
# was read. On a mismatch it prints the first one and exits 1.
#
# With -v lost=N, up to N frames may have no edge seen: the observer's loss
# (gpiomon's v1 event thread makes one event of two edges when the emulated
# CPU stalls for longer than a pulse), not the trigger's. Each frame's
# rising edge is then the first edge between its due time and the loop's
# clock reading after the commit (its kind not trusted, as below), the
# figures are over the frames seen, and pulse widths are not checked.
#
# With -v frame_ns=F (the scene's frame period), also the rate the pulses
# came at against it, as an observer with the kernel's timestamps measures
# it, as BENCH gpio_edge_rate_ppm: each rising edge's time less its frame's
# nominal one, the 10th percentile of that in the first and in the last
# third of the run, and the slope between them. An edge is late, never
# early, and a stall of the emulated CPU makes a burst of edges late, which
# a line through all of them would follow; the lower edge does not.

function fail(msg) {
	print "edges: " msg
	bad = 1
	exit 1
}

# the q-quantile of v[1..n], sorted in place (insertion sort: n is small)
function quantile(v, n, q,    i, j, t, k) {
	for (i = 2; i <= n; i++) {
		t = v[i]
		for (j = i - 1; j >= 1 && v[j] > t; j--)
			v[j + 1] = v[j]
		v[j + 1] = t
	}
	k = int(q * n + 0.999999)
	if (k < 1)
		k = 1
	if (k > n)
		k = n
	return v[k]
}

FNR == 1 && NR == 1 {
	FS = ","
	$0 = $0
	for (i = 1; i <= NF; i++)
		col[$i] = i
	if (!("due_ns" in col) || !("mono_ns" in col) || !("state" in col))
		fail("not a strand journal: " $0)
	next
}

NR == FNR {
	if ($col["state"] != "fired")
		fail("journal row " FNR - 1 " is " $col["state"])
	nj++
	frame[nj] = $col["frame"]
	due[nj] = $col["due_ns"] + 0
	mono[nj] = $col["mono_ns"] + 0
	next
}

# The wire starts low, so its edges alternate rising, falling, ... The
# kind gpiomon prints is not trusted: the kernel's v1 ABI labels an edge
# by reading the line in its interrupt thread, which under emulation can
# run after the next edge (counted, as a note). A lost edge shows as a
# count that does not match.
{
	split($0, f, " ")
	ts = f[2] * 1000000000 + f[3]
	ne++
	ev[ne] = ts
	if (ne % 2 == 1)
		rise[++nr] = ts
	else
		fall[++nf] = ts
	if (f[1] != ne % 2)
		mislabelled++
}

# the rate the rising edges rise[1..n] of frames fr[1..n] came at
function rate(rise, fr, n,    h, k, f1, f3, r1, r3, per) {
	h = int(n / 3)
	f1 = f3 = 0
	for (k = 1; k <= h; k++) {
		r1[k] = rise[k] - fr[k] * frame_ns
		r3[k] = rise[n - h + k] - fr[n - h + k] * frame_ns
		f1 += fr[k] / h
		f3 += fr[n - h + k] / h
	}
	per = frame_ns + (quantile(r3, h, 0.1) - quantile(r1, h, 0.1)) / (f3 - f1)
	printf "BENCH gpio_edge_rate_ppm %.1f\n", (frame_ns / per - 1) * 1e6
}

function lossy(    j, k, seen, sr, sf, sl) {
	j = 1
	seen = 0
	for (k = 1; k <= nj; k++) {
		while (j <= ne && ev[j] < due[k])
			j++
		if (j <= ne && ev[j] <= mono[k]) {
			seen++
			sr[seen] = ev[j]
			sf[seen] = frame[k]
			sl[seen] = (ev[j] - due[k]) / 1000
			j++
		}
	}
	if (nj - seen > lost)
		fail(sprintf("%d of %d frames without an edge between due time and journal time " \
			     "(%d edges; up to %d may be lost by the observer)", nj - seen, nj, ne, lost))
	printf "edges: %d frames, %d of them seen rising between their due time and the loop's " \
	       "clock reading (%d lost by the observer)\n", nj, seen, nj - seen
	printf "BENCH gpio_trigger_edges %d\n", seen
	if (frame_ns > 0 && seen >= 30)
		rate(sr, sf, seen)
	printf "BENCH gpio_edge_late_p50 %.1f us\n", quantile(sl, seen, 0.5)
	printf "BENCH gpio_edge_late_p99 %.1f us\n", quantile(sl, seen, 0.99)
	printf "BENCH gpio_edge_late_max %.1f us\n", sl[seen]
}

END {
	if (bad)
		exit 1
	if (nj == 0)
		fail("the journal has no frame")
	if (lost != "") {
		lossy()
		exit bad
	}
	if (nr != nj)
		fail(nr " rising edges on the wire, " nj " frames in the journal")
	if (nf != nj)
		fail(nf " falling edges on the wire, " nj " frames in the journal")
	worst_w = 0
	for (k = 1; k <= nj; k++) {
		if (k > 1 && rise[k] <= fall[k - 1])
			fail("frame " frame[k] ": rises before the previous pulse fell")
		if (rise[k] < due[k])
			fail(sprintf("frame %d: the edge came %.1f us before its tick was due",
				     frame[k], (due[k] - rise[k]) / 1000))
		if (rise[k] > mono[k])
			fail(sprintf("frame %d: the edge came %.1f us after the loop's reading " \
				     "of the clock that followed the commit", frame[k],
				     (rise[k] - mono[k]) / 1000))
		late[k] = (rise[k] - due[k]) / 1000
		lag[k] = (mono[k] - rise[k]) / 1000
		if (late[k] > max_late_us)
			fail(sprintf("frame %d: the edge came %.1f us after its tick was due " \
				     "(bound %d us)", frame[k], late[k], max_late_us))
		# the falling edge is due width_ns after the rising edge's tick
		flate[k] = (fall[k] - due[k] - width_ns) / 1000
		if (flate[k] < 0)
			fail(sprintf("frame %d: the pulse fell %.1f us before it was due (%.1f us " \
				     "wide, want %.1f)", frame[k], -flate[k],
				     (fall[k] - rise[k]) / 1000, width_ns / 1000))
		if (flate[k] > max_late_us)
			fail(sprintf("frame %d: the pulse fell %.1f us after it was due (bound %d us)",
				     frame[k], flate[k], max_late_us))
		w = (fall[k] - rise[k] - width_ns) / 1000
		aw = w < 0 ? -w : w
		if (aw > worst_w)
			worst_w = aw
	}
	printf "edges: %d frames, %d pulses on the wire, in order, each between its due " \
	       "time and the loop's clock reading\n", nj, nr
	if (mislabelled)
		printf "edges: %d edges labelled the other way by the kernel's v1 event thread\n",
		       mislabelled
	printf "BENCH gpio_trigger_edges %d\n", nj
	printf "BENCH gpio_edge_late_p50 %.1f us\n", quantile(late, nj, 0.5)
	printf "BENCH gpio_edge_late_p99 %.1f us\n", quantile(late, nj, 0.99)
	printf "BENCH gpio_edge_late_max %.1f us\n", late[nj]
	printf "BENCH gpio_fall_late_p50 %.1f us\n", quantile(flate, nj, 0.5)
	printf "BENCH gpio_fall_late_max %.1f us\n", flate[nj]
	printf "BENCH gpio_pulse_width_error_max %.1f us\n", worst_w
	printf "BENCH gpio_journal_after_edge_p50 %.1f us\n", quantile(lag, nj, 0.5)
	printf "BENCH gpio_journal_after_edge_max %.1f us\n", lag[nj]
	if (frame_ns > 0 && nj >= 30)
		rate(rise, frame, nj)
}
