#include "cover/sim/world_params.hpp"

#include <cmath>

#include "cover/vocabulary/world_state.hpp"

namespace cover::sim {

namespace {

using cover::config::check;

// Sensors sample on physics steps, so their period must be a whole number of steps.
void check_divides(double base_rate_hz, double sensor_rate_hz, const std::string& key,
                   const char* base_key = "physics_rate_hz") {
  const double ratio = base_rate_hz / sensor_rate_hz;
  check(ratio >= 1.0 && std::abs(ratio - std::round(ratio)) < 1e-9, key,
        std::string("must divide ") + base_key + " (" + std::to_string(base_rate_hz) + ")");
}

}  // namespace

UgvParams UgvParams::load(cover::config::YamlReader& reader) {
  UgvParams p;
  cover::config::load_fields(p, reader);
  p.validate(reader.context());
  return p;
}

void UgvParams::validate(const std::string& context) const {
  cover::config::check_fields(*this, context);
  check(!name.empty(), context + ".name", "must not be empty");
  pattern.validate(context + ".pattern");
}

WorldParams WorldParams::load(cover::config::YamlReader& reader) {
  WorldParams p;
  // The agent's configuration owns the filter, so the in-process harness filters exactly
  // as cover-ugv-agent does.
  check(!reader.has("imu_filter"), reader.context() + ".imu_filter",
        "moved to config/ugv_agent.yaml (section ugv_agent.imu_filter)");
  check(!reader.has("speed_estimator"), reader.context() + ".speed_estimator",
        "belongs to config/ugv_agent.yaml (section ugv_agent.speed_estimator)");
  YAML::Node ugv_list;
  reader.require("ugvs", ugv_list);
  check(ugv_list.IsSequence(), reader.context() + ".ugvs", "must be a list of UGVs");
  for (std::size_t i = 0; i < ugv_list.size(); ++i) {
    cover::config::YamlReader ugv_reader(ugv_list[i],
                                         reader.context() + ".ugvs[" + std::to_string(i) + "]");
    p.ugvs.push_back(UgvParams::load(ugv_reader));
  }
  cover::config::load_fields(p, reader);
  p.imu_filter = ugv::ImuFilterParams::load_default();
  p.speed_estimator = ugv::SpeedEstimatorParams::load_default();
  p.validate(reader.context());
  return p;
}

std::vector<bool> WorldParams::ugvs_with_odometry() const {
  std::vector<bool> has;
  for (const UgvParams& ugv : ugvs) has.push_back(ugv.has_wheel_odometry);
  return has;
}

WorldParams WorldParams::load_file(const std::string& path) {
  return from_yaml(cover::config::load_yaml_file(path), path);
}

WorldParams WorldParams::from_yaml(const YAML::Node& document, const std::string& source) {
  cover::config::YamlReader reader(document, source);
  return load(reader);
}

WorldParams WorldParams::load_default() {
  return load_file(cover::config::default_config_dir() + "/sim/world_default.yaml");
}

void WorldParams::validate(const std::string& context) const {
  // Every field's bounds, the sections' included; then each section's checks between its
  // fields, and the world's between sections.
  cover::config::check_fields(*this, context);
  uav.validate(context + ".uav.plant");
  relative_sensor.validate(context + ".relative_sensor");
  imu.validate(context + ".imu");
  odometry.validate(context + ".odometry");
  check(!ugvs.empty() && static_cast<int>(ugvs.size()) <= kMaxUgvs, context + ".ugvs",
        "must list 1 to " + std::to_string(kMaxUgvs) + " UGVs");
  for (std::size_t i = 0; i < ugvs.size(); ++i) {
    ugvs[i].validate(context + ".ugvs[" + std::to_string(i) + "]");
  }
  check(uav_initial.start_on_ugv < static_cast<int>(ugvs.size()),
        context + ".uav.initial.start_on_ugv", "must be -1 or the index of a listed UGV");
  check(uav_initial.position_m.z() >= 0.0, context + ".uav.initial.position_m", "must have z >= 0");
  check(payload.mass_kg < uav.mass_true_kg, context + ".payload.mass_kg",
        "must be below uav.plant.mass_true_kg");
  imu_filter.validate(context + ".imu_filter");
  speed_estimator.validate(context + ".speed_estimator");
  check_divides(physics_rate_hz, relative_sensor.rate_hz, context + ".relative_sensor.rate_hz");
  check_divides(physics_rate_hz, imu.rate_hz, context + ".imu.rate_hz");
  // Odometry rides on IMU samples, so each of its samples must fall on one.
  check_divides(imu.rate_hz, odometry.rate_hz, context + ".odometry.rate_hz", "imu.rate_hz");
}

}  // namespace cover::sim
