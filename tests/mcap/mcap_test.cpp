// The MCAP writer and our reader: round trip for each compression, chunks closed on size
// and on age, a file cut anywhere (as by SIGKILL) read up to its last complete chunk, and
// corrupt bytes reported with their offset, never a crash.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cover/mcap/reader.hpp"
#include "cover/mcap/writer.hpp"
#include "cover/test/file_contents.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"

namespace cover::mcap {
namespace {

using test::read_bytes;
using test::write_bytes;

struct Recorded {
  std::string topic;
  MessageHeader header;
  std::vector<std::uint8_t> data;
};

std::vector<std::uint8_t> payload(std::uint32_t i) {
  std::vector<std::uint8_t> bytes{0x00, 0x01, 0x00, 0x00};
  for (int k = 0; k < 4 + static_cast<int>(i % 13); ++k)
    bytes.push_back(static_cast<std::uint8_t>(i + k));
  return bytes;
}

// Writes `count` messages alternating between two channels.
void write_file(const std::string& path, WriterOptions options, std::uint32_t count) {
  Writer writer(path, options);
  const auto schema =
      writer.add_schema("t::P", "omgidl", "module t { @final struct P { uint32 a; }; };");
  const std::uint16_t channels[] = {writer.add_channel(schema, "a", "cdr"),
                                    writer.add_channel(schema, "b", "cdr", {{"k", "v"}})};
  for (std::uint32_t i = 0; i < count; ++i) {
    const auto data = payload(i);
    MessageHeader header{channels[i % 2], i, 1000 + i * 10ULL, 900 + i * 10ULL};
    ASSERT_TRUE(writer.write(header, data.data(), data.size()));
  }
  ASSERT_TRUE(writer.close());
}

std::vector<Recorded> read_all(Reader& reader) {
  std::vector<Recorded> out;
  reader.scan([&](const MessageView& m) {
    out.push_back({m.channel->topic, m.header, {m.data, m.data + m.size}});
    return true;
  });
  return out;
}

class McapRoundTrip : public ::testing::TestWithParam<Compression> {};

TEST_P(McapRoundTrip, EveryMessageBackInOrderWithTheSummary) {
  const std::string path = test::scratch_path("round_trip.mcap");
  WriterOptions options;
  options.compression = GetParam();
  options.chunk_size_bytes = 4096;  // several chunks
  write_file(path, options, 2000);
  Reader reader(path);
  const auto messages = read_all(reader);
  EXPECT_TRUE(reader.finished());
  EXPECT_TRUE(reader.issues().empty()) << reader.issues().front().what;
  ASSERT_EQ(messages.size(), 2000U);
  for (std::uint32_t i = 0; i < messages.size(); ++i) {
    EXPECT_EQ(messages[i].header.sequence, i);
    EXPECT_EQ(messages[i].topic, i % 2 ? "b" : "a");
    EXPECT_EQ(messages[i].header.log_time_ns, 1000 + i * 10ULL);
    EXPECT_EQ(messages[i].header.publish_time_ns, 900 + i * 10ULL);
    EXPECT_EQ(messages[i].data, payload(i));
  }
  EXPECT_GT(reader.chunks().size(), 5U);
  for (const auto& chunk : reader.chunks()) {
    EXPECT_EQ(chunk.compression, compression_name(GetParam()));
  }
  ASSERT_TRUE(reader.has_summary_statistics());
  EXPECT_EQ(reader.summary_statistics().message_count, 2000U);
  EXPECT_EQ(reader.summary_statistics().chunk_count, reader.chunks().size());
  EXPECT_EQ(reader.channels().at(2).metadata.at("k"), "v");
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapRoundTrip,
                         ::testing::Values(Compression::None, Compression::Lz4, Compression::Zstd),
                         [](const ::testing::TestParamInfo<Compression>& info) {
                           const auto name = compression_name(info.param);
                           return name.empty() ? std::string("none") : std::string(name);
                         });

TEST(McapWriter, ClosesAChunkOnceItIsOlderThanItsDuration) {
  const std::string path = test::scratch_path("aged.mcap");
  WriterOptions options;
  options.chunk_duration_ns = 50'000'000;
  Writer writer(path, options);
  const auto channel = writer.add_channel(writer.add_schema("t::P", "omgidl", ""), "a", "cdr");
  const auto data = payload(1);
  ASSERT_TRUE(writer.write({channel, 1, 1, 1}, data.data(), data.size()));
  EXPECT_EQ(writer.statistics().chunk_count, 0U);
  // flush_due() is what the recorder calls between samples: it closes the chunk once aged.
  test::wait_until(
      [&] {
        writer.flush_due();
        return writer.statistics().chunk_count != 0;
      },
      std::chrono::seconds(5));
  EXPECT_EQ(writer.statistics().chunk_count, 1U);
  // Already on disk, before close(): what a SIGKILL would leave.
  Reader reader(path);
  EXPECT_EQ(read_all(reader).size(), 1U);
  EXPECT_FALSE(reader.finished());
}

TEST(McapReader, AFileCutAnywhereGivesItsCompleteChunksAndSaysWhere) {
  const std::string path = test::scratch_path("whole.mcap");
  WriterOptions options;
  options.chunk_size_bytes = 2048;
  write_file(path, options, 600);
  const auto bytes = read_bytes(path);
  const std::string cut = test::scratch_path("cut.mcap");
  std::size_t previous = 0;
  for (std::size_t length = 0; length < bytes.size(); length += 97) {
    write_bytes(cut, {bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(length)});
    Reader reader(cut);
    const auto messages = read_all(reader);
    EXPECT_FALSE(reader.finished());
    ASSERT_FALSE(reader.issues().empty()) << length;
    EXPECT_LE(reader.issues().front().offset, length);
    EXPECT_GE(messages.size(), previous);  // more file, never fewer messages
    previous = messages.size();
    for (std::uint32_t i = 0; i < messages.size(); ++i) EXPECT_EQ(messages[i].header.sequence, i);
  }
  EXPECT_GT(previous, 500U);
}

TEST(McapReader, CorruptBytesAreReportedWithTheirOffsetAndSkipped) {
  const std::string path = test::scratch_path("corrupt.mcap");
  WriterOptions options;
  options.chunk_size_bytes = 2048;
  options.compression = Compression::Zstd;
  write_file(path, options, 600);
  auto bytes = read_bytes(path);
  Reader clean(path);
  read_all(clean);
  ASSERT_GT(clean.chunks().size(), 3U);
  // Flip a byte in the middle of the second chunk's compressed records.
  const auto& second = clean.chunks()[1];
  bytes[second.offset + 60 + second.compressed_size / 2] ^= 0x5A;
  write_bytes(path, bytes);
  Reader reader(path);
  const auto messages = read_all(reader);
  ASSERT_FALSE(reader.issues().empty());
  EXPECT_EQ(reader.issues().front().offset, second.offset);
  EXPECT_NE(reader.issues().front().what.find("Chunk"), std::string::npos)
      << reader.issues().front().what;
  EXPECT_EQ(messages.size(), 600U - second.message_count);
}

TEST(McapReader, NotAnMcapFileSaysSo) {
  const std::string path = test::scratch_path("text.mcap");
  write_bytes(path, {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd'});
  Reader reader(path);
  EXPECT_FALSE(reader.scan(nullptr));
  ASSERT_EQ(reader.issues().size(), 1U);
  EXPECT_NE(reader.issues()[0].what.find("not an MCAP file"), std::string::npos);
  Reader missing(test::scratch_path("missing.mcap"));
  EXPECT_FALSE(missing.scan(nullptr));
  EXPECT_NE(missing.issues().at(0).what.find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace cover::mcap
