#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "cover/config/param_fields.hpp"
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

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("name", self.name, Field("", "label in logs and plots; not empty"));
    visit("deck_height_m", self.deck_height_m,
          Field("m", "deck centre (origin of G_k) above ground").at_least(0.0).at_most(5.0));
    visit("deck_half_length_m", self.deck_half_length_m,
          Field("m", "deck half size along the UGV's x: landing area").above(0.0).at_most(5.0));
    visit("deck_half_width_m", self.deck_half_width_m,
          Field("m", "deck half size along the UGV's y").above(0.0).at_most(5.0));
    visit("has_wheel_odometry", self.has_wheel_odometry,
          Field("", "wheel encoders: the speed estimate's first source; false: IMU only"));
    visit("pattern", self.pattern, Field("", "the UGV's motion (ugv_motion_pattern.hpp)"));
  }

  static UgvParams load(cover::config::YamlReader& reader);
  void validate(const std::string& context) const;
};

// Where the UAV starts: on a UGV's deck (the paper's tasks take off from G_k0) or at a
// world position.
struct UavInitialParams {
  int start_on_ugv = 0;                                  // -1: start at `position_m` instead
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // world frame, used when start_on_ugv = -1
  double yaw_rad = 0.0;  // relative to the UGV when on a deck, else world yaw

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("start_on_ugv", self.start_on_ugv,
          Field("", "index of the UGV whose deck the UAV starts on; -1: at position_m")
              .at_least(-1.0));
    visit("position_m", self.position_m,
          Field("m", "world start position when start_on_ugv = -1; z >= 0 (0: on the ground)"));
    visit("yaw_rad", self.yaw_rad,
          Field("rad", "start yaw: relative to the UGV on a deck, world yaw otherwise"));
  }
};

struct PayloadParams {
  bool attached_at_start = false;
  double mass_kg = 0.1;  // adds to the UAV's true mass while attached (unknown to the controller)

  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("attached_at_start", self.attached_at_start,
          Field("", "the UAV carries a parcel at start"));
    visit("mass_kg", self.mass_kg,
          Field("kg",
                "parcel mass, added to the true mass until released; below uav.plant's "
                "mass_true_kg")
              .at_least(0.0));
  }
};

struct WorldParams;

namespace detail {

// The world file's `world` and `uav` mappings hold members of WorldParams itself: these
// views list them as its sub-sections. `Params` is WorldParams or const WorldParams.
template <typename Params>
struct WorldSection {
  Params& params;
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    // 1 kHz is the floor the issue sets for the RK4 step; 100 kHz is a sanity ceiling.
    visit("physics_rate_hz", self.params.physics_rate_hz,
          Field("Hz", "fixed RK4 step rate; sensor rates must divide it")
              .at_least(1000.0)
              .at_most(1e5));
    visit("gravity_m_s2", self.params.gravity_m_s2,
          Field("m/s^2", "gravity magnitude").above(0.0).below(30.0));
    visit("seed", self.params.seed,
          Field("", "seed of every random stream (sensor noise, IMU biases); same seed, same run"));
  }
};

template <typename Params>
struct UavSection {
  Params& params;
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("plant", self.params.uav,
          Field("", "the true quadrotor; the controller assumes none of its lags or drag"));
    visit("initial", self.params.uav_initial, Field("", "where the UAV starts"));
  }
};

}  // namespace detail

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

  // Each field once (config/param_fields.hpp), but for the list `ugvs` (required, 1 to
  // kMaxUgvs entries, each UgvParams::fields) that load() reads itself.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    detail::WorldSection<Self> world{self};
    visit("world", world, Field("", "the physics"));
    detail::UavSection<Self> uav{self};
    visit("uav", uav, Field("", "the UAV's plant and start"));
    visit("payload", self.payload, Field("", "the parcel the UAV carries"));
    visit("relative_sensor", self.relative_sensor,
          Field("", "relative state of the UAV in every G_k (motion-capture-like)"));
    visit("imu", self.imu, Field("", "each UGV's IMU, in its body frame, gravity included"));
    visit("odometry", self.odometry,
          Field("", "wheel odometry of the UGVs with has_wheel_odometry"));
  }

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
