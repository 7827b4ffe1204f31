#pragma once

#include <string>

#include "cover/config/yaml_reader.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/speed_estimator.hpp"

namespace cover::ugv {

// The agent's parameters: section `ugv_agent` of config/ugv_agent.yaml (documents each key).
struct UgvAgentParams {
  ImuFilterParams imu_filter;
  SpeedEstimatorParams speed_estimator;
  double nominal_imu_rate_hz = 200.0;  // the simulator's IMU rate (config/sim world imu.rate_hz)
  double status_rate_hz = 1.0;         // heartbeat of cover/ugv/<k>/status
  double segment_wait_s = 10.0;        // sim source: how long the simulator may take to start

  static UgvAgentParams load(cover::config::YamlReader& reader);
  // Section `ugv_agent` of `path`; throws ConfigError naming the file and key.
  static UgvAgentParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static UgvAgentParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate(const std::string& context = "ugv_agent") const;
};

}  // namespace cover::ugv
