"""Reads an MCAP file with Foxglove's own Python libraries (`pip install mcap
mcap-ros2-support`), decoding every `ros2msg`/`cdr` channel as a rosbag2 reader does,
and prints one JSON object: per topic its schema, encodings, message count and the
essentials of its messages."""

import json
import sys

from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory


def main():
    topics = {}
    with open(sys.argv[1], "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summary = reader.get_summary()
        ros = []
        for channel in summary.channels.values():
            schema = summary.schemas.get(channel.schema_id)
            topics[channel.topic] = {
                "schema": schema.name if schema else None,
                "schema_encoding": schema.encoding if schema else None,
                "message_encoding": channel.message_encoding,
                "count": summary.statistics.channel_message_counts.get(channel.id, 0),
            }
            if channel.message_encoding == "cdr":
                ros.append(channel.topic)
        for schema, channel, _, m in reader.iter_decoded_messages(topics=ros):
            t = topics[channel.topic]
            t["decoded"] = t.get("decoded", 0) + 1
            if schema.name == "nav_msgs/msg/Odometry":
                p = m.pose.pose.position
                t["last"] = {"x": p.x, "y": p.y, "frame": m.header.frame_id}
            elif schema.name == "geometry_msgs/msg/Twist":
                t["max_linear_x"] = max(t.get("max_linear_x", 0.0), m.linear.x)
            elif schema.name == "sensor_msgs/msg/LaserScan":
                t["beams"] = len(m.ranges)
            elif schema.name == "sensor_msgs/msg/BatteryState":
                t["voltage"] = m.voltage
    print(json.dumps(topics))


if __name__ == "__main__":
    main()
