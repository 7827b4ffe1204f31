#include "record_builder.hpp"

namespace cover::mcap {

void append_schema(Bytes& out, const Schema& schema) {
  RecordBuilder record(out, Op::Schema);
  auto& w = record.content();
  w.u16(schema.id);
  w.string(schema.name);
  w.string(schema.encoding);
  w.u32(static_cast<std::uint32_t>(schema.data.size()));
  w.raw(schema.data.data(), schema.data.size());
  record.end();
}

void append_channel(Bytes& out, const Channel& channel) {
  RecordBuilder record(out, Op::Channel);
  auto& w = record.content();
  w.u16(channel.id);
  w.u16(channel.schema_id);
  w.string(channel.topic);
  w.string(channel.message_encoding);
  const std::size_t map_length_at = w.size();
  w.u32(0);
  for (const auto& [key, value] : channel.metadata) {
    w.string(key);
    w.string(value);
  }
  w.patch_u32(map_length_at, static_cast<std::uint32_t>(w.size() - map_length_at - 4));
  record.end();
}

}  // namespace cover::mcap
