#include "fleet.hpp"

#include <cmath>

#include "cover/config/format_number.hpp"
#include "cover/sim/raw_imu.hpp"
#include "cover/sim/world_uav_io.hpp"

namespace cover::sim {

Fleet::Fleet(const Scenario& scenario, const SimProcessParams& params,
             const mission::MissionParams& mission, const FleetAutopilots& autopilots)
    : scenario_(scenario),
      physics_per_control_(
          static_cast<int>(std::lround(scenario.world.physics_rate_hz / params.control_rate_hz))),
      autopilots_(autopilots) {
  // One tick is one step of every agent: their control period (mission.yaml's).
  mission::check_control_period(mission, 1.0 / params.control_rate_hz,
                                "sim/sim_process.yaml: sim_process.control_rate_hz " +
                                    config::format_number(params.control_rate_hz) + " Hz");
  options_.control_rate_hz = params.control_rate_hz;
  for (int u = 0; u < scenario.uav_count(); ++u) {
    Uav uav{std::make_unique<World>(scenario.world_of(u)),
            nullptr,
            OffboardFailsafe(params.offboard_timeout_s, params.loss_descent_rate_m_s),
            nullptr,
            nullptr,
            {},
            OffboardState::WaitingForAgent,
            {},
            {}};
    uav.recorder =
        std::make_unique<RunRecorder>(scenario_, scenario_.task_of(u), mission, options_);
    if (autopilots_.profile) {
      uav.autopilot = std::make_unique<fc::SimulatedAutopilot>(
          *autopilots_.profile, static_cast<std::uint8_t>(autopilots_.params.system_id_base + u),
          autopilots_.params, autopilots_.closing);
    }
    uavs_.push_back(std::move(uav));
  }
  shared_.ugv_count = uavs_[0].world->ugv_count();
  shared_.uav_count = uav_count();
  fill_shared();
}

Fleet::Fleet(const Scenario& scenario, const SimProcessParams& params,
             const mission::MissionParams& mission, FleetFirmware firmware)
    : Fleet(scenario, params, mission, FleetAutopilots{}) {
  if (static_cast<int>(firmware.links.size()) != uav_count()) {
    throw std::invalid_argument("a firmware link per UAV: " + std::to_string(uav_count()) +
                                " UAVs, " + std::to_string(firmware.links.size()) + " links");
  }
  firmware_name_ = firmware.name;
  for (int u = 0; u < uav_count(); ++u) {
    uavs_[u].world = std::make_unique<World>(scenario.world_of(u), firmware.uav);
    uavs_[u].firmware = std::move(firmware.links[u]);
  }
  fill_shared();
}

void Fleet::apply(int u, const mission::ControllerStatus& status,
                  const mission::ControlCommand& command, double command_age_s) {
  Uav& uav = uavs_[u];
  World& world = *uav.world;
  if (uav.firmware) {
    // The command went to the bridge and on to the firmware; the plant flies its motors.
    uav.recorder->record(status, command, world);
    uav.last_status = status;
    return;
  }
  uav.plant_command =
      uav.failsafe.plant_command(to_plant_command(command), command_age_s, command.handover, world);
  const bool offboard = uav.failsafe.state() == OffboardState::Offboard;
  if (offboard && command.release_payload && world.release_payload()) {
    uav.recorder->record_release(world);
  }
  uav.recorder->record(status, command, world);
  uav.last_status = status;
}

std::vector<mavlink::EncodedFrame> Fleet::apply_autopilot(int u,
                                                          const mission::ControllerStatus& status) {
  Uav& uav = uavs_[u];
  World& world = *uav.world;
  fc::AutopilotStep step = uav.autopilot->step(world.state().time_s, world);
  uav.plant_command = step.plant_command;
  if (step.release_payload && world.release_payload()) uav.recorder->record_release(world);
  // What the plant got, in the controller's terms (the agent's own command went to the bridge).
  mission::ControlCommand flown;
  flown.thrust_m_s2 = step.plant_command.thrust_m_s2;
  flown.body_rate_rad_s = step.plant_command.body_rate_rad_s.eigen();
  flown.armed = uav.autopilot->armed();
  uav.recorder->record(status, flown, world);
  uav.last_status = status;
  uav.autopilot_view = offboard_view(*uav.autopilot);
  return std::move(step.frames);
}

void Fleet::advance() {
  for (int i = 0; i < physics_per_control_; ++i) {
    for (Uav& uav : uavs_) {
      if (uav.firmware) {
        step_firmware_uav(uav);
      } else {
        uav.world->step(uav.plant_command);
      }
    }
    capture_imu();
  }
  ++tick_;
  fill_shared();
}

// One physics step on the outputs the firmware gave for it, then the firmware's turn: what
// the step produced goes to it, and its answer is held over the next step.
void Fleet::step_firmware_uav(Uav& uav) {
  uav.world->step(uav.outputs);
  const World& world = *uav.world;
  uav.outputs =
      uav.firmware->exchange(firmware_link::plant_sample(world.motor_uav(), world.state().uav));
  uav.firmware_was_armed = uav.firmware_was_armed || uav.firmware->stats().armed;
}

void Fleet::settle_firmware() {
  for (int i = 0; i < physics_per_control_; ++i) {
    for (Uav& uav : uavs_) {
      uav.world->settle_uav(uav.outputs);
      const World& world = *uav.world;
      uav.outputs =
          uav.firmware->exchange(firmware_link::plant_sample(world.motor_uav(), world.state().uav));
    }
  }
  fill_shared();
}

void Fleet::capture_imu() {
  const World& world = *uavs_[0].world;
  if (!world.imu_sensor().has_reading()) return;
  const double stamp_s = world.imu_sensor().latest(0).raw.stamp_s;
  if (stamp_s <= latest_imu_stamp_s_) return;
  latest_imu_stamp_s_ = stamp_s;
  for (int k = 0; k < world.ugv_count(); ++k) {
    ImuRing& ring = shared_.imu[k];
    ring.slots[ring.written % kImuRingCapacity] = to_raw(world.imu_sensor().latest(k).raw);
    ++ring.written;
  }
}

void Fleet::fill_shared() {
  const WorldState& ws = uavs_[0].world->state();
  shared_.time_s = ws.time_s;
  shared_.tick = tick_;
  shared_.ugvs = ws.ugvs;
  for (int u = 0; u < uav_count(); ++u) {
    const WorldState& w = uavs_[u].world->state();
    SharedUav& s = shared_.uavs[u];
    s.state = w.uav;
    s.contact = w.uav_contact;
    s.payload = w.payload;
    s.command = w.last_command;
    s.offboard = offboard_view(uavs_[u]);
  }
}

OffboardState Fleet::offboard_view(const Uav& uav) {
  if (uav.autopilot) return uav.autopilot_view;
  if (uav.firmware) {
    if (uav.firmware->stats().armed) {
      return uav.firmware_landing ? OffboardState::LossDescent : OffboardState::Offboard;
    }
    return uav.firmware_was_armed ? OffboardState::LossDisarmed : OffboardState::WaitingForAgent;
  }
  return uav.failsafe.state();
}

// The segment's OffboardState of a UAV flown by a simulated autopilot: flying the
// companion's setpoints, descending in land mode, disarmed after it (PX4 by then shows the
// mode before the landing again), or before the first arming.
OffboardState Fleet::offboard_view(const fc::SimulatedAutopilot& autopilot) {
  const bool landing = autopilot.mode() == fc::FlightMode::Land;
  if (autopilot.armed()) {
    if (landing) return OffboardState::LossDescent;
    return autopilot.mode() == fc::FlightMode::Offboard ? OffboardState::Offboard
                                                        : OffboardState::WaitingForAgent;
  }
  return landing || autopilot.landed_in_land_mode() ? OffboardState::LossDisarmed
                                                    : OffboardState::WaitingForAgent;
}

bool Fleet::finished() const {
  for (const Uav& uav : uavs_) {
    if (!uav.recorder->finished(uav.world->state().time_s)) return false;
  }
  return true;
}

ClosedLoopResult Fleet::result(int u, const std::string& status, mission::MissionState state) {
  Uav& uav = uavs_[u];
  ClosedLoopResult result = uav.recorder->finish(*uav.world, uav.last_status, status, state);
  // The same metrics as the in-process harness (its JSON equals ours on the same seed).
  if (options_.transition_bounds) uav.recorder->add_transition_bounds(result);
  return result;
}

}  // namespace cover::sim
