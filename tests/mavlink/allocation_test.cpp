// The stream parser never allocates after construction, signed frames included: count
// every allocation (malloc, so OpenSSL's too: cover/test/malloc_counter.hpp; its own
// executable) while it parses.
#include <gtest/gtest.h>

#include <tuple>

#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/parser.hpp"
#include "cover/test/malloc_counter.hpp"
#include "sample_messages.hpp"
#include "stream_builder.hpp"

namespace cover::mavlink {
namespace {

TEST(MavlinkAllocation, TheParserDoesNotAllocate) {
  if (!cover::test::malloc_counted()) GTEST_SKIP() << "malloc belongs to the sanitizer";
  Encoder plain(1, 1);
  Encoder signer(2, 2, test::test_key());
  test::Bytes stream{0x00, kMagicV2, 0x42};  // garbage and a broken candidate
  for (int i = 0; i < 20; ++i) {
    std::apply([&](const auto&... m) { (test::append(stream, test::encode(plain, m)), ...); },
               test::sample_messages());
    std::apply([&](const auto&... m) { (test::append(stream, test::encode(signer, m)), ...); },
               test::sample_messages());
  }
  ParserOptions options;
  options.signing_key = test::test_key();
  StreamParser parser(options);
  std::size_t frames = 0;
  const StreamParser::FrameHandler count = [&frames](const Frame&) { ++frames; };
  const long before = cover::test::counted_allocations();
  cover::test::count_this_thread(true);
  for (std::size_t at = 0; at < stream.size(); at += 7) {
    parser.feed(stream.data() + at, std::min<std::size_t>(7, stream.size() - at), count);
  }
  cover::test::count_this_thread(false);
  EXPECT_EQ(cover::test::counted_allocations() - before, 0);
  EXPECT_EQ(frames, 20U * 2U * std::tuple_size<test::AllMessages>::value);
  EXPECT_EQ(parser.stats().signature_errors, 0U);
}

}  // namespace
}  // namespace cover::mavlink
