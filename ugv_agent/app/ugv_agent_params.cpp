#include "ugv_agent_params.hpp"

#include <cmath>

namespace cover::ugv {

UgvAgentParams UgvAgentParams::load(cover::config::YamlReader& reader) {
  UgvAgentParams p;
  auto filter = reader.child("imu_filter");
  p.imu_filter = ImuFilterParams::load(filter);
  auto speed = reader.child("speed_estimator");
  p.speed_estimator = SpeedEstimatorParams::load(speed);
  reader.optional("nominal_imu_rate_hz", p.nominal_imu_rate_hz);
  reader.optional("status_rate_hz", p.status_rate_hz);
  reader.optional("segment_wait_s", p.segment_wait_s);
  reader.reject_unknown_keys();
  p.validate(reader.context());
  return p;
}

UgvAgentParams UgvAgentParams::load_file(const std::string& path) {
  return from_yaml(cover::config::load_yaml_file(path), path);
}

UgvAgentParams UgvAgentParams::from_yaml(const YAML::Node& document, const std::string& source) {
  auto reader = cover::config::open_section(document, source, "ugv_agent", /*required=*/true);
  return load(reader);
}

void UgvAgentParams::validate(const std::string& context) const {
  using cover::config::check;
  check(std::isfinite(nominal_imu_rate_hz) && nominal_imu_rate_hz > 0.0 &&
            nominal_imu_rate_hz <= 10000.0,
        context + ".nominal_imu_rate_hz", "must be in (0, 10000] Hz");
  check(std::isfinite(status_rate_hz) && status_rate_hz > 0.0 && status_rate_hz <= 100.0,
        context + ".status_rate_hz", "must be in (0, 100] Hz");
  check(std::isfinite(segment_wait_s) && segment_wait_s >= 0.0 && segment_wait_s <= 3600.0,
        context + ".segment_wait_s", "must be in [0, 3600] s");
  imu_filter.validate(context + ".imu_filter");
  speed_estimator.validate(context + ".speed_estimator");
}

}  // namespace cover::ugv
