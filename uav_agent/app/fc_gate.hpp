#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>

#include "cover/dds/participant.hpp"
#include "cover/dds/topics.hpp"

namespace cover::uav_agent {

// Whether the UAV's autopilot flies COVER's setpoints, from its bridge's cover/uav/<u>/fc.
// Where a bridge runs (told by --fc-bridge, or heard on the topic), a task starts only
// while the autopilot is ready (link up, armed, in OFFBOARD / GUIDED_NOGPS), and a running
// task fails the moment it is not. Where none runs (the simulator's direct path), every
// question here answers "ready".
class FcGate {
 public:
  // `required`: a bridge flies this UAV even before its first state is heard.
  // `stale_after_s`: a bridge silent this long (wall clock) counts as not ready.
  FcGate(dds::Participant& participant, std::uint32_t uav_id, bool required, double stale_after_s);

  bool bridge_present() const;
  // nullopt: COVER's setpoints fly the UAV (or no bridge runs); otherwise why not.
  std::optional<std::string> not_ready_reason() const;
  // Lockstep: blocks until a state stamped >= `stamp_ns` arrived (the bridge sends one with
  // each step's frames, stamped with the step); false at `deadline`.
  bool wait_for_stamp(std::int64_t stamp_ns, std::chrono::steady_clock::time_point deadline) const;

 private:
  bool required_;
  double stale_after_s_;
  mutable std::mutex mutex_;
  mutable std::condition_variable arrived_;
  std::optional<msg::FcState> latest_;
  std::int64_t received_monotonic_ns_ = 0;
  dds::Reader<msg::FcState> reader_;  // last: its callback uses the members above
};

}  // namespace cover::uav_agent
