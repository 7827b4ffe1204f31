#pragma once

#include "cover/sim/world_params.hpp"

namespace cover::sim::test {

// A world with noise-free sensors and no IMU bias, so tests can compare against truth.
inline WorldParams noiseless_world(std::vector<UgvMotionPatternParams> patterns) {
  WorldParams params;
  for (std::size_t i = 0; i < patterns.size(); ++i) {
    UgvParams ugv;
    ugv.name = "G" + std::to_string(i);
    ugv.pattern = patterns[i];
    params.ugvs.push_back(ugv);
  }
  params.relative_sensor.position_noise_m = 0.0;
  params.relative_sensor.velocity_noise_m_s = 0.0;
  params.relative_sensor.attitude_noise_rad = 0.0;
  params.imu.specific_force_noise_m_s2 = 0.0;
  params.imu.angular_velocity_noise_rad_s = 0.0;
  params.imu.specific_force_bias_sigma_m_s2 = 0.0;
  params.imu.angular_velocity_bias_sigma_rad_s = 0.0;
  params.odometry.speed_noise_m_s = 0.0;
  params.odometry.scale_error_sigma = 0.0;
  return params;
}

inline UgvMotionPatternParams stationary_at(double x, double y, double yaw = 0.0) {
  UgvMotionPatternParams p;
  p.kind = MotionPatternKind::Stationary;
  p.origin_m = {x, y};
  p.orientation_rad = yaw;
  return p;
}

inline UgvMotionPatternParams circle(double speed, double yaw_rate, double cx = 0.0,
                                     double cy = 0.0) {
  UgvMotionPatternParams p;
  p.kind = MotionPatternKind::Circle;
  p.origin_m = {cx, cy};
  p.speed_m_s = speed;
  p.yaw_rate_rad_s = yaw_rate;
  return p;
}

}  // namespace cover::sim::test
