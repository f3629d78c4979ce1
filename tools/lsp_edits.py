#!/usr/bin/env python3
"""The language server as an editor sees it, measured with a client this project did
not write the protocol side of (plain JSON-RPC over the server's stdio, from Python's
standard library): how late the diagnostics of the last of a burst of quick edits
arrive, and how long completion takes, at 10,000 and 100,000 lines.

    python3 tools/lsp_edits.py [--server target/release/ilmr-lsp] [--lines 10000 100000]
                               [--edits 200] [--lens]

Each size: open a generated task (the shape of lsp/benches/latency.rs: searches,
guards, waits, counting loops, skill calls, 12 lines a block), wait for its first
diagnostics, send EDITS one-character edits as fast as the pipe takes them, and time
from the last edit sent to the diagnostics of its version; then completion after
`gotoxy(` in the middle of the file (median of 20) and the number of items it offered.
Prints a Markdown table row per size (docs/performance.md).

With --lens, the requests of the concurrency lens and its neighbours instead, on the
same task: inlay hints of a 60-line screen in the middle, the first after an edit
(which computes the file's schedule) and then the median of 20; inlay hints of the
whole file; code lenses; workspace symbols (an empty query and a name); document
highlights of a variable. Medians of 20, in ms.
"""

import argparse
import json
import statistics
import subprocess
import sys
import threading
import time
import queue


def task(lines):
    out, i = [], 0
    while i * 12 < lines:
        k = i % 50
        out.append(
            f"ovi_ö{i} = sensor(scanner,door,left)\nif(ovi_ö{i})\n    speed(0.3)\n"
            f"    g{i} = gotoxy(ovi_ö{i})\n    wait(g{i})\n    taito{k}\nendif\n"
            f"käännös{i} = 0\nwhile(käännös{i} < 3)\n    käännös{i} = käännös{i} + 1\nendwhile\n\n"
        )
        i += 1
    return "".join(out)


def skills():
    return "".join(f"taito{k}:\nspeed(-0.3)\nt{k}=turn(d=90,c=0.5)\nwait(t{k})\n\n" for k in range(50))


class Client:
    def __init__(self, server):
        self.proc = subprocess.Popen([server], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL)
        self.messages = queue.Queue()
        self.next_id = 0
        self.lock = threading.Lock()
        threading.Thread(target=self.read, daemon=True).start()

    def read(self):
        out = self.proc.stdout
        while True:
            length = None
            while True:
                line = out.readline()
                if not line:
                    return
                line = line.strip()
                if not line:
                    break
                if line.lower().startswith(b"content-length:"):
                    length = int(line.split(b":")[1])
            message = json.loads(out.read(length))
            if "method" in message and "id" in message:
                # The server's own requests (client/registerCapability): accepted.
                self.send({"jsonrpc": "2.0", "id": message["id"], "result": None})
                continue
            self.messages.put((time.perf_counter(), message))

    def send(self, message):
        body = json.dumps(message).encode()
        with self.lock:
            self.proc.stdin.write(b"Content-Length: %d\r\n\r\n" % len(body) + body)
            self.proc.stdin.flush()

    def notify(self, method, params):
        self.send({"jsonrpc": "2.0", "method": method, "params": params})

    def request(self, method, params):
        self.next_id += 1
        me = self.next_id
        self.send({"jsonrpc": "2.0", "id": me, "method": method, "params": params})
        return self.wait(lambda m: m.get("id") == me and "method" not in m)

    def wait(self, found, patience=600):
        deadline = time.perf_counter() + patience
        while True:
            at, m = self.messages.get(timeout=max(0.0, deadline - time.perf_counter()))
            if found(m):
                return at, m


def opened(server, lines):
    """A server with the skill file and a task of `lines` lines open, its first
    diagnostics in: the client, the task's URI, its text, the wait for a version's
    diagnostics and a line in its middle."""
    c = Client(server)
    c.request("initialize", {"processId": None, "rootUri": None, "capabilities": {}})
    c.notify("initialized", {})
    uri = f"file:///bench/task{lines}.ilmr"
    c.notify("textDocument/didOpen", {"textDocument": {
        "uri": "file:///bench/skills.ilms", "languageId": "ilmr", "version": 1, "text": skills()}})
    text = task(lines)
    c.notify("textDocument/didOpen", {"textDocument": {
        "uri": uri, "languageId": "ilmr", "version": 1, "text": text}})
    diagnostics_of = lambda v: (lambda m: m.get("method") == "textDocument/publishDiagnostics"
                                and m["params"]["uri"] == uri and m["params"].get("version") == v)
    c.wait(diagnostics_of(1))
    middle = (lines // 2) // 12 * 12 + 3
    return c, uri, text, diagnostics_of, middle


def measure(server, lines, edits):
    c, uri, text, diagnostics_of, middle = opened(server, lines)
    edit = {"start": {"line": middle, "character": 4}, "end": {"line": middle, "character": 5}}
    for v in range(2, edits + 2):
        c.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": v},
                                            "contentChanges": [{"range": edit, "text": "g"}]})
    sent = time.perf_counter()
    at, _ = c.wait(diagnostics_of(edits + 1))
    late = at - sent
    times, count = [], 0
    for _ in range(20):
        t0 = time.perf_counter()
        at, m = c.request("textDocument/completion", {
            "textDocument": {"uri": uri}, "position": {"line": middle, "character": 18}})
        times.append(at - t0)
        result = m.get("result") or []
        items = result["items"] if isinstance(result, dict) else result
        count = len(items)
    c.request("shutdown", None)
    c.notify("exit", None)
    c.proc.stdin.close()
    try:
        c.proc.wait(timeout=60)
    except subprocess.TimeoutExpired:
        c.proc.kill()
        raise SystemExit("the server did not exit after `exit`")
    return late, statistics.median(times), count


def timed(c, method, params, n=20):
    times, answer = [], None
    for _ in range(n):
        t0 = time.perf_counter()
        at, m = c.request(method, params)
        times.append(at - t0)
        answer = m.get("result")
    return statistics.median(times) * 1e3, answer


def measure_lens(server, lines):
    c, uri, text, diagnostics_of, middle = opened(server, lines)
    doc = {"uri": uri}
    screen = {"textDocument": doc, "range": {"start": {"line": middle - 30, "character": 0},
                                             "end": {"line": middle + 30, "character": 0}}}
    # An edit, its diagnostics, then the first hints: they compute the schedule.
    edit = {"start": {"line": middle, "character": 4}, "end": {"line": middle, "character": 5}}
    c.notify("textDocument/didChange", {"textDocument": {"uri": uri, "version": 2},
                                        "contentChanges": [{"range": edit, "text": "g"}]})
    c.wait(diagnostics_of(2))
    t0 = time.perf_counter()
    at, m = c.request("textDocument/inlayHint", screen)
    first = (at - t0) * 1e3
    screen_ms, hints = timed(c, "textDocument/inlayHint", screen)
    whole = {"textDocument": doc, "range": {"start": {"line": 0, "character": 0},
                                            "end": {"line": lines + 1, "character": 0}}}
    whole_ms, all_hints = timed(c, "textDocument/inlayHint", whole, n=5)
    lens_ms, _ = timed(c, "textDocument/codeLens", {"textDocument": doc})
    empty_ms, found = timed(c, "workspace/symbol", {"query": ""})
    name_ms, _ = timed(c, "workspace/symbol", {"query": f"käännös{lines // 24}"})
    high_ms, marks = timed(c, "textDocument/documentHighlight", {
        "textDocument": doc, "position": {"line": middle, "character": 6}})
    c.request("shutdown", None)
    c.notify("exit", None)
    c.proc.stdin.close()
    try:
        c.proc.wait(timeout=60)
    except subprocess.TimeoutExpired:
        c.proc.kill()
        raise SystemExit("the server did not exit after `exit`")
    return (first, screen_ms, len(hints or []), whole_ms, len(all_hints or []), lens_ms,
            empty_ms, len(found or []), name_ms, high_ms, len(marks or []))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--server", default="target/release/ilmr-lsp")
    p.add_argument("--lines", type=int, nargs="+", default=[10_000, 100_000])
    p.add_argument("--edits", type=int, default=200)
    p.add_argument("--lens", action="store_true")
    a = p.parse_args()
    if a.lens:
        print("| lines | hints of a screen, first after an edit | then | hints | hints of the whole file | hints "
              "| code lenses | symbols `\"\"` | found | symbols by name | highlights | found |")
        print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for n in a.lines:
            r = measure_lens(a.server, n)
            print(f"| {n:,} | {r[0]:.1f} | {r[1]:.1f} | {r[2]} | {r[3]:.1f} | {r[4]:,} | {r[5]:.2f} "
                  f"| {r[6]:.1f} | {r[7]} | {r[8]:.1f} | {r[9]:.1f} | {r[10]} |")
            sys.stdout.flush()
        return
    print(f"| lines | last of {a.edits} edits: diagnostics after, s | completion after `gotoxy(`, ms (median of 20) | items |")
    print("| ---: | ---: | ---: | ---: |")
    for n in a.lines:
        late, completion, count = measure(a.server, n, a.edits)
        print(f"| {n:,} | {late:.2f} | {completion * 1e3:.1f} | {count:,} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
