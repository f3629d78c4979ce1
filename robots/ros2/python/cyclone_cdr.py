"""Serialises the ROS 2 messages of ilmr-ros2 with Eclipse Cyclone DDS's C library
(through its Python binding) for tests/cyclonedds.rs.

Reads JSON lines {"type": NAME, "value": {...}, "rust": HEX} on stdin and writes, for
each, one JSON line: Cyclone's sample for the value ("cyclone": HEX) and what Cyclone
reads from the Rust sample ("decoded": {...})."""

import json
import sys
import typing
from dataclasses import asdict, fields, is_dataclass

from ros2_msgs import BatteryState, LaserScan, Odometry, Twist


TYPES = {t.__idl_typename__: t for t in [Twist, Odometry, LaserScan, BatteryState]}


def build(cls, value):
    """A dataclass instance from the JSON of its fields."""
    hints = typing.get_type_hints(cls)
    args = {}
    for f in fields(cls):
        v = value[f.name]
        hint = hints[f.name]
        args[f.name] = build(hint, v) if isinstance(hint, type) and is_dataclass(hint) else v
    return cls(**args)


for line in sys.stdin:
    request = json.loads(line)
    cls = TYPES[request["type"]]
    sample = build(cls, request["value"]).serialize()
    decoded = cls.deserialize(bytes.fromhex(request["rust"]))
    print(json.dumps({"cyclone": sample.hex(), "decoded": asdict(decoded)}), flush=True)
