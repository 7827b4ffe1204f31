#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <thread>

#include "cover/shm/seqlock_reader.hpp"
#include "cover/shm/seqlock_writer.hpp"
#include "cover/test/wait_until.hpp"
#include "shm_test_support.hpp"

namespace {

using cover::shm::SeqlockReader;
using cover::shm::SeqlockWriter;
using cover::shm::test::CounterPayload;
using cover::shm::test::kCounterLayout;
using cover::shm::test::segment_exists;
using namespace std::chrono_literals;

class ShmSeqlock : public cover::shm::test::ShmFixture {};

// What a reader saw while a writer published counters 1..N.
struct ReadTally {
  std::uint64_t reads = 0;
  std::uint64_t distinct = 0;
  std::uint64_t torn = 0;       // elements differ: a copy overlapped a write
  std::uint64_t backwards = 0;  // a counter lower than one already seen
  std::uint64_t bad_stamp = 0;  // the stamp does not belong to the payload
  std::uint64_t last = 0;

  void add(const CounterPayload& value, std::int64_t stamp) {
    ++reads;
    const std::uint64_t counter = value.values[0];
    if (!cover::shm::test::uniform(value)) ++torn;
    if (stamp != static_cast<std::int64_t>(counter)) ++bad_stamp;
    if (counter < last) ++backwards;
    if (counter > last) ++distinct;
    if (counter > last) last = counter;
  }
};

TEST_F(ShmSeqlock, NothingToReadBeforeTheFirstWrite) {
  const std::string name = unique_name();
  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
  auto value = std::make_unique<CounterPayload>();
  EXPECT_EQ(reader.sequence(), 0u);
  EXPECT_FALSE(reader.read(*value));

  cover::shm::test::fill(*value, 42);
  writer.write(*value, 1234);
  auto out = std::make_unique<CounterPayload>();
  std::int64_t stamp = 0;
  ASSERT_TRUE(reader.read(*out, &stamp));
  EXPECT_EQ(out->values[8191], 42u);
  EXPECT_EQ(stamp, 1234);
  EXPECT_EQ(reader.sequence(), 2u);
  EXPECT_EQ(reader.last_read_sequence(), reader.sequence());  // nothing new since
  EXPECT_EQ(reader.writer_pid(), getpid());
  EXPECT_TRUE(reader.writer_alive());
}

TEST_F(ShmSeqlock, ConcurrentReaderNeverSeesATornOrOlderValue) {
  const std::string name = unique_name();
  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
  constexpr std::uint64_t kWrites = 20000;
  std::atomic<bool> done{false};
  std::thread writer_thread([&] {
    auto value = std::make_unique<CounterPayload>();
    for (std::uint64_t counter = 1; counter <= kWrites; ++counter) {
      cover::shm::test::fill(*value, counter);
      writer.write(*value, static_cast<std::int64_t>(counter));
      cover::shm::test::work_between_writes();
    }
    done = true;
  });

  ReadTally tally;
  auto out = std::make_unique<CounterPayload>();
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while ((!done || tally.last < kWrites) && std::chrono::steady_clock::now() < deadline) {
    std::int64_t stamp = 0;
    if (reader.read(*out, &stamp)) tally.add(*out, stamp);
  }
  writer_thread.join();
  EXPECT_EQ(tally.torn, 0u);
  EXPECT_EQ(tally.backwards, 0u);
  EXPECT_EQ(tally.bad_stamp, 0u);
  EXPECT_EQ(tally.last, kWrites);
  // Overlap happened: the reader saw many values in between, not only the last one.
  EXPECT_GT(tally.distinct, 100u) << tally.reads << " reads";
}

// The simulator appends IMU samples to a ring in place; readers see whole appends only.
struct Ring {
  std::uint32_t count;
  std::uint32_t head;
  std::int64_t samples[1000];
};

TEST_F(ShmSeqlock, UpdateMutatesInPlaceUnderTheLock) {
  const std::string name = unique_name();
  SeqlockWriter<Ring> writer(name, 1);
  auto reader = SeqlockReader<Ring>::open(name, 1, 1s);
  constexpr int kAppends = 20000;
  std::atomic<bool> done{false};
  std::thread writer_thread([&] {
    for (int i = 1; i <= kAppends; ++i) {
      writer.update(
          [i](Ring& ring) {
            ring.samples[ring.head] = i;
            ring.head = (ring.head + 1) % 1000;
            ring.count = static_cast<std::uint32_t>(i);
          },
          i);
      cover::shm::test::work_between_writes();
    }
    done = true;
  });
  Ring out{};
  std::uint32_t seen =
      0;  // out.count of the last successful read; out may be torn after a failed one
  std::uint64_t inconsistent = 0;
  std::int64_t stamp = 0;
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while ((!done || seen < kAppends) && std::chrono::steady_clock::now() < deadline) {
    if (!reader.read(out, &stamp)) continue;
    // The newest sample sits just before head and equals the count and the stamp.
    const std::int64_t newest = out.samples[(out.head + 999) % 1000];
    if (newest != out.count || stamp != out.count || out.head != out.count % 1000) ++inconsistent;
    seen = out.count;
  }
  writer_thread.join();
  EXPECT_EQ(inconsistent, 0u);
  EXPECT_EQ(seen, static_cast<std::uint32_t>(kAppends));
  EXPECT_EQ(writer.sequence(), 2u * kAppends);
}

TEST_F(ShmSeqlock, ReaderWaitsForTheWriterToAppear) {
  const std::string name = unique_name();
  std::atomic<bool> opened{false};
  std::thread reader_thread([&] {
    auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 10s);
    opened = true;
  });
  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  reader_thread.join();  // open() returned rather than threw
  EXPECT_TRUE(opened);
}

TEST_F(ShmSeqlock, WriterUnlinksOnDestructionAndReadersKeepTheirMapping) {
  const std::string name = unique_name();
  auto value = std::make_unique<CounterPayload>();
  cover::shm::test::fill(*value, 9);
  std::optional<SeqlockReader<CounterPayload>> reader;
  {
    SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
    writer.write(*value, 9);
    EXPECT_TRUE(segment_exists(name));
    reader.emplace(SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s));
  }
  EXPECT_FALSE(segment_exists(name));
  auto out = std::make_unique<CounterPayload>();
  ASSERT_TRUE(reader->read(*out));
  EXPECT_EQ(out->values[100], 9u);
}

}  // namespace

// A reader that would poll blocks on the sequence instead (SeqlockReader::wait_for_write):
// the next write wakes it, through its own mapping of the segment (as in another process).
TEST_F(ShmSeqlock, AWriteWakesAReaderBlockedOnTheSequence) {
  const std::string name = unique_name();
  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  const auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
  const auto value = std::make_unique<CounterPayload>();
  cover::shm::test::fill(*value, 1);
  writer.write(*value, 1);
  const std::uint64_t seen = reader.sequence();

  // Unchanged: the wait lasts its timeout.
  const auto start = std::chrono::steady_clock::now();
  reader.wait_for_write(seen, 20ms);
  EXPECT_GE(std::chrono::steady_clock::now() - start, 15ms);

  // A write while it waits (or before it got to wait) ends it long before its timeout; a
  // write that did not wake it would keep it 60 s.
  std::atomic<bool> woke{false};
  std::chrono::steady_clock::duration waited{};
  std::thread waiter([&] {
    const auto begin = std::chrono::steady_clock::now();
    reader.wait_for_write(seen, 60s);
    waited = std::chrono::steady_clock::now() - begin;
    woke = true;
  });
  cover::shm::test::fill(*value, 2);
  writer.write(*value, 2);
  const bool returned = cover::test::wait_until([&] { return woke.load(); }, 10000ms);
  waiter.join();
  EXPECT_TRUE(returned);
  EXPECT_LT(waited, 30s);
  EXPECT_NE(reader.sequence(), seen);
}
