"""Times `{"status": true}` against `ilmrc serve` running a task of many variables
(docs/performance.md, "`status` of a task of many variables"), on loopback.

  python3 -c "open('/tmp/vars.ilmr','w').write(''.join(f'v{i}={i}\\n' for i in range(50000))+'wait(1000)\\n')"
  python3 tools/serve_status.py target/release/ilmrc /tmp/vars.ilmr
"""
import socket, subprocess, time, json, sys, re
binary = sys.argv[1]
p = subprocess.Popen([binary, "serve", "--robot", "moro", "--no-tls", "--listen", "127.0.0.1:0", "--task", sys.argv[2]], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
port = None
for line in p.stdout:
    m = re.search(r"127\.0\.0\.1:(\d+)", line)
    if m:
        port = int(m.group(1)); break
time.sleep(1)
s = socket.create_connection(("127.0.0.1", port))
f = s.makefile("rw")
for i in range(3):
    t = time.time()
    f.write(json.dumps({"status": True}) + "\n"); f.flush()
    ans = f.readline()
    print("status %.3f s, %d bytes" % (time.time() - t, len(ans)))
p.kill()
