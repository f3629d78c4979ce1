"""A Foxglove viewer that subscribes to every channel of a live run and then never
reads again, for tests/foxglove_live.rs. Run it in a network namespace whose TCP send
buffers are small (the test sets net.ipv4.tcp_wmem), so that the server's socket to
it fills within seconds and its per-client backlog overflows.

Usage: python3 stalled_viewer.py ILMRC ARGS...  (ILMRC gets `--foxglove=127.0.0.1:0`)
Prints one JSON object: exit code, seconds from subscribing to the run's end, the
largest send queue seen on the server's side of the connection, stdout and stderr.
"""

import json
import re
import socket
import subprocess
import sys
import time


def frame(text):
    data = text.encode()
    mask = b"\x01\x02\x03\x04"
    head = bytes([0x81, 0x80 | 126]) + len(data).to_bytes(2, "big")
    return head + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data))


def main():
    run = subprocess.Popen(
        [sys.argv[1], "run", "--foxglove=127.0.0.1:0", *sys.argv[2:]],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    first = run.stderr.readline()
    host, port = re.search(r"ws://([0-9.]+):(\d+)", first).groups()
    s = socket.socket()
    s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
    s.connect((host, int(port)))
    s.sendall(
        (
            f"GET / HTTP/1.1\r\nHost: {host}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
            "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n"
            "Sec-WebSocket-Protocol: foxglove.sdk.v1\r\n\r\n"
        ).encode()
    )
    seen = b""
    advertised = None
    while advertised is None:
        chunk = s.recv(65536)
        if not chunk:
            sys.exit("the server closed before advertising")
        seen += chunk
        start = seen.find(b'{"op":"advertise"')
        end = seen.find(b"]}", start)
        if start >= 0 and end >= 0:
            advertised = json.loads(seen[start : end + 2])
    subscriptions = [{"id": i, "channelId": c["id"]} for i, c in enumerate(advertised["channels"])]
    s.sendall(frame(json.dumps({"op": "subscribe", "subscriptions": subscriptions})))
    subscribed = time.monotonic()
    send_queue = 0
    while run.poll() is None:
        ss = subprocess.run(["ss", "-tn", f"sport = :{port}"], capture_output=True, text=True)
        for line in ss.stdout.splitlines()[1:]:
            send_queue = max(send_queue, int(line.split()[2]))
        time.sleep(0.2)
    took = time.monotonic() - subscribed
    print(
        json.dumps(
            {
                "exit": run.returncode,
                "took": took,
                "send_queue": send_queue,
                "stdout": run.stdout.read(),
                "stderr": first + run.stderr.read(),
            }
        )
    )
    s.close()


if __name__ == "__main__":
    main()
