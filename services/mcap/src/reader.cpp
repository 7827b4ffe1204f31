#include "cover/mcap/reader.hpp"

#include <algorithm>
#include <cstring>

#include "cover/mcap/compression.hpp"
#include "cover/mcap/crc32.hpp"

namespace cover::mcap {
namespace {

// Far beyond any chunk or record the recorder writes (1 MiB chunks): a larger length is
// a corrupt field, not something to allocate.
constexpr std::uint64_t kMaxRecordBytes = 512ULL * 1024 * 1024;
constexpr std::size_t kMaxIssues = 32;

struct PendingMessage {
  MessageHeader header;
  const std::uint8_t* data;
  std::size_t size;
};

bool read_message(ByteReader& in, PendingMessage& message) {
  auto& h = message.header;
  if (!in.u16(h.channel_id) || !in.u32(h.sequence) || !in.u64(h.log_time_ns) ||
      !in.u64(h.publish_time_ns)) {
    return false;
  }
  message.size = in.remaining();
  return in.span(message.size, message.data);
}

bool read_u16_u64_map(ByteReader& in, std::map<std::uint16_t, std::uint64_t>& map) {
  std::uint32_t length = 0;
  const std::uint8_t* start = nullptr;
  if (!in.u32(length) || !in.span(length, start)) return false;
  ByteReader entries(start, length);
  while (entries.remaining() > 0) {
    std::uint16_t key = 0;
    std::uint64_t value = 0;
    if (!entries.u16(key) || !entries.u64(value)) return false;
    map[key] = value;
  }
  return true;
}

}  // namespace

std::string op_name(std::uint8_t op) {
  static const char* const kNames[] = {
      "",         "Header",        "Footer",        "Schema",     "Channel",         "Message",
      "Chunk",    "MessageIndex",  "ChunkIndex",    "Attachment", "AttachmentIndex", "Statistics",
      "Metadata", "MetadataIndex", "SummaryOffset", "DataEnd"};
  if (op >= 1 && op <= 0x0F) return kNames[op];
  return "opcode " + std::to_string(op);
}

void Reader::report(std::uint64_t offset, std::string what) {
  if (issues_.size() < kMaxIssues) issues_.push_back({offset, std::move(what)});
}

bool Reader::scan(const MessageCallback& on_message) {
  std::ifstream file(path_, std::ios::binary);
  if (!file) {
    report(0, "cannot open " + path_ + ": " + std::strerror(errno));
    return false;
  }
  file.seekg(0, std::ios::end);
  file_size_ = static_cast<std::uint64_t>(file.tellg());
  file.seekg(0);
  std::uint8_t magic[sizeof(kMagic)] = {};
  if (file_size_ < sizeof(kMagic) || !file.read(reinterpret_cast<char*>(magic), sizeof(magic)) ||
      std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
    report(0, "not an MCAP file: it does not start with the magic \\x89MCAP0\\r\\n");
    return false;
  }
  magic_seen_ = true;
  // Over every byte before DataEnd: the only check of the records chunk CRCs do not cover.
  std::uint32_t data_crc = crc32_update(0, magic, sizeof(magic));
  bool in_data = true;
  std::uint64_t offset = sizeof(kMagic);
  Bytes content;
  while (!stopped_) {
    const std::uint64_t left = file_size_ - offset;
    if (footer_seen_) {
      std::uint8_t closing[sizeof(kMagic)] = {};
      if (left != sizeof(kMagic) || !file.read(reinterpret_cast<char*>(closing), sizeof(closing)) ||
          std::memcmp(closing, kMagic, sizeof(kMagic)) != 0) {
        report(offset, "after the Footer: " + std::to_string(left) +
                           " bytes where the closing magic (8 bytes) belongs");
      }
      break;
    }
    if (left == 0) {
      report(offset,
             "the file ends without its summary and Footer (not closed: recorder killed "
             "or file cut); the " +
                 std::to_string(chunks_.size()) + " complete chunks before were read");
      break;
    }
    std::uint8_t prefix[kRecordPrefixBytes] = {};
    if (left < kRecordPrefixBytes || !file.read(reinterpret_cast<char*>(prefix), sizeof(prefix))) {
      report(offset, "truncated: " + std::to_string(left) +
                         " bytes left where a record (at least 9 bytes) begins");
      break;
    }
    ByteReader prefix_reader(prefix, sizeof(prefix));
    std::uint8_t op = 0;
    std::uint64_t length = 0;
    prefix_reader.u8(op);
    prefix_reader.u64(length);
    if (length > left - kRecordPrefixBytes || length > kMaxRecordBytes) {
      report(offset, op_name(op) + " record declares " + std::to_string(length) +
                         " bytes, the file has " + std::to_string(left - kRecordPrefixBytes) +
                         " left (truncated or corrupt length)");
      break;
    }
    content.resize(length);
    if (length > 0 && !file.read(reinterpret_cast<char*>(content.data()), length)) {
      report(offset, "read error in a " + op_name(op) + " record");
      break;
    }
    if (op == static_cast<std::uint8_t>(Op::DataEnd) && in_data) {
      in_data = false;
      check_data_crc(offset, content, data_crc);
    } else if (in_data) {
      data_crc = crc32_update(data_crc, prefix, sizeof(prefix));
      data_crc = crc32_update(data_crc, content.data(), content.size());
    }
    if (read_record(offset, op, content, on_message) == Step::Stop) break;
    offset += kRecordPrefixBytes + length;
  }
  return issues_.empty() && footer_seen_;
}

void Reader::check_data_crc(std::uint64_t offset, const Bytes& content, std::uint32_t computed) {
  ByteReader in(content.data(), content.size());
  std::uint32_t stored = 0;
  if (!in.u32(stored)) {
    report(offset, "malformed DataEnd record");
  } else if (stored != 0 && stored != computed) {
    report(offset, "data section CRC mismatch: a byte before offset " + std::to_string(offset) +
                       " is corrupt (in a record no chunk CRC covers, if no chunk was reported)");
  }
}

Reader::Step Reader::read_record(std::uint64_t offset, std::uint8_t op, const Bytes& content,
                                 const MessageCallback& on_message) {
  ByteReader in(content.data(), content.size());
  bool ok = true;
  switch (static_cast<Op>(op)) {
    case Op::Header:
      ok = in.string(profile_) && in.string(library_);
      break;
    case Op::Footer:
      footer_seen_ = true;
      break;
    case Op::Schema:
      ok = read_schema(in);
      break;
    case Op::Channel:
      ok = read_channel(in);
      break;
    case Op::Statistics:
      ok = read_statistics(in);
      break;
    case Op::Chunk:
      return read_chunk(offset, content, on_message);
    case Op::Message: {
      PendingMessage message{};
      ok = read_message(in, message);
      const auto channel = channels_.find(message.header.channel_id);
      if (ok && channel != channels_.end()) {
        const auto schema = schemas_.find(channel->second.schema_id);
        MessageView view{&channel->second, schema == schemas_.end() ? nullptr : &schema->second,
                         message.header, message.data, message.size};
        ++counts_[message.header.channel_id];
        if (on_message && !on_message(view)) stopped_ = true;
      } else if (ok) {
        report(offset, "Message of unknown channel " + std::to_string(message.header.channel_id));
      }
      break;
    }
    default:
      break;  // indexes and records we do not use: their lengths let us step over them
  }
  if (!ok) report(offset, "malformed " + op_name(op) + " record (fields run past its length)");
  return Step::Continue;
}

bool Reader::read_schema(ByteReader& in) {
  Schema schema;
  std::uint32_t data_length = 0;
  const std::uint8_t* data = nullptr;
  if (!in.u16(schema.id) || !in.string(schema.name) || !in.string(schema.encoding) ||
      !in.u32(data_length) || !in.span(data_length, data)) {
    return false;
  }
  schema.data.assign(reinterpret_cast<const char*>(data), data_length);
  schemas_.emplace(schema.id, std::move(schema));
  return true;
}

bool Reader::read_channel(ByteReader& in) {
  Channel channel;
  std::uint32_t map_length = 0;
  const std::uint8_t* map_start = nullptr;
  if (!in.u16(channel.id) || !in.u16(channel.schema_id) || !in.string(channel.topic) ||
      !in.string(channel.message_encoding) || !in.u32(map_length) ||
      !in.span(map_length, map_start)) {
    return false;
  }
  ByteReader entries(map_start, map_length);
  while (entries.remaining() > 0) {
    std::string key;
    std::string value;
    if (!entries.string(key) || !entries.string(value)) return false;
    channel.metadata[key] = value;
  }
  channels_.emplace(channel.id, std::move(channel));
  return true;
}

bool Reader::read_statistics(ByteReader& in) {
  Statistics& s = statistics_;
  statistics_seen_ = in.u64(s.message_count) && in.u16(s.schema_count) && in.u32(s.channel_count) &&
                     in.u32(s.attachment_count) && in.u32(s.metadata_count) &&
                     in.u32(s.chunk_count) && in.u64(s.message_start_time_ns) &&
                     in.u64(s.message_end_time_ns) &&
                     read_u16_u64_map(in, s.channel_message_counts);
  return statistics_seen_;
}

Reader::Step Reader::read_chunk(std::uint64_t offset, const Bytes& content,
                                const MessageCallback& on_message) {
  ByteReader in(content.data(), content.size());
  ChunkInfo info;
  info.offset = offset;
  std::uint32_t crc = 0;
  std::uint64_t records_length = 0;
  const std::uint8_t* compressed = nullptr;
  if (!in.u64(info.start_time_ns) || !in.u64(info.end_time_ns) || !in.u64(info.uncompressed_size) ||
      !in.u32(crc) || !in.string(info.compression) || !in.u64(records_length) ||
      !in.span(records_length, compressed)) {
    report(offset, "malformed Chunk record (fields run past its length)");
    return Step::Continue;
  }
  info.compressed_size = records_length;
  if (info.uncompressed_size > kMaxRecordBytes) {
    report(offset, "Chunk declares " + std::to_string(info.uncompressed_size) +
                       " uncompressed bytes (corrupt size); chunk skipped");
    return Step::Continue;
  }
  Bytes records;
  std::string error;
  if (!decompress(info.compression, compressed, records_length, info.uncompressed_size, records,
                  error)) {
    report(offset, "Chunk (" + (info.compression.empty() ? std::string("none") : info.compression) +
                       ") cannot be decompressed: " + error + "; chunk skipped");
    return Step::Continue;
  }
  if (crc != 0 && crc32_update(0, records.data(), records.size()) != crc) {
    report(offset, "Chunk CRC mismatch: its records are corrupt; chunk skipped");
    return Step::Continue;
  }
  std::vector<PendingMessage> messages;
  ByteReader inner(records.data(), records.size());
  while (inner.remaining() > 0) {
    const std::size_t at = inner.position();
    std::uint8_t op = 0;
    std::uint64_t length = 0;
    const std::uint8_t* start = nullptr;
    if (!inner.u8(op) || !inner.u64(length) || !inner.span(length, start)) {
      report(offset, "Chunk: record at byte " + std::to_string(at) +
                         " of its records runs past the chunk; rest of the chunk skipped");
      break;
    }
    ByteReader record(start, length);
    bool ok = true;
    if (op == static_cast<std::uint8_t>(Op::Message)) {
      PendingMessage message{};
      ok = read_message(record, message);
      if (ok) messages.push_back(message);
    } else if (op == static_cast<std::uint8_t>(Op::Schema)) {
      ok = read_schema(record);
    } else if (op == static_cast<std::uint8_t>(Op::Channel)) {
      ok = read_channel(record);
    }
    if (!ok) {
      report(offset, "Chunk: malformed " + op_name(op) + " record at byte " + std::to_string(at) +
                         " of its records");
    }
  }
  std::stable_sort(messages.begin(), messages.end(),
                   [](const PendingMessage& a, const PendingMessage& b) {
                     return a.header.log_time_ns < b.header.log_time_ns;
                   });
  info.message_count = messages.size();
  chunks_.push_back(info);
  for (const auto& message : messages) {
    const auto channel = channels_.find(message.header.channel_id);
    if (channel == channels_.end()) {
      report(offset, "Chunk: message of unknown channel " +
                         std::to_string(message.header.channel_id) + " skipped");
      continue;
    }
    const auto schema = schemas_.find(channel->second.schema_id);
    MessageView view{&channel->second, schema == schemas_.end() ? nullptr : &schema->second,
                     message.header, message.data, message.size};
    ++counts_[message.header.channel_id];
    if (on_message && !on_message(view)) {
      stopped_ = true;
      return Step::Stop;
    }
  }
  return Step::Continue;
}

}  // namespace cover::mcap
