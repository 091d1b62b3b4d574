# can.awk - a strand play run on vcan0 checked from candump's record of the
# bus (tests/vm/t_can_play.sh), with the run's journal and the scene's export
# as the reference:
#
#   awk -f can.awk -v nodes="1 2 3" -v cols="pan.angle tilt.angle spin.rpm" \
#       -v cpu="1000 1000 100" -v hz=250 -v fps=25 -v ticks=N -v startup=S \
#       -v max_late_us=U journal.csv export.csv bus.log
#
# journal.csv: `strand journal` (the loop tick of every frame fired; of a
# run of several passes, the first pass is compared);
# export.csv: `strand export --at ticks` (every channel at every scene
# tick); bus.log: `candump -ta`, in the order the frames were on the bus.
# ticks: the loop's ticks run, startup: the SYNCs of the master's start-up
# (both from strand's summary). fps: a whole frame rate.
#
# The loop's SYNCs are found by what the frames say, not by their times:
# the start-up ends with a cycle in which every RPDO says "enable operation"
# (0x0f), the orderly stop begins with the first cycle that says something
# else (shutdown), and the loop's ticks are the SYNCs just before it. Under
# qemu's emulation the kernel's receive timestamps now and then step back by
# up to 25 ms (seen with a lone cansend as well), so times only measure the
# period, and a step back shows as jitter.
#
# Checks, each printed, the first failure exits 1:
#  1. start-up, per node: NMT reset communication, its boot-up, SDO requests,
#     NMT start, then RPDO controlwords 0x06, 0x07, 0x0f in this order, and
#     TPDO statuswords ready, switched on, operation enabled in this order;
#  2. one SYNC per tick: between the start-up (its SYNCs as strand counts
#     them; the loop's first comes after every drive said it is enabled)
#     and the stop exactly the loop's ticks, each after one RPDO per node;
#  3. each loop tick's RPDO targets are the export's values of its tick times
#     counts per unit (within the rounding of export's 10 digits), for every
#     tick the export covers: a SYNC too many or too few would shift them;
#  4. the SYNC period: mean over the loop within 1% of 1/hz, no gap beyond a
#     period and max_late_us; BENCH lines with the jitter, from candump's
#     times and, with -v synclog=FILE, from a drive's (strand-simdrive
#     --sync-log);
#  5. the stop: every node gets NMT pre-operational after the last SYNC.

function fail(msg) {
	print "can: FAIL " msg
	failed = 1
	exit 1
}

function hexval(h) {
	return ("0x" h) + 0
}

# the p-th quantile (0..1) of the n values counted in hist[0..max] (whole us)
function quantile(p, n, max,    c, v) {
	c = 0
	for (v = 0; v <= max; v++) {
		c += hist[v]
		if (c >= p * n)
			return v
	}
	return max
}

# a little-endian signed 32-bit value from bytes i..i+3 of record r
function le32(r, i,    v) {
	v = hexval(B[r, i]) + 256 * (hexval(B[r, i + 1]) + 256 * (hexval(B[r, i + 2]) + \
	    256 * hexval(B[r, i + 3])))
	return v >= 2147483648 ? v - 4294967296 : v
}

function le16(r, i) {
	return hexval(B[r, i]) + 256 * hexval(B[r, i + 1])
}

BEGIN {
	nn = split(nodes, node, " ")
	split(cols, col, " ")
	split(cpu, per, " ")
	period_us = 1e6 / hz
	file = 0
}

FNR == 1 {
	file++
	if (file <= 2) {
		nh = split($0, h, ",")
		for (i = 1; i <= nh; i++)
			hdr[file, h[i]] = i
		next
	}
}

# the journal's rows of the first pass (a run of --passes repeats frames)
file == 1 {
	split($0, f, ",")
	fr = f[hdr[1, "frame"]] + 0
	if (nframes && fr <= jframe[nframes])
		pass_over = 1
	if (!pass_over) {
		jframe[++nframes] = fr
		jtick[nframes] = f[hdr[1, "tick"]]
	}
	next
}

file == 2 {
	split($0, f, ",")
	t = f[hdr[2, "tick"]]
	for (k = 1; k <= nn; k++)
		val[t, k] = f[hdr[2, col[k]]]
	if (t > last_scene_tick)
		last_scene_tick = t
	next
}

file == 3 && $2 ~ /can/ {
	ts = $1
	gsub(/[()]/, "", ts)
	split(ts, p, ".")
	n++
	T[n] = p[1] * 1e6 + p[2]
	ID[n] = $3
	L[n] = substr($4, 2, length($4) - 2) + 0
	for (i = 1; i <= L[n]; i++)
		B[n, i] = $(4 + i)
	if ($3 == "080")
		S[++ns] = n
}

END {
	if (failed)
		exit 1
	if (!n || !nframes || !last_scene_tick)
		fail("empty input: " n " frames on the bus, " nframes " journal rows, " \
		     last_scene_tick + 0 " export ticks")

	# 1. the start-up sequence of each node
	for (k = 1; k <= nn; k++) {
		id = node[k]
		reset = boot = start = enabled_at = 0
		sdo = 0
		ncw = nst = 0
		for (i = 1; i <= n; i++) {
			if (ID[i] == "000" && hexval(B[i, 2]) == id) {
				if (hexval(B[i, 1]) == 130 && !reset)
					reset = i
				if (hexval(B[i, 1]) == 1 && !start)
					start = i
			} else if (hexval(ID[i]) == 1792 + id && B[i, 1] == "00" && reset && !boot) {
				boot = i
			} else if (hexval(ID[i]) == 1536 + id && boot && !start) {
				sdo++
			} else if (hexval(ID[i]) == 512 + id && start && ncw < 3) {
				cw = le16(i, 1)
				if (!ncw || cw != cws[ncw])
					cws[++ncw] = cw
			} else if (hexval(ID[i]) == 384 + id && start && nst < 3) {
				st = and(le16(i, 1), 111)   # 0x6f: the state bits
				if (!nst || st != sts[nst])
					sts[++nst] = st
				if (st == 39 && !enabled_at)
					enabled_at = i
			}
		}
		if (!reset || !boot || !start || sdo < 29)
			fail("node " id ": start-up: reset communication at " reset ", boot-up at " \
			     boot ", " sdo " SDO requests, NMT start at " start)
		if (ncw != 3 || cws[1] != 6 || cws[2] != 7 || cws[3] != 15)
			fail(sprintf("node %d: controlwords 0x%02x 0x%02x 0x%02x, want 0x06 0x07 0x0f", \
				     id, cws[1], cws[2], cws[3]))
		if (nst != 3 || sts[1] != 33 || sts[2] != 35 || sts[3] != 39)
			fail(sprintf("node %d: statuswords 0x%02x 0x%02x 0x%02x, want ready 0x21, " \
				     "switched on 0x23, enabled 0x27", id, sts[1], sts[2], sts[3]))
		# the master leaves its start-up once every drive says so
		if (enabled_at > last_enabled)
			last_enabled = enabled_at
		printf "can: node %d start-up: reset communication, boot-up, %d SDO requests, NMT " \
		       "start, controlwords 0x06 0x07 0x0f, ready, switched on, operation enabled\n", \
		       id, sdo
	}

	# 2. the loop's SYNCs: after the start-up's last cycle (an RPDO for
	# every node, each 0x0f, and the last drive's TPDO saying it is
	# enabled: a drive that answers late, as one on a loaded machine does,
	# keeps the master in its start-up for more cycles of 0x0f), before the
	# stop's first (one that is not)
	k1 = k2 = 0
	for (k = 1; k <= ns; k++) {
		all = 1
		c = 0
		for (i = (k > 1 ? S[k - 1] : 0) + 1; i < S[k]; i++)
			if (hexval(ID[i]) >= 513 && hexval(ID[i]) <= 639) {
				c++
				if (le16(i, 1) != 15)
					all = 0
			}
		if (c < nn && !k1)
			continue
		if (all && !k1 && S[k] > last_enabled)
			k1 = k
		if (!all && k1) {
			k2 = k
			break
		}
	}
	if (!k1 || !k2)
		fail("no start-up's last cycle (" k1 ") or stop's first (" k2 ") among " ns " SYNCs")
	# strand's own count of its start-up's cycles (its summary): a
	# start-up goes on for as many cycles as the drives need to answer
	# the latest SYNC in time, which the frames alone cannot tell from
	# the loop's first ticks; the loop's first SYNC must come after the
	# last drive said it is enabled (k1 is the first that does), and the
	# loop's ticks fill the rest up to the stop
	off0 = startup + 1
	if (off0 < k1)
		fail("strand counts " startup " SYNCs of the start-up, but the drives were not all " \
		     "enabled before SYNC " k1)
	if (k2 - off0 != ticks)
		fail(k2 - off0 " SYNCs between the start-up's last cycle (SYNC " startup ") and " \
		     "the stop, for " ticks " ticks")
	for (k = 0; k < ticks; k++) {
		s = S[off0 + k]
		for (q = 1; q <= nn; q++) {
			c = 0
			for (i = S[off0 + k - 1] + 1; i < s; i++)
				if (hexval(ID[i]) == 512 + node[q]) {
					c++
					rp[k, q] = i
				}
			if (c != 1)
				fail("tick " k ": " c " RPDOs for node " node[q] " before its SYNC")
		}
	}
	printf "can: one SYNC per tick: %d SYNCs between the start-up's %d (%d after the one " \
	       "that followed every drive's enabled) and the stop, for %d ticks, each after " \
	       "one RPDO per node\n", k2 - off0, startup, off0 - k1, ticks

	# 3. the targets: scene tick = loop tick - (frame's loop tick - its scene
	# tick), over the first pass
	for (r = 1; r <= nframes; r++) {
		sh = jtick[r] - int((jframe[r] * hz + fps - 1) / fps)
		if (r == 1)
			shift = sh
		else if (sh != shift)
			fail("frame " jframe[r] " at tick " jtick[r] ": not " shift \
			     " ticks after its scene tick")
	}
	compared = 0
	worst_dev = 0
	for (k = 0; k < ticks; k++) {
		st = k - shift
		if (st < 0 || st > last_scene_tick || k > shift + last_scene_tick)
			continue
		for (q = 1; q <= nn; q++) {
			got = le32(rp[k, q], 3)
			want = val[st, q] * per[q]
			dev = got - want
			if (dev < 0)
				dev = -dev
			if (dev > worst_dev)
				worst_dev = dev
			# export prints 10 significant digits: a count is exact to far
			# better than 0.001 of one, so only a value within that of a
			# half count could round the other way
			if (dev > 0.501)
				fail("tick " k " (scene tick " st "): node " node[q] " got target " got \
				     ", the export says " val[st, q] " x " per[q] " = " want)
			compared++
		}
	}
	printf "can: %d RPDO targets (ticks %d to %d) equal to the export's setpoints times " \
	       "counts per unit (largest difference %.4f count, its rounding)\n", compared, \
	       shift, shift + last_scene_tick, worst_dev
	if (compared != nn * (last_scene_tick + 1))
		fail("only " compared " targets compared, for " last_scene_tick + 1 " scene ticks")

	# 4. the period over the loop's ticks
	worst = 0
	back = 0
	for (k = 1; k < ticks; k++) {
		d = T[S[off0 + k]] - T[S[off0 + k - 1]]
		back += d < 0
		dev = d - period_us
		if (dev < 0)
			dev = -dev
		hist[int(dev)]++
		if (dev > worst)
			worst = dev
		if (d > period_us + max_late_us)
			fail("tick " k ": the SYNC came " d " us after the last one")
	}
	mean = (T[S[off0 + ticks - 1]] - T[S[off0]]) / (ticks - 1)
	if (mean < period_us * 0.99 || mean > period_us * 1.01)
		fail("mean SYNC period " mean " us, want " period_us)
	p50 = quantile(0.5, ticks - 1, int(worst))
	p99 = quantile(0.99, ticks - 1, int(worst))
	printf "can: SYNC period over %d ticks: mean %.2f us (%d us due); |period - due| " \
	       "p50 %d, p99 %d, max %d us\n", ticks, mean, period_us, p50, p99, worst
	printf "BENCH can_sync_period_mean_us %.2f\n", mean
	printf "BENCH can_sync_jitter_p50_us %d\nBENCH can_sync_jitter_p99_us %d\n", p50, p99
	printf "BENCH can_sync_jitter_max_us %d\n", worst
	printf "can: %d of candump's SYNC timestamps earlier than the one before\n", back
	printf "BENCH can_candump_time_steps_back %d\n", back

	# the same SYNCs as a drive received them (strand-simdrive --sync-log:
	# CLOCK_MONOTONIC after its receive, its own wake-up included); it
	# listened before the first SYNC, so its n-th is candump's n-th
	if (synclog != "") {
		ds = 0
		while ((getline line < synclog) > 0)
			D[++ds] = line / 1000
		if (ds < off0 + ticks - 1)
			fail("the drive's log has " ds " SYNCs, the bus " ns)
		split("", hist)
		worst = 0
		for (k = 1; k < ticks; k++) {
			dev = D[off0 + k] - D[off0 + k - 1] - period_us
			if (dev < 0)
				dev = -dev
			hist[int(dev)]++
			if (dev > worst)
				worst = dev
		}
		mean = (D[off0 + ticks - 1] - D[off0]) / (ticks - 1)
		p50 = quantile(0.5, ticks - 1, int(worst))
		p99 = quantile(0.99, ticks - 1, int(worst))
		printf "can: as node %s received them: mean %.2f us; |period - due| p50 %d, " \
		       "p99 %d, max %d us\n", node[1], mean, p50, p99, worst
		printf "BENCH can_sync_drive_jitter_p50_us %d\n", p50
		printf "BENCH can_sync_drive_jitter_p99_us %d\n", p99
		printf "BENCH can_sync_drive_jitter_max_us %d\n", worst
	}

	# 5. the stop: NMT pre-operational to every node after the loop's last SYNC
	for (q = 1; q <= nn; q++) {
		seen = 0
		for (i = S[off0 + ticks - 1]; i <= n; i++)
			if (ID[i] == "000" && hexval(B[i, 1]) == 128 && hexval(B[i, 2]) == node[q])
				seen = 1
		if (!seen)
			fail("node " node[q] ": no NMT pre-operational after the run")
	}
	print "can: every node put in pre-operational at the end"
}
