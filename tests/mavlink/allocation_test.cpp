// The stream parser never allocates after construction, signed frames included: count
// every global operator new and every OpenSSL allocation while it parses.
#include <gtest/gtest.h>
#include <openssl/crypto.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <tuple>

#include "cover/mavlink/encoder.hpp"
#include "cover/mavlink/parser.hpp"
#include "sample_messages.hpp"
#include "stream_builder.hpp"

namespace {
std::atomic<long> g_allocations{0};

void* counting_malloc(std::size_t size, const char*, int) {
  ++g_allocations;
  return std::malloc(size);
}
void* counting_realloc(void* p, std::size_t size, const char*, int) {
  ++g_allocations;
  return std::realloc(p, size);
}
void plain_free(void* p, const char*, int) {
  std::free(p);
}

// Before OpenSSL allocates anything (it refuses a change afterwards).
const bool g_openssl_counted =
    CRYPTO_set_mem_functions(counting_malloc, counting_realloc, plain_free) == 1;
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace cover::mavlink {
namespace {

TEST(MavlinkAllocation, TheParserDoesNotAllocate) {
  ASSERT_TRUE(g_openssl_counted) << "OpenSSL allocated before the counters were installed";
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
  const long before = g_allocations.load();
  for (std::size_t at = 0; at < stream.size(); at += 7) {
    parser.feed(stream.data() + at, std::min<std::size_t>(7, stream.size() - at), count);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_EQ(frames, 20U * 2U * 13U);
  EXPECT_EQ(parser.stats().signature_errors, 0U);
}

}  // namespace
}  // namespace cover::mavlink
