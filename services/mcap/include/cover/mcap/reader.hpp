#pragma once

#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cover/mcap/byte_io.hpp"
#include "cover/mcap/records.hpp"

namespace cover::mcap {

// A damaged or missing part of a file: where (byte offset) and what.
struct ReadIssue {
  std::uint64_t offset = 0;
  std::string what;
};

struct ChunkInfo {
  std::uint64_t offset = 0;
  std::string compression;  // "" none, "zstd", "lz4"
  std::uint64_t compressed_size = 0;
  std::uint64_t uncompressed_size = 0;
  std::uint64_t message_count = 0;
  std::uint64_t start_time_ns = 0;
  std::uint64_t end_time_ns = 0;
};

// One message, valid during the callback that receives it.
struct MessageView {
  const Channel* channel = nullptr;
  const Schema* schema = nullptr;  // nullptr when the channel has none
  MessageHeader header;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

// Reads an MCAP file from its first record to its last, the way a recovering reader must
// (a recorder killed mid-run leaves no summary): every complete chunk is decompressed and
// checked (CRC), its messages delivered in log-time order. Bad bytes never stop it with a
// crash: a damaged chunk is reported and skipped when its length still fits the file;
// a record running past the end ends the scan. issues() says where and what.
class Reader {
 public:
  // Returning false stops the scan.
  using MessageCallback = std::function<bool(const MessageView&)>;

  explicit Reader(std::string path) : path_(std::move(path)) {}

  // True when the file was read to its closing magic without an issue.
  bool scan(const MessageCallback& on_message);

  const std::string& profile() const { return profile_; }
  const std::string& library() const { return library_; }
  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  const std::vector<ChunkInfo>& chunks() const { return chunks_; }
  // Messages delivered per channel.
  const std::map<std::uint16_t, std::uint64_t>& message_counts() const { return counts_; }
  // The file opened and begins with MCAP's magic (scan() ran).
  bool is_mcap() const { return magic_seen_; }
  bool finished() const { return footer_seen_; }  // Footer and closing magic present
  bool has_summary_statistics() const { return statistics_seen_; }
  const Statistics& summary_statistics() const { return statistics_; }
  const std::vector<ReadIssue>& issues() const { return issues_; }
  std::uint64_t file_size() const { return file_size_; }

 private:
  enum class Step { Continue, Stop };
  Step read_record(std::uint64_t offset, std::uint8_t op, const Bytes& content,
                   const MessageCallback& on_message);
  Step read_chunk(std::uint64_t offset, const Bytes& content, const MessageCallback& on_message);
  void check_data_crc(std::uint64_t offset, const Bytes& content, std::uint32_t computed);
  bool read_schema(ByteReader& in);
  bool read_channel(ByteReader& in);
  bool read_statistics(ByteReader& in);
  void report(std::uint64_t offset, std::string what);

  std::string path_;
  std::uint64_t file_size_ = 0;
  std::string profile_;
  std::string library_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::vector<ChunkInfo> chunks_;
  std::map<std::uint16_t, std::uint64_t> counts_;
  Statistics statistics_;
  bool statistics_seen_ = false;
  bool magic_seen_ = false;
  bool footer_seen_ = false;
  bool stopped_ = false;
  std::vector<ReadIssue> issues_;
};

}  // namespace cover::mcap
