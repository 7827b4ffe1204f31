#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cover/dds/participant.hpp"

namespace cover::bench {

// Round trips of a RelativeState between this process (ping) and a `cover-bench dds-pong`
// child (pong), each hop a real DDS hop between two processes. The floor of a process
// chain is what its hops cost with no work done at either end.
struct PingPongOptions {
  dds::Vendor ping_vendor = dds::Vendor::FastDds;
  dds::Vendor pong_vendor = dds::Vendor::FastDds;
  int domain_id = 0;
  std::string prefix;  // topic names: <prefix>/ping, <prefix>/pong
  // The hops' QoS. Reliable keep-last 1 by default (a lost ping would be retransmitted,
  // not counted); the e2e floor uses the sensor profile out and the command profile back,
  // as the relative state and the command travel.
  dds::QosProfile ping_qos;
  dds::QosProfile pong_qos;
  // SCHED_FIFO priorities (1..99) of the ping side (this process's participant threads and
  // the pinging thread, while the PingPong lives) and of the pong process; 0: normal
  // scheduling. A floor compared with a system's latency runs as that system's processes do.
  int ping_realtime_priority = 0;
  int pong_realtime_priority = 0;
  // The CPUs the pong process runs on (empty: any), as the process it stands for is pinned.
  std::vector<int> pong_cpu_affinity;
};

struct RoundTrips {
  int sent = 0;
  int received = 0;
  std::vector<double> round_trip_us;  // one per received pong
};

// A running pong process and the pinger's participant, matched.
class PingPong {
 public:
  // Starts the pong process and waits (20 s) for the two to match; throws
  // std::runtime_error when the pong does not start or never matches.
  explicit PingPong(const PingPongOptions& options);
  ~PingPong();
  PingPong(const PingPong&) = delete;
  PingPong& operator=(const PingPong&) = delete;

  // `count` round trips, back to back (rate_hz 0) or one per period (each ping after a
  // sleep, so both ends wake from sleep as a paced control loop does). A pong not back
  // within 1 s is counted as lost.
  RoundTrips run(int count, double rate_hz);

  // The SCHED_FIFO priorities each end runs at (0: normal scheduling, also when asked for
  // but refused: that needs root, CAP_SYS_NICE or an rtprio limit).
  int ping_realtime_priority() const;
  int pong_realtime_priority() const;
  // The CPUs the pong process may run on.
  std::vector<int> pong_cpus() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The reliable keep-last-1 profile the `dds` benchmark measures with.
dds::QosProfile reliable_bench_qos();

// The pong side (`cover-bench dds-pong`), run as a child by PingPong.
int run_pong(const std::vector<std::string>& args);

}  // namespace cover::bench
