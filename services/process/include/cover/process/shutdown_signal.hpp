#pragma once

#include <chrono>

namespace cover::process {

// SIGINT/SIGTERM handling for long-running processes, without a flag written from a
// signal handler: the signals are blocked in every thread and a watcher thread waits for
// them with sigwait, then wakes whoever waits here.
class ShutdownSignal {
 public:
  // Call first in main(), before any thread (DDS participants start threads) exists; once
  // per process (a later call does nothing).
  static void install();
  static bool requested();
  // Blocks until a signal arrives or `timeout` passes; true when shutdown was requested.
  static bool wait_for(std::chrono::milliseconds timeout);
  // Lets code (tests, a "quit" command) request shutdown too.
  static void request();
};

}  // namespace cover::process
