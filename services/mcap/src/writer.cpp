#include "cover/mcap/writer.hpp"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "cover/mcap/crc32.hpp"
#include "record_builder.hpp"

namespace cover::mcap {
namespace {

std::int64_t monotonic_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void append_u16_u64_map(ByteWriter& w, const std::map<std::uint16_t, std::uint64_t>& map) {
  w.u32(static_cast<std::uint32_t>(map.size() * (2 + 8)));
  for (const auto& [key, value] : map) {
    w.u16(key);
    w.u64(value);
  }
}

void append_chunk_index(Bytes& out, const ChunkIndex& index) {
  RecordBuilder record(out, Op::ChunkIndex);
  auto& w = record.content();
  w.u64(index.message_start_time_ns);
  w.u64(index.message_end_time_ns);
  w.u64(index.chunk_start_offset);
  w.u64(index.chunk_length);
  append_u16_u64_map(w, index.message_index_offsets);
  w.u64(index.message_index_length);
  w.string(index.compression);
  w.u64(index.compressed_size);
  w.u64(index.uncompressed_size);
  record.end();
}

void append_statistics(Bytes& out, const Statistics& s) {
  RecordBuilder record(out, Op::Statistics);
  auto& w = record.content();
  w.u64(s.message_count);
  w.u16(s.schema_count);
  w.u32(s.channel_count);
  w.u32(s.attachment_count);
  w.u32(s.metadata_count);
  w.u32(s.chunk_count);
  w.u64(s.message_start_time_ns);
  w.u64(s.message_end_time_ns);
  append_u16_u64_map(w, s.channel_message_counts);
  record.end();
}

void append_summary_offset(Bytes& out, Op group, std::uint64_t start, std::uint64_t length) {
  if (length == 0) return;
  RecordBuilder record(out, Op::SummaryOffset);
  record.content().u8(static_cast<std::uint8_t>(group));
  record.content().u64(start);
  record.content().u64(length);
  record.end();
}

}  // namespace

Writer::Writer(const std::string& path, WriterOptions options) : options_(std::move(options)) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    throw std::runtime_error("cannot create " + path + ": " + std::strerror(errno));
  }
  Bytes head(std::begin(kMagic), std::end(kMagic));
  RecordBuilder header(head, Op::Header);
  header.content().string(options_.profile);
  header.content().string(options_.library);
  header.end();
  if (!emit(head) || std::fflush(file_) != 0) {
    throw std::runtime_error("cannot write " + path + ": " + error_);
  }
}

Writer::~Writer() {
  close();
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding,
                                 const std::string& data) {
  Schema schema{static_cast<std::uint16_t>(schemas_.size() + 1), name, encoding, data};
  Bytes record;
  append_schema(record, schema);
  emit(record);
  schemas_.push_back(std::move(schema));
  return schemas_.back().id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema_id, const std::string& topic,
                                  const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  Channel channel{static_cast<std::uint16_t>(channels_.size() + 1), schema_id, topic,
                  message_encoding, metadata};
  Bytes record;
  append_channel(record, channel);
  emit(record);
  channels_.push_back(std::move(channel));
  return channels_.back().id;
}

bool Writer::write(const MessageHeader& header, const std::uint8_t* data, std::size_t size) {
  if (closed_ || !error_.empty()) return false;
  if (chunk_.records.empty()) {
    chunk_.opened_monotonic_ns = monotonic_ns();
    chunk_.start_time_ns = chunk_.end_time_ns = header.log_time_ns;
  }
  chunk_.index[header.channel_id].emplace_back(header.log_time_ns, chunk_.records.size());
  RecordBuilder record(chunk_.records, Op::Message);
  auto& w = record.content();
  w.u16(header.channel_id);
  w.u32(header.sequence);
  w.u64(header.log_time_ns);
  w.u64(header.publish_time_ns);
  w.raw(data, size);
  record.end();
  chunk_.start_time_ns = std::min(chunk_.start_time_ns, header.log_time_ns);
  chunk_.end_time_ns = std::max(chunk_.end_time_ns, header.log_time_ns);

  if (statistics_.message_count == 0) {
    statistics_.message_start_time_ns = header.log_time_ns;
    statistics_.message_end_time_ns = header.log_time_ns;
  }
  ++statistics_.message_count;
  ++statistics_.channel_message_counts[header.channel_id];
  statistics_.message_start_time_ns =
      std::min(statistics_.message_start_time_ns, header.log_time_ns);
  statistics_.message_end_time_ns = std::max(statistics_.message_end_time_ns, header.log_time_ns);

  if (chunk_.records.size() >= options_.chunk_size_bytes) return write_chunk();
  return flush_due();
}

bool Writer::flush_due() {
  if (chunk_.records.empty()) return error_.empty();
  if (monotonic_ns() - chunk_.opened_monotonic_ns < options_.chunk_duration_ns) {
    return error_.empty();
  }
  return write_chunk();
}

void Writer::append_message_indexes(Bytes& out) const {
  for (const auto& [channel_id, entries] : chunk_.index) {
    RecordBuilder record(out, Op::MessageIndex);
    auto& w = record.content();
    w.u16(channel_id);
    w.u32(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [log_time_ns, offset] : entries) {
      w.u64(log_time_ns);
      w.u64(offset);
    }
    record.end();
  }
}

bool Writer::write_chunk() {
  if (chunk_.records.empty()) return error_.empty();
  const std::string compression(compression_name(options_.compression));
  Bytes out;
  {
    RecordBuilder record(out, Op::Chunk);
    auto& w = record.content();
    w.u64(chunk_.start_time_ns);
    w.u64(chunk_.end_time_ns);
    w.u64(chunk_.records.size());
    w.u32(crc32_update(0, chunk_.records.data(), chunk_.records.size()));
    w.string(compression);
    const std::size_t size_at = w.size();
    w.u64(0);
    compress(options_.compression, chunk_.records.data(), chunk_.records.size(), out);
    w.patch_u64(size_at, out.size() - size_at - 8);
    record.end();
  }
  ChunkIndex index;
  index.message_start_time_ns = chunk_.start_time_ns;
  index.message_end_time_ns = chunk_.end_time_ns;
  index.chunk_start_offset = offset_;
  index.chunk_length = out.size();
  index.compression = compression;
  index.uncompressed_size = chunk_.records.size();
  // Chunk prefix (9) + times (16) + size (8) + crc (4) + compression string + records length.
  index.compressed_size =
      out.size() - (kRecordPrefixBytes + 16 + 8 + 4 + 4 + compression.size() + 8);
  const std::size_t indexes_at = out.size();
  append_message_indexes(out);
  std::uint64_t at = offset_ + indexes_at;
  for (std::size_t pos = indexes_at; pos < out.size();) {
    const std::uint16_t channel_id =
        static_cast<std::uint16_t>(out[pos + 9] | (out[pos + 10] << 8));
    std::uint64_t length = 0;
    for (int i = 0; i < 8; ++i) length |= std::uint64_t{out[pos + 1 + i]} << (8 * i);
    index.message_index_offsets[channel_id] = at;
    at += kRecordPrefixBytes + length;
    pos += kRecordPrefixBytes + length;
  }
  index.message_index_length = out.size() - indexes_at;
  chunk_ = OpenChunk{};
  if (!emit(out)) return false;
  chunk_indexes_.push_back(std::move(index));
  ++statistics_.chunk_count;
  if (std::fflush(file_) != 0) {
    error_ = std::string("flush: ") + std::strerror(errno);
    return false;
  }
  return true;
}

void Writer::write_summary() {
  Bytes data_end;
  RecordBuilder end_record(data_end, Op::DataEnd);
  end_record.content().u32(data_crc_);
  end_record.end();
  emit(data_end);

  statistics_.schema_count = static_cast<std::uint16_t>(schemas_.size());
  statistics_.channel_count = static_cast<std::uint32_t>(channels_.size());
  const std::uint64_t summary_start = offset_;
  Bytes summary;
  Bytes offsets;
  auto group = [&](Op op, auto&& append_all) {
    const std::size_t start = summary.size();
    append_all();
    append_summary_offset(offsets, op, summary_start + start, summary.size() - start);
  };
  group(Op::Schema, [&] {
    for (const auto& schema : schemas_) append_schema(summary, schema);
  });
  group(Op::Channel, [&] {
    for (const auto& channel : channels_) append_channel(summary, channel);
  });
  group(Op::Statistics, [&] { append_statistics(summary, statistics_); });
  group(Op::ChunkIndex, [&] {
    for (const auto& index : chunk_indexes_) append_chunk_index(summary, index);
  });
  const std::uint64_t summary_offset_start = summary_start + summary.size();
  Bytes tail = std::move(summary);
  tail.insert(tail.end(), offsets.begin(), offsets.end());
  ByteWriter footer(tail);
  footer.u8(static_cast<std::uint8_t>(Op::Footer));
  footer.u64(8 + 8 + 4);
  footer.u64(summary_start);
  footer.u64(summary_offset_start);
  footer.u32(crc32_update(0, tail.data(), tail.size()));
  footer.raw(kMagic, sizeof(kMagic));
  emit(tail);
}

bool Writer::close() {
  if (closed_) return error_.empty();
  closed_ = true;
  write_chunk();
  write_summary();
  if (std::fclose(file_) != 0 && error_.empty()) {
    error_ = std::string("close: ") + std::strerror(errno);
  }
  file_ = nullptr;
  return error_.empty();
}

bool Writer::emit(const Bytes& bytes) {
  if (!error_.empty()) return false;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    error_ = std::string("write: ") + std::strerror(errno);
    return false;
  }
  data_crc_ = crc32_update(data_crc_, bytes.data(), bytes.size());
  offset_ += bytes.size();
  return true;
}

}  // namespace cover::mcap
