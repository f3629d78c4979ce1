// Watches a live ILMR run as Foxglove does: connects with Foxglove's own client
// (@foxglove/ws-protocol), lists the advertised
// channels, subscribes to the topics asked for, and decodes each message with the
// protobuf schema its channel advertised (protobufjs, as Foxglove decodes). Prints one
// JSON object when the server closes or after the time limit:
// { protocol, serverInfo, channels: [{topic, schemaName, encoding}], messages: {topic: [...]},
//   time: last broadcast time (ns), statuses: [...] }
//
// Usage: [FOXGLOVE_PROTOCOLS=a,b] node watch.mjs ws://127.0.0.1:PORT SECONDS TOPIC...

import wsProtocol from "@foxglove/ws-protocol";
import protobuf from "protobufjs";
import descriptor from "protobufjs/ext/descriptor/index.js";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol;

const [url, seconds, ...topics] = process.argv.slice(2);
const out = { protocol: null, serverInfo: null, channels: [], messages: {}, time: null, statuses: [] };
const bySubscription = new Map();

function decoderFor(channel) {
  if (channel.encoding !== "protobuf" || channel.schemaEncoding !== "protobuf") {
    throw new Error(`${channel.topic}: ${channel.encoding}/${channel.schemaEncoding}, not protobuf`);
  }
  const set = descriptor.FileDescriptorSet.decode(Buffer.from(channel.schema, "base64"));
  const root = protobuf.Root.fromDescriptor(set);
  return root.lookupType(channel.schemaName);
}

function essentials(topic, type, message) {
  const bytes = new Uint8Array(message.data.buffer, message.data.byteOffset, message.data.byteLength);
  const m = type.toObject(type.decode(bytes), { longs: Number, defaults: true });
  const logTime = Number(message.timestamp) * 1e-9;
  if (m.pose && m.pose.position) {
    return { logTime, x: m.pose.position.x, y: m.pose.position.y, frame: m.frameId };
  }
  if (topic === "/commands") {
    return { logTime, level: m.level, message: m.message, line: m.line };
  }
  if (topic === "/world" || topic === "/paths" || topic === "/trajectory") {
    return { logTime, entities: m.entities.map((e) => e.id) };
  }
  return { logTime };
}

const finish = (code) => {
  console.log(JSON.stringify(out));
  process.exit(code);
};

// The client offers what the ws-protocol package offers, `foxglove.websocket.v1`, unless
// FOXGLOVE_PROTOCOLS names others (comma-separated), such as `foxglove.sdk.v1`, the name
// Foxglove's SDK took when the protocol moved into it.
const protocols = process.env.FOXGLOVE_PROTOCOLS
  ? process.env.FOXGLOVE_PROTOCOLS.split(",")
  : [FoxgloveClient.SUPPORTED_SUBPROTOCOL];
const ws = new WebSocket(url, protocols);
ws.on("open", () => {
  out.protocol = ws.protocol;
});
const client = new FoxgloveClient({ ws });
client.on("serverInfo", (info) => {
  out.serverInfo = { name: info.name, capabilities: info.capabilities };
});
client.on("advertise", (channels) => {
  for (const c of channels) {
    out.channels.push({ topic: c.topic, schemaName: c.schemaName, encoding: c.encoding });
    if (topics.includes(c.topic)) {
      const type = decoderFor(c);
      bySubscription.set(client.subscribe(c.id), { topic: c.topic, type });
      out.messages[c.topic] = [];
    }
  }
});
client.on("message", (message) => {
  const sub = bySubscription.get(message.subscriptionId);
  if (sub) {
    out.messages[sub.topic].push(essentials(sub.topic, sub.type, message));
  }
});
client.on("time", (t) => {
  out.time = Number(t.timestamp);
});
client.on("status", (s) => {
  out.statuses.push(s.message);
});
client.on("error", (e) => {
  console.error(String(e));
});
client.on("close", () => finish(0));
setTimeout(() => finish(0), Number(seconds) * 1000);
