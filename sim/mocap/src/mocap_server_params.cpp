#include "cover/sim/mocap/mocap_server_params.hpp"

#include <cmath>

namespace cover::sim::mocap {

MocapServerParams MocapServerParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

MocapServerParams MocapServerParams::from_yaml(const YAML::Node& document,
                                               const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "mocap", false);
  MocapServerParams p;
  reader.optional("rate_hz", p.rate_hz);
  reader.optional("latency_s", p.latency_s);
  reader.optional("position_noise_m", p.position_noise_m);
  reader.optional("attitude_noise_rad", p.attitude_noise_rad);
  reader.optional("dropout_probability", p.dropout_probability);
  reader.optional("up_axis", p.up_axis);
  reader.optional("units", p.units);
  reader.optional("uav_prefix", p.uav_prefix);
  reader.optional("ugv_prefix", p.ugv_prefix);
  reader.optional("seed", p.seed);
  reader.reject_unknown_keys();
  p.validate();
  return p;
}

void MocapServerParams::validate() const {
  auto in = [](double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; };
  config::check(in(rate_hz, 1.0, 1000.0), "mocap.rate_hz", "must be in [1, 1000] Hz");
  config::check(in(latency_s, 0.0, 0.5), "mocap.latency_s", "must be in [0, 0.5] s");
  config::check(in(position_noise_m, 0.0, 0.1), "mocap.position_noise_m", "must be in [0, 0.1] m");
  config::check(in(attitude_noise_rad, 0.0, 0.2), "mocap.attitude_noise_rad",
                "must be in [0, 0.2] rad");
  config::check(in(dropout_probability, 0.0, 0.5), "mocap.dropout_probability",
                "must be in [0, 0.5]");
  config::check(up_axis == "z" || up_axis == "y", "mocap.up_axis", "must be z or y");
  config::check(units == "m" || units == "mm", "mocap.units", "must be m or mm");
  config::check(!uav_prefix.empty() && !ugv_prefix.empty() && uav_prefix != ugv_prefix,
                "mocap.uav_prefix", "the prefixes must be non-empty and differ");
}

}  // namespace cover::sim::mocap
