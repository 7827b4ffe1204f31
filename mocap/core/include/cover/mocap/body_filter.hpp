#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

#include "cover/mocap/frame_convention.hpp"
#include "cover/mocap/relay_params.hpp"

namespace cover::mocap {

// One axis of a constant-velocity Kalman filter: state (p, v), white acceleration.
class CvAxis {
 public:
  void reset(double position, double position_var, double velocity_var);
  void predict(double dt_s, double accel_var);
  // Returns the innovation (measurement - prediction).
  double update(double measurement, double measurement_var);
  double position() const { return x_[0]; }
  double velocity() const { return x_[1]; }
  double position_var() const { return p_[0][0]; }
  // The state `dt_s` ahead, without changing the filter.
  double position_at(double dt_s) const { return x_[0] + x_[1] * dt_s; }

 private:
  double x_[2] = {0.0, 0.0};
  double p_[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
};

// A constant-acceleration Kalman filter on one angle: state (angle, rate, acceleration),
// white jerk. A UGV's yaw rate follows its turns without the lag a constant-rate model has
// while the rate changes (the lag times the UAV's distance is a velocity error).
class CaAxis {
 public:
  void reset(double angle, double angle_var, double rate_var, double accel_var);
  void predict(double dt_s, double jerk_var);
  void update(double measurement, double measurement_var);
  double angle() const { return x_[0]; }
  double rate() const { return x_[1]; }
  double angle_at(double dt_s) const { return x_[0] + x_[1] * dt_s + 0.5 * x_[2] * dt_s * dt_s; }

 private:
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d p_ = Eigen::Matrix3d::Identity();
};

// What the relay knows of one rigid body: position and velocity (three CV axes), yaw and
// yaw rate (a CV filter on the unwrapped yaw), the last measured attitude's tilt, and
// whether it is tracked. Times are the capture times, ns.
class BodyFilter {
 public:
  enum class Update { Accepted, Started, Jump, Restarted };

  explicit BodyFilter(const RelayParams& params) : params_(&params) {}

  // A measurement at `stamp_ns` (later than the last one).
  Update measure(std::int64_t stamp_ns, const WorldPose& pose);
  // Tracked at `stamp_ns`: warmed up, measured within lost_after_s, not jumping.
  bool tracked_at(std::int64_t stamp_ns) const;
  bool jumping() const { return jump_since_ns_ >= 0; }
  bool started() const { return updates_ > 0; }
  std::int64_t last_measured_ns() const { return last_ns_; }

  // The state predicted to `stamp_ns` (>= the last measurement).
  Eigen::Vector3d position_at(std::int64_t stamp_ns) const;
  Eigen::Vector3d velocity() const;
  double position_std_m() const;
  // The attitude smoothed for use as a frame (a UGV's G_k): yaw from the filter, tilt
  // low-passed; and the angular velocity about world z. A UGV's attitude noise times the
  // UAV's distance is a position error, its yaw-rate noise a velocity error.
  Eigen::Quaterniond attitude_at(std::int64_t stamp_ns) const;
  // The last accepted attitude as measured (the UAV's own: no lag).
  const Eigen::Quaterniond& measured_attitude() const { return measured_; }
  double yaw_rate_rad_s() const { return yaw_.rate(); }

 private:
  void restart(std::int64_t stamp_ns, const WorldPose& pose);
  void predict_to(std::int64_t stamp_ns);

  const RelayParams* params_;
  CvAxis axes_[3];
  CaAxis yaw_;
  Eigen::Quaterniond tilt_ = Eigen::Quaterniond::Identity();  // attitude without its yaw
  Eigen::Quaterniond measured_ = Eigen::Quaterniond::Identity();
  std::int64_t last_ns_ = -1;
  std::int64_t jump_since_ns_ = -1;
  int updates_ = 0;
};

// The yaw (about world z) of an attitude.
double yaw_of(const Eigen::Quaterniond& q);

}  // namespace cover::mocap
