#include "cover/ugv/imu_filter.hpp"

#include <cmath>

#include "cover/ugv/first_order_lag.hpp"

namespace cover::ugv {

ImuFilterParams ImuFilterParams::load(cover::config::YamlReader& reader) {
  ImuFilterParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

ImuFilterParams ImuFilterParams::load_file(const std::string& path) {
  auto agent = cover::config::open_section(path, "ugv_agent", /*required=*/true);
  auto filter = agent.child("imu_filter");
  return load(filter);
}

ImuFilterParams ImuFilterParams::load_default() {
  return load_file(cover::config::default_config_dir() + "/ugv_agent.yaml");
}

void ImuFilterParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

const char* to_string(ImuFilterStatus status) {
  switch (status) {
    case ImuFilterStatus::Updated:
      return "updated";
    case ImuFilterStatus::Started:
      return "started";
    case ImuFilterStatus::RestartedAfterGap:
      return "restarted after gap";
    case ImuFilterStatus::RejectedNonFinite:
      return "rejected: non-finite sample";
    case ImuFilterStatus::RejectedOutOfRange:
      return "rejected: beyond sensor full scale";
    case ImuFilterStatus::RejectedStaleStamp:
      return "rejected: stamp not increasing";
  }
  return "unknown";
}

ImuFilter::ImuFilter(const ImuFilterParams& params)
    : params_(params),
      specific_force_tau_s_(lag_time_constant_s(params.specific_force_cutoff_hz)),
      angular_velocity_tau_s_(lag_time_constant_s(params.angular_velocity_cutoff_hz)),
      angular_acceleration_tau_s_(lag_time_constant_s(params.angular_acceleration_cutoff_hz)) {}

void ImuFilter::reset() {
  started_ = false;
  output_ = FilteredImu{};
}

bool ImuFilter::is_plausible(const ImuSample& sample) const {
  return sample.specific_force_m_s2.norm() <= params_.max_specific_force_m_s2 &&
         sample.angular_velocity_rad_s.norm() <= params_.max_angular_velocity_rad_s;
}

void ImuFilter::start_from(const ImuSample& sample) {
  started_ = true;
  output_.stamp_s = sample.stamp_s;
  output_.specific_force_m_s2 = sample.specific_force_m_s2;
  output_.angular_velocity_rad_s = sample.angular_velocity_rad_s;
  output_.angular_acceleration_rad_s2.setZero();
}

ImuFilterStatus ImuFilter::update(const ImuSample& sample) {
  if (!std::isfinite(sample.stamp_s) || !sample.specific_force_m_s2.allFinite() ||
      !sample.angular_velocity_rad_s.allFinite()) {
    return ImuFilterStatus::RejectedNonFinite;
  }
  if (!is_plausible(sample)) return ImuFilterStatus::RejectedOutOfRange;
  if (!started_) {
    start_from(sample);
    return ImuFilterStatus::Started;
  }
  const double dt_s = sample.stamp_s - output_.stamp_s;
  if (dt_s <= 0.0) return ImuFilterStatus::RejectedStaleStamp;
  if (dt_s > params_.max_sample_gap_s) {
    start_from(sample);
    return ImuFilterStatus::RestartedAfterGap;
  }

  output_.specific_force_m_s2 += lag_blend_weight(dt_s, specific_force_tau_s_) *
                                 (sample.specific_force_m_s2 - output_.specific_force_m_s2);

  // Differentiate the *filtered* gyro (noise already attenuated), then low-pass the
  // derivative: a "dirty derivative" whose cut-off bounds the noise gain.
  const Eigen::Vector3d previous_rate = output_.angular_velocity_rad_s;
  output_.angular_velocity_rad_s += lag_blend_weight(dt_s, angular_velocity_tau_s_) *
                                    (sample.angular_velocity_rad_s - previous_rate);
  const Eigen::Vector3d raw_derivative = (output_.angular_velocity_rad_s - previous_rate) / dt_s;
  output_.angular_acceleration_rad_s2 += lag_blend_weight(dt_s, angular_acceleration_tau_s_) *
                                         (raw_derivative - output_.angular_acceleration_rad_s2);

  output_.stamp_s = sample.stamp_s;
  return ImuFilterStatus::Updated;
}

}  // namespace cover::ugv
