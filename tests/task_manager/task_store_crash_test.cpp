// A manager killed at any moment loses nothing it acknowledged and leaves no half-written
// task: a child process submits in a loop, reports each id on a pipe once submit() has
// returned, and is SIGKILLed after a seeded number of reports (not after a sleep: the child
// keeps writing while the parent counts, so the kill lands mid-transaction at varying points).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <set>
#include <string>

#include "cover/task_manager/task_store.hpp"
#include "test_support.hpp"

namespace cover::task_manager {
namespace {

// The child: submit, report, then dispatch every other task (a second transaction per task,
// so the kill can also land between a task's submission and its first state change).
[[noreturn]] void child_submits_forever(const std::string& path, int round, int fd) {
  try {
    TaskStore store(path);
    for (int i = 0;; ++i) {
      const std::string id = "r" + std::to_string(round) + "-" + std::to_string(i);
      store.submit(testing::make_task(id, i % 3), "child", "req", TaskState::Queued, "", i);
      const std::string line = id + "\n";
      if (write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) _exit(3);
      if (i % 2 == 0) store.set_state(id, TaskState::Dispatched, "sent", i + 0.5);
    }
  } catch (...) {
    _exit(2);
  }
}

// Reads newline-terminated ids until `count` are read or the pipe closes.
std::vector<std::string> read_ids(FILE* in, std::size_t count) {
  std::vector<std::string> ids;
  std::string line;
  for (int c; ids.size() < count && (c = std::fgetc(in)) != EOF;) {
    if (c == '\n') {
      ids.push_back(line);
      line.clear();
    } else {
      line.push_back(static_cast<char>(c));
    }
  }
  return ids;
}

// The parent reads each id as soon as it is written, so a kill right after the n-th report
// would always land at the same point of the child's loop. A seeded spin of up to a few
// submit cycles moves it anywhere in the loop. Not a synchronisation: the order of events
// is already fixed by the pipe; this only picks where within the next cycles the kill falls.
void spin_for(std::chrono::microseconds duration) {
  const auto until = std::chrono::steady_clock::now() + duration;
  while (std::chrono::steady_clock::now() < until) {
  }
}

// Runs one child, kills it after `kill_after` reports and `delay`; returns every id it
// reported.
std::vector<std::string> run_and_kill(const std::string& path, int round, std::size_t kill_after,
                                      std::chrono::microseconds delay) {
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(fds[0]);
    child_submits_forever(path, round, fds[1]);
  }
  close(fds[1]);
  FILE* in = fdopen(fds[0], "r");
  std::vector<std::string> ids = read_ids(in, kill_after);
  spin_for(delay);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::vector<std::string> rest = read_ids(in, SIZE_MAX);  // written before the kill
  std::fclose(in);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
      << "the child ended by itself (status " << status << ")";
  ids.insert(ids.end(), rest.begin(), rest.end());
  return ids;
}

TEST(TaskStoreCrash, SigkillMidSubmitLosesNothingCommittedAndLeavesNoPartialTask) {
  constexpr int kRounds = 20;
  testing::TempDir dir;
  const std::string path = dir.file("crash.db");
  std::set<std::string> reported;
  for (int round = 0; round < kRounds; ++round) {
    std::mt19937 rng(1000 + round);
    const std::size_t kill_after = std::uniform_int_distribution<std::size_t>(5, 60)(rng);
    const std::chrono::microseconds delay(std::uniform_int_distribution<int>(0, 8000)(rng));
    const auto ids = run_and_kill(path, round, kill_after, delay);
    ASSERT_GE(ids.size(), kill_after) << "round " << round;
    reported.insert(ids.begin(), ids.end());

    TaskStore store(path);  // recovers the WAL
    const auto all = store.list(true);
    std::set<std::string> stored;
    std::int64_t last_position = 0;
    for (const TaskRecord& r : all) {
      stored.insert(r.task_id);
      EXPECT_GT(r.queue_position, last_position) << r.task_id;
      last_position = r.queue_position;
      const auto history = store.history(r.task_id);
      ASSERT_FALSE(history.empty()) << r.task_id << " has no submission row";
      EXPECT_EQ(history[0].from, TaskState::Queued);
      EXPECT_EQ(history[0].to, TaskState::Queued);
      EXPECT_EQ(history.back().to, r.state) << r.task_id;
      EXPECT_EQ(history.size(), r.state == TaskState::Dispatched ? 2u : 1u) << r.task_id;
      EXPECT_EQ(r.task.processes.size(), 1u);
    }
    for (const std::string& id : reported) EXPECT_EQ(stored.count(id), 1u) << id << " was lost";
    // Per round at most the one task committed just before the kill, whose id never reached
    // the pipe.
    EXPECT_LE(stored.size(), reported.size() + round + 1) << "round " << round;
    testing::RawDb raw(path);
    EXPECT_EQ(raw.scalar("PRAGMA integrity_check"), "ok");
    EXPECT_EQ(raw.scalar("SELECT COUNT(*) FROM task_history WHERE task_id NOT IN"
                         " (SELECT task_id FROM tasks)"),
              "0");
    EXPECT_EQ(raw.scalar("SELECT COUNT(DISTINCT queue_position) = COUNT(*) FROM tasks"), "1");
  }
}

}  // namespace
}  // namespace cover::task_manager
