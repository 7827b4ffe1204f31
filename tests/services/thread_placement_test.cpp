// place_calling_thread_alone: the calling thread ends up alone on its CPU, the process's
// other threads (one started before, one after) on the others; a CPU the process may not use
// is refused with the reason, and nothing moves.
#include "cover/process/thread_placement.hpp"

#include <gtest/gtest.h>
#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <atomic>
#include <future>
#include <string>
#include <thread>

namespace {

cpu_set_t affinity_of(pid_t tid) {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(sched_getaffinity(tid, sizeof set, &set), 0);
  return set;
}

pid_t this_tid() {
  return static_cast<pid_t>(syscall(SYS_gettid));
}

// The test's main thread gets its CPUs back, whatever the test did to it.
class ThreadPlacement : public ::testing::Test {
 protected:
  void SetUp() override { started_ = affinity_of(0); }
  void TearDown() override { sched_setaffinity(0, sizeof started_, &started_); }
  cpu_set_t started_;
};

TEST_F(ThreadPlacement, CallingThreadAloneOthersElsewhere) {
  if (CPU_COUNT(&started_) < 2) {
    const auto placed = cover::process::place_calling_thread_alone(sched_getcpu());
    EXPECT_FALSE(placed.placed);
    EXPECT_NE(placed.error.find("no other CPU"), std::string::npos) << placed.error;
    return;
  }
  int control = -1;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (CPU_ISSET(cpu, &started_)) control = cpu;  // the last one
  }
  std::atomic<bool> done{false};
  std::promise<pid_t> before_tid;
  std::thread before([&] {
    before_tid.set_value(this_tid());
    while (!done) std::this_thread::yield();
  });
  const pid_t before_id = before_tid.get_future().get();
  cover::process::ThreadPlacement placed;
  cpu_set_t controller_cpus;
  cpu_set_t later_cpus;
  std::thread controller([&] {
    placed = cover::process::place_calling_thread_alone(control);
    controller_cpus = affinity_of(0);
    // A thread this one starts inherits its CPU until placed again.
    std::thread later([&] { later_cpus = affinity_of(0); });
    later.join();
  });
  controller.join();
  const cpu_set_t others = affinity_of(before_id);  // while `before` still runs
  done = true;
  before.join();
  ASSERT_TRUE(placed.placed) << placed.error;
  EXPECT_GE(placed.threads_moved, 2);  // the main thread and `before`, at least
  EXPECT_FALSE(CPU_ISSET(control, &others));
  EXPECT_EQ(CPU_COUNT(&others), CPU_COUNT(&started_) - 1);
  const cpu_set_t main = affinity_of(0);
  EXPECT_FALSE(CPU_ISSET(control, &main));
  EXPECT_FALSE(placed.others.empty());
  EXPECT_EQ(CPU_COUNT(&controller_cpus), 1);
  EXPECT_TRUE(CPU_ISSET(control, &controller_cpus));
  EXPECT_TRUE(CPU_EQUAL(&later_cpus, &controller_cpus));
}

TEST_F(ThreadPlacement, ACpuTheProcessMayNotUseIsRefusedAndNothingMoves) {
  const auto placed = cover::process::place_calling_thread_alone(CPU_SETSIZE + 5);
  EXPECT_FALSE(placed.placed);
  EXPECT_NE(placed.error.find("not among the process's CPUs"), std::string::npos) << placed.error;
  const cpu_set_t now = affinity_of(0);
  EXPECT_TRUE(CPU_EQUAL(&now, &started_));
}

}  // namespace
