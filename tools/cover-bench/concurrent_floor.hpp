#pragma once

#include <condition_variable>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "dds_ping_pong.hpp"

namespace cover::bench {

// A latency floor measured while the system it is the floor of runs: paced round trips
// between this process and a bare pong process, from before the run starts until stop().
// Floor and system then live through the same seconds of the machine: this VM pauses for
// 1-27 ms about once a second (a SCHED_FIFO thread sleeping 1 ms, idle machine: 28 wake-ups
// late by > 1 ms in 20 s), so a floor measured before or after the run saw other pauses
// than the run did, and their p99s compared the pauses, not the paths.
class ConcurrentFloor {
 public:
  // Starts the pong process and a pinging thread (with `options`' scheduling: the thread,
  // not the caller, takes the SCHED_FIFO priority, so processes the caller starts inherit
  // none), waits until it has matched and warmed up (50 trips), then returns; pinging goes
  // on at `rate_hz` until stop(). failed() when it could not start.
  ConcurrentFloor(const PingPongOptions& options, double rate_hz);
  ~ConcurrentFloor();
  ConcurrentFloor(const ConcurrentFloor&) = delete;
  ConcurrentFloor& operator=(const ConcurrentFloor&) = delete;

  bool failed() const;
  // Stops pinging; p50_ms, p99_ms, samples, lost, both ends' priorities and the pong's
  // CPUs, or null (with the reason on stderr) when it never ran.
  nlohmann::json stop();

 private:
  void ping(PingPongOptions options);
  void stop_pinging();  // asks the pinging thread to end and joins it

  const double rate_hz_;
  mutable std::mutex mutex_;
  std::condition_variable started_cv_;
  bool started_ = false;
  bool stop_requested_ = false;
  std::string error_;
  RoundTrips trips_;
  int ping_priority_ = 0;
  int pong_priority_ = 0;
  std::vector<int> pong_cpus_;
  std::thread thread_;
};

}  // namespace cover::bench
