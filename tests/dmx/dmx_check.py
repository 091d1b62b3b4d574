#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""dmx_check.py - what tests/dmx/dmx-ola.sh saw, checked:

1. olad (through its client) received strand's frames, and every value in
   them is `strand export --at ticks`'s value of its channel for the tick
   the frame's tick slots carry, scaled as tests/dmx/lights.yaml maps it
   (within half a count: export prints ten digits); no frame is missing
   from the first to the last of each universe.
2. tshark decodes every packet strand sent as sACN or ArtDmx, none
   malformed, with the universe, length, priority and source the scene
   says, sequence numbers moving forward, and the stream's end (three sACN
   packets with Stream_Terminated); every packet went to a destination the
   scene names (239.255.0.1, sACN's group for universe 1, and 198.18.0.1):
   every packet of DMX data in the namespace is strand's (olad's ports are
   inputs; it sends only Art-Net's poll replies, which are left aside).

usage: dmx_check.py SCENE FRAMES JOURNAL_CSV EXPORT_CSV PLAY_OUT PCAP
"""
import csv
import subprocess
import sys

EVERY = 23         # ticks between frames at 44 Hz on 1 kHz (dmx_every)
TICK_SLOT = 508    # slots 509-512, 0-based 508-511: the loop's tick
# (OLA universe, channel, first slot 0-based, bits, counts a unit, offset)
MAP = []
for i in range(4):
    MAP.append((1, "heads.%d.pan" % i, 8 * i, 16, 121.3611, 32768))
    MAP.append((1, "heads.%d.tilt" % i, 8 * i + 2, 16, 242.7222, 32768))
    for k, c in enumerate("r g b alpha".split()):
        MAP.append((2, "spark.%d.%s" % (i, c), 4 * i + k, 8, 255.0, 0))


def fail(msg):
    print("dmx_check: FAIL " + msg)
    sys.exit(1)


def main():
    scene, frames_path, journal_path, export_path, play_path, pcap = sys.argv[1:7]
    j = list(csv.DictReader(open(journal_path)))
    if not j:
        fail("the journal has no frame")
    tick0 = int(j[0]["tick"])  # frame 0's loop tick
    rows = list(csv.reader(open(export_path)))
    col = {n: i for i, n in enumerate(rows[0])}
    export = {int(r[0]): r for r in rows[1:]}
    last = max(export)
    frames = {1: [], 2: []}
    for line in open(frames_path):
        uni, t, hexdata = line.split()
        frames[int(uni)].append(bytes.fromhex(hexdata))
    checked = values = 0
    worst = 0.0
    for uni, fl in frames.items():
        if len(fl) < 50:
            fail("olad handed its client %d frames of universe %d" % (len(fl), uni))
        ticks = [int.from_bytes(f[TICK_SLOT:TICK_SLOT + 4], "big") for f in fl]
        # the frames between the first and the last: every one, in order
        # (olad repeats none; each is a tick EVERY after the one before)
        inner = [t for t in ticks if t > 0]
        for a, b in zip(inner, inner[1:]):
            if b != a + EVERY:
                fail("universe %d: frame of tick %d follows tick %d (one missing or out of "
                     "order)" % (uni, b, a))
        for f, t in zip(fl, ticks):
            st = t - tick0
            if st < 0 or st > last:
                continue  # the pre-roll and post-roll: moves, not the scene
            r = export[st]
            for u, name, slot, bits, cpu, off in MAP:
                if u != uni:
                    continue
                got = f[slot] * 256 + f[slot + 1] if bits == 16 else f[slot]
                want = float(r[col[name]]) * cpu + off
                err = abs(got - want)
                worst = max(worst, err)
                if err > 0.5 + 1e-5:
                    fail("universe %d tick %d (scene tick %d): %s is %d, export says %.6f"
                         % (uni, t, st, name, got, want))
                values += 1
            checked += 1
    if checked < 100:
        fail("only %d frames fell within the scene's ticks" % checked)
    print("BOUND dmx_values worst=%.3g bound=0.5 counts (olad's %d frames in the scene, "
          "%d values)" % (worst, checked, values))
    tshark_check(pcap)
    print("dmx_check: ok: %d frames, %d values equal export's, tshark agrees"
          % (checked, values))


def tshark_check(pcap):
    fields = ["frame.number", "ip.dst", "udp.dstport", "acn.dmx.universe",
              "acn.dmx.seq_number", "acn.dmx.option_s", "acn.dmx.count",
              "acn.dmx.priority", "acn.dmx.source_name", "artnet.output.universe",
              "artnet.output.sequence", "artnet.output.length", "_ws.malformed",
              "_ws.expert.severity"]
    cmd = ["tshark", "-r", pcap, "--enable-heuristic", "acn", "-o", "acn.dmx_enable:TRUE",
           "-T", "fields", "-E", "separator=|", "-E", "occurrence=f"]
    for f in fields:
        cmd += ["-e", f]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    sacn, art = [], []
    for line in out.splitlines():
        v = dict(zip(fields, line.split("|")))
        if not v["udp.dstport"]:
            continue  # the kernel's IGMP and ICMPv6, not strand's
        if v["_ws.malformed"]:
            fail("tshark: packet %s is malformed" % v["frame.number"])
        if not v["acn.dmx.universe"] and not v["artnet.output.length"]:
            continue  # olad's Art-Net replies (to 127.0.0.1): it has no DMX outputs
        if v["ip.dst"] not in ("239.255.0.1", "198.18.0.1"):
            fail("tshark: packet %s went to %s, not a destination the scene names"
                 % (v["frame.number"], v["ip.dst"]))
        if v["udp.dstport"] == "5568":
            if (v["acn.dmx.universe"] != "1" or v["acn.dmx.count"] != "513" or
                    v["acn.dmx.priority"] != "100" or v["acn.dmx.source_name"] != "movers"):
                fail("tshark: sACN packet %s: %s" % (v["frame.number"], line))
            sacn.append(v)
        elif v["udp.dstport"] == "6454":
            if v["artnet.output.universe"] != "2" or v["artnet.output.length"] != "512":
                fail("tshark: Art-Net packet %s: %s" % (v["frame.number"], line))
            art.append(v)
    if len(sacn) < 50 or len(art) < 50:
        fail("tshark saw %d sACN and %d ArtDmx packets" % (len(sacn), len(art)))
    for a, b in zip(sacn, sacn[1:]):
        if int(b["acn.dmx.seq_number"]) != (int(a["acn.dmx.seq_number"]) + 1) % 256:
            fail("tshark: sACN sequence %s after %s" % (b["acn.dmx.seq_number"],
                                                        a["acn.dmx.seq_number"]))
    for a, b in zip(art, art[1:]):
        if int(b["artnet.output.sequence"]) != int(a["artnet.output.sequence"]) % 255 + 1:
            fail("tshark: Art-Net sequence %s after %s" % (b["artnet.output.sequence"],
                                                           a["artnet.output.sequence"]))
    term = [v["acn.dmx.option_s"] for v in sacn]
    if term[-3:] != ["1"] * 3 or "1" in term[:-3]:
        fail("tshark: Stream_Terminated flags %s" % term[-6:])
    print("tshark: %d sACN and %d ArtDmx packets decoded, none malformed, sequences forward, "
          "stream terminated" % (len(sacn), len(art)))


if __name__ == "__main__":
    main()
