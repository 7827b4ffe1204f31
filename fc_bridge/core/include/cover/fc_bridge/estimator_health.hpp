#pragma once

#include <cstdint>
#include <string>

#include "cover/fc_bridge/autopilot_profile.hpp"
#include "cover/mavlink/messages.hpp"

namespace cover::fc_bridge {

// The autopilot's own estimator as it reports it: SYS_STATUS's sensor health bits (both
// autopilots), PX4's ESTIMATOR_STATUS or ArduPilot's EKF_STATUS_REPORT flags. COVER flies
// body rates and thrust and needs only the attitude estimate, but an operator must see why
// an autopilot refuses to arm (PX4 does not align while the deck turns faster than 15
// deg/s) or flies badly.
struct EstimatorHealth {
  bool reported = false;     // a SYS_STATUS or an estimator message arrived
  bool attitude_ok = false;  // the attitude estimate is valid (as far as reported)
  std::string text;          // "attitude, vertical velocity ok; no horizontal position"
};

class EstimatorHealthTracker {
 public:
  explicit EstimatorHealthTracker(Autopilot kind) : kind_(kind) {}
  void on_sys_status(const mavlink::SysStatus& status);
  void on_estimator_flags(std::uint16_t flags);  // ESTIMATOR_STATUS / EKF_STATUS_REPORT
  EstimatorHealth health() const;
  // False only when the estimator's flags say its vertical velocity is not valid (no flags
  // reported: the velocity's own stream is the evidence).
  bool vertical_velocity_ok() const;

 private:
  std::string sensor_problems() const;
  std::string flag_summary() const;

  Autopilot kind_;
  bool sys_status_seen_ = false;
  std::uint32_t present_ = 0;
  std::uint32_t enabled_ = 0;
  std::uint32_t healthy_ = 0;
  bool flags_seen_ = false;
  std::uint16_t flags_ = 0;
};

}  // namespace cover::fc_bridge
