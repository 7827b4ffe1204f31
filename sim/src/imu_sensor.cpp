#include "cover/sim/imu_sensor.hpp"

#include <cmath>
#include <limits>

#include "cover/sim/seeding.hpp"

namespace cover::sim {

ImuSensorParams ImuSensorParams::load(cover::config::YamlReader& reader) {
  ImuSensorParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

void ImuSensorParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

ugv::ImuSample true_imu_sample(const UgvState& ugv, double gravity_m_s2, double stamp_s) {
  ugv::ImuSample sample;
  sample.stamp_s = stamp_s;
  const Eigen::Vector3d proper_acceleration =
      ugv.acceleration_m_s2.eigen() + Eigen::Vector3d(0.0, 0.0, gravity_m_s2);
  sample.specific_force_m_s2 = ugv.attitude().inverse() * proper_acceleration;
  sample.angular_velocity_rad_s = ugv.angular_velocity_in_body_rad_s();
  return sample;
}

ImuSensor::ImuSensor(const ImuSensorParams& params, const ugv::ImuFilterParams& filter_params,
                     const ugv::SpeedEstimatorParams& speed_params, double physics_rate_hz,
                     int ugv_count, double gravity_m_s2, std::uint64_t seed)
    : params_(params),
      sample_period_steps_(
          static_cast<std::uint64_t>(std::llround(physics_rate_hz / params.rate_hz))),
      ugv_count_(ugv_count),
      gravity_m_s2_(gravity_m_s2) {
  if (sample_period_steps_ == 0) sample_period_steps_ = 1;
  for (int k = 0; k < kMaxUgvs; ++k) {
    UgvImu& imu = imus_[k];
    imu.rng.seed(derive_seed(seed, static_cast<std::uint64_t>(k)));
    imu.specific_force_bias_m_s2 = white_noise(imu, params_.specific_force_bias_sigma_m_s2);
    imu.angular_velocity_bias_rad_s = white_noise(imu, params_.angular_velocity_bias_sigma_rad_s);
    imu.pipeline = ugv::UgvSensorPipeline(filter_params, speed_params);
  }
}

Eigen::Vector3d ImuSensor::white_noise(UgvImu& imu, double sigma) {
  return sigma * Eigen::Vector3d(imu.unit_normal(imu.rng), imu.unit_normal(imu.rng),
                                 imu.unit_normal(imu.rng));
}

void ImuSensor::update(const WorldState& world, const OdometrySensor& odometry) {
  if (world.step_index % sample_period_steps_ != 0) return;
  for (int k = 0; k < ugv_count_; ++k) {
    UgvImu& imu = imus_[k];
    ugv::ImuSample sample = true_imu_sample(world.ugvs[k], gravity_m_s2_, world.time_s);
    sample.specific_force_m_s2 +=
        imu.specific_force_bias_m_s2 + white_noise(imu, params_.specific_force_noise_m_s2);
    sample.angular_velocity_rad_s +=
        imu.angular_velocity_bias_rad_s + white_noise(imu, params_.angular_velocity_noise_rad_s);
    if (params_.fault_probability > 0.0 && imu.unit_uniform(imu.rng) < params_.fault_probability) {
      sample.angular_velocity_rad_s.x() = std::numeric_limits<double>::quiet_NaN();
    }
    sample.wheel_speed_m_s = odometry.sampled_now(k);
    ImuReading& reading = latest_[k];
    reading.raw = sample;
    reading.status = imu.pipeline.update(sample).imu_status;
    reading.filtered = imu.pipeline.filter().output();
    reading.speed = imu.pipeline.speed().estimate();
  }
  has_reading_ = true;
}

}  // namespace cover::sim
