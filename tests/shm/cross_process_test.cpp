#include <gtest/gtest.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <memory>
#include <optional>
#include <string>

#include "cover/process/child_process.hpp"
#include "cover/shm/seqlock_reader.hpp"
#include "cover/shm/seqlock_writer.hpp"
#include "shm_test_support.hpp"

namespace {

using cover::process::ChildProcess;
using cover::shm::SeqlockReader;
using cover::shm::SeqlockWriter;
using cover::shm::test::CounterPayload;
using cover::shm::test::kCounterLayout;
using cover::shm::test::segment_exists;
using namespace std::chrono_literals;

class ShmCrossProcess : public cover::shm::test::ShmFixture {};

struct Tally {
  std::uint64_t reads = 0, distinct = 0, torn = 0, backwards = 0, last = 0;
};

// Reads until `distinct` different counters were seen or the deadline passes.
Tally read_counters(SeqlockReader<CounterPayload>& reader, std::uint64_t distinct) {
  Tally tally;
  auto out = std::make_unique<CounterPayload>();
  const auto deadline = std::chrono::steady_clock::now() + 60s;
  while (tally.distinct < distinct && std::chrono::steady_clock::now() < deadline) {
    std::int64_t stamp = 0;
    if (!reader.read(*out, &stamp)) continue;
    ++tally.reads;
    const std::uint64_t counter = out->values[0];
    if (!cover::shm::test::uniform(*out) || stamp != static_cast<std::int64_t>(counter)) {
      ++tally.torn;
    }
    if (counter < tally.last) ++tally.backwards;
    if (counter > tally.last) ++tally.distinct;
    if (counter > tally.last) tally.last = counter;
  }
  return tally;
}

void expect_clean(const Tally& tally, std::uint64_t distinct) {
  EXPECT_EQ(tally.torn, 0u);
  EXPECT_EQ(tally.backwards, 0u);
  EXPECT_GE(tally.distinct, distinct) << tally.reads << " reads";
}

TEST_F(ShmCrossProcess, ReaderSeesWholeValuesFromAnotherProcess) {
  const std::string name = unique_name();
  ChildProcess writer({COVER_SHM_TEST_WRITER, name, std::to_string(kCounterLayout)}, {}, true);
  auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 10s);
  EXPECT_EQ(reader.writer_pid(), writer.pid());
  expect_clean(read_counters(reader, 500), 500);

  EXPECT_EQ(writer.terminate(), 0);  // SIGTERM: a normal exit unlinks the segment
  EXPECT_FALSE(segment_exists(name));
  EXPECT_FALSE(reader.writer_alive());
}

TEST_F(ShmCrossProcess, LiveWriterInAnotherProcessIsNamedThenAKilledOneIsReplaced) {
  const std::string name = unique_name();
  ChildProcess child({COVER_SHM_TEST_WRITER, name, std::to_string(kCounterLayout)}, {}, true);
  ASSERT_EQ(child.read_line(10s), std::optional<std::string>("ready"));
  try {
    SeqlockWriter<CounterPayload> second(name, kCounterLayout);
    ADD_FAILURE() << "a second writer was created beside pid " << child.pid();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("pid " + std::to_string(child.pid())), std::string::npos)
        << e.what();
  }

  EXPECT_EQ(child.terminate(5s, SIGKILL), 128 + SIGKILL);
  EXPECT_TRUE(segment_exists(name));  // killed: nobody unlinked it
  SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
  auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 1s);
  EXPECT_EQ(reader.writer_pid(), getpid());
}

TEST_F(ShmCrossProcess, ForkedWriterAndParentReader) {
  const std::string name = unique_name();
  int stop_pipe[2];
  ASSERT_EQ(pipe(stop_pipe), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // Writes until the parent closes its end of the pipe, then exits with destructors.
    close(stop_pipe[1]);
    int code = 0;
    try {
      SeqlockWriter<CounterPayload> writer(name, kCounterLayout);
      pollfd stop{stop_pipe[0], POLLIN, 0};
      for (std::uint64_t counter = 1; poll(&stop, 1, 0) == 0; ++counter) {
        writer.update([counter](CounterPayload& p) { cover::shm::test::fill(p, counter); },
                      static_cast<std::int64_t>(counter));
        cover::shm::test::work_between_writes();
      }
    } catch (...) {
      code = 1;
    }
    _exit(code);
  }
  close(stop_pipe[0]);
  {
    auto reader = SeqlockReader<CounterPayload>::open(name, kCounterLayout, 10s);
    EXPECT_EQ(reader.writer_pid(), child);
    expect_clean(read_counters(reader, 500), 500);
  }
  close(stop_pipe[1]);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_FALSE(segment_exists(name));
}

}  // namespace
