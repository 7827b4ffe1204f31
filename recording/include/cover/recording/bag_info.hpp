#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cover/mcap/reader.hpp"

namespace cover::recording {

struct BagTopic {
  std::string topic;
  std::string type;      // the schema's name
  std::string encoding;  // the channel's message encoding
  std::uint64_t count = 0;
  std::uint64_t first_log_ns = 0;
  std::uint64_t last_log_ns = 0;
  double rate_hz = 0.0;  // (count - 1) over first..last; 0 below two messages
};

// What `cover bag info` reports of a recording: read through to the end (a crashed
// recorder's file has no summary to trust), with every issue found on the way.
struct BagSummary {
  std::string path;
  std::uint64_t size_bytes = 0;
  bool is_mcap = false;   // false: not readable at all (issues say why)
  bool finished = false;  // summary and footer present
  std::string library;    // the Header's
  std::uint64_t message_count = 0;
  std::uint64_t start_ns = 0;
  std::uint64_t end_ns = 0;
  std::map<std::string, std::uint64_t> chunks_by_compression;  // "none", "zstd", "lz4"
  std::uint64_t compressed_bytes = 0;
  std::uint64_t uncompressed_bytes = 0;
  std::vector<BagTopic> topics;  // by topic name
  std::vector<mcap::ReadIssue> issues;
};

BagSummary summarize_bag(const std::string& path);
// ros2 bag info's layout: Files, Bag size, Duration, Start, End, Messages, Compression,
// Topic information, then any problem with its byte offset.
std::string format_bag_summary(const BagSummary& summary);
nlohmann::json bag_summary_json(const BagSummary& summary);

}  // namespace cover::recording
