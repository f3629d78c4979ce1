"""Measures a fleet over DDS: N simulated robots, each its own process
(`ilmrc sim --ros2`, launched by the fleet), driven by one `ilmrc serve --fleet`,
observed from outside with Eclipse Cyclone DDS. Prints a Markdown table:

- DDS messages per second that Cyclone receives from the fleet (every robot's odom,
  tf, ground_truth, scan, battery_state and cmd_vel);
- latency from an ILMR line sent to `serve` to the first moving `cmd_vel` of that
  robot on DDS (one clock: both ends are this process);
- CPU per robot: each simulator's, and `serve`'s divided by N, from /proc over the
  window, while every robot drives.

    unshare -n python3 fleet_bench.py --ilmrc target/release/ilmrc --robots 10

Runs only in a network namespace of its own (netns_run.isolate)."""

import argparse
import json
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

from netns_run import CYCLONE_LOOPBACK, isolate
from ros2_msgs import BatteryState, LaserScan, Odometry, TFMessage, Twist

TICK = os.sysconf("SC_CLK_TCK")


def cpu_seconds(pid):
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / TICK


def children(pid):
    out = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        out.append(int(entry))
            except OSError:
                pass
    return out


class Planner:
    def __init__(self, addr):
        host, port = addr.rsplit(":", 1)
        self.sock = socket.create_connection((host, int(port)))
        self.file = self.sock.makefile("r")

    def ask(self, request):
        self.sock.sendall((json.dumps(request) + "\n").encode())
        return json.loads(self.file.readline())


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--ilmrc", required=True)
    p.add_argument("--robots", type=int, default=10)
    p.add_argument("--seconds", type=float, default=10.0, help="the measuring window")
    p.add_argument("--rounds", type=int, default=3, help="latency samples per robot")
    args = p.parse_args()
    isolate()
    os.environ["CYCLONEDDS_URI"] = CYCLONE_LOOPBACK
    n = args.robots
    names = [f"r{k}" for k in range(1, n + 1)]
    tmp = tempfile.mkdtemp()
    fleet = os.path.join(tmp, "fleet.toml")
    with open(fleet, "w") as f:
        for name in names:
            f.write(
                f'[[robot]]\nname = "{name}"\nrobot = "ros2"\nmodel = "moro"\nloopback = true\n'
                f'launch = true\nworld = "empty"\nstart = "0,0,0"\n\n'
            )
    started = time.monotonic()
    serve = subprocess.Popen(
        [args.ilmrc, "serve", "--fleet", fleet, "--no-tls", "--listen", "127.0.0.1:0"],
        stdout=subprocess.PIPE,
        text=True,
    )
    line = serve.stdout.readline()
    if not line.startswith("listening on "):
        serve.kill()
        sys.exit(f"serve did not start: {line!r}")
    up = time.monotonic() - started
    planner = Planner(line.split()[2])

    dp = DomainParticipant(0)
    qos = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(100))
    kinds = [("odom", Odometry), ("tf", TFMessage), ("ground_truth", Odometry), ("scan", LaserScan), ("battery_state", BatteryState)]
    observed = [DataReader(dp, Topic(dp, f"rt/{r}/{t}", cls), qos=qos) for r in names for t, cls in kinds]
    commands = {r: DataReader(dp, Topic(dp, f"rt/{r}/cmd_vel", Twist), qos=qos) for r in names}
    time.sleep(2.0)  # discovery
    for r in list(commands.values()) + observed:
        r.take(N=10000)

    latencies = []
    for _ in range(args.rounds):
        for name in names:
            reader = commands[name]
            reader.take(N=10000)
            sent = time.monotonic()
            answer = planner.ask({"robot": name, "ilmr": "goahead(0.3)"})
            assert answer.get("ok"), answer
            moving = None
            while moving is None and time.monotonic() - sent < 5.0:
                for s in reader.take(N=100):
                    if isinstance(s, Twist) and s.linear.x > 0:
                        moving = time.monotonic()
                        break
                else:
                    time.sleep(0.0002)
            assert moving is not None, f"{name}: no moving cmd_vel within 5 s"
            latencies.append(moving - sent)
        time.sleep(2.0)

    # The window: every robot drives.
    for name in names:
        planner.ask({"robot": name, "ilmr": "goahead(5)"})
    sims = children(serve.pid)
    cpu0 = {pid: cpu_seconds(pid) for pid in [serve.pid] + sims}
    for r in list(commands.values()) + observed:
        r.take(N=10000)
    count = 0
    t0 = time.monotonic()
    while time.monotonic() - t0 < args.seconds:
        for r in list(commands.values()) + observed:
            count += len(r.take(N=10000))
        time.sleep(0.01)
    window = time.monotonic() - t0
    cpu = {pid: (cpu_seconds(pid) - c) / window for pid, c in cpu0.items()}
    serve.terminate()
    serve.wait(timeout=30)

    serve_share = cpu[serve.pid] / n
    sim_cpu = [cpu[pid] for pid in sims]
    result = {
        "robots": n,
        "startup_s": up,
        "dds_messages_per_s": count / window,
        "latency_ms_median": statistics.median(latencies) * 1000,
        "latency_ms_max": max(latencies) * 1000,
        "serve_cpu_per_robot": serve_share,
        "sim_cpu_mean": statistics.mean(sim_cpu) if sim_cpu else None,
        "simulators": len(sims),
    }
    print(json.dumps(result))
    print(f"| robots | DDS messages/s seen | line to first cmd_vel (median / max) | serve CPU per robot | each simulator's CPU |")
    print("| --- | --- | --- | --- | --- |")
    print(
        f"| {n} | {result['dds_messages_per_s']:.0f} | {result['latency_ms_median']:.1f} / {result['latency_ms_max']:.1f} ms "
        f"| {100 * serve_share:.1f} % of a core | {100 * (result['sim_cpu_mean'] or 0):.1f} % of a core |"
    )


if __name__ == "__main__":
    main()
