"""Runs the Cyclone DDS robot (cyclone_robot.py), or other programs (`--background`),
and a command against them, inside a network namespace of their own, and prints one
JSON object: the command's exit code, stdout and stderr, the robot's report and what
the background programs printed.

    unshare -n python3 netns_run.py --robot-arg=--namespace=/r1 ... -- ilmrc run ...
    unshare -n python3 netns_run.py --no-robot --background 'ilmrc sim --ros2' -- ilmrc run ...

A background program must print a line on stdout when it is ready (its endpoints
exist); it is stopped with SIGTERM after the command ends.

DDS finds peers by multicast. In a namespace of its own, with loopback the only
interface, nothing it sends can leave this machine; the script refuses to run
anywhere else. Loopback is brought up with multicast and a route for 224.0.0.0/4, and
Cyclone is pinned to it as well."""

import argparse
import json
import os
import shlex
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

CYCLONE_LOOPBACK = (
    "<CycloneDDS><Domain id='any'><General><Interfaces>"
    "<NetworkInterface name='lo' multicast='true'/>"
    "</Interfaces></General></Domain></CycloneDDS>"
)


def isolate():
    # /proc/net/dev is the namespace's own (/sys/class/net is not, unless remounted).
    with open("/proc/net/dev") as f:
        interfaces = sorted(line.split(":")[0].strip() for line in f.readlines()[2:])
    if interfaces != ["lo"]:
        sys.exit(f"netns_run.py runs only in a network namespace of its own (unshare -n); here: {interfaces}")
    subprocess.run(["ip", "link", "set", "lo", "up", "multicast", "on"], check=True)
    subprocess.run(["ip", "route", "add", "224.0.0.0/4", "dev", "lo"], check=True)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--robot-arg", action="append", default=[], help="passed to cyclone_robot.py")
    p.add_argument("--timeout", type=float, default=120.0, help="for the ILMR command, s")
    p.add_argument("--no-robot", action="store_true", help="do not start cyclone_robot.py")
    p.add_argument("--background", action="append", default=[], help="a command line to start first")
    p.add_argument("command", nargs=argparse.REMAINDER)
    args = p.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    isolate()
    env = dict(os.environ, CYCLONEDDS_URI=CYCLONE_LOOPBACK)
    with tempfile.TemporaryDirectory() as tmp:
        report = os.path.join(tmp, "robot.json")
        background = []
        for line in args.background:
            background.append(start(shlex.split(line), env))
        robot = None
        if not args.no_robot:
            robot = start(
                [sys.executable, os.path.join(HERE, "cyclone_robot.py"), "--report", report, *args.robot_arg],
                env,
            )
        started = time.monotonic()
        try:
            ran = subprocess.run(command, capture_output=True, text=True, timeout=args.timeout)
            outcome = {"code": ran.returncode, "stdout": ran.stdout, "stderr": ran.stderr}
        except subprocess.TimeoutExpired as e:
            outcome = {"code": None, "stdout": e.stdout or "", "stderr": f"timed out after {args.timeout} s"}
        outcome["seconds"] = time.monotonic() - started
        # The robot keeps running a moment after the command, so that what it does
        # once commands stop (its own timeout) is in its report.
        time.sleep(1.0)
        robot_out = None
        if robot is not None:
            stop(robot)
            robot_out = {"error": robot.stderr.read()}
            if os.path.exists(report):
                with open(report) as f:
                    robot_out = json.load(f)
        others = []
        for b in background:
            code = stop(b)
            others.append({"code": code, "stdout": b.ready + b.stdout.read(), "stderr": b.stderr.read()})
        print(json.dumps({"ilmrc": outcome, "robot": robot_out, "background": others}))


def start(argv, env):
    """Starts a program and waits for its first line on stdout."""
    p = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    p.ready = p.stdout.readline()
    if not p.ready:
        p.kill()
        sys.exit(f"{argv[0]} did not start: {p.stderr.read()}")
    return p


def stop(p):
    p.terminate()
    try:
        return p.wait(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
        return p.wait()


if __name__ == "__main__":
    main()
