#pragma once

#include <cstddef>
#include <deque>
#include <map>
#include <optional>
#include <string>

#include "cover/msg/types.hpp"
#include "cover/task_manager/live_view.hpp"
#include "cover/wire/intake.hpp"

namespace cover::task_manager {

// What the manager takes from the fleet's samples, checked first (wire/intake.hpp): a
// heartbeat, autopilot state or IMU sample naming another vehicle than the topic it came
// on, an IMU sample
// that is not finite or beyond full scale, a task status naming an unknown UAV or an id no
// task can have, is dropped and counted (the reason is returned, for the log). Otherwise a
// foreign or broken writer could make a down UGV look up, or grow the manager's memory
// without bound. No DDS, no threads, no clock: FleetWatch feeds it under its mutex.
class FleetIntake {
 public:
  // Agents' messages are kept for this many task ids (the oldest forgotten first), each
  // cut to kMaxMessageLength characters: they end up in the store's history.
  static constexpr std::size_t kRememberedMessages = 1024;
  static constexpr std::size_t kMaxMessageLength = 512;

  FleetIntake(int max_uavs, int max_ugvs, wire::IntakeLimits limits = {});

  // `topic_id`: the u or k of the topic the sample came on; `now_s`: the host's clock at
  // arrival (wall clock, Unix seconds).
  std::optional<wire::Rejection> on_uav_status(const msg::UavStatus& status, int topic_id,
                                               double now_s);
  std::optional<wire::Rejection> on_task_status(const msg::TaskStatus& status);
  std::optional<wire::Rejection> on_ugv_imu(const msg::UgvImu& imu, int topic_id, double now_s);
  // A flight-controller bridge's report of UAV `topic_id`'s autopilot: from then on that
  // UAV is flown through a bridge, and dispatched to only while its autopilot is ready.
  std::optional<wire::Rejection> on_fc_state(const msg::FcState& state, int topic_id, double now_s);

  const LiveView& view() const { return view_; }
  const wire::RejectionCounts& rejections() const { return rejections_; }
  std::size_t remembered_messages() const { return task_messages_.size(); }

 private:
  std::optional<wire::Rejection> counted(std::optional<wire::Rejection> why);

  int max_uavs_;
  int max_ugvs_;
  wire::IntakeLimits limits_;
  LiveView view_;
  std::map<std::string, std::string> task_messages_;  // the agents' last word per task id
  std::deque<std::string> message_order_;             // task ids, oldest first
  wire::RejectionCounts rejections_;
};

}  // namespace cover::task_manager
