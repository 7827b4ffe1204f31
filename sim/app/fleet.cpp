#include "fleet.hpp"

#include <cmath>

#include "cover/sim/world_uav_io.hpp"

namespace cover::sim {

Fleet::Fleet(const Scenario& scenario, const SimProcessParams& params,
             const mission::MissionParams& mission)
    : scenario_(scenario),
      physics_per_control_(
          static_cast<int>(std::lround(scenario.world.physics_rate_hz / params.control_rate_hz))) {
  options_.control_rate_hz = params.control_rate_hz;
  for (int u = 0; u < scenario.uav_count(); ++u) {
    Uav uav{std::make_unique<World>(scenario.world_of(u)),
            nullptr,
            OffboardFailsafe(params.offboard_timeout_s, params.loss_descent_rate_m_s),
            {},
            {}};
    uav.recorder =
        std::make_unique<RunRecorder>(scenario_, scenario_.task_of(u), mission, options_);
    uavs_.push_back(std::move(uav));
  }
  shared_.ugv_count = uavs_[0].world->ugv_count();
  shared_.uav_count = uav_count();
  fill_shared();
}

void Fleet::apply(int u, const mission::ControllerStatus& status,
                  const mission::ControlCommand& command, double command_age_s) {
  Uav& uav = uavs_[u];
  World& world = *uav.world;
  uav.plant_command =
      uav.failsafe.plant_command(to_plant_command(command), command_age_s, command.handover, world);
  const bool offboard = uav.failsafe.state() == OffboardState::Offboard;
  if (offboard && command.release_payload && world.release_payload()) {
    uav.recorder->record_release(world);
  }
  uav.recorder->record(status, command, world);
  uav.last_status = status;
}

void Fleet::advance() {
  for (int i = 0; i < physics_per_control_; ++i) {
    for (Uav& uav : uavs_) uav.world->step(uav.plant_command);
    capture_imu();
  }
  ++tick_;
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
    s.offboard = uavs_[u].failsafe.state();
  }
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
