#include "cover/sim/mocap/mocap_feed.hpp"

#include <cmath>

namespace cover::sim::mocap {

std::vector<std::string> body_names(const MocapServerParams& params, int ugv_count, int uav_count) {
  std::vector<std::string> names;
  for (int k = 0; k < ugv_count; ++k) names.push_back(params.ugv_prefix + std::to_string(k));
  for (int u = 0; u < uav_count; ++u) names.push_back(params.uav_prefix + std::to_string(u));
  return names;
}

WirePose to_wire(const BodyTruth& truth, const std::string& up_axis, const std::string& units) {
  Eigen::Vector3d p = truth.position_m;
  Eigen::Quaterniond q = truth.attitude.normalized();
  if (up_axis == "y") {
    const Eigen::Quaterniond world_to_y_up(
        Eigen::AngleAxisd(-M_PI / 2.0, Eigen::Vector3d::UnitX()));
    p = world_to_y_up * p;
    // The body's own axes follow the same convention (a body created level reports the
    // identity): the rotation is conjugated, not only composed.
    q = world_to_y_up * q * world_to_y_up.inverse();
  }
  if (units == "mm") p *= 1000.0;
  WirePose pose;
  pose.present = true;
  for (int i = 0; i < 3; ++i) pose.position[i] = p[i];
  pose.quaternion_xyzw[0] = q.x();
  pose.quaternion_xyzw[1] = q.y();
  pose.quaternion_xyzw[2] = q.z();
  pose.quaternion_xyzw[3] = q.w();
  return pose;
}

MocapFeed::MocapFeed(const MocapServerParams& params, std::size_t body_count)
    : params_(params),
      body_count_(body_count),
      period_ns_(std::llround(1e9 / params.rate_hz)),
      latency_ns_(std::llround(params.latency_s * 1e9)),
      rng_(params.seed) {}

WirePose MocapFeed::measure(const BodyTruth& truth) {
  if (params_.dropout_probability > 0.0 && uniform_(rng_) < params_.dropout_probability) {
    return WirePose{};
  }
  BodyTruth noisy = truth;
  noisy.position_m +=
      params_.position_noise_m * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
  const Eigen::Vector3d rotation =
      params_.attitude_noise_rad * Eigen::Vector3d(normal_(rng_), normal_(rng_), normal_(rng_));
  if (rotation.norm() > 0.0) {
    noisy.attitude = truth.attitude * Eigen::AngleAxisd(rotation.norm(), rotation.normalized());
  }
  return to_wire(noisy, params_.up_axis, params_.units);
}

void MocapFeed::step(std::int64_t t_ns, const std::vector<BodyTruth>& truth,
                     std::vector<MocapFrame>& released) {
  if (!started_) {
    next_capture_ns_ = t_ns;
    started_ = true;
  }
  // Half a microsecond of slack: simulated times are sums of doubles.
  if (t_ns + 500 >= next_capture_ns_) {
    MocapFrame frame;
    frame.capture_ns = t_ns;
    frame.poses.reserve(body_count_);
    for (std::size_t i = 0; i < body_count_; ++i) {
      frame.poses.push_back(i < truth.size() ? measure(truth[i]) : WirePose{});
    }
    queue_.push_back(std::move(frame));
    next_capture_ns_ += period_ns_;
    if (next_capture_ns_ <= t_ns) next_capture_ns_ = t_ns + period_ns_;
  }
  while (!queue_.empty() && queue_.front().capture_ns + latency_ns_ <= t_ns + 500) {
    released.push_back(std::move(queue_.front()));
    queue_.pop_front();
  }
}

}  // namespace cover::sim::mocap
