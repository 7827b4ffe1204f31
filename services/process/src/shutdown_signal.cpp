#include "cover/process/shutdown_signal.hpp"

#include <pthread.h>
#include <signal.h>

#include <condition_variable>
#include <mutex>
#include <thread>

namespace cover::process {
namespace {
std::mutex g_mutex;
std::condition_variable g_changed;
bool g_requested = false;  // guarded by g_mutex; never touched by a signal handler
}  // namespace

void ShutdownSignal::install() {
  // Once per process: a second waiting thread would take signals from the first.
  static std::once_flag installed;
  std::call_once(installed, [] {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every thread created later
    std::thread([set] {
      int received = 0;
      sigwait(&set, &received);
      request();
    }).detach();
  });
}

void ShutdownSignal::request() {
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    g_requested = true;
  }
  g_changed.notify_all();
}

bool ShutdownSignal::requested() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_requested;
}

bool ShutdownSignal::wait_for(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(g_mutex);
  return g_changed.wait_for(lock, timeout, [] { return g_requested; });
}

}  // namespace cover::process
