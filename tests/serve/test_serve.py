#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""test_serve.py STRAND OUTDIR - strand serve against real peers it did not
write: curl, Debian's python3-websockets, and headless Chromium driven by
python3-selenium. The simulated robot arm in virtual time. Every safety
rule of the server has a check here: a missing token, a foreign Origin, a
second controller, a dead-man timeout mid-jog, a client that stops
reading, a teach that breaks the scene (refused, file unchanged)."""
import asyncio
import csv, json, os, shutil, socket, subprocess, sys, tempfile, time

import websockets

STRAND, OUT = sys.argv[1], sys.argv[2]
SIMDRIVE = os.path.join(os.path.dirname(STRAND), "strand-simdrive")
os.makedirs(OUT, exist_ok=True)
failed = 0


def check(ok, what):
    global failed
    print(("PASS " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failed += 1


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def start(scene, *args, sim=True):
    port = free_port()
    p = subprocess.Popen([STRAND, "serve"] + ([scene] if scene else []) +
                         (["--sim"] if sim else []) + ["--clock", "virtual",
                          "--listen", "127.0.0.1:%d" % port] + list(args),
                         stderr=subprocess.PIPE, text=True)
    line = p.stderr.readline()
    if "listening" not in line:
        raise SystemExit("strand serve did not start: " + line + p.stderr.read())
    return p, port


def stop(p):
    p.send_signal(2)
    try:
        p.wait(10)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()


def curl(port, body, *hdr, ctype="application/json"):
    cmd = ["curl", "-s", "-w", "\n%{http_code}", "-X", "POST", "-H", "Content-Type: " + ctype]
    for h in hdr:
        cmd += ["-H", h]
    cmd += ["--data-binary", body if isinstance(body, str) else json.dumps(body),
            "http://127.0.0.1:%d/rpc" % port]
    out = subprocess.run(cmd, capture_output=True, text=True, timeout=20).stdout
    text, code = out.rsplit("\n", 1)
    return int(code), text


def rpc(method, params=None, id=1):
    m = {"jsonrpc": "2.0", "id": id, "method": method}
    if params is not None:
        m["params"] = params
    return m


class Client:
    def __init__(self, ws):
        self.ws, self.n, self.status = ws, 0, None

    async def call(self, method, params=None):
        self.n += 1
        await self.ws.send(json.dumps(rpc(method, params, self.n)))
        while True:
            m = json.loads(await asyncio.wait_for(self.ws.recv(), 10))
            if m.get("id") == self.n:
                return m
            if m.get("method") == "status":
                self.status = m["params"]

    async def wait(self, pred, what, timeout=15):
        t = time.time()
        while time.time() - t < timeout:
            m = json.loads(await asyncio.wait_for(self.ws.recv(), 10))
            if m.get("method") == "status":
                self.status = m["params"]
                if pred(self.status):
                    return self.status
        raise AssertionError("timed out waiting for " + what)


def raw_upgrade(port, path="/websocket", extra=b""):
    """The status line a WebSocket upgrade gets, read off a plain socket."""
    s = socket.create_connection(("127.0.0.1", port))
    s.sendall(b"GET %s HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nUpgrade: websocket\r\n"
              b"Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
              b"Sec-WebSocket-Version: 13\r\n%s\r\n" % (path.encode(), port, extra))
    s.settimeout(5)
    line = s.recv(200).split(b"\r\n")[0].decode()
    s.close()
    return line


def url(port):
    return "ws://127.0.0.1:%d/websocket" % port


async def ws_tests(port, scene):
    async with websockets.connect(url(port)) as a, websockets.connect(url(port)) as b:
        A, B = Client(a), Client(b)
        r = await A.call("enable")
        check("result" in r, "websocket client A enables the drives")
        st = await A.wait(lambda s: s["state"] == "enabled", "enabled")
        r = await B.call("goto", {"frame": 10})
        check(r.get("error", {}).get("code") == -32001,
              "a second controller is refused (-32001: %s)" % r.get("error", {}).get("message"))
        # status rate to this client over one second
        n, t0 = 0, time.time()
        while time.time() - t0 < 1.0:
            m = json.loads(await a.recv())
            n += m.get("method") == "status"
        check(n >= 20, "status to a client at %d updates a second (>= 20)" % n)
        # a jog without refreshes: the dead-man stops it, at rest within limits
        info = (await A.call("info"))["result"]
        lim = info["outputs"][0]
        r = await A.call("jog", {"output": 0, "speed": 1.0, "seq": 1})
        check("result" in r, "jog output 0 at its velocity limit")
        await A.wait(lambda s: s["loop"] == "jog", "the jog")
        st = await A.wait(lambda s: s["loop"] == "hold", "rest after the dead-man")
        sp = st["outputs"][0]["sp"]
        check(0 < sp <= lim["max"] and st["outputs"][0]["vel"] == 0,
              "dead-man: the axis stopped at %.3f %s, at rest within its limits [%g, %g]"
              % (sp, lim["unit"], lim["min"], lim["max"]))
        r = await A.call("jog", {"output": 0, "speed": 1.0, "seq": 1})
        st = A.status
        check("result" in r, "a doubled jog (same seq) is answered and ignored")
        # bad requests: a JSON-RPC error and nothing else
        for bad, code in ((rpc("jog", {"output": 0, "speed": 2, "seq": 2}), -32602),
                          (rpc("goto", {"frame": "ten"}), -32602),
                          (rpc("fly"), -32601),
                          (rpc("load", {"file": "../../etc/passwd"}), -32000)):
            await a.send(json.dumps(bad))
            while True:
                m = json.loads(await a.recv())
                if "id" in m:
                    break
            check(m.get("error", {}).get("code") == code,
                  "%s -> error %d (%s)" % (bad["method"], code, m.get("error", {}).get("message")))
        await a.send("{not json")
        while True:
            m = json.loads(await a.recv())
            if "id" in m:
                break
        check(m.get("error", {}).get("code") == -32700, "malformed JSON -> -32700")
        await a.send("x" * 70000)
        while True:
            m = json.loads(await a.recv())
            if "id" in m:
                break
        check(m.get("error", {}).get("code") == -32002, "an oversized message -> -32002")
        # a teach that breaks a limit: refused, the file unchanged
        before = open(scene).read()
        r = await A.call("goto", {"frame": 96})
        await A.wait(lambda s: s["loop"] == "hold" and s["frame"] == 96, "rest at 96")
        r = await A.call("teach", {"frame": 1, "nodes": ["base"]})
        check("error" in r and open(scene).read() == before,
              "a teach that breaks a limit is refused, the file unchanged (%s)"
              % r.get("error", {}).get("message", "")[:80])
        # e-stop from the watching client: accepted, latched
        r = await B.call("estop")
        check("result" in r, "e-stop from a client without the lease is accepted")
        st = await A.wait(lambda s: s["state"] == "e-stopped", "e-stopped")
        r = await A.call("enable")
        check("error" in r, "enable refused while e-stopped")
        r = await A.call("reset")
        st = await A.wait(lambda s: s["state"] == "disabled", "disabled after reset")
        check(True, "reset: e-stopped -> disabled")


async def slow_client(port):
    """A client that connects and never reads: the others keep their rate."""
    raw = socket.create_connection(("127.0.0.1", port))
    raw.sendall(b"GET /websocket HTTP/1.1\r\nHost: 127.0.0.1:%d\r\nUpgrade: websocket\r\n"
                b"Connection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                b"Sec-WebSocket-Version: 13\r\n\r\n" % port)
    raw.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    async with websockets.connect(url(port)) as a:
        A = Client(a)
        await A.call("enable")
        await A.call("play", {"loop": True})
        await asyncio.sleep(1.0)  # the stalled socket fills
        n, t0 = 0, time.time()
        while time.time() - t0 < 2.0:
            m = json.loads(await a.recv())
            n += m.get("method") == "status"
        check(n >= 40, "with a client that stops reading, another gets %d status in 2 s" % n)
        await A.call("stop")
        await A.call("disable")
    raw.close()


async def origin_token(port, tport, token):
    line = raw_upgrade(port, extra=b"Origin: http://evil.example\r\n")
    check(" 403" in line, "a WebSocket from a foreign Origin is refused (%s)" % line)
    line = raw_upgrade(port, extra=b"Origin: http://127.0.0.1:%d\r\n" % port)
    check(" 101" in line, "a WebSocket from the server's own page is taken (%s)" % line)
    code, text = curl(port, rpc("status"), "Origin: http://evil.example")
    check(code == 403, "POST /rpc from a foreign Origin: 403")
    code, text = curl(port, rpc("status"), ctype="text/plain")
    check(code == 415, "POST /rpc as text/plain (a form a foreign page may send): 415")
    code, text = curl(port, rpc("status"), "Host: attacker.example:%d" % port)
    check(code == 403, "a Host that is not a loopback name (DNS rebinding): 403")
    code, text = curl(tport, rpc("enable"))
    check(code == 401, "no token: 401")
    code, text = curl(tport, rpc("enable"), "Authorization: Bearer wrong-token-xxxxxxxx")
    check(code == 401, "a wrong token: 401")
    line = raw_upgrade(tport)
    check(" 401" in line, "a WebSocket without the token: %s" % line)
    code, text = curl(tport, rpc("ticket"), "Authorization: Bearer " + token)
    ticket = json.loads(text)["result"]["ticket"]
    async with websockets.connect(url(tport) + "?ticket=" + ticket) as w:
        m = json.loads(await w.recv())
        check(m.get("method") == "status", "a WebSocket with a ticket gets status")
    line = raw_upgrade(tport, "/websocket?ticket=" + ticket)
    check(" 401" in line, "a ticket used twice: %s" % line)
    code, text = curl(tport, rpc("status"), "Authorization: Bearer " + token)
    check(code == 200 and json.loads(text)["result"]["state"] == "disabled",
          "curl with the token: status")


MB_SCENE = """scene: mb
timing: {tick_hz: 1000, frame_rate: 24, frames: [0, 72]}
nodes:
  - {name: a, joint: {type: revolute, axis: y},
     limits: {min: -170, max: 170, velocity: 90, acceleration: 360}}
strands:
  - {node: a, keys: [{frame: 0, angle: 0}, {frame: 72, angle: 40}]}
devices:
  - name: drives
    driver: modbus
    modbus:
      tcp: {host: 127.0.0.1, port: %d}
      unit: 1
      response_timeout_ms: 5000
      enable: {coil: 0}
      axes:
        - {register: 0, type: int32, actual: {register: 100}}
  - {name: io, driver: sim}
outputs:
  - {channel: a.angle, device: drives, axis: 0, counts_per_unit: 1000}
triggers:
  - {name: camera, device: io, line: 0, pulse_ms: 2}
"""


async def estop_during_enable(tmp):
    """A command that takes long (an enable whose Modbus drive answers each
    request 1.5 s late) holds up neither the status nor another client's
    e-stop, which gives the start up."""
    scene = os.path.join(tmp, "mb.yaml")
    open(scene, "w").write(MB_SCENE % free_port())
    drive = subprocess.Popen([SIMDRIVE, scene, "--late-after", "1", "--late-ms", "1500"],
                             stdout=subprocess.PIPE, text=True)
    try:
        if "serving" not in drive.stdout.readline():
            check(False, "strand-simdrive serves the slow drive")
            return
        p, port = start(scene, sim=False)
        try:
            async with websockets.connect(url(port)) as a, websockets.connect(url(port)) as b:
                A, B = Client(a), Client(b)
                await a.send(json.dumps(rpc("enable", None, 1)))
                await asyncio.sleep(0.3)
                t0 = time.time()
                r = await B.call("estop")
                took = time.time() - t0
                check("result" in r and took < 0.25,
                      "an e-stop while an enable waits on a slow drive: answered in %.0f ms"
                      % (took * 1e3))
                st = await B.wait(lambda s: s["state"] == "e-stopped", "e-stopped", 0.5)
                check(time.time() - t0 < 0.5,
                      "the state shows it while the enable still waits: %.0f ms"
                      % ((time.time() - t0) * 1e3))
                while True:
                    m = json.loads(await asyncio.wait_for(a.recv(), 20))
                    if m.get("id") == 1:
                        break
                st = (await A.call("status"))["result"]
                check("error" in m and st["state"] == "e-stopped",
                      "the enable gave up, the e-stop latched (%s)"
                      % m.get("error", {}).get("message", "")[:70])
        finally:
            stop(p)
    finally:
        drive.terminate()
        drive.wait()


async def no_scene(tmp):
    """strand serve without a scene: a client loads one of the data folder."""
    data = os.path.join(tmp, "data")
    os.makedirs(data)
    shutil.copy("examples/robot_arm.yaml", os.path.join(data, "arm.yaml"))
    open(os.path.join(data, "bad.yaml"), "w").write("scene: bad\ntiming: {tick_hz: 0}\n")
    journals = os.path.join(tmp, "journals")
    os.makedirs(journals)
    p, port = start(None, "--data", data, "--journal", journals)
    try:
        code, text = curl(port, rpc("enable"))
        check("no scene" in json.loads(text).get("error", {}).get("message", ""),
              "no scene yet: enable refused, saying so")
        code, text = curl(port, rpc("load", {"file": "bad.yaml"}))
        msg = json.loads(text).get("error", {}).get("message", "")
        check("bad.yaml:" in msg, "a bad scene's file:line:column reaches the client (%s)"
              % msg[-60:])
        code, text = curl(port, rpc("load", {"file": "arm.yaml"}))
        code, text = curl(port, rpc("info"))
        check(json.loads(text)["result"]["scene"] == "robot-arm", "then a scene is loaded")
        code, text = curl(port, rpc("enable"))
        check("result" in json.loads(text), "and the drives enable")
        # a play segment's journal: every frame fired, read by strand journal
        code, text = curl(port, rpc("play", {"from": 0, "to": 10}))
        t0 = time.time()
        while time.time() - t0 < 10:
            st = json.loads(curl(port, rpc("status"))[1])["result"]
            if st["loop"] == "hold" and st["fired"] == 11:
                break
            time.sleep(0.1)
        time.sleep(0.1)
        files = os.listdir(journals)
        rows = subprocess.run([STRAND, "journal", os.path.join(journals, files[0])],
                              capture_output=True, text=True).stdout.splitlines() if files else []
        check(len(files) == 1 and len(rows) == 12 and st["journal"] == 11,
              "the segment's journal (--journal): %s, %d frames read back, status says %d"
              % (files, len(rows) - 1, st["journal"]))
        # go-motion (step mode's shutter): its segment's journal has each
        # frame's exposure, opening with the trigger's edge and lasting half
        # a frame (180 degrees: 1000 / 24 / 2 = 20.8 ticks, so 20 or 21)
        code, text = curl(port, rpc("play", {"from": 20, "to": 22, "shutter": 180}))
        check("shutter is go-motion" in json.loads(text).get("error", {}).get("message", ""),
              "a shutter without step mode is refused")
        code, text = curl(port, rpc("play", {"mode": "step", "from": 20, "to": 22,
                                             "shutter": 180, "settle": 20, "exposure": 20}))
        t0 = time.time()
        while "result" in json.loads(text) and time.time() - t0 < 20:
            st = json.loads(curl(port, rpc("status"))[1])["result"]
            if st["loop"] == "hold" and st["fired"] == 3:
                break
            time.sleep(0.1)
        time.sleep(0.1)
        files = sorted(f for f in os.listdir(journals) if f.endswith("-2.journal"))
        rows = list(csv.DictReader(subprocess.run(
            [STRAND, "journal", os.path.join(journals, files[0])], capture_output=True,
            text=True).stdout.splitlines())) if files else []
        ok = len(rows) == 3 and all(int(r.get("open_tick", -1)) == int(r["tick"]) and
                                    20 <= int(r.get("close_tick", -1)) - int(r["open_tick"]) <= 21
                                    for r in rows)
        check(ok, "go-motion through play's shutter: %s, %d frames with their exposures (%s)"
              % (files, len(rows), ", ".join("%s-%s" % (r.get("open_tick"), r.get("close_tick"))
                                             for r in rows)))
    finally:
        stop(p)
        check(p.returncode == 0, "strand serve without a scene stops on SIGINT, exit 0")


def png_pixels(path):
    """(width, height, rows of RGB tuples) of an 8-bit non-interlaced PNG."""
    import struct, zlib
    data = open(path, "rb").read()
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            bpp = {2: 3, 6: 4}[ctype]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev = zlib.decompress(idat), [], bytearray(w * bpp)
    for y in range(h):
        row = y * (w * bpp + 1)
        f, line = raw[row], bytearray(raw[row + 1:row + 1 + w * bpp])
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1: line[i] = (line[i] + a) & 255
            elif f == 2: line[i] = (line[i] + b) & 255
            elif f == 3: line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                pred = a if pa <= pb and pa <= pc else b if pb <= pc else c
                line[i] = (line[i] + pred) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def screenshot_content(path, what):
    """The console drawn: the e-stop's red, the panels' dark grey, and some
    thousands of colours (text, plots), not a blank or an error page."""
    w, h, rows = png_pixels(path)
    red = sum(1 for r in rows for p in r if p[0] > 200 and p[1] < 110 and p[2] < 110)
    colours = len({p for r in rows[::4] for p in r[::4]})
    check(red > 1500 and colours > 100,
          "screenshot %s (%dx%d): the e-stop's red on %d pixels, %d colours"
          % (what, w, h, red, colours))


def browser(port, scene):
    from selenium import webdriver
    from selenium.webdriver.common.by import By
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.common.action_chains import ActionChains

    prof = tempfile.mkdtemp(prefix="strand-chromium-")
    o = webdriver.ChromeOptions()
    o.binary_location = "/usr/bin/chromium"
    for a in ("--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
              "--disable-background-networking", "--disable-component-update", "--disable-sync",
              "--window-size=1280,900", "--user-data-dir=" + prof):
        o.add_argument(a)
    from selenium.webdriver.chrome.service import Service
    svc = Service(executable_path="/usr/bin/chromedriver")
    d = webdriver.Chrome(options=o, service=svc)
    try:
        d.get("http://127.0.0.1:%d/" % port)

        def state():
            return d.find_element(By.ID, "state").text

        def until(pred, what, t=15):
            t0 = time.time()
            while time.time() - t0 < t:
                if pred():
                    return True
                time.sleep(0.05)
            check(False, "browser: " + what + " (state '%s')" % state())
            return False

        until(lambda: state() not in ("…", ""), "the page connects")
        d.find_element(By.ID, "enable").click()
        until(lambda: state().startswith("enabled"), "enabled")
        d.find_element(By.ID, "play").click()
        frames = set()
        t0 = time.time()
        while time.time() - t0 < 5 and len(frames) < 3:
            frames.add(d.find_element(By.ID, "tc").text)
            time.sleep(0.02)
        check(len(frames) >= 3, "browser: play, the frame advances (%s; %s)"
              % (sorted(frames)[:3], d.find_element(By.ID, "reason").text))
        d.find_element(By.ID, "stop").click()
        until(lambda: "hold" in state(), "at rest after stop")
        v0 = d.find_element(By.ID, "v0").text
        d.find_element(By.TAG_NAME, "body").click()
        ActionChains(d).send_keys("1").key_down(Keys.ARROW_RIGHT).pause(0.6).key_up(
            Keys.ARROW_RIGHT).perform()
        until(lambda: "hold" in state() and d.find_element(By.ID, "v0").text != v0,
              "a jog from the keyboard moves output 1")
        check(d.find_element(By.ID, "v0").text != v0,
              "browser: keyboard jog moved output 1 (%s -> %s)"
              % (v0, d.find_element(By.ID, "v0").text))
        # at frame 48's pose (base at 60 degrees until frame 96), base keyed
        # there at frame 72
        d.find_element(By.ID, "frame").clear()
        d.find_element(By.ID, "frame").send_keys("48")
        d.find_element(By.ID, "goto").click()
        until(lambda: "FRAME 48 " in d.find_element(By.ID, "tc").text.upper() and "hold" in state(),
              "at frame 48 (%s; %s)" % (d.find_element(By.ID, "tc").text,
                                        d.find_element(By.ID, "log").text[:120]))
        before = open(scene).read().count("{frame: 72, angle:")
        d.find_element(By.ID, "tframe").clear()
        d.find_element(By.ID, "tframe").send_keys("72")
        d.find_element(By.ID, "tnode").send_keys("base")
        d.find_element(By.ID, "teach").click()
        until(lambda: "key" in d.find_element(By.ID, "tmsg").text, "teach answered")
        check(open(scene).read().count("{frame: 72, angle:") == before + 1,
              "browser: a taught key is in the file ('%s')"
              % d.find_element(By.ID, "tmsg").text)
        d.save_screenshot(os.path.join(OUT, "serve-desktop.png"))
        d.find_element(By.ID, "estop").click()
        until(lambda: state().startswith("e-stopped"), "e-stop latches")
        check(state().startswith("e-stopped"), "browser: e-stop, the state latches")
        d.set_window_size(390, 844)
        time.sleep(0.5)
        d.save_screenshot(os.path.join(OUT, "serve-phone.png"))
        est = d.find_element(By.ID, "estop")
        check(est.is_displayed() and est.location["y"] < 200,
              "browser: on a phone's width the e-stop stays in view")
        # the rows rebuilt (as an event does) while the rig stands and no new
        # status comes: they must keep the last status's values
        v0 = d.execute_script("return loadInfo().then(() => $('v0').textContent)")
        check(v0.endswith("deg"),
              "browser: after the e-stop the jog rows still show where the rig stands (%s)" % v0)
        for f in ("serve-desktop.png", "serve-phone.png"):
            screenshot_content(os.path.join(OUT, f), f)
    finally:
        d.quit()
        shutil.rmtree(prof, ignore_errors=True)


def main():
    tmp = tempfile.mkdtemp(prefix="strand-serve-")
    scene = os.path.join(tmp, "arm.yaml")
    shutil.copy("examples/robot_arm.yaml", scene)
    tokf = os.path.join(tmp, "token")
    token = "t0ken-for-the-test-0123456789"
    open(tokf, "w").write(token + "\n")
    p, port = start(scene)
    tp, tport = start(scene, "--token-file", tokf)
    try:
        asyncio.run(origin_token(port, tport, token))
        asyncio.run(ws_tests(port, scene))
        asyncio.run(slow_client(port))
        asyncio.run(estop_during_enable(tmp))
        asyncio.run(no_scene(tmp))
        if os.environ.get("SERVE_BROWSER", "1") == "1":
            browser(port, scene)
    finally:
        stop(p)
        stop(tp)
        check(p.returncode == 0, "strand serve stops on SIGINT, exit 0")
        shutil.rmtree(tmp, ignore_errors=True)
    print("%d failed" % failed)
    sys.exit(1 if failed else 0)


main()
