#pragma once

#include "cover/vocabulary/ugv_motion.hpp"

namespace cover::ugv {

// A UGV's forward speed as its agent estimates it (wheel odometry, else lateral specific
// force over yaw rate) and publishes it with the filtered IMU.
struct SpeedEstimate {
  double stamp_s = 0.0;  // the latest sample stamp taken into account
  double speed_m_s = 0.0;
  model::SpeedSource source = model::SpeedSource::None;

  bool valid() const { return source != model::SpeedSource::None; }
};

}  // namespace cover::ugv
