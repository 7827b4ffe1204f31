#include "cover/process/thread_placement.hpp"

#include <sched.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "cover/process/cpu_list.hpp"

namespace cover::process {

namespace {

// The CPUs the process was started with, read once: after the first placement the calling
// thread's own mask is a single CPU.
const cpu_set_t& started_cpus() {
  static const cpu_set_t set = [] {
    cpu_set_t s;
    CPU_ZERO(&s);
    if (sched_getaffinity(0, sizeof s, &s) != 0) CPU_ZERO(&s);
    return s;
  }();
  return set;
}

}  // namespace

ThreadPlacement place_calling_thread_alone(int cpu) {
  ThreadPlacement result;
  const cpu_set_t& allowed = started_cpus();
  if (cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &allowed)) {
    result.error = "CPU " + std::to_string(cpu) + " is not among the process's CPUs (" +
                   cpu_list(cpus_of(allowed)) + ")";
    return result;
  }
  cpu_set_t others = allowed;
  CPU_CLR(cpu, &others);
  if (CPU_COUNT(&others) == 0) {
    result.error = "the process may use CPU " + std::to_string(cpu) +
                   " only: no other CPU for its other threads";
    return result;
  }
  const auto self = static_cast<pid_t>(syscall(SYS_gettid));
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    const auto tid = static_cast<pid_t>(std::atoi(entry.path().filename().c_str()));
    // A thread that ended since the listing is no error.
    if (tid > 0 && tid != self && sched_setaffinity(tid, sizeof others, &others) == 0) {
      ++result.threads_moved;
    }
  }
  if (ec) {
    result.error = "cannot list the process's threads: " + ec.message();
    return result;
  }
  cpu_set_t mine;
  CPU_ZERO(&mine);
  CPU_SET(cpu, &mine);
  if (sched_setaffinity(0, sizeof mine, &mine) != 0) {
    result.error = "cannot move the calling thread to CPU " + std::to_string(cpu);
    return result;
  }
  result.placed = true;
  result.others = cpu_list(cpus_of(others));
  return result;
}

}  // namespace cover::process
