"""Reads an MCAP file with Foxglove's own Python libraries (`pip install mcap
mcap-protobuf-support mcap-ros2-support`), decoding every message with its channel's
schema: protobuf (ILMR's topics, Foxglove's schemas) as Foxglove's protobuf decoder
does, `ros2msg`/`cdr` (a ROS 2 robot's topics) as a rosbag2 reader does, `json`
(the recorded inputs, `/ilmr/inputs`, with their JSON Schema) as JSON. Prints one
JSON object: per topic its schema, encodings, message count, how many messages
decoded, and the essentials of its messages. Exits 1 when a message does not decode.

Usage: python3 tools/read_mcap.py FILE.mcap
"""

import json
import sys

from mcap.decoder import DecoderFactory
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory as ProtobufDecoders
from mcap_ros2.decoder import DecoderFactory as Ros2Decoders


class JsonDecoders(DecoderFactory):
    """JSON messages whose schema is a JSON Schema, as Foxglove reads them."""

    def decoder_for(self, message_encoding, schema):
        if message_encoding == "json" and schema is not None and schema.encoding == "jsonschema":
            return lambda data: json.loads(data)
        return None


def stamp(m):
    return m.timestamp.seconds + m.timestamp.nanos * 1e-9


def essentials(t, name, m, log_time):
    """What the tests compare, by schema."""
    if name == "foxglove.PoseInFrame":
        p = m.pose.position
        t.setdefault("poses", []).append([log_time * 1e-9, p.x, p.y, m.pose.orientation.z])
        t["frame"] = m.frame_id
    elif name == "foxglove.FrameTransforms":
        f = m.transforms[0]
        t["frames"] = [f.parent_frame_id, f.child_frame_id]
    elif name == "foxglove.LaserScan":
        t["beams"] = len(m.ranges)
    elif name == "foxglove.Log":
        t.setdefault("logs", []).append(
            {"t": stamp(m), "level": m.level, "message": m.message, "file": m.file, "line": m.line}
        )
    elif name == "foxglove.SceneUpdate":
        for e in m.entities:
            t.setdefault("entities", []).append(e.id)
    elif name == "ilmr.Motion":
        t["max_speed"] = max(t.get("max_speed", 0.0), m.speed)
    elif name == "ilmr.Variable":
        t.setdefault("variables", []).append({"name": m.name, "value": m.value, "line": m.line})
    elif name == "nav_msgs/msg/Odometry":
        p = m.pose.pose.position
        t["last"] = {"x": p.x, "y": p.y, "frame": m.header.frame_id}
    elif name == "geometry_msgs/msg/Twist":
        t["max_linear_x"] = max(t.get("max_linear_x", 0.0), m.linear.x)
    elif name == "sensor_msgs/msg/LaserScan":
        t["beams"] = len(m.ranges)
    elif name == "sensor_msgs/msg/BatteryState":
        t["voltage"] = m.voltage
    elif name == "ilmr.trace.Line":
        events = t.setdefault("events", {})
        events[m["event"]] = events.get(m["event"], 0) + 1
        if m["event"] == "input":
            t["calls"] = t.get("calls", 0) + len(m["calls"])


def main():
    topics = {}
    with open(sys.argv[1], "rb") as f:
        reader = make_reader(f, decoder_factories=[ProtobufDecoders(), Ros2Decoders(), JsonDecoders()])
        summary = reader.get_summary()
        for channel in summary.channels.values():
            schema = summary.schemas.get(channel.schema_id)
            topics[channel.topic] = {
                "schema": schema.name if schema else None,
                "schema_encoding": schema.encoding if schema else None,
                "message_encoding": channel.message_encoding,
                "count": summary.statistics.channel_message_counts.get(channel.id, 0),
                "decoded": 0,
            }
        for schema, channel, message, m in reader.iter_decoded_messages():
            t = topics[channel.topic]
            t["decoded"] += 1
            essentials(t, schema.name, m, message.log_time)
    print(json.dumps(topics))
    if any(t["decoded"] != t["count"] for t in topics.values()):
        sys.exit(1)


if __name__ == "__main__":
    main()
