#include "cover/sim/world_params.hpp"

#include <cmath>

#include "cover/sim/world_state.hpp"

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
  reader.optional("name", p.name);
  reader.optional("deck_height_m", p.deck_height_m);
  reader.optional("deck_half_length_m", p.deck_half_length_m);
  reader.optional("deck_half_width_m", p.deck_half_width_m);
  reader.optional("has_wheel_odometry", p.has_wheel_odometry);
  auto pattern_reader = reader.child("pattern");
  p.pattern = UgvMotionPatternParams::load(pattern_reader);
  reader.reject_unknown_keys();
  p.validate(reader.context());
  return p;
}

void UgvParams::validate(const std::string& context) const {
  check(!name.empty(), context + ".name", "must not be empty");
  check(std::isfinite(deck_height_m) && deck_height_m >= 0.0 && deck_height_m <= 5.0,
        context + ".deck_height_m", "must be in [0, 5] m");
  check(std::isfinite(deck_half_length_m) && deck_half_length_m > 0.0 && deck_half_length_m <= 5.0,
        context + ".deck_half_length_m", "must be in (0, 5] m");
  check(std::isfinite(deck_half_width_m) && deck_half_width_m > 0.0 && deck_half_width_m <= 5.0,
        context + ".deck_half_width_m", "must be in (0, 5] m");
  pattern.validate(context + ".pattern");
}

UavInitialParams UavInitialParams::load(cover::config::YamlReader& reader) {
  UavInitialParams p;
  reader.optional("start_on_ugv", p.start_on_ugv);
  reader.optional("position_m", p.position_m);
  reader.optional("yaw_rad", p.yaw_rad);
  reader.reject_unknown_keys();
  return p;
}

PayloadParams PayloadParams::load(cover::config::YamlReader& reader) {
  PayloadParams p;
  reader.optional("attached_at_start", p.attached_at_start);
  reader.optional("mass_kg", p.mass_kg);
  reader.reject_unknown_keys();
  return p;
}

WorldParams WorldParams::load(cover::config::YamlReader& reader) {
  WorldParams p;
  auto world = reader.child("world");
  world.optional("physics_rate_hz", p.physics_rate_hz);
  world.optional("gravity_m_s2", p.gravity_m_s2);
  world.optional("seed", p.seed);
  world.reject_unknown_keys();

  auto uav = reader.child("uav");
  auto plant = uav.child("plant");
  p.uav = QuadrotorParams::load(plant);
  auto initial = uav.child("initial");
  p.uav_initial = UavInitialParams::load(initial);
  uav.reject_unknown_keys();

  auto payload = reader.child("payload");
  p.payload = PayloadParams::load(payload);

  YAML::Node ugv_list;
  reader.require("ugvs", ugv_list);
  check(ugv_list.IsSequence(), reader.context() + ".ugvs", "must be a list of UGVs");
  for (std::size_t i = 0; i < ugv_list.size(); ++i) {
    cover::config::YamlReader ugv_reader(ugv_list[i],
                                         reader.context() + ".ugvs[" + std::to_string(i) + "]");
    p.ugvs.push_back(UgvParams::load(ugv_reader));
  }

  auto relative = reader.child("relative_sensor");
  p.relative_sensor = RelativeSensorParams::load(relative);
  auto imu = reader.child("imu");
  p.imu = ImuSensorParams::load(imu);
  auto odometry = reader.child("odometry");
  p.odometry = OdometrySensorParams::load(odometry);
  // The agent's configuration owns the filter, so the in-process harness filters exactly
  // as cover-ugv-agent does.
  check(!reader.has("imu_filter"), reader.context() + ".imu_filter",
        "moved to config/ugv_agent.yaml (section ugv_agent.imu_filter)");
  p.imu_filter = ugv::ImuFilterParams::load_default();
  check(!reader.has("speed_estimator"), reader.context() + ".speed_estimator",
        "belongs to config/ugv_agent.yaml (section ugv_agent.speed_estimator)");
  p.speed_estimator = ugv::SpeedEstimatorParams::load_default();
  reader.reject_unknown_keys();
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
  // 1 kHz is the floor the issue sets for the RK4 step; 100 kHz is a sanity ceiling.
  check(std::isfinite(physics_rate_hz) && physics_rate_hz >= 1000.0 && physics_rate_hz <= 1e5,
        context + ".world.physics_rate_hz", "must be in [1000, 100000] Hz");
  check(std::isfinite(gravity_m_s2) && gravity_m_s2 > 0.0 && gravity_m_s2 < 30.0,
        context + ".world.gravity_m_s2", "must be in (0, 30) m/s^2");
  check(!ugvs.empty() && static_cast<int>(ugvs.size()) <= kMaxUgvs, context + ".ugvs",
        "must list 1 to " + std::to_string(kMaxUgvs) + " UGVs");
  for (std::size_t i = 0; i < ugvs.size(); ++i) {
    ugvs[i].validate(context + ".ugvs[" + std::to_string(i) + "]");
  }
  uav.validate(context + ".uav.plant");
  check(uav_initial.start_on_ugv >= -1 && uav_initial.start_on_ugv < static_cast<int>(ugvs.size()),
        context + ".uav.initial.start_on_ugv", "must be -1 or the index of a listed UGV");
  check(uav_initial.position_m.allFinite() && uav_initial.position_m.z() >= 0.0,
        context + ".uav.initial.position_m", "must be finite with z >= 0");
  check(std::isfinite(uav_initial.yaw_rad), context + ".uav.initial.yaw_rad", "must be finite");
  check(std::isfinite(payload.mass_kg) && payload.mass_kg >= 0.0 &&
            payload.mass_kg < uav.mass_true_kg,
        context + ".payload.mass_kg", "must be in [0, uav mass_true_kg)");
  relative_sensor.validate(context + ".relative_sensor");
  imu.validate(context + ".imu");
  odometry.validate(context + ".odometry");
  imu_filter.validate(context + ".imu_filter");
  speed_estimator.validate(context + ".speed_estimator");
  check_divides(physics_rate_hz, relative_sensor.rate_hz, context + ".relative_sensor.rate_hz");
  check_divides(physics_rate_hz, imu.rate_hz, context + ".imu.rate_hz");
  // Odometry rides on IMU samples, so each of its samples must fall on one.
  check_divides(imu.rate_hz, odometry.rate_hz, context + ".odometry.rate_hz", "imu.rate_hz");
}

}  // namespace cover::sim
