// ChildProcess: what it starts, how it reports a start that fails, and that its children
// never outlive it.
#include "cover/process/child_process.hpp"

#include <gtest/gtest.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cover/test/process_alive.hpp"
#include "cover/test/scratch_dir.hpp"
#include "cover/test/wait_until.hpp"

namespace {

using cover::process::ChildProcess;
using cover::process::SpawnOptions;
using namespace std::chrono_literals;

// Whether `pid` no longer runs within `timeout` (scaled).
bool ends_within(pid_t pid, std::chrono::milliseconds timeout) {
  return cover::test::wait_until([&] { return !cover::test::process_alive(pid); }, timeout);
}

// Reads one pid from `fd` within `timeout`; -1 if none came.
pid_t read_pid(int fd, std::chrono::milliseconds timeout) {
  pollfd ready{fd, POLLIN, 0};
  pid_t pid = -1;
  if (poll(&ready, 1, static_cast<int>(timeout.count())) != 1) return -1;
  return read(fd, &pid, sizeof pid) == static_cast<ssize_t>(sizeof pid) ? pid : -1;
}

TEST(ChildProcess, RunsTheCommandAndReadsItsLines) {
  SpawnOptions options;
  options.capture_stdout = true;
  options.extra_env = {"COVER_CHILD_TEST=one two"};
  ChildProcess child({"/bin/sh", "-c", "echo \"$COVER_CHILD_TEST\"; echo three; exit 3"}, options);
  EXPECT_EQ(child.read_line(10s), std::optional<std::string>("one two"));
  EXPECT_EQ(child.read_line(10s), std::optional<std::string>("three"));
  EXPECT_EQ(child.read_line(10s), std::nullopt);  // EOF
  EXPECT_EQ(child.wait(10s), std::optional<int>(3));
  EXPECT_EQ(child.killed_by_signal(), 0);
}

// An entry of extra_env replaces the parent's value of its key: the child sees the key
// once, with the given value (getenv() returns a key's first entry, so an appended one was
// lost to a value the user exported: issue 31, item 1).
TEST(ChildProcess, ExtraEnvironmentReplacesTheParentsValue) {
  ASSERT_EQ(setenv("COVER_CHILD_OVERRIDE", "parent", 1), 0);
  SpawnOptions options;
  options.capture_stdout = true;
  options.extra_env = {"COVER_CHILD_OVERRIDE=first", "COVER_CHILD_OVERRIDE=child",
                       "COVER_CHILD_ADDED=added"};
  // env(1) itself, not a shell: a shell would tidy a doubled key before passing it on.
  ChildProcess child({"/usr/bin/env"}, options);
  unsetenv("COVER_CHILD_OVERRIDE");
  std::vector<std::string> ours;
  while (const auto line = child.read_line(10s)) {
    if (line->rfind("COVER_CHILD_", 0) == 0) ours.push_back(*line);
  }
  EXPECT_EQ(ours,
            (std::vector<std::string>{"COVER_CHILD_OVERRIDE=child", "COVER_CHILD_ADDED=added"}));
  EXPECT_EQ(child.wait(10s), std::optional<int>(0));
}

// Pinned before exec: the program and what it runs see only the CPUs asked for; a CPU the
// machine lacks is left out, and with none left the child keeps the parent's CPUs.
TEST(ChildProcess, CpuAffinityPinsTheChild) {
  SpawnOptions options;
  options.capture_stdout = true;
  options.cpu_affinity = {0};
  ChildProcess pinned({"/bin/sh", "-c", "grep Cpus_allowed_list /proc/self/status; exec sleep 60"},
                      options);
  EXPECT_EQ(pinned.cpus(), std::vector<int>{0});
  EXPECT_EQ(pinned.read_line(10s), std::optional<std::string>("Cpus_allowed_list:\t0"));
  pinned.terminate();

  options.cpu_affinity = {4095};
  ChildProcess unpinnable({"/bin/sh", "-c", "exec sleep 60"}, options);
  cpu_set_t parent;
  CPU_ZERO(&parent);
  ASSERT_EQ(sched_getaffinity(0, sizeof parent, &parent), 0);
  EXPECT_EQ(static_cast<int>(unpinnable.cpus().size()), CPU_COUNT(&parent));
  unpinnable.terminate();
}

TEST(ChildProcess, LogFileTakesStdoutAndStderr) {
  SpawnOptions options;
  options.log_file = cover::test::scratch_path("child.log");
  ChildProcess({"/bin/sh", "-c", "echo out; echo err >&2"}, options).wait(10s);
  std::ifstream log(options.log_file);
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_EQ(text.str(), "out\nerr\n");
}

TEST(ChildProcess, AStartThatFailsThrowsSayingWhy) {
  try {
    ChildProcess child({"/nonexistent/cover-no-such-tool"});
    FAIL() << "started pid " << child.pid();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/cover-no-such-tool"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("No such file"), std::string::npos) << e.what();
  }
  SpawnOptions options;
  options.log_file = "/nonexistent/folder/child.log";
  EXPECT_THROW(ChildProcess({"/bin/true"}, options), std::runtime_error);
  EXPECT_THROW(ChildProcess(std::vector<std::string>{}), std::runtime_error);
}

TEST(ChildProcess, TerminateReportsTheSignal) {
  ChildProcess child({"/bin/sleep", "600"});
  EXPECT_EQ(child.terminate(10s, SIGTERM), 128 + SIGTERM);
  EXPECT_EQ(child.killed_by_signal(), SIGTERM);
}

// A parent killed with SIGKILL runs no destructor: its child must die with it anyway. The
// parent here is a helper forked from the test, which starts `sleep 600`, reports its pid
// and waits to be killed.
TEST(ChildProcess, DiesWhenItsParentIsKilled) {
  int report[2];
  ASSERT_EQ(pipe(report), 0);
  const pid_t helper = fork();
  ASSERT_GE(helper, 0);
  if (helper == 0) {
    close(report[0]);
    try {
      ChildProcess sleeper({"/bin/sleep", "600"});
      const pid_t pid = sleeper.pid();
      if (write(report[1], &pid, sizeof pid) != static_cast<ssize_t>(sizeof pid)) _exit(2);
      while (true) pause();  // until the test's SIGKILL
    } catch (...) {
      _exit(1);
    }
  }
  close(report[1]);
  const pid_t grandchild = read_pid(report[0], 10s);
  close(report[0]);
  ASSERT_GT(grandchild, 0) << "the helper never reported its child";
  EXPECT_TRUE(cover::test::process_alive(grandchild));
  kill(helper, SIGKILL);
  int status = 0;
  ASSERT_EQ(waitpid(helper, &status, 0), helper);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  const bool ended = ends_within(grandchild, 5s);
  if (!ended) kill(grandchild, SIGKILL);  // not left running by a failure either
  EXPECT_TRUE(ended) << "pid " << grandchild << " outlived its parent";
}

}  // namespace
