#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "cover/config/yaml_reader.hpp"
#include "cover/sim/imu_sensor.hpp"
#include "cover/sim/odometry_sensor.hpp"
#include "cover/sim/quadrotor.hpp"
#include "cover/sim/relative_sensor.hpp"
#include "cover/sim/ugv_motion_pattern.hpp"
#include "cover/ugv/imu_filter.hpp"
#include "cover/ugv/speed_estimator.hpp"

namespace cover::sim {

struct UgvParams {
  std::string name = "G0";
  UgvMotionPatternParams pattern;
  double deck_height_m = 0.3;       // height of the deck centre (G_k origin) above ground
  double deck_half_length_m = 0.3;  // deck footprint along the UGV's x (contact area)
  double deck_half_width_m = 0.25;  // deck footprint along the UGV's y
  bool has_wheel_odometry = true;   // wheel encoders give the speed estimate its best source

  static UgvParams load(cover::config::YamlReader& reader);
  void validate(const std::string& context) const;
};

// Where the UAV starts: on a UGV's deck (the paper's tasks take off from G_k0) or at a
// world position.
struct UavInitialParams {
  int start_on_ugv = 0;                                  // -1: start at `position_m` instead
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // world frame, used when start_on_ugv = -1
  double yaw_rad = 0.0;  // relative to the UGV when on a deck, else world yaw

  static UavInitialParams load(cover::config::YamlReader& reader);
};

struct PayloadParams {
  bool attached_at_start = false;
  double mass_kg = 0.1;  // adds to the UAV's true mass while attached (unknown to the controller)

  static PayloadParams load(cover::config::YamlReader& reader);
};

// A whole simulated world. Loaded from YAML (config/sim/world_default.yaml documents
// every key); `validate` throws cover::config::ConfigError naming the bad key.
struct WorldParams {
  double physics_rate_hz = 1000.0;  // fixed RK4 step; sensor rates must divide it
  double gravity_m_s2 = 9.81;
  std::uint64_t seed = 1;  // every random stream derives from it
  std::vector<UgvParams> ugvs;
  QuadrotorParams uav;
  UavInitialParams uav_initial;
  PayloadParams payload;
  RelativeSensorParams relative_sensor;
  ImuSensorParams imu;
  OdometrySensorParams odometry;
  // Not read from the world file: load() takes them from config/ugv_agent.yaml, the
  // agent's configuration, so that in-process and multi-process runs filter alike.
  ugv::ImuFilterParams imu_filter;
  ugv::SpeedEstimatorParams speed_estimator;

  // has_wheel_odometry of each listed UGV, in order.
  std::vector<bool> ugvs_with_odometry() const;

  static WorldParams load(cover::config::YamlReader& reader);
  static WorldParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static WorldParams from_yaml(const YAML::Node& document, const std::string& source);
  // config/sim/world_default.yaml
  static WorldParams load_default();
  void validate(const std::string& context = "world") const;
};

}  // namespace cover::sim
