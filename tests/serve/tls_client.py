"""A client of `ilmrc serve --credentials` that this project did not write the TLS of:
Python's `ssl` module. Used by tests/serve/secure.rs.

    python3 tls_client.py PORT CA_PEM [CERT_PEM KEY_PEM]

Reads commands on stdin, one per line, and prints one line on stdout for each:
a JSON request is sent and the next line from the server printed; `@read` prints the
next line the server sends; `@connect` (re)connects. A connection the server closes
prints `@closed`; a handshake the server refuses prints `@refused: REASON`. Every read
waits at most 20 s.
"""

import socket
import ssl
import sys

port, ca = int(sys.argv[1]), sys.argv[2]
context = ssl.create_default_context(cafile=ca)
if len(sys.argv) > 4:
    context.load_cert_chain(sys.argv[3], sys.argv[4])

conn = None
reader = None


def say(text):
    sys.stdout.write(text + "\n")
    sys.stdout.flush()


def connect():
    global conn, reader
    raw = socket.create_connection(("127.0.0.1", port), timeout=20)
    try:
        conn = context.wrap_socket(raw, server_hostname="localhost")
    except (ssl.SSLError, OSError) as e:
        conn = None
        return f"@refused: {e}"
    reader = conn.makefile("rb")
    return "@connected " + conn.version()


def read_line():
    try:
        line = reader.readline()
    except (ssl.SSLError, OSError) as e:
        # TLS 1.3 reports a refused client certificate only on the first read.
        return f"@refused: {e}"
    return line.decode().rstrip("\n") if line else "@closed"


for command in sys.stdin:
    command = command.strip()
    if command == "@connect":
        say(connect())
    elif conn is None:
        say("@closed")
    elif command == "@read":
        say(read_line())
    else:
        try:
            conn.sendall((command + "\n").encode())
        except (ssl.SSLError, OSError):
            say("@closed")
            continue
        say(read_line())
