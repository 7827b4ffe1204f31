// An independent reader of COVER's MCAP files: @mcap/core opens the file (the indexed
// reader for a finished file, the stream reader for one cut by a crash), and every message
// is decoded with @foxglove/omgidl-serialization from the schema stored in the file, as
// Foxglove does. Prints JSON lines: one per message, then a summary line.
//   node read_mcap.js FILE indexed|stream
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { FileHandleReadable } = require("@mcap/nodejs");
const { loadDecompressHandlers } = require("@mcap/support");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");

function toJson(value) {
  return JSON.stringify(value, (_key, v) => {
    if (typeof v === "bigint") return v.toString();  // int64 stamps exceed 2^53
    if (ArrayBuffer.isView(v)) return Array.from(v, (x) => (typeof x === "bigint" ? x.toString() : x));
    return v;
  });
}

class Decoder {
  constructor() {
    this.readers = new Map();  // channel id -> MessageReader
    this.counts = {};
  }
  addChannel(channel, schema) {
    if (channel.messageEncoding !== "cdr") throw new Error(`${channel.topic}: encoding ${channel.messageEncoding}`);
    if (schema.encoding !== "omgidl") throw new Error(`${schema.name}: schema encoding ${schema.encoding}`);
    const text = new TextDecoder().decode(schema.data);
    this.readers.set(channel.id, { topic: channel.topic, schema: schema.name,
                                   reader: new MessageReader(schema.name, parseIDL(text)) });
  }
  message(m) {
    const entry = this.readers.get(m.channelId);
    if (!entry) throw new Error(`message of unknown channel ${m.channelId}`);
    const value = entry.reader.readMessage(m.data);
    this.counts[entry.topic] = (this.counts[entry.topic] || 0) + 1;
    process.stdout.write(toJson({ topic: entry.topic, schema: entry.schema, sequence: m.sequence,
                                  log_time: m.logTime, publish_time: m.publishTime, value }) + "\n");
  }
}

async function readIndexed(path, decompressHandlers) {
  const handle = await fs.promises.open(path, "r");
  try {
    const reader = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(handle),
                                                        decompressHandlers });
    const decoder = new Decoder();
    for (const channel of reader.channelsById.values()) {
      decoder.addChannel(channel, reader.schemasById.get(channel.schemaId));
    }
    for await (const message of reader.readMessages()) decoder.message(message);
    const stats = reader.statistics;
    const compressions = [...new Set(reader.chunkIndexes.map((c) => c.compression))];
    return { decoder, extra: { statistics_message_count: stats ? Number(stats.messageCount) : null,
                               chunks: reader.chunkIndexes.length, compressions } };
  } finally {
    await handle.close();
  }
}

function readStream(path, decompressHandlers) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(fs.readFileSync(path));
  const decoder = new Decoder();
  const schemas = new Map();
  let record;
  while ((record = reader.nextRecord()) !== undefined) {
    if (record.type === "Schema") schemas.set(record.id, record);
    else if (record.type === "Channel") decoder.addChannel(record, schemas.get(record.schemaId));
    else if (record.type === "Message") decoder.message(record);
  }
  return { decoder, extra: { done: reader.done(), bytes_remaining: reader.bytesRemaining() } };
}

async function main() {
  const [path, mode] = process.argv.slice(2);
  const decompressHandlers = await loadDecompressHandlers();
  const { decoder, extra } = mode === "stream" ? readStream(path, decompressHandlers)
                                               : await readIndexed(path, decompressHandlers);
  process.stdout.write(toJson({ summary: true, mode, counts: decoder.counts, ...extra }) + "\n");
}

main().catch((error) => {
  process.stderr.write(`read_mcap: ${error.stack || error}\n`);
  process.exit(1);
});
