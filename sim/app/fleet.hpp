#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cover/firmware_link/firmware_link.hpp"
#include "cover/mission/mission_controller.hpp"
#include "cover/sim/fc/simulated_autopilot.hpp"
#include "cover/sim/run_recorder.hpp"
#include "cover/sim/scenario.hpp"
#include "cover/sim/world.hpp"
#include "cover/vocabulary/world_segment.hpp"
#include "offboard_failsafe.hpp"
#include "sim_process_params.hpp"

namespace cover::sim {

// Which flight controller sits between a UAV agent and its plant: the direct path (the
// agent's cover/uav/<u>/cmd through OffboardFailsafe), or a simulated PX4 / ArduPilot
// autopilot that a flight-controller bridge talks MAVLink to.
struct FleetAutopilots {
  std::optional<cover::Autopilot> profile;  // nullopt: direct
  fc::SimFcParams params;
  // Lockstep: every step's frames end with a HIGHRES_IMU (the simulator's own contract with
  // a bridge; real firmware has none).
  fc::StepClosing closing = fc::StepClosing::None;
};

// Real firmware (cover-sim --firmware px4|ardupilot): each UAV is the motor-level quadrotor
// its firmware (PX4 or ArduCopter SITL) flies through its physics link. The agents'
// commands reach the firmware through cover-fc-bridge over MAVLink, which the simulator
// does not see: it steps the plant on the firmware's motor outputs.
struct FleetFirmware {
  std::string name;  // "PX4", "ArduCopter"
  FirmwareUavParams uav;
  std::vector<std::unique_ptr<firmware_link::FirmwareLink>> links;  // one per UAV, in order
};

// The simulated fleet: one World per UAV over the same UGVs (UAVs do not interact
// physically, so each keeps its own plant, sensors and payload; UAV 0's world is exactly
// the in-process harness's), each with its flight controller and its run recorder. UGV
// IMUs come from UAV 0's world: one IMU per UGV, shared by every UAV agent.
class Fleet {
 public:
  Fleet(const Scenario& scenario, const SimProcessParams& params,
        const mission::MissionParams& mission, const FleetAutopilots& autopilots = {});
  // A fleet flown by real firmware (`firmware.links` has one link per UAV).
  Fleet(const Scenario& scenario, const SimProcessParams& params,
        const mission::MissionParams& mission, FleetFirmware firmware);

  int uav_count() const { return static_cast<int>(uavs_.size()); }
  const World& world(int uav) const { return *uavs_[uav].world; }
  double time_s() const { return uavs_[0].world->state().time_s; }
  std::uint64_t tick() const { return tick_; }
  const Scenario& scenario() const { return scenario_; }

  // One control period: what UAV `uav`'s agent reported (trace) and commanded this tick;
  // `command_age_s` < 0 when it has never commanded.
  void apply(int uav, const mission::ControllerStatus& status,
             const mission::ControlCommand& command, double command_age_s);
  // With simulated autopilots: one control period of UAV `uav`'s autopilot (the plant
  // gets what it commands; the recorder records that, beside the agent's trace). Returns
  // the frames it sends now.
  std::vector<mavlink::EncodedFrame> apply_autopilot(int uav,
                                                     const mission::ControllerStatus& status);
  bool has_autopilots() const { return autopilots_.profile.has_value(); }
  // UAV `uav`'s simulated autopilot; only when has_autopilots().
  fc::SimulatedAutopilot& autopilot(int uav) { return *uavs_[uav].autopilot; }
  const fc::SimulatedAutopilot& autopilot(int uav) const { return *uavs_[uav].autopilot; }
  bool has_firmware() const { return firmware_name_.has_value(); }
  const std::string& firmware_name() const { return *firmware_name_; }
  firmware_link::FirmwareLink& firmware_link(int uav) { return *uavs_[uav].firmware; }
  const firmware_link::FirmwareLink& firmware_link(int uav) const { return *uavs_[uav].firmware; }
  // Real firmware: one control period of the firmware alone on a still deck (its clock
  // runs, the world's stands: World::settle_uav), while it boots and aligns.
  void settle_firmware();
  // What UAV `uav`'s bridge last said of its firmware's mode: in its own land mode or not
  // (the segment's OffboardState for it: LossDescent while it lands).
  void note_firmware_landing(int uav, bool landing) { uavs_[uav].firmware_landing = landing; }
  // The firmware's time of UAV `uav` (its steps since it booted), s.
  double firmware_time_s(int uav) const { return uavs_[uav].world->motor_uav().firmware_time_s(); }
  // Advances every world one control period (each holding its applied command).
  void advance();
  bool finished() const;
  OffboardState offboard_state(int uav) const { return uavs_[uav].failsafe.state(); }
  bool offboard_changed(int uav) const { return uavs_[uav].failsafe.changed(); }
  bool offboard_handed_over(int uav) const { return uavs_[uav].failsafe.handed_over(); }

  // The world as the shared-memory segment carries it (IMU rings included).
  const SharedWorld& shared() const { return shared_; }
  // Newest raw IMU stamp in the segment, s (< 0: none yet).
  double latest_imu_stamp_s() const { return latest_imu_stamp_s_; }

  // The task state UAV `uav`'s agent last reported (its trace).
  mission::MissionState reported_state(int uav) const { return uavs_[uav].last_status.stage.state; }
  ClosedLoopResult result(int uav, const std::string& status, mission::MissionState state);

 private:
  struct Uav {
    std::unique_ptr<World> world;
    std::unique_ptr<RunRecorder> recorder;
    OffboardFailsafe failsafe;
    std::unique_ptr<fc::SimulatedAutopilot> autopilot;      // with FleetAutopilots::profile
    std::unique_ptr<firmware_link::FirmwareLink> firmware;  // with FleetFirmware
    MotorOutputs outputs{};                                 // the firmware's, held
    // The autopilot's state as the segment shows it, taken at its last step (the autopilot
    // itself changes on its link's thread; advance() must not read it).
    OffboardState autopilot_view = OffboardState::WaitingForAgent;
    QuadrotorCommand plant_command;
    mission::ControllerStatus last_status;
    bool firmware_landing = false;  // its bridge says: in the firmware's land mode
    bool firmware_was_armed = false;
  };
  void step_firmware_uav(Uav& uav);
  void capture_imu();
  void fill_shared();
  static OffboardState offboard_view(const Uav& uav);
  static OffboardState offboard_view(const fc::SimulatedAutopilot& autopilot);

  const Scenario& scenario_;
  int physics_per_control_;
  ClosedLoopOptions options_;
  FleetAutopilots autopilots_;
  std::optional<std::string> firmware_name_;
  std::vector<Uav> uavs_;
  SharedWorld shared_;
  std::uint64_t tick_ = 0;
  double latest_imu_stamp_s_ = -1.0;
};

}  // namespace cover::sim
