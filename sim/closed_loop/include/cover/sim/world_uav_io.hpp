#pragma once

#include "cover/sim/quadrotor.hpp"
#include "cover/sim/world.hpp"
#include "cover/uav/uav_io.hpp"

namespace cover::sim {

// The UAV loop's inputs in process: the simulated sensors' latest outputs, exactly what
// the agents would receive over DDS (relative states, and each UGV's IMU after the UGV
// agent's filter).
class WorldUavInputs : public uav::UavInputs {
 public:
  explicit WorldUavInputs(const World& world) : world_(world) {}
  bool relative_state(int ugv, mission::RelativeMeasurement& out) override;
  bool ugv_imu(int ugv, mission::UgvImuMeasurement& out) override;

 private:
  const World& world_;
};

// The UAV loop's command in process: kept for the plant (motors off when disarmed).
class PlantCommandOutput : public uav::CommandOutput {
 public:
  void write(const uav::StepOutput& step) override;
  const QuadrotorCommand& command() const { return command_; }

 private:
  QuadrotorCommand command_;
};

// The plant's command for a controller command: zero thrust and rates when disarmed.
QuadrotorCommand to_plant_command(const mission::ControlCommand& command);

// The controller's view of one filtered UGV IMU reading and the speed estimated with it.
mission::UgvImuMeasurement to_imu_measurement(const ugv::FilteredImu& imu,
                                              const ugv::SpeedEstimate& speed);

}  // namespace cover::sim
