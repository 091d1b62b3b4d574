#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""serve_bench.py STRAND SCENE OUTDIR - strand serve on the wall clock, the
robot arm on its simulated rig. Prints BENCH lines:

  - a command's way from its arrival at the server (the message whole) to
    the first tick that acts on it: ping, a command that does nothing,
    answered by the tick that takes it (p50, p99 over BENCH_SERVE_PINGS)
  - status updates a second that 1 and 10 WebSocket clients each get while
    a looped play runs
  - the loop's wake-up latency with the server up and ten clients streaming
    its status, beside strand play's without a server and cyclictest's,
    at 1 kHz and the same priority, in alternating rounds of
    BENCH_SERVE_CHUNK seconds for BENCH_SERVE_SECONDS each: the server may
    not move the loop's p99 by more than 10%.
"""
import asyncio, json, os, socket, subprocess, sys, time

import websockets

STRAND, SCENE, OUT = sys.argv[1:4]
SECS = int(os.environ.get("BENCH_SERVE_SECONDS", "30"))
CHUNK = int(os.environ.get("BENCH_SERVE_CHUNK", "3"))
PRIO = os.environ.get("BENCH_SERVE_PRIORITY", "80")
PINGS = int(os.environ.get("BENCH_SERVE_PINGS", "2000"))
os.makedirs(OUT, exist_ok=True)


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def pct(xs, q):
    xs = sorted(xs)
    return xs[min(len(xs) - 1, max(0, int(q * len(xs) + 0.5) - 1))]


class Serve:
    def __init__(self, hist):
        self.port = free_port()
        self.p = subprocess.Popen([STRAND, "serve", SCENE, "--sim", "--priority", PRIO,
                                   "--latency-hist", hist, "--listen",
                                   "127.0.0.1:%d" % self.port],
                                  stderr=subprocess.PIPE, text=True)
        line = self.p.stderr.readline()
        if "listening" not in line:
            raise SystemExit("serve_bench: strand serve did not start: " + line)
        self.url = "ws://127.0.0.1:%d/websocket" % self.port

    def stop(self):
        self.p.send_signal(2)
        self.p.wait(20)
        return self.p.stderr.read()


async def call(ws, method, params=None, n=[0]):
    n[0] += 1
    m = {"jsonrpc": "2.0", "id": n[0], "method": method}
    if params is not None:
        m["params"] = params
    await ws.send(json.dumps(m))
    while True:
        r = json.loads(await ws.recv())
        if r.get("id") == n[0]:
            return r


async def count_status(url, secs):
    async with websockets.connect(url, max_queue=None) as w:
        n, t0 = 0, time.monotonic()
        while time.monotonic() - t0 < secs:
            m = json.loads(await w.recv())
            n += m.get("method") == "status"
        return n / secs


async def commands_and_status():
    s = Serve(os.path.join(OUT, "serve-cmd.hist"))
    try:
        async with websockets.connect(s.url, max_queue=None) as w:
            await call(w, "enable")
            await asyncio.sleep(0.5)
            lat, rtt = [], []
            for i in range(PINGS):
                t0 = time.monotonic()
                r = await call(w, "ping")
                rtt.append((time.monotonic() - t0) * 1e6)
                lat.append(r["result"]["latency_us"])
            print("BENCH serve_command_to_tick p50 %.0f us p99 %.0f us max %.0f us "
                  "(%d pings at a 1 kHz tick; the client's round trip p50 %.0f p99 %.0f us)"
                  % (pct(lat, .5), pct(lat, .99), max(lat), PINGS, pct(rtt, .5),
                     pct(rtt, .99)))
            r = await call(w, "play", {"loop": True})
            for n in (1, 10):
                rates = await asyncio.gather(*[count_status(s.url, 5) for _ in range(n)])
                print("BENCH serve_status_rate %d client%s: %.1f updates/s each (min %.1f)"
                      % (n, "s" if n > 1 else "", sorted(rates)[len(rates) // 2], min(rates)))
            await call(w, "stop")
            await call(w, "disable")
    finally:
        s.stop()


async def stream(url, stop):
    async with websockets.connect(url, max_queue=None) as w:
        while not stop.is_set():
            try:
                await asyncio.wait_for(w.recv(), 0.5)
            except asyncio.TimeoutError:
                pass


async def serve_round(hist):
    s = Serve(hist)
    try:
        stop = asyncio.Event()
        async with websockets.connect(s.url, max_queue=None) as w:
            await call(w, "enable")
            await call(w, "play", {"loop": True})
            clients = [asyncio.create_task(stream(s.url, stop)) for _ in range(10)]
            await asyncio.sleep(CHUNK)
            await call(w, "disable")
            stop.set()
            await asyncio.gather(*clients)
    finally:
        err = s.stop()
    return err


def hist_read(path, acc):
    for line in open(path):
        f = line.split()
        if len(f) == 2 and f[0].isdigit() and int(f[1]):
            acc[int(f[0])] = acc.get(int(f[0]), 0) + int(f[1])


def hist_pct(h, q):
    n, s = sum(h.values()), 0
    for k in sorted(h):
        s += h[k]
        if s >= q * n:
            return k
    return 0


def latency():
    rounds = (SECS + CHUNK - 1) // CHUNK
    hs, hp, hc = {}, {}, {}
    policy = "SCHED_FIFO"
    for r in range(rounds):
        sh = os.path.join(OUT, "serve.round")
        err = asyncio.run(serve_round(sh))
        if "real-time priority" in err:
            policy = "SCHED_OTHER (refused)"
        hist_read(sh, hs)
        ph = os.path.join(OUT, "play.round")
        subprocess.run([STRAND, "play", SCENE, "--sim", "--loop", "--duration", str(CHUNK),
                        "--no-journal", "--priority", PRIO, "--latency-hist", ph, "--quiet"],
                       check=True, stderr=subprocess.DEVNULL)
        hist_read(ph, hp)
        ch = os.path.join(OUT, "cyclictest.round")
        with open(ch, "w") as f:
            subprocess.run(["cyclictest", "-m", "-t1", "-p", PRIO, "-i", "1000", "-l",
                            str(CHUNK * 1000), "-h", "10000", "-q"], check=True, stdout=f,
                           stderr=subprocess.DEVNULL)
        hist_read(ch, hc)
    print("BENCH serve_latency: %d s at 1 kHz each in %d alternating rounds, priority %s (%s)"
          % (rounds * CHUNK, rounds, PRIO, policy))
    for name, h in (("serve+10clients", hs), ("play", hp), ("cyclictest", hc)):
        print("BENCH serve_latency %s p50 %d us p99 %d us max %d us (%d wake-ups)"
              % (name, hist_pct(h, .5), hist_pct(h, .99), max(h) if h else 0,
                 sum(h.values())))
    p99s, p99p = hist_pct(hs, .99), hist_pct(hp, .99)
    ratio = p99s / p99p if p99p else float("inf")
    print("BENCH serve_latency p99 with the server / without: %.2f (%s: at most 1.10)"
          % (ratio, "ok" if ratio <= 1.10 else "OVER"))


asyncio.run(commands_and_status())
latency()
