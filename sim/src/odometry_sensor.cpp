#include "cover/sim/odometry_sensor.hpp"

#include <cmath>

#include "cover/sim/seeding.hpp"

namespace cover::sim {

OdometrySensorParams OdometrySensorParams::load(cover::config::YamlReader& reader) {
  OdometrySensorParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

void OdometrySensorParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

double true_forward_speed_m_s(const UgvState& ugv) {
  return std::cos(ugv.yaw_rad) * ugv.velocity_m_s.x + std::sin(ugv.yaw_rad) * ugv.velocity_m_s.y;
}

OdometrySensor::OdometrySensor(const OdometrySensorParams& params, double physics_rate_hz,
                               const std::vector<bool>& has_odometry, std::uint64_t seed)
    : params_(params),
      sample_period_steps_(
          static_cast<std::uint64_t>(std::llround(physics_rate_hz / params.rate_hz))) {
  if (sample_period_steps_ == 0) sample_period_steps_ = 1;
  for (int k = 0; k < kMaxUgvs; ++k) {
    UgvOdometry& odometry = ugvs_[k];
    odometry.equipped = k < static_cast<int>(has_odometry.size()) && has_odometry[k];
    odometry.rng.seed(derive_seed(seed, static_cast<std::uint64_t>(k)));
    odometry.scale = 1.0 + params_.scale_error_sigma * odometry.unit_normal(odometry.rng);
  }
}

void OdometrySensor::update(const WorldState& world) {
  const bool due = world.step_index % sample_period_steps_ == 0;
  for (int k = 0; k < kMaxUgvs; ++k) {
    UgvOdometry& odometry = ugvs_[k];
    now_[k].reset();
    if (!due || !odometry.equipped || k >= world.ugv_count) continue;
    now_[k] = odometry.scale * true_forward_speed_m_s(world.ugvs[k]) +
              params_.speed_noise_m_s * odometry.unit_normal(odometry.rng);
  }
}

}  // namespace cover::sim
