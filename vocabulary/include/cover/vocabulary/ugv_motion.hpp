#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

#include "cover/vocabulary/state.hpp"

namespace cover::model {

// Where a UGV's forward speed estimate comes from. A ground vehicle moves along its body x
// axis (no side slip), so one signed number is its whole translational velocity in G_k.
enum class SpeedSource : std::uint8_t {
  None = 0,           // no valid estimate (driving straight without odometry, at start-up)
  WheelOdometry = 1,  // the vehicle's wheel encoders
  Imu = 2,            // lateral specific force over yaw rate, valid only while turning
};

// What the UAV knows of the reference UGV's motion, all in the UGV body frame G_k.
// Over the prediction horizon `a` and `beta` are held constant and `Omega` integrates
// `beta` (docs/model.md: a' = 0, beta' = 0, Omega' = beta).
struct UgvMotion {
  // Accelerometer reading (gravity included): a UGV at rest on flat ground reads [0, 0, g].
  Eigen::Vector3d specific_force_m_s2{0.0, 0.0, kGravity_m_s2};
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration_rad_s2 = Eigen::Vector3d::Zero();
  // Forward speed along G_k's x axis (negative: reversing) and where it comes from; only
  // meaningful when speed_valid(). Not part of the dynamics model (which needs no world
  // motion): the intercept law uses it to predict where the UGV will be.
  double speed_m_s = 0.0;
  SpeedSource speed_source = SpeedSource::None;
  // The UGV's own acceleration along its x axis (m/s^2): its accelerometer's x reading, since
  // a ground vehicle without side slip feels its speed change along x and its turn along y
  // (level ground; on a slope g sin(pitch) is read as acceleration). Not part of the model:
  // kept apart from specific_force_m_s2, which the UAV's loop corrects by its own
  // disturbance estimate (so its x is no longer the UGV's alone); the intercept law uses it.
  double forward_acceleration_m_s2 = 0.0;

  bool speed_valid() const { return speed_source != SpeedSource::None && std::isfinite(speed_m_s); }

  // The motion `dt_s` later under the horizon's assumption (constant a and beta).
  UgvMotion advanced(double dt_s) const {
    UgvMotion next = *this;
    next.angular_velocity_rad_s += angular_acceleration_rad_s2 * dt_s;
    return next;
  }

  bool all_finite() const {
    return specific_force_m_s2.allFinite() && angular_velocity_rad_s.allFinite() &&
           angular_acceleration_rad_s2.allFinite();
  }

  static UgvMotion at_rest() { return UgvMotion{}; }
};

// The full 19-state vector from its UAV part and the UGV motion.
inline State make_state(const UavState& uav, const UgvMotion& ugv) {
  State x;
  x.head<kUavStateSize>() = uav;
  x.segment<3>(idx::kSpecificForce) = ugv.specific_force_m_s2;
  x.segment<3>(idx::kAngularVelocity) = ugv.angular_velocity_rad_s;
  x.segment<3>(idx::kAngularAccel) = ugv.angular_acceleration_rad_s2;
  return x;
}

inline UavState uav_part(const State& x) {
  return x.head<kUavStateSize>();
}

inline UgvMotion ugv_part(const State& x) {
  UgvMotion ugv;
  ugv.specific_force_m_s2 = x.segment<3>(idx::kSpecificForce);
  ugv.angular_velocity_rad_s = x.segment<3>(idx::kAngularVelocity);
  ugv.angular_acceleration_rad_s2 = x.segment<3>(idx::kAngularAccel);
  return ugv;
}

}  // namespace cover::model
