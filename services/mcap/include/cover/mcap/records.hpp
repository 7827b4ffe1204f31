#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cover::mcap {

// The MCAP record layout (https://mcap.dev/spec, version 0). Every record is
// opcode (uint8) | content length (uint64 LE) | content; times are uint64 nanoseconds.
inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr std::size_t kRecordPrefixBytes = 1 + 8;

enum class Op : std::uint8_t {
  Header = 0x01,
  Footer = 0x02,
  Schema = 0x03,
  Channel = 0x04,
  Message = 0x05,
  Chunk = 0x06,
  MessageIndex = 0x07,
  ChunkIndex = 0x08,
  Attachment = 0x09,
  AttachmentIndex = 0x0A,
  Statistics = 0x0B,
  Metadata = 0x0C,
  MetadataIndex = 0x0D,
  SummaryOffset = 0x0E,
  DataEnd = 0x0F,
};

// "Chunk", "Footer"...; "opcode 0x42" for an unknown one.
std::string op_name(std::uint8_t op);

struct Schema {
  std::uint16_t id = 0;  // 0 is reserved for "no schema"
  std::string name;      // e.g. "cover::idl::UgvImu"
  std::string encoding;  // e.g. "omgidl"
  std::string data;      // e.g. the IDL text
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;  // e.g. "cdr"
  std::map<std::string, std::string> metadata;
};

struct MessageHeader {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time_ns = 0;      // when the recorder received it
  std::uint64_t publish_time_ns = 0;  // the sample's own stamp
};

struct ChunkIndex {
  std::uint64_t message_start_time_ns = 0;
  std::uint64_t message_end_time_ns = 0;
  std::uint64_t chunk_start_offset = 0;
  std::uint64_t chunk_length = 0;  // the Chunk record, prefix included
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;
  std::string compression;
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
};

struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_start_time_ns = 0;
  std::uint64_t message_end_time_ns = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;
};

}  // namespace cover::mcap
