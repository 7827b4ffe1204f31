#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cover/mcap/byte_io.hpp"
#include "cover/mcap/compression.hpp"
#include "cover/mcap/records.hpp"

namespace cover::mcap {

struct WriterOptions {
  Compression compression = Compression::Zstd;
  // A chunk is closed (compressed, written and flushed to the OS) when its uncompressed
  // records reach this size...
  std::size_t chunk_size_bytes = 1024 * 1024;
  // ... or this long after its first message: what a SIGKILL can lose.
  std::int64_t chunk_duration_ns = 1'000'000'000;
  std::string profile;  // the Header's profile ("" = none)
  std::string library = "cover";
};

// Writes one MCAP file: magic, Header, Schema and Channel records as they are added, then
// Chunks each followed by its MessageIndex records; close() adds DataEnd, the summary
// (Schemas, Channels, Statistics, ChunkIndexes), SummaryOffsets, Footer and the closing
// magic. Every closed chunk is flushed, so a killed writer leaves a file readable up to
// its last chunk. Not thread-safe: one thread writes.
class Writer {
 public:
  // Creates (or truncates) `path`; throws std::runtime_error naming it when it cannot.
  Writer(const std::string& path, WriterOptions options);
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  // Ids start at 1 and are valid until close().
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           const std::string& data);
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});

  // False once the file cannot be written (disk full...): error() says why.
  bool write(const MessageHeader& header, const std::uint8_t* data, std::size_t size);
  // Closes the open chunk when it is older than chunk_duration_ns: call it periodically so
  // that the last samples of a quiet recording reach the file too.
  bool flush_due();
  // Writes the open chunk and the summary; idempotent. False on a write error.
  bool close();

  const std::string& error() const { return error_; }
  const Statistics& statistics() const { return statistics_; }
  std::uint64_t bytes_written() const { return offset_; }

 private:
  struct OpenChunk {
    Bytes records;
    std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> index;
    std::uint64_t start_time_ns = 0;
    std::uint64_t end_time_ns = 0;
    std::int64_t opened_monotonic_ns = 0;
  };

  bool write_chunk();
  void append_message_indexes(Bytes& out) const;
  void write_summary();
  bool emit(const Bytes& bytes);

  WriterOptions options_;
  std::FILE* file_ = nullptr;
  std::uint64_t offset_ = 0;
  std::uint32_t data_crc_ = 0;
  bool closed_ = false;
  std::string error_;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<ChunkIndex> chunk_indexes_;
  Statistics statistics_;
  OpenChunk chunk_;
};

}  // namespace cover::mcap
