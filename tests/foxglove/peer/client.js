// An independent Foxglove WebSocket client for cover-foxglove-bridge's tests:
// @foxglove/ws-protocol's FoxgloveClient over `ws`, each message decoded as Foxglove does
// (cdr + omgidl: @foxglove/omgidl-serialization from the advertised schema; json: parsed).
//   node client.js URL OPTIONS_JSON
// OPTIONS_JSON: {"subscribe": [topics] (default: none), "subprotocol": "foxglove.websocket.v1",
//                "malformed": false (after the first advertise, sends three bad messages),
//                "duration_ms": 10000 (then closes and exits)}
// Prints JSON lines: {"event":"open"}, {"event":"serverInfo",...}, {"event":"advertise",
// "channels":[...]}, {"event":"message","topic","schema","log_time","recv_ns","value"},
// {"event":"status",...}, {"event":"close","code"}, {"event":"error","message"}.
"use strict";
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");

const url = process.argv[2];
const options = JSON.parse(process.argv[3] || "{}");
const wanted = new Set(options.subscribe || []);

function print(value) {
  process.stdout.write(JSON.stringify(value, (_key, v) => {
    if (typeof v === "bigint") return v.toString();  // int64 stamps exceed 2^53
    if (ArrayBuffer.isView(v)) return Array.from(v, (x) => (typeof x === "bigint" ? x.toString() : x));
    return v;
  }) + "\n");
}

function nowNs() {
  return BigInt(Math.round((performance.timeOrigin + performance.now()) * 1e6));
}

const ws = new WebSocket(url, [options.subprotocol || FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
const channels = new Map();       // channel id -> {topic, schemaName, decode}
const subscriptions = new Map();  // subscription id -> channel id
let sentMalformed = false;

function decoder(channel) {
  if (channel.encoding === "cdr" && channel.schemaEncoding === "omgidl") {
    const reader = new MessageReader(channel.schemaName, parseIDL(channel.schema));
    return (bytes) => reader.readMessage(bytes);
  }
  if (channel.encoding === "json") {
    const text = new TextDecoder();
    return (bytes) => JSON.parse(text.decode(bytes));
  }
  throw new Error(`${channel.topic}: encoding ${channel.encoding} / ${channel.schemaEncoding}`);
}

client.on("open", () => print({ event: "open", protocol: ws.protocol }));
client.on("serverInfo", (info) => print({ event: "serverInfo", ...info }));
client.on("status", (status) => print({ event: "status", ...status }));
client.on("error", (error) => print({ event: "error", message: String(error && error.message) }));
client.on("close", (event) => {
  print({ event: "close", code: event.code });
  process.exit(0);
});
client.on("advertise", (advertised) => {
  print({ event: "advertise", channels: advertised.map((c) => ({ id: c.id, topic: c.topic,
    encoding: c.encoding, schemaName: c.schemaName, schemaEncoding: c.schemaEncoding })) });
  for (const channel of advertised) {
    channels.set(channel.id, { topic: channel.topic, schemaName: channel.schemaName,
                               decode: decoder(channel) });
    if (wanted.has(channel.topic)) subscriptions.set(client.subscribe(channel.id), channel.id);
  }
  if (options.malformed && !sentMalformed) {
    sentMalformed = true;
    ws.send("{not json");
    ws.send(JSON.stringify({ op: "subscribe", subscriptions: [{ id: "x", channelId: 1 }] }));
    ws.send(Buffer.from([7, 1, 2, 3]));
  }
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const recv_ns = nowNs();
  const channel = channels.get(subscriptions.get(subscriptionId));
  if (!channel) {
    print({ event: "error", message: `message of unknown subscription ${subscriptionId}` });
    return;
  }
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  let value;
  try {
    value = channel.decode(bytes);
  } catch (error) {
    print({ event: "error", message: `${channel.topic}: ${error.message}` });
    return;
  }
  print({ event: "message", topic: channel.topic, schema: channel.schemaName, log_time: timestamp,
          recv_ns, value });
});

setTimeout(() => {
  client.close();
  setTimeout(() => process.exit(0), 1000);
}, options.duration_ms || 10000);
