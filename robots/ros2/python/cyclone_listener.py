"""Listens, with Eclipse Cyclone DDS, to what a ROS 2 robot publishes under a namespace
for a while, and prints one JSON object: per topic the number of messages and their
rate, and the last message's essentials. What `ilmrc sim --ros2` is checked with.

    python3 cyclone_listener.py --namespace /r1 --seconds 4
"""

import argparse
import json
import math
import time

from cyclonedds.core import Policy, Qos
from cyclonedds.domain import DomainParticipant
from cyclonedds.sub import DataReader
from cyclonedds.topic import Topic

from ros2_msgs import BatteryState, Clock, LaserScan, Odometry, TFMessage


def yaw(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def essentials(topic, m):
    if isinstance(m, Odometry):
        p = m.pose.pose
        return {
            "frame": m.header.frame_id,
            "child": m.child_frame_id,
            "x": p.position.x,
            "y": p.position.y,
            "h": yaw(p.orientation),
            "v": m.twist.twist.linear.x,
            "stamp": m.header.stamp.sec + m.header.stamp.nanosec * 1e-9,
        }
    if isinstance(m, LaserScan):
        return {
            "frame": m.header.frame_id,
            "beams": len(m.ranges),
            "angle_min": m.angle_min,
            "angle_increment": m.angle_increment,
            "range_max": m.range_max,
            "finite": sum(1 for r in m.ranges if math.isfinite(r)),
        }
    if isinstance(m, TFMessage):
        return {"pairs": [[t.header.frame_id, t.child_frame_id] for t in m.transforms]}
    if isinstance(m, BatteryState):
        return {"voltage": m.voltage, "percentage": m.percentage}
    if isinstance(m, Clock):
        return {"clock": m.clock.sec + m.clock.nanosec * 1e-9}
    return {}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--domain", type=int, default=0)
    p.add_argument("--namespace", default="")
    p.add_argument("--seconds", type=float, default=4.0)
    args = p.parse_args()
    ns = args.namespace.rstrip("/")
    dp = DomainParticipant(args.domain)
    qos = Qos(Policy.Reliability.BestEffort, Policy.History.KeepLast(100))
    topics = {
        "odom": (f"rt{ns}/odom", Odometry),
        "ground_truth": (f"rt{ns}/ground_truth", Odometry),
        "scan": (f"rt{ns}/scan", LaserScan),
        "tf": (f"rt{ns}/tf", TFMessage),
        "battery_state": (f"rt{ns}/battery_state", BatteryState),
        "clock": ("rt/clock", Clock),
    }
    readers = {k: DataReader(dp, Topic(dp, name, cls), qos=qos) for k, (name, cls) in topics.items()}
    seen = {k: {"count": 0, "first": None, "last": None, "message": None} for k in topics}
    end = time.monotonic() + args.seconds
    while time.monotonic() < end:
        for k, r in readers.items():
            for m in r.take(N=100):
                if not isinstance(m, topics[k][1]):
                    continue
                now = time.monotonic()
                s = seen[k]
                s["count"] += 1
                s["first"] = s["first"] if s["first"] is not None else now
                s["last"] = now
                s["message"] = essentials(k, m)
        time.sleep(0.005)
    out = {}
    for k, s in seen.items():
        span = (s["last"] - s["first"]) if s["count"] > 1 else 0.0
        out[k] = {
            "count": s["count"],
            "rate": (s["count"] - 1) / span if span > 0 else 0.0,
            "last": s["message"],
        }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
