"""A small ROS 2 robot on Eclipse Cyclone DDS (its Python binding): what ILMR's
`--robot ros2` is tested against, written with software this project did not write.

It behaves as a differential-drive base driver does: it subscribes `cmd_vel`
(geometry_msgs/Twist), stops when no command arrives for `--cmd-timeout` seconds,
integrates a unicycle with bounded acceleration at 100 Hz, and publishes `odom`
(nav_msgs/Odometry, 50 Hz), `scan` (sensor_msgs/LaserScan, 10 Hz, 181 beams over the
front half, cast against the walls of a rectangular room) and `battery_state`
(sensor_msgs/BatteryState, 1 Hz), all under `--namespace`.

Streams can be made to stop (`--odom-stop-at`, `--scan-stop-at`, seconds after start;
the scan again from `--scan-resume-at`) to test what a controller does when a robot's
sensor link dies. Every twist received
is logged; on SIGTERM or after `--duration` the robot writes a JSON report (true pose,
the twists, when streams stopped) to `--report` and exits.

Prints `ready` on stdout once its endpoints exist."""

import argparse
import json
import math
import signal
import sys
import time

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.pub import DataWriter
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic
from cyclonedds.util import duration

from ros2_msgs import (
    BatteryState,
    Header,
    LaserScan,
    Odometry,
    Point,
    Pose,
    PoseWithCovariance,
    Quaternion,
    Time,
    Twist,
    TwistWithCovariance,
    Vector3,
)

STEP = 0.01


def stamp(t):
    sec = math.floor(t)
    return Time(sec=sec, nanosec=int((t - sec) * 1e9))


def header(t, frame):
    return Header(stamp=stamp(t), frame_id=frame)


class Room:
    """An axis-aligned rectangle of walls."""

    def __init__(self, x0, y0, x1, y1):
        self.x0, self.y0, self.x1, self.y1 = x0, y0, x1, y1

    def ray(self, x, y, a):
        """Distance from (x, y) along heading a to the nearest wall."""
        c, s = math.cos(a), math.sin(a)
        best = math.inf
        for wall, d in ((self.x0, c), (self.x1, c)):
            if abs(d) > 1e-12:
                t = (wall - x) / d
                if t > 0 and self.y0 <= y + t * s <= self.y1:
                    best = min(best, t)
        for wall, d in ((self.y0, s), (self.y1, s)):
            if abs(d) > 1e-12:
                t = (wall - y) / d
                if t > 0 and self.x0 <= x + t * c <= self.x1:
                    best = min(best, t)
        return best


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--domain", type=int, default=0)
    p.add_argument("--namespace", default="")
    p.add_argument("--start", default="0,0,0", help="x,y,heading in degrees")
    p.add_argument("--room", default="-3,-5,7,5", help="x0,y0,x1,y1 of the walls, m")
    p.add_argument("--duration", type=float, default=60.0)
    p.add_argument("--cmd-timeout", type=float, default=0.5)
    p.add_argument("--max-accel", type=float, default=1.0)
    p.add_argument("--odom-stop-at", type=float, default=math.inf)
    p.add_argument("--scan-stop-at", type=float, default=math.inf)
    p.add_argument("--scan-resume-at", type=float, default=math.inf)
    p.add_argument("--report", required=True)
    args = p.parse_args()

    ns = args.namespace.rstrip("/")
    dp = DomainParticipant(args.domain)
    # Sensor data best effort, as ROS 2 drivers publish it; commands reliable.
    sensor_qos = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(5))
    cmd_qos = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
    cmd_reader = DataReader(dp, Topic(dp, f"rt{ns}/cmd_vel", Twist), qos=cmd_qos)
    odom_writer = DataWriter(dp, Topic(dp, f"rt{ns}/odom", Odometry), qos=sensor_qos)
    scan_writer = DataWriter(dp, Topic(dp, f"rt{ns}/scan", LaserScan), qos=sensor_qos)
    battery_writer = DataWriter(dp, Topic(dp, f"rt{ns}/battery_state", BatteryState), qos=sensor_qos)

    x, y, h = (float(v) for v in args.start.split(","))
    h = math.radians(h)
    room = Room(*(float(v) for v in args.room.split(",")))
    v = w = 0.0
    cmd = (0.0, 0.0)
    cmd_at = -math.inf
    twists = []
    stopping = []
    signal.signal(signal.SIGTERM, lambda *_: stopping.append(True))

    print("ready", flush=True)
    start = time.monotonic()
    tick = 0
    while not stopping:
        tick += 1
        due = start + tick * STEP
        now = time.monotonic()
        if due > now:
            time.sleep(due - now)
        t = time.monotonic() - start
        if t > args.duration:
            break
        for s in cmd_reader.take(N=100):
            if isinstance(s, Twist):
                cmd = (s.linear.x, s.angular.z)
                cmd_at = t
                twists.append([round(t, 4), s.linear.x, s.angular.z])
        want_v, want_w = cmd if t - cmd_at <= args.cmd_timeout else (0.0, 0.0)
        dv = args.max_accel * STEP
        v += max(-dv, min(dv, want_v - v))
        w = want_w if abs(v) > 1e-6 or want_v == 0.0 else 0.0
        h += w * STEP
        x += v * math.cos(h) * STEP
        y += v * math.sin(h) * STEP

        wall = time.time()
        if tick % 2 == 0 and t < args.odom_stop_at:
            odom_writer.write(
                Odometry(
                    header=header(wall, "odom"),
                    child_frame_id="base_link",
                    pose=PoseWithCovariance(
                        pose=Pose(
                            position=Point(x=x, y=y, z=0.0),
                            orientation=Quaternion(x=0.0, y=0.0, z=math.sin(h / 2), w=math.cos(h / 2)),
                        ),
                        covariance=[0.0] * 36,
                    ),
                    twist=TwistWithCovariance(
                        twist=Twist(linear=Vector3(x=v, y=0.0, z=0.0), angular=Vector3(x=0.0, y=0.0, z=w)),
                        covariance=[0.0] * 36,
                    ),
                )
            )
        scanning = t < args.scan_stop_at or t >= args.scan_resume_at
        if tick % 10 == 0 and scanning:
            step = math.radians(1.0)
            ranges = [room.ray(x, y, h - math.pi / 2 + i * step) for i in range(181)]
            scan_writer.write(
                LaserScan(
                    header=header(wall, "base_scan"),
                    angle_min=-math.pi / 2,
                    angle_max=math.pi / 2,
                    angle_increment=step,
                    time_increment=0.0,
                    scan_time=0.1,
                    range_min=0.05,
                    range_max=30.0,
                    ranges=[r if r <= 30.0 else math.inf for r in ranges],
                    intensities=[],
                )
            )
        if tick % 100 == 0:
            nan = math.nan
            battery_writer.write(
                BatteryState(
                    header=header(wall, "base_link"),
                    voltage=24.5,
                    temperature=nan,
                    current=nan,
                    charge=nan,
                    capacity=nan,
                    design_capacity=nan,
                    percentage=0.9,
                    power_supply_status=2,
                    power_supply_health=1,
                    power_supply_technology=0,
                    present=True,
                    cell_voltage=[],
                    cell_temperature=[],
                    location="",
                    serial_number="",
                )
            )

    with open(args.report, "w") as f:
        json.dump(
            {
                "pose": [x, y, math.degrees(h)],
                "speed": v,
                "ran": time.monotonic() - start,
                "twists": twists,
            },
            f,
        )


if __name__ == "__main__":
    sys.exit(main())
