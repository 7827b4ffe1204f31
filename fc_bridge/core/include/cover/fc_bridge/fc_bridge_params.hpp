#pragma once

#include <cstdint>
#include <string>

#include "cover/config/param_fields.hpp"
#include "cover/config/yaml_reader.hpp"

namespace cover::fc_bridge {

// cover-fc-bridge's settings (config/fc_bridge.yaml, section `fc_bridge`); the YAML file
// documents each one.
struct FcBridgeParams {
  // Normalised collective thrust (0..1) that hovers the vehicle, the estimator's start.
  // 9.81 / 20: the simulated quadrotor's nominal hover (full throttle gives 20 m/s^2).
  double hover_thrust = 0.4905;
  double hover_thrust_min = 0.15;  // the estimate stays within [min, max]
  double hover_thrust_max = 0.85;
  double hover_thrust_initial_std = 0.1;          // 1-sigma doubt about hover_thrust at start
  double hover_thrust_noise_per_sqrt_s = 0.0015;  // random walk of the true hover thrust
  double accel_noise_m_s2 = 1.0;                  // 1-sigma of the body z specific force
  // The autopilot's vertical velocity (LOCAL_POSITION_NED) aiding the estimate.
  double velocity_noise_m_s = 0.05;                   // its 1-sigma noise
  double velocity_model_noise_m_s_per_sqrt_s = 0.02;  // drag, wind, lag beyond the model
  double velocity_timeout_s = 0.5;                    // older: the accelerometer alone
  double velocity_drag_per_s = 0.0;   // vertical deceleration per m/s of vertical speed
  double estimator_min_thrust = 0.1;  // below this commanded thrust the estimator rests
  double cmd_timeout_s = 0.1;         // armed in offboard with no agent command: land
  double heartbeat_timeout_s = 1.5;   // no autopilot HEARTBEAT: link lost
  double ack_timeout_s = 0.25;        // a COMMAND_LONG unanswered this long is sent again
  int command_retries = 3;            // resends before "no answer"
  double offboard_stream_s = 1.0;     // setpoints stream this long before OFFBOARD
  double state_rate_hz = 10.0;        // cover/uav/U/fc
  int system_id = 0;                  // the companion's MAVLink system id; 0: the autopilot's
  int component_id = 191;             // MAV_COMP_ID_ONBOARD_COMPUTER
  bool auto_arm = false;              // simulation only: arm without an operator
  double gravity_m_s2 = 9.81;
  // Streams asked of the autopilot (SET_MESSAGE_INTERVAL); 0: left as the autopilot sends it.
  double stream_highres_imu_hz = 100.0;
  double stream_extended_sys_state_hz = 5.0;
  double stream_sys_status_hz = 2.0;
  double stream_battery_status_hz = 1.0;
  double stream_estimator_status_hz = 1.0;
  double stream_attitude_target_hz = 0.0;
  double stream_local_position_ned_hz = 50.0;  // optional: not every vehicle has one
  double stream_reask_s = 5.0;                 // a missing stream is asked for again this often
  double param_read_timeout_s = 0.5;           // a PARAM_REQUEST_READ unanswered this long: again
  int param_read_tries = 3;                    // tries per name before "absent"
  double param_refresh_s = 10.0;               // the parameters are read again this often
  bool hover_thrust_from_autopilot = false;  // start the estimate at MPC_THR_HOVER / MOT_THST_HOVER

  // Each field once (config/param_fields.hpp): load, validate, the shipped-file test and
  // the documentation walk this list.
  template <typename Self, typename Visit>
  static void fields(Self& self, Visit& visit) {
    using config::Field;
    visit("hover_thrust", self.hover_thrust,
          Field("",
                "normalised thrust that hovers: the estimator's start; in "
                "[hover_thrust_min, hover_thrust_max]")
              .at_least(0.01)
              .at_most(0.99));
    visit("hover_thrust_min", self.hover_thrust_min,
          Field("", "lowest hover thrust estimate").at_least(0.01).at_most(0.99));
    visit("hover_thrust_max", self.hover_thrust_max,
          Field("", "highest hover thrust estimate, >= hover_thrust_min")
              .at_least(0.01)
              .at_most(0.99));
    visit("hover_thrust_initial_std", self.hover_thrust_initial_std,
          Field("", "1-sigma doubt about hover_thrust at start").at_least(1e-4).at_most(1.0));
    visit("hover_thrust_noise_per_sqrt_s", self.hover_thrust_noise_per_sqrt_s,
          Field("1/sqrt(s)", "random walk of the true hover thrust").at_least(0.0).at_most(1.0));
    visit("accel_noise_m_s2", self.accel_noise_m_s2,
          Field("m/s^2", "1-sigma of the body z specific force").at_least(0.01).at_most(50.0));
    visit("velocity_noise_m_s", self.velocity_noise_m_s,
          Field("m/s", "1-sigma noise of the autopilot's vertical velocity (LOCAL_POSITION_NED)")
              .at_least(0.001)
              .at_most(5.0));
    visit("velocity_model_noise_m_s_per_sqrt_s", self.velocity_model_noise_m_s_per_sqrt_s,
          Field("m/s/sqrt(s)",
                "how far the vertical velocity departs from the thrust model (drag, wind, the "
                "motors' lag)")
              .at_least(0.0)
              .at_most(5.0));
    visit("velocity_timeout_s", self.velocity_timeout_s,
          Field("s", "no vertical velocity this long: the estimate on the accelerometer alone")
              .at_least(0.05)
              .at_most(10.0));
    visit("velocity_drag_per_s", self.velocity_drag_per_s,
          Field("1/s",
                "the vehicle's vertical deceleration per m/s of vertical speed (drag over mass, "
                "the rotors' loss of thrust in a climb) in the velocity model; 0: none")
              .at_least(0.0)
              .at_most(10.0));
    visit("estimator_min_thrust", self.estimator_min_thrust,
          Field("", "below this commanded thrust the estimator rests").at_least(0.0).at_most(0.9));
    visit("cmd_timeout_s", self.cmd_timeout_s,
          Field("s", "armed in offboard with no agent command this long: land")
              .at_least(0.01)
              .at_most(1.0)
              .hint("PX4's own offboard loss is 1 s"));
    visit("heartbeat_timeout_s", self.heartbeat_timeout_s,
          Field("s", "no autopilot HEARTBEAT this long: link lost")
              .at_least(0.5)
              .at_most(30.0)
              .hint("autopilots send HEARTBEAT at 1 Hz"));
    visit("ack_timeout_s", self.ack_timeout_s,
          Field("s", "a COMMAND_LONG unanswered this long is sent again")
              .at_least(0.01)
              .at_most(5.0));
    visit("command_retries", self.command_retries,
          Field("", "resends before \"no answer\"").at_least(0.0).at_most(20.0));
    visit("offboard_stream_s", self.offboard_stream_s,
          Field("s", "setpoints stream this long before OFFBOARD").at_least(0.0).at_most(30.0));
    visit("state_rate_hz", self.state_rate_hz,
          Field("Hz", "rate of cover/uav/U/fc (and on every change)").at_least(5.0).at_most(100.0));
    visit("system_id", self.system_id,
          Field("", "the companion's MAVLink system id; 0: the autopilot's")
              .at_least(0.0)
              .at_most(255.0)
              .hint("0: the autopilot's"));
    visit("component_id", self.component_id,
          Field("", "the companion's MAVLink component id (191: onboard computer)")
              .at_least(1.0)
              .at_most(255.0));
    visit("auto_arm", self.auto_arm, Field("", "simulation only: arm without an operator"));
    visit("gravity_m_s2", self.gravity_m_s2, Field("m/s^2", "gravity").at_least(9.0).at_most(10.5));
    visit(
        "stream_highres_imu_hz", self.stream_highres_imu_hz,
        Field(
            "Hz",
            "HIGHRES_IMU asked of the autopilot (the hover-thrust estimator's input); 0: not asked")
            .at_least(0.0)
            .at_most(500.0));
    visit("stream_extended_sys_state_hz", self.stream_extended_sys_state_hz,
          Field("Hz", "EXTENDED_SYS_STATE asked of the autopilot (landed state); 0: not asked")
              .at_least(0.0)
              .at_most(500.0));
    visit("stream_sys_status_hz", self.stream_sys_status_hz,
          Field("Hz", "SYS_STATUS asked of the autopilot (sensor health, battery); 0: not asked")
              .at_least(0.0)
              .at_most(500.0));
    visit("stream_battery_status_hz", self.stream_battery_status_hz,
          Field("Hz", "BATTERY_STATUS asked of the autopilot; 0: not asked")
              .at_least(0.0)
              .at_most(500.0));
    visit("stream_estimator_status_hz", self.stream_estimator_status_hz,
          Field("Hz", "ESTIMATOR_STATUS (PX4) / EKF_STATUS_REPORT (ArduPilot) asked; 0: not asked")
              .at_least(0.0)
              .at_most(500.0));
    visit(
        "stream_attitude_target_hz", self.stream_attitude_target_hz,
        Field("Hz",
              "ATTITUDE_TARGET asked (the autopilot's echo of the setpoint it flies); 0: not asked")
            .at_least(0.0)
            .at_most(500.0));
    visit("stream_local_position_ned_hz", self.stream_local_position_ned_hz,
          Field("Hz",
                "LOCAL_POSITION_NED asked (its vertical velocity aids the hover-thrust estimate); "
                "optional: not named missing when the autopilot has no position estimate; 0: not "
                "asked")
              .at_least(0.0)
              .at_most(500.0));
    visit("stream_reask_s", self.stream_reask_s,
          Field("s", "a requested stream that does not arrive is asked for again this often")
              .at_least(0.5)
              .at_most(600.0));
    visit("param_read_timeout_s", self.param_read_timeout_s,
          Field("s", "a PARAM_REQUEST_READ unanswered this long is sent again")
              .at_least(0.05)
              .at_most(10.0));
    visit("param_read_tries", self.param_read_tries,
          Field("", "tries per parameter name before it counts as absent")
              .at_least(1.0)
              .at_most(20.0));
    visit("param_refresh_s", self.param_refresh_s,
          Field("s", "the parameters COVER depends on are read again this often")
              .at_least(1.0)
              .at_most(3600.0));
    visit("hover_thrust_from_autopilot", self.hover_thrust_from_autopilot,
          Field("",
                "start the hover-thrust estimate at the autopilot's MPC_THR_HOVER / "
                "MOT_THST_HOVER once read, before the estimator has learned"));
  }

  static FcBridgeParams load_file(const std::string& path);
  // The same from a document already parsed (config::parse_yaml); `source` names it.
  static FcBridgeParams from_yaml(const YAML::Node& document, const std::string& source);
  void validate() const;
};

}  // namespace cover::fc_bridge
