#include "cover/sim/relative_sensor.hpp"

#include <cmath>

namespace cover::sim {

RelativeSensorParams RelativeSensorParams::load(cover::config::YamlReader& reader) {
  RelativeSensorParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

void RelativeSensorParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

RelativeState true_relative_state(const QuadrotorState& uav, const UgvState& ugv, double stamp_s) {
  const Eigen::Quaterniond ugv_attitude = ugv.attitude();
  const Eigen::Quaterniond world_to_ugv = ugv_attitude.inverse();
  RelativeState rel;
  rel.stamp_s = stamp_s;
  rel.position_m = world_to_ugv * (uav.position_m.eigen() - ugv.position_m.eigen());
  rel.velocity_m_s = world_to_ugv * (uav.velocity_m_s.eigen() - ugv.velocity_m_s.eigen()) -
                     ugv.angular_velocity_in_body_rad_s().cross(rel.position_m);
  rel.attitude = (world_to_ugv * uav.attitude.eigen()).normalized();
  return rel;
}

RelativeSensor::RelativeSensor(const RelativeSensorParams& params, double physics_rate_hz,
                               int ugv_count, std::uint64_t seed)
    : params_(params),
      physics_dt_s_(1.0 / physics_rate_hz),
      sample_period_steps_(
          static_cast<std::uint64_t>(std::llround(physics_rate_hz / params.rate_hz))),
      latency_steps_(static_cast<std::uint64_t>(std::llround(params.latency_s * physics_rate_hz))),
      ugv_count_(ugv_count),
      rng_(seed) {
  if (sample_period_steps_ == 0) sample_period_steps_ = 1;
}

RelativeState RelativeSensor::add_noise(const RelativeState& truth) {
  auto noise = [&](double sigma) {
    return Eigen::Vector3d(sigma * unit_normal_(rng_), sigma * unit_normal_(rng_),
                           sigma * unit_normal_(rng_));
  };
  RelativeState measured = truth;
  measured.position_m += noise(params_.position_noise_m);
  measured.velocity_m_s += noise(params_.velocity_noise_m_s);
  const Eigen::Vector3d rotation_error = noise(params_.attitude_noise_rad);
  if (rotation_error.norm() > 0.0) {
    measured.attitude = (truth.attitude * Eigen::Quaterniond(Eigen::AngleAxisd(
                                              rotation_error.norm(), rotation_error.normalized())))
                            .normalized();
  }
  return measured;
}

void RelativeSensor::update(const WorldState& world) {
  const bool sampling = world.step_index % sample_period_steps_ == 0;
  // Draw only when dropouts are enabled, so enabling them is the only thing that
  // changes the noise sequence.
  const bool dropped = sampling && params_.dropout_probability > 0.0 &&
                       unit_uniform_(rng_) < params_.dropout_probability;
  if (sampling && !dropped) {
    Pending sample{world.step_index + latency_steps_, {}};
    for (int k = 0; k < ugv_count_; ++k) {
      sample.states[k] = add_noise(true_relative_state(world.uav, world.ugvs[k], world.time_s));
    }
    pending_.push_back(sample);
  }
  while (!pending_.empty() && pending_.front().release_step <= world.step_index) {
    latest_ = pending_.front().states;
    has_measurement_ = true;
    pending_.pop_front();
  }
}

}  // namespace cover::sim
