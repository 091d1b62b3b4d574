#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""ola_reader.py - olad as strand's DMX peer: patch its E1.31 input port 0 to
OLA universe 1 and its Art-Net input port 0 (port-address 0) to universe 2,
then write every frame olad hands its client as one line:

    UNIVERSE MONOTONIC_NS HEX_OF_512_SLOTS

until `idle` seconds pass without one (after the first). Writes READY_FILE
once registered. Debian's ola-python, run by Debian's /usr/bin/python3.

usage: ola_reader.py RPC_PORT OUT_FILE READY_FILE IDLE_S MAX_S
"""
import socket
import sys
import time

from ola.ClientWrapper import ClientWrapper
from ola.OlaClient import OlaClient

E131, ARTNET = 11, 2  # OLA's plugin ids (Ola.proto PluginIds)


def main():
    port, out_path, ready_path = int(sys.argv[1]), sys.argv[2], sys.argv[3]
    idle, max_s = float(sys.argv[4]), float(sys.argv[5])
    sock = socket.create_connection(("127.0.0.1", port), timeout=5)
    sock.settimeout(None)
    wrapper = ClientWrapper(sock)
    client = wrapper.Client()
    out = open(out_path, "w")
    state = {"last": None, "start": time.monotonic(), "pending": 0, "frames": 0}

    def data(universe):
        def cb(buf):
            state["last"] = time.monotonic()
            state["frames"] += 1
            out.write("%d %d %s\n" % (universe, time.monotonic_ns(), bytes(buf).hex()))
        return cb

    def done(status):
        if not status.Succeeded():
            print("ola_reader: %s" % status.message, file=sys.stderr)
            sys.exit(1)
        state["pending"] -= 1
        if state["pending"] == 0:
            open(ready_path, "w").close()

    def devices(status, devs):
        if not status.Succeeded():
            print("ola_reader: devices: %s" % status.message, file=sys.stderr)
            sys.exit(1)
        want = {E131: 1, ARTNET: 2}
        found = {}
        for d in devs:
            if d.plugin_id in want and d.input_ports:
                found[d.plugin_id] = d
        if set(found) != set(want):
            print("ola_reader: olad has devices of plugins %s, wants E1.31 and Art-Net"
                  % sorted(found), file=sys.stderr)
            sys.exit(1)
        state["pending"] = 4
        for pid, uni in want.items():
            client.PatchPort(found[pid].alias, found[pid].input_ports[0].id, False,
                             OlaClient.PATCH, uni, done)
            client.RegisterUniverse(uni, client.REGISTER, data(uni), done)

    def tick():
        now = time.monotonic()
        if now - state["start"] > max_s or (state["last"] and now - state["last"] > idle):
            wrapper.Stop()
            return
        wrapper.AddEvent(50, tick)

    client.FetchDevices(devices)
    wrapper.AddEvent(50, tick)
    wrapper.Run()
    out.close()
    print("ola_reader: %d frames" % state["frames"])


if __name__ == "__main__":
    main()
