#pragma once

#include <string>

#include "cover/config/param_fields.hpp"
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

  // Each field once (config/param_fields.hpp), the filter's and the estimator's as
  // sub-sections: load, validate, the shipped-file test and the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using cover::config::Field;
    visit("nominal_imu_rate_hz", self.nominal_imu_rate_hz,
          Field("Hz", "the IMU's rate; healthy needs >= 80 % of it").above(0.0).at_most(10000.0));
    visit("status_rate_hz", self.status_rate_hz,
          Field("Hz", "cover/ugv/<k>/status heartbeat rate").above(0.0).at_most(100.0));
    visit("segment_wait_s", self.segment_wait_s,
          Field("s", "sim source: how long the simulator may take to start")
              .at_least(0.0)
              .at_most(3600.0));
    visit("imu_filter", self.imu_filter, Field("", "the IMU pre-processing"));
    visit("speed_estimator", self.speed_estimator, Field("", "the UGV's forward speed"));
  }

  static UgvAgentParams load(cover::config::YamlReader& reader);
  // Section `ugv_agent` of `path`; throws ConfigError naming the file and key.
  static UgvAgentParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static UgvAgentParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate(const std::string& context = "ugv_agent") const;
};

}  // namespace cover::ugv
