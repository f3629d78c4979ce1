"""Serialises the ROS 2 messages of ilmr-ros2 with Eclipse Cyclone DDS's C library
(through its Python binding) for tests/cyclonedds.rs.

Reads JSON lines {"type": NAME, "value": {...}, "rust": HEX} on stdin and writes, for
each, one JSON line: Cyclone's sample for the value ("cyclone": HEX) and what Cyclone
reads from the Rust sample ("decoded": {...})."""

import json
import sys
import typing
from dataclasses import asdict, fields, is_dataclass

from ros2_msgs import BatteryState, Clock, LaserScan, Odometry, TFMessage, TransformStamped, Twist


TYPES = {t.__idl_typename__: t for t in [Twist, Odometry, LaserScan, BatteryState, TFMessage, Clock]}


def build(cls, value):
    """A dataclass instance from the JSON of its fields."""
    hints = typing.get_type_hints(cls)
    args = {}
    for f in fields(cls):
        v = value[f.name]
        hint = hints[f.name]
        if isinstance(hint, type) and is_dataclass(hint):
            v = build(hint, v)
        elif f.name == "transforms":
            v = [build(TransformStamped, t) for t in v]
        args[f.name] = v
    return cls(**args)


for line in sys.stdin:
    request = json.loads(line)
    cls = TYPES[request["type"]]
    sample = build(cls, request["value"]).serialize()
    decoded = cls.deserialize(bytes.fromhex(request["rust"]))
    print(json.dumps({"cyclone": sample.hex(), "decoded": asdict(decoded)}), flush=True)
