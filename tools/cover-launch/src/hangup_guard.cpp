#include "cover/launch/hangup_guard.hpp"

#include <pthread.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <thread>

namespace cover::launch {
namespace {
std::atomic<int> g_hangups{0};
}  // namespace

void HangupGuard::install() {
  sigset_t blocked;
  sigemptyset(&blocked);
  sigaddset(&blocked, SIGHUP);
  sigaddset(&blocked, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &blocked, nullptr);  // inherited by every thread created later
  // The watcher starts with every signal blocked, so that it never takes one meant for
  // another handler (SIGINT and SIGTERM are ShutdownSignal's) by its default action.
  sigset_t all;
  sigset_t kept;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &kept);
  sigset_t hangup;
  sigemptyset(&hangup);
  sigaddset(&hangup, SIGHUP);
  std::thread watcher([hangup] {
    while (true) {
      int received = 0;
      if (sigwait(&hangup, &received) != 0) continue;
      const int n = ++g_hangups;
      // The terminal may be gone: launch.log keeps the line.
      spdlog::warn(
          "SIGHUP received ({}): the terminal closed or the SSH session dropped; ignored, every "
          "process keeps running (stop the launch with SIGINT or SIGTERM)",
          n);
    }
  });
  watcher.detach();
  pthread_sigmask(SIG_SETMASK, &kept, nullptr);
}

int HangupGuard::count() {
  return g_hangups.load();
}

}  // namespace cover::launch
