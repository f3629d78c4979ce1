"""A hostile ROS 2 peer on Eclipse Cyclone DDS, for the tests of what ILMR does with bad
samples: it publishes, under a robot's namespace, samples that claim a robot's types
but are not what they claim, as fast as it can or at a steady rate.

    --mode malformed  `odom` samples of the right type name but another layout (too
                      short to be an Odometry), 200 per second
    --mode nan        well-formed `odom` samples whose pose is NaN, as fast as Cyclone
                      takes them (a flood)
    --mode oversize   a `scan` of 3 million beams (12 MB) every second
    --mode cmd_vel    a second driver: zero twists on `cmd_vel` at 20 Hz for
                      `--seconds` (default 3), then silence, as a teleop that lets go

Prints `ready` once its writer exists; runs until SIGTERM. Prints how many it sent."""

import argparse
import math
import signal
import time
from dataclasses import dataclass

from cyclonedds.core import Policy, Qos
from cyclonedds.util import duration
from cyclonedds.domain import DomainParticipant
from cyclonedds.idl import IdlStruct
from cyclonedds.idl.types import int32
from cyclonedds.pub import DataWriter
from cyclonedds.topic import Topic

from ros2_msgs import Header, LaserScan, Odometry, Point, Pose, PoseWithCovariance, Quaternion, Time, Twist, TwistWithCovariance, Vector3


@dataclass
class NotOdometry(IdlStruct, typename="nav_msgs::msg::dds_::Odometry_"):
    only: int32


def nan_odometry():
    nan = math.nan
    return Odometry(
        header=Header(stamp=Time(sec=0, nanosec=0), frame_id="odom"),
        child_frame_id="base_link",
        pose=PoseWithCovariance(
            pose=Pose(position=Point(x=nan, y=nan, z=0.0), orientation=Quaternion(x=0.0, y=0.0, z=0.0, w=1.0)),
            covariance=[0.0] * 36,
        ),
        twist=TwistWithCovariance(
            twist=Twist(linear=Vector3(x=nan, y=0.0, z=0.0), angular=Vector3(x=0.0, y=0.0, z=0.0)),
            covariance=[0.0] * 36,
        ),
    )


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--domain", type=int, default=0)
    p.add_argument("--namespace", default="")
    p.add_argument("--mode", choices=["malformed", "nan", "oversize", "cmd_vel"], required=True)
    p.add_argument("--seconds", type=float, default=3.0)
    args = p.parse_args()
    ns = args.namespace.rstrip("/")
    dp = DomainParticipant(args.domain)
    qos = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(5))
    stopping = []
    signal.signal(signal.SIGTERM, lambda *_: stopping.append(True))
    if args.mode == "malformed":
        w = DataWriter(dp, Topic(dp, f"rt{ns}/odom", NotOdometry), qos=qos)
        sample, pause = NotOdometry(only=7), 0.005
    elif args.mode == "cmd_vel":
        # Reliable, as a teleop or Nav2 writes it, so the robot obeys it too.
        reliable = Qos(Policy.Reliability.Reliable(duration(milliseconds=100)), Policy.History.KeepLast(10))
        w = DataWriter(dp, Topic(dp, f"rt{ns}/cmd_vel", Twist), qos=reliable)
        sample, pause = Twist(linear=Vector3(x=0.0, y=0.0, z=0.0), angular=Vector3(x=0.0, y=0.0, z=0.0)), 0.05
    elif args.mode == "nan":
        w = DataWriter(dp, Topic(dp, f"rt{ns}/odom", Odometry), qos=qos)
        sample, pause = nan_odometry(), 0.0
    else:
        w = DataWriter(dp, Topic(dp, f"rt{ns}/scan", LaserScan), qos=qos)
        sample = LaserScan(
            header=Header(stamp=Time(sec=0, nanosec=0), frame_id="laser"),
            angle_min=-1.0,
            angle_max=1.0,
            angle_increment=1e-6,
            time_increment=0.0,
            scan_time=0.1,
            range_min=0.0,
            range_max=30.0,
            ranges=[0.01] * 3_000_000,
            intensities=[],
        )
        pause = 1.0
    print("ready", flush=True)
    sent = 0
    until = time.monotonic() + args.seconds if args.mode == "cmd_vel" else math.inf
    while not stopping:
        if time.monotonic() < until:
            w.write(sample)
            sent += 1
        if pause:
            time.sleep(pause)
    print(f"sent {sent}", flush=True)


if __name__ == "__main__":
    main()
