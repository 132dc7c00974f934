#!/usr/bin/env python3
"""Times `rigor lsp` as an editor sees it (issue #33: diagnostics for a handout file
within 50 ms of an edit; a 1 MB document stays responsive).

It starts the release binary, opens the handout's rolling cylinder
(derivations/rolling_cylinder.deriv) and edits one step back and forth between false
and true, timing each edit from the moment `didChange` is sent to the moment the
diagnostics of that version arrive (and checking that the false version's error is at
the step's line and the true version has none). Then a burst of keystrokes 5 ms apart,
timed from the last one. Then a generated 1 MB derivation is opened: while it is being
checked, the handout is edited and hovered again (the big document must not hold it
up), and the big document's own edit is timed.

Usage: bench/lsp_latency.py [edits]   (needs a release build: cargo build --release)
"""
import json
import os
import statistics
import subprocess
import sys
import threading
import queue
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TARGET = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
BIN = os.path.join(TARGET, "release", "rigor")


class Server:
    def __init__(self):
        self.p = subprocess.Popen([BIN, "lsp"], stdin=subprocess.PIPE, stdout=subprocess.PIPE)
        self.q = queue.Queue()
        self.next_id = 1
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        out = self.p.stdout
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                line = line.strip()
                if not line:
                    break
                if line.startswith(b"Content-Length:"):
                    length = int(line.split(b":")[1])
            self.q.put((time.perf_counter(), json.loads(out.read(length))))

    def send(self, msg):
        body = json.dumps(msg).encode()
        self.p.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
        self.p.stdin.flush()
        return time.perf_counter()

    def notify(self, method, params):
        return self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method, params):
        i = self.next_id
        self.next_id += 1
        sent = self.send({"jsonrpc": "2.0", "id": i, "method": method, "params": params})
        at, msg = self.wait(lambda m: m.get("id") == i)
        return at - sent, msg.get("result")

    def wait(self, want, timeout=120):
        while True:
            at, msg = self.q.get(timeout=timeout)
            if want(msg):
                return at, msg

    def diagnostics(self, uri, version):
        return self.wait(lambda m: m.get("method") == "textDocument/publishDiagnostics"
                         and m["params"]["uri"] == uri and m["params"].get("version") == version)


def cpu_ms(pid):
    """The CPU time (user + system) the process has used so far, in ms (Linux)."""
    try:
        fields = open(f"/proc/{pid}/stat").read().rsplit(")", 1)[1].split()
        return 1000 * (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except OSError:
        return float("nan")


def change(s, uri, version, text):
    return s.notify("textDocument/didChange", {
        "textDocument": {"uri": uri, "version": version}, "contentChanges": [{"text": text}]})


def summary(name, ms):
    ms = sorted(ms)
    p95 = ms[min(len(ms) - 1, int(0.95 * len(ms)))]
    print(f"{name:<58} n={len(ms):<4} median {statistics.median(ms):7.1f} ms"
          f"   p95 {p95:7.1f} ms   max {ms[-1]:7.1f} ms")


def main():
    edits = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    if not os.access(BIN, os.X_OK):
        sys.exit(f"{BIN}: build it first (cargo build --release)")
    path = os.path.join(ROOT, "derivations", "rolling_cylinder.deriv")
    uri = "file://" + path
    good = open(path).read()
    step = "claim [N] N = m g cos(beta) by [Fy], [onslope]"
    assert step in good
    bad = good.replace(step, step.replace("cos(beta)", "sin(beta)"))
    line = good[: good.index(step)].count("\n")
    s = Server()
    s.request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
    s.notify("initialized", {})
    sent = s.notify("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "rigor", "version": 1, "text": good}})
    at, _ = s.diagnostics(uri, 1)
    summary("open the handout file: first diagnostics", [1000 * (at - sent)])
    version, times = 1, []
    cpu = cpu_ms(s.p.pid)
    for i in range(edits):
        version += 1
        wrong = i % 2 == 0
        sent = change(s, uri, version, bad if wrong else good)
        at, msg = s.diagnostics(uri, version)
        ds = msg["params"]["diagnostics"]
        if wrong:
            errors = [(d["range"]["start"]["line"], d["code"]) for d in ds if d["severity"] == 1]
            assert errors == [(line, "E0301")], ds
        else:
            assert ds == [], ds
        times.append(1000 * (at - sent))
    summary("edit a step (false <-> true): its diagnostics", times)
    per_edit = (cpu_ms(s.p.pid) - cpu) / edits
    label = "  the server's CPU time per edit"
    print(f"{label:<58} {per_edit:.1f} ms "
          f"(load average now {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores)")
    # A burst of keystrokes: the newest version is checked, the older ones stopped.
    burst = []
    for _ in range(10):
        for k in range(5):
            version += 1
            last = change(s, uri, version, bad if k % 2 == 0 else good)
            time.sleep(0.005)
        at, _ = s.diagnostics(uri, version)
        burst.append(1000 * (at - last))
    summary("5 keystrokes 5 ms apart: the last one's diagnostics", burst)
    big_doc(s, uri, good, bad, version)
    s.request("shutdown", None)
    s.notify("exit", None)
    s.p.wait(timeout=30)


def big_doc(s, uri, good, bad, version):
    lines = ["# A long derivation", "symbols x"]
    i = 0
    while sum(len(l) + 1 for l in lines) < 1_000_000:
        i += 1
        lines.append(f"claim [c{i}] (x + {i})^2 = x^2 + {2 * i} x + {i * i}")
    text = "\n".join(lines) + "\n"
    big = "file:///tmp/rigor-bench-big.deriv"
    sent = s.notify("textDocument/didOpen", {"textDocument": {
        "uri": big, "languageId": "rigor", "version": 1, "text": text}})
    # While the big document is checked, the handout's edits and hovers go on.
    times, hovers = [], []
    for k in range(10):
        version += 1
        t0 = change(s, uri, version, bad if k % 2 == 0 else good)
        at, _ = s.diagnostics(uri, version)
        times.append(1000 * (at - t0))
        took, _ = s.request("textDocument/hover", {
            "textDocument": {"uri": uri}, "position": {"line": 30, "character": 12}})
        hovers.append(1000 * took)
    at, msg = s.diagnostics(big, 1)
    print(f"(the 1 MB document: {len(text)} bytes, {i} claims, "
          f"{len(msg['params']['diagnostics'])} diagnostics)")
    summary("1 MB document: open to its diagnostics", [1000 * (at - sent)])
    summary("handout edits while the 1 MB document is checked", times)
    summary("handout hovers while the 1 MB document is checked", hovers)
    # An edit at the end of the big document, as a keystroke: an incremental change.
    n = len(lines)
    t0 = s.notify("textDocument/didChange", {
        "textDocument": {"uri": big, "version": 2},
        "contentChanges": [{"range": {"start": {"line": n, "character": 0},
                                      "end": {"line": n, "character": 0}},
                            "text": "claim [last] x + x = 2 x\n"}]})
    at, _ = s.diagnostics(big, 2)
    summary("1 MB document: a keystroke to its diagnostics", [1000 * (at - t0)])
    took, _ = s.request("textDocument/documentSymbol", {"textDocument": {"uri": big}})
    summary("1 MB document: its outline", [1000 * took])


if __name__ == "__main__":
    main()
