#include "cover/mocap/body_filter.hpp"

#include <algorithm>
#include <cmath>

namespace cover::mocap {
namespace {

constexpr double kInitialVelocityVar = 25.0;  // (5 m/s)^2: anything a vehicle does
// Weight of a new tilt measurement: a time constant of ~0.1 s at 100 Hz (vehicles' roll and
// pitch as frames change slowly; mocap attitude noise is ~2 mrad).
constexpr double kTiltGain = 0.1;

double wrap_pi(double a) {
  return std::remainder(a, 2.0 * M_PI);
}

}  // namespace

double yaw_of(const Eigen::Quaterniond& q) {
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()),
                    1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

void CvAxis::reset(double position, double position_var, double velocity_var) {
  x_[0] = position;
  x_[1] = 0.0;
  p_[0][0] = position_var;
  p_[0][1] = p_[1][0] = 0.0;
  p_[1][1] = velocity_var;
}

void CvAxis::predict(double dt, double q) {
  x_[0] += x_[1] * dt;
  const double p00 = p_[0][0] + dt * (p_[1][0] + p_[0][1]) + dt * dt * p_[1][1];
  const double p01 = p_[0][1] + dt * p_[1][1];
  const double dt2 = dt * dt;
  p_[0][0] = p00 + q * dt2 * dt2 / 4.0;
  p_[0][1] = p_[1][0] = p01 + q * dt2 * dt / 2.0;
  p_[1][1] += q * dt2;
}

double CvAxis::update(double z, double r) {
  const double innovation = z - x_[0];
  const double s = p_[0][0] + r;
  const double k0 = p_[0][0] / s;
  const double k1 = p_[1][0] / s;
  x_[0] += k0 * innovation;
  x_[1] += k1 * innovation;
  const double p00 = p_[0][0], p01 = p_[0][1], p11 = p_[1][1];
  p_[0][0] = (1.0 - k0) * p00;
  p_[0][1] = p_[1][0] = (1.0 - k0) * p01;
  p_[1][1] = p11 - k1 * p01;
  return innovation;
}

void CaAxis::reset(double angle, double angle_var, double rate_var, double accel_var) {
  x_ << angle, 0.0, 0.0;
  p_ = Eigen::Vector3d(angle_var, rate_var, accel_var).asDiagonal();
}

void CaAxis::predict(double dt, double q) {
  Eigen::Matrix3d f;
  f << 1.0, dt, 0.5 * dt * dt, 0.0, 1.0, dt, 0.0, 0.0, 1.0;
  const double d2 = dt * dt, d3 = d2 * dt, d4 = d3 * dt, d5 = d4 * dt;
  Eigen::Matrix3d noise;
  noise << d5 / 20.0, d4 / 8.0, d3 / 6.0, d4 / 8.0, d3 / 3.0, d2 / 2.0, d3 / 6.0, d2 / 2.0, dt;
  x_ = f * x_;
  p_ = f * p_ * f.transpose() + q * noise;
}

void CaAxis::update(double z, double r) {
  const double s = p_(0, 0) + r;
  const Eigen::Vector3d k = p_.col(0) / s;
  x_ += k * (z - x_[0]);
  p_ -= k * p_.row(0);
}

void BodyFilter::restart(std::int64_t stamp_ns, const WorldPose& pose) {
  const double r = params_->filter.position_noise_m * params_->filter.position_noise_m;
  for (int i = 0; i < 3; ++i) axes_[i].reset(pose.position_m[i], r, kInitialVelocityVar);
  const double yaw = yaw_of(pose.attitude);
  const double ry = params_->filter.yaw_noise_rad * params_->filter.yaw_noise_rad;
  yaw_.reset(yaw, ry, 4.0, 4.0);
  tilt_ = Eigen::Quaterniond(Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ())) * pose.attitude;
  measured_ = pose.attitude;
  last_ns_ = stamp_ns;
  jump_since_ns_ = -1;
  updates_ = 1;
}

void BodyFilter::predict_to(std::int64_t stamp_ns) {
  const double dt = static_cast<double>(stamp_ns - last_ns_) * 1e-9;
  const double qa = params_->filter.accel_noise_m_s2 * params_->filter.accel_noise_m_s2;
  for (auto& axis : axes_) axis.predict(dt, qa);
  const double qy = params_->filter.yaw_jerk_noise_rad_s3 * params_->filter.yaw_jerk_noise_rad_s3;
  yaw_.predict(dt, qy);
}

BodyFilter::Update BodyFilter::measure(std::int64_t stamp_ns, const WorldPose& pose) {
  const double lost_ns = params_->lost_after_s * 1e9;
  // Back after a loss: start again wherever it is. (While it jumps, jump_reset_s decides.)
  if (updates_ == 0 || (!jumping() && static_cast<double>(stamp_ns - last_ns_) > lost_ns)) {
    const bool first = updates_ == 0;
    restart(stamp_ns, pose);
    return first ? Update::Started : Update::Restarted;
  }
  if (stamp_ns <= last_ns_) return Update::Accepted;  // a repeat: nothing new
  const Eigen::Vector3d predicted = position_at(stamp_ns);
  if ((pose.position_m - predicted).norm() > params_->jump_gate_m) {
    if (jump_since_ns_ < 0) jump_since_ns_ = stamp_ns;
    if (static_cast<double>(stamp_ns - jump_since_ns_) >= params_->jump_reset_s * 1e9) {
      restart(stamp_ns, pose);
      return Update::Restarted;
    }
    return Update::Jump;
  }
  predict_to(stamp_ns);
  const double r = params_->filter.position_noise_m * params_->filter.position_noise_m;
  for (int i = 0; i < 3; ++i) axes_[i].update(pose.position_m[i], r);
  // Yaw unwrapped against the prediction.
  const double yaw = yaw_of(pose.attitude);
  const double measured = yaw_.angle() + wrap_pi(yaw - yaw_.angle());
  const double ry = params_->filter.yaw_noise_rad * params_->filter.yaw_noise_rad;
  yaw_.update(measured, ry);
  const Eigen::Quaterniond tilt =
      Eigen::Quaterniond(Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ())) * pose.attitude;
  tilt_ = tilt_.slerp(kTiltGain, tilt).normalized();
  measured_ = pose.attitude;
  last_ns_ = stamp_ns;
  jump_since_ns_ = -1;
  ++updates_;
  return Update::Accepted;
}

bool BodyFilter::tracked_at(std::int64_t stamp_ns) const {
  return updates_ >= params_->warmup_updates && !jumping() &&
         static_cast<double>(stamp_ns - last_ns_) <= params_->lost_after_s * 1e9 + 1e3;
}

Eigen::Vector3d BodyFilter::position_at(std::int64_t stamp_ns) const {
  const double dt = static_cast<double>(stamp_ns - last_ns_) * 1e-9;
  return {axes_[0].position_at(dt), axes_[1].position_at(dt), axes_[2].position_at(dt)};
}

Eigen::Vector3d BodyFilter::velocity() const {
  return {axes_[0].velocity(), axes_[1].velocity(), axes_[2].velocity()};
}

double BodyFilter::position_std_m() const {
  return std::sqrt(
      std::max({axes_[0].position_var(), axes_[1].position_var(), axes_[2].position_var()}));
}

Eigen::Quaterniond BodyFilter::attitude_at(std::int64_t stamp_ns) const {
  const double dt = static_cast<double>(stamp_ns - last_ns_) * 1e-9;
  return (Eigen::Quaterniond(Eigen::AngleAxisd(yaw_.angle_at(dt), Eigen::Vector3d::UnitZ())) *
          tilt_)
      .normalized();
}

}  // namespace cover::mocap
