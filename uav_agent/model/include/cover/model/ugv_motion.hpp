#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "cover/model/state.hpp"

namespace cover::model {

// What the UAV knows of the reference UGV's motion, all in the UGV body frame G_k.
// Over the prediction horizon `a` and `beta` are held constant and `Omega` integrates
// `beta` (NOTES.md: a' = 0, beta' = 0, Omega' = beta).
struct UgvMotion {
  // Accelerometer reading (gravity included): a UGV at rest on flat ground reads [0, 0, g].
  Eigen::Vector3d specific_force_m_s2{0.0, 0.0, kGravity_m_s2};
  Eigen::Vector3d angular_velocity_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_acceleration_rad_s2 = Eigen::Vector3d::Zero();

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
