#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "cover/shm/seqlock_reader.hpp"
#include "cover/shm/seqlock_writer.hpp"
#include "shm_test_support.hpp"

namespace {

using cover::shm::SeqlockReader;
using cover::shm::SeqlockWriter;
using cover::shm::test::CounterPayload;
using cover::shm::test::kCounterLayout;
using cover::shm::test::segment_exists;
using namespace std::chrono_literals;

class ShmLifetime : public cover::shm::test::ShmFixture {};

// Creates `name` holding `bytes` as a foreign or crashed process would have left it.
void create_raw_segment(const std::string& name, const std::string& bytes) {
  const int fd = shm_open(name.c_str(), O_CREAT | O_EXCL | O_RDWR, 0600);
  ASSERT_GE(fd, 0) << std::strerror(errno);
  ASSERT_EQ(write(fd, bytes.data(), bytes.size()), static_cast<ssize_t>(bytes.size()));
  close(fd);
}

std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST_F(ShmLifetime, WriterOfADeadProcessIsReplaced) {
  const std::string name = unique_name();
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // Exit without destructors, as a crashed simulator would: the segment stays.
    try {
      SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
      _exit(0);
    } catch (...) {
      _exit(1);
    }
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);  // reaped: the pid no longer exists
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ASSERT_TRUE(segment_exists(name));
  {
    auto stale = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
    EXPECT_EQ(stale.writer_pid(), child);
    EXPECT_FALSE(stale.writer_alive());
  }

  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
  EXPECT_EQ(reader.writer_pid(), getpid());
}

TEST_F(ShmLifetime, SecondWriterOfALiveOneFailsNamingThePid) {
  const std::string name = unique_name();
  SeqlockWriter<CounterPayload> first(name, kCounterLayout);
  const std::string message =
      message_of([&] { SeqlockWriter<CounterPayload> second(name, kCounterLayout); });
  EXPECT_NE(message.find(name), std::string::npos) << message;
  EXPECT_NE(message.find("pid " + std::to_string(getpid())), std::string::npos) << message;
  auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
  EXPECT_EQ(reader.writer_pid(), getpid());  // the first one's segment is untouched
}

TEST_F(ShmLifetime, GarbageAndIncompleteSegmentsAreReplaced) {
  const std::string garbage = unique_name();
  create_raw_segment(garbage, std::string(4096, 'g'));
  SeqlockWriter<CounterPayload> over_garbage(garbage, kCounterLayout);

  const std::string empty = unique_name();  // a creator died before ftruncate
  create_raw_segment(empty, "");
  SeqlockWriter<CounterPayload> over_empty(empty, kCounterLayout);

  const std::string zeros = unique_name();  // ... or before publishing its header
  create_raw_segment(zeros, std::string(128, '\0'));
  SeqlockWriter<CounterPayload> over_zeros(zeros, kCounterLayout);

  for (const auto* name : {&garbage, &empty, &zeros}) {
    auto reader = SeqlockReader<CounterPayload>::open(*name, kCounterLayout, 1s);
    EXPECT_EQ(reader.writer_pid(), getpid()) << *name;
  }
}

TEST_F(ShmLifetime, LayoutVersionMismatchIsNamed) {
  const std::string name = unique_name();
  SeqlockWriter<CounterPayload> writer(name, 3);
  const std::string message = message_of([&] { SeqlockReader<CounterPayload>::open(name, 2, 1s); });
  EXPECT_EQ(message,
            "shared-memory segment " + name + " has layout version 3, this reader expects 2");
}

TEST_F(ShmLifetime, PayloadSizeMismatchIsNamed) {
  const std::string name = unique_name();
  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  const std::string message =
      message_of([&] { SeqlockReader<std::uint64_t>::open(name, kCounterLayout, 1s); });
  EXPECT_EQ(message, "shared-memory segment " + name +
                         " has a payload of 65536 bytes, this reader expects 8");
}

TEST_F(ShmLifetime, ForeignSegmentIsNotACoverOne) {
  const std::string name = unique_name();
  create_raw_segment(name, std::string(4096, 'g'));
  const std::string message =
      message_of([&] { SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s); });
  EXPECT_NE(message.find("is not a COVER segment"), std::string::npos) << message;
  EXPECT_TRUE(cover::shm::remove_segment(name));
}

TEST_F(ShmLifetime, OpenGivesUpAtTheDeadline) {
  const std::string name = unique_name();
  const auto start = std::chrono::steady_clock::now();
  const std::string message =
      message_of([&] { SeqlockReader<CounterPayload>::open(name, kCounterLayout, 150ms); });
  const auto waited = std::chrono::steady_clock::now() - start;
  EXPECT_EQ(message, "shared-memory segment " + name + " does not exist after waiting 150 ms");
  EXPECT_GE(waited, 150ms);
  EXPECT_LT(waited, 5s);
}

TEST_F(ShmLifetime, OpenWaitsForAnIncompleteHeaderThenGivesUp) {
  const std::string name = unique_name();
  create_raw_segment(name, std::string(128, '\0'));
  const std::string message =
      message_of([&] { SeqlockReader<CounterPayload>::open(name, kCounterLayout, 50ms); });
  EXPECT_NE(message.find("header is not complete after waiting 50 ms"), std::string::npos)
      << message;
  EXPECT_TRUE(cover::shm::remove_segment(name));
}

TEST_F(ShmLifetime, RemoveSegmentReportsWhetherItExisted) {
  const std::string name = unique_name();
  create_raw_segment(name, "x");
  EXPECT_TRUE(cover::shm::remove_segment(name));
  EXPECT_FALSE(cover::shm::remove_segment(name));
  EXPECT_THROW(cover::shm::remove_segment("no_slash"), std::invalid_argument);
}

TEST_F(ShmLifetime, WriterDoesNotUnlinkASegmentThatReplacedIt) {
  const std::string name = unique_name();
  std::optional<SeqlockWriter<CounterPayload>> old_writer;
  old_writer.emplace(name, kCounterLayout);
  ASSERT_TRUE(cover::shm::remove_segment(name));  // a launcher cleaned up
  SeqlockWriter<std::uint64_t> new_writer(name, 1);
  old_writer.reset();
  EXPECT_TRUE(segment_exists(name));
  auto reader = SeqlockReader<std::uint64_t>::open(name, 1, 1s);
  EXPECT_EQ(reader.writer_pid(), getpid());
}

}  // namespace
