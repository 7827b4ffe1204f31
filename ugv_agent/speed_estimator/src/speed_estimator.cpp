#include "cover/ugv/speed_estimator.hpp"

#include <cmath>

#include "cover/ugv/first_order_lag.hpp"

namespace cover::ugv {

SpeedEstimatorParams SpeedEstimatorParams::load(cover::config::YamlReader& reader) {
  SpeedEstimatorParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

SpeedEstimatorParams SpeedEstimatorParams::load_file(const std::string& path) {
  auto agent = cover::config::open_section(path, "ugv_agent", /*required=*/true);
  auto section = agent.child("speed_estimator");
  return load(section);
}

SpeedEstimatorParams SpeedEstimatorParams::load_default() {
  return load_file(cover::config::default_config_dir() + "/ugv_agent.yaml");
}

void SpeedEstimatorParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
}

const char* to_string(SpeedSampleStatus status) {
  switch (status) {
    case SpeedSampleStatus::Accepted:
      return "accepted";
    case SpeedSampleStatus::RejectedNonFinite:
      return "rejected: non-finite sample";
    case SpeedSampleStatus::RejectedOutOfRange:
      return "rejected: speed beyond max_speed_m_s";
    case SpeedSampleStatus::RejectedStaleStamp:
      return "rejected: stamp not increasing";
  }
  return "unknown";
}

const char* to_string(model::SpeedSource source) {
  switch (source) {
    case model::SpeedSource::None:
      return "none";
    case model::SpeedSource::WheelOdometry:
      return "wheel odometry";
    case model::SpeedSource::Imu:
      return "imu";
  }
  return "unknown";
}

SpeedEstimator::SpeedEstimator(const SpeedEstimatorParams& params)
    : params_(params),
      odometry_tau_s_(lag_time_constant_s(params.odometry_cutoff_hz)),
      imu_speed_tau_s_(lag_time_constant_s(params.imu_speed_cutoff_hz)) {}

void SpeedEstimator::reset() {
  odometry_ = Lowpass{};
  imu_seen_ = false;
  imu_stamp_s_ = 0.0;
  imu_speed_ = ImuSpeed{};
  estimate_ = SpeedEstimate{};
}

SpeedSampleStatus SpeedEstimator::update_odometry(const WheelOdometrySample& sample) {
  if (!std::isfinite(sample.stamp_s) || !std::isfinite(sample.speed_m_s)) {
    return SpeedSampleStatus::RejectedNonFinite;
  }
  if (std::abs(sample.speed_m_s) > params_.max_speed_m_s) {
    return SpeedSampleStatus::RejectedOutOfRange;
  }
  if (odometry_.started && sample.stamp_s <= odometry_.stamp_s) {
    return SpeedSampleStatus::RejectedStaleStamp;
  }
  const double dt_s = sample.stamp_s - odometry_.stamp_s;
  // After a timeout the old value says nothing: restart from this sample.
  if (!odometry_.started || dt_s > params_.odometry_timeout_s) {
    odometry_.value = sample.speed_m_s;
  } else {
    odometry_.value +=
        lag_blend_weight(dt_s, odometry_tau_s_) * (sample.speed_m_s - odometry_.value);
  }
  odometry_.started = true;
  odometry_.stamp_s = sample.stamp_s;
  refresh(imu_seen_ && imu_stamp_s_ > sample.stamp_s ? imu_stamp_s_ : sample.stamp_s);
  return SpeedSampleStatus::Accepted;
}

SpeedSampleStatus SpeedEstimator::update_imu(const FilteredImu& imu) {
  if (!std::isfinite(imu.stamp_s) || !imu.specific_force_m_s2.allFinite() ||
      !imu.angular_velocity_rad_s.allFinite()) {
    return SpeedSampleStatus::RejectedNonFinite;
  }
  if (imu_seen_ && imu.stamp_s <= imu_stamp_s_) return SpeedSampleStatus::RejectedStaleStamp;
  imu_seen_ = true;
  imu_stamp_s_ = imu.stamp_s;

  const double yaw_rate_rad_s = imu.angular_velocity_rad_s.z();
  const double ratio_m_s = imu.specific_force_m_s2.y() / yaw_rate_rad_s;
  const bool turning = std::abs(yaw_rate_rad_s) >= params_.imu_min_yaw_rate_rad_s &&
                       std::abs(ratio_m_s) <= params_.max_speed_m_s;
  if (turning) {
    update_imu_speed(imu.stamp_s, ratio_m_s);
  } else {
    imu_speed_.turning = false;  // straight (or implausible): the window starts again
  }
  refresh(imu.stamp_s);
  return SpeedSampleStatus::Accepted;
}

void SpeedEstimator::update_imu_speed(double stamp_s, double ratio_m_s) {
  ImuSpeed& s = imu_speed_;
  // A gap in turning (or in samples) longer than the odometry timeout restarts the window.
  if (!s.turning || stamp_s - s.stamp_s > params_.odometry_timeout_s) {
    s = ImuSpeed{true, stamp_s, stamp_s, ratio_m_s, 0.0};
    return;
  }
  const double w = lag_blend_weight(stamp_s - s.stamp_s, imu_speed_tau_s_);
  const double deviation = ratio_m_s - s.mean_m_s;
  s.mean_m_s += w * deviation;
  // Exponentially weighted variance (West's incremental form).
  s.variance_m2_s2 = (1.0 - w) * (s.variance_m2_s2 + w * deviation * deviation);
  s.stamp_s = stamp_s;
}

bool SpeedEstimator::imu_speed_valid(double now_s) const {
  const ImuSpeed& s = imu_speed_;
  return s.turning && s.stamp_s == now_s && now_s - s.since_s >= params_.imu_settle_s &&
         std::abs(s.mean_m_s) <= params_.max_speed_m_s &&
         s.variance_m2_s2 <= params_.imu_max_spread_m_s * params_.imu_max_spread_m_s;
}

void SpeedEstimator::refresh(double now_s) {
  estimate_.stamp_s = now_s;
  if (odometry_.started && now_s - odometry_.stamp_s <= params_.odometry_timeout_s) {
    estimate_.speed_m_s = odometry_.value;
    estimate_.source = model::SpeedSource::WheelOdometry;
  } else if (imu_speed_valid(now_s)) {
    estimate_.speed_m_s = imu_speed_.mean_m_s;
    estimate_.source = model::SpeedSource::Imu;
  } else {
    estimate_.speed_m_s = 0.0;
    estimate_.source = model::SpeedSource::None;
  }
}

}  // namespace cover::ugv
