#include "cover/sampc/sampc_params.hpp"

namespace cover::sampc {

Eigen::Vector4d SampcParams::input_lower_bound() const {
  return {thrust_min_m_s2, -roll_pitch_rate_max_rad_s, -roll_pitch_rate_max_rad_s,
          -yaw_rate_max_rad_s};
}

Eigen::Vector4d SampcParams::input_upper_bound() const {
  return {thrust_max_m_s2, roll_pitch_rate_max_rad_s, roll_pitch_rate_max_rad_s,
          yaw_rate_max_rad_s};
}

SampcParams SampcParams::load(config::YamlReader& reader) {
  SampcParams p;
  config::load_fields(p, reader);
  p.validate();
  return p;
}

SampcParams SampcParams::load_file(const std::string& path) {
  return from_yaml(config::load_yaml_file(path), path);
}

SampcParams SampcParams::from_yaml(const YAML::Node& document, const std::string& source) {
  config::YamlReader reader = config::open_section(document, source, "sampc", /*required=*/true);
  return load(reader);
}

void SampcParams::validate() const {
  const std::string c = "sampc";
  config::check_fields(*this, c);
  // Bounds that are other fields.
  config::check(yaw_reference_rate_rad_s <= yaw_rate_max_rad_s, c + ".yaw_reference_rate_rad_s",
                "must be <= yaw_rate_max_rad_s");
  config::check(custom_velocity_nodes <= horizon_steps, c + ".custom_velocity_nodes",
                "must be <= horizon_steps");
  config::check(intercept.velocity_nodes <= horizon_steps, c + ".intercept.velocity_nodes",
                "must be <= horizon_steps");
}

}  // namespace cover::sampc
