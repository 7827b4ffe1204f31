#include "cover/process/stop_children_on_shutdown.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <thread>

namespace cover::process {

namespace {

struct ProcStat {
  pid_t parent = 0;
  char state = '?';
};

// /proc/<pid>/stat: "pid (comm) state ppid ..."; comm may hold spaces and parentheses, so
// the fields after it are read from its last ')'.
bool read_stat(pid_t pid, ProcStat& stat) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(in, line)) return false;
  const auto close = line.rfind(')');
  if (close == std::string::npos) return false;
  char state = '?';
  long parent = 0;
  if (std::sscanf(line.c_str() + close + 1, " %c %ld", &state, &parent) != 2) return false;
  stat.parent = static_cast<pid_t>(parent);
  stat.state = state;
  return true;
}

bool is_live(pid_t pid) {
  ProcStat stat;
  return read_stat(pid, stat) && stat.state != 'Z' && stat.state != 'X';
}

void stop_children(std::chrono::milliseconds grace) {
  std::vector<pid_t> children = live_children(getpid());
  std::fprintf(stderr, "stopping on a signal: SIGINT to %zu child process(es), %.1f s to end\n",
               children.size(), std::chrono::duration<double>(grace).count());
  for (const pid_t pid : children) kill(pid, SIGINT);
  const auto deadline = std::chrono::steady_clock::now() + grace;
  while (!children.empty() && std::chrono::steady_clock::now() < deadline) {
    children.erase(
        std::remove_if(children.begin(), children.end(), [](pid_t pid) { return !is_live(pid); }),
        children.end());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (const pid_t pid : children) {
    std::fprintf(stderr, "child %d still running after %.1f s: killed\n", static_cast<int>(pid),
                 std::chrono::duration<double>(grace).count());
    kill(pid, SIGKILL);
  }
}

}  // namespace

std::vector<pid_t> live_children(pid_t parent) {
  std::vector<pid_t> children;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    const auto pid = static_cast<pid_t>(std::atol(name.c_str()));
    ProcStat stat;
    if (read_stat(pid, stat) && stat.parent == parent && stat.state != 'Z' && stat.state != 'X') {
      children.push_back(pid);
    }
  }
  std::sort(children.begin(), children.end());
  return children;
}

void stop_children_on_shutdown(std::chrono::milliseconds grace, int exit_code) {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread created later
  // A thread blocked in sigwait does not hold up the process's exit (a condition variable's
  // waiter would: its destruction at exit waits for it).
  std::thread([set, grace, exit_code] {
    int received = 0;
    sigwait(&set, &received);
    stop_children(grace);
    std::fflush(nullptr);
    _exit(exit_code);
  }).detach();
}

}  // namespace cover::process
