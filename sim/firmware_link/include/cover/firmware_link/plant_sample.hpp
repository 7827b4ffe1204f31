#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "cover/sim/motor_uav.hpp"
#include "cover/sim/uav_sensor_suite.hpp"
#include "cover/vocabulary/quadrotor_state.hpp"

namespace cover::firmware_link {

// What a firmware's simulator interface is given after each physics step, in the
// simulator's frames (ENU world, FLU body; the links convert to NED / FRD).
struct PlantSample {
  std::uint64_t firmware_step = 0;  // physics steps since the firmware booted (its clock)
  double firmware_time_s = 0.0;     // that many steps, in seconds
  double dt_s = 0.0;                // one physics step
  sim::QuadrotorState body;
  Eigen::Vector3d acceleration_world_m_s2 = Eigen::Vector3d::Zero();
  sim::UavSensorFrame sensors;  // the samples due on this step
};

inline PlantSample plant_sample(const sim::MotorUav& uav, const sim::QuadrotorState& body) {
  PlantSample sample;
  sample.firmware_step = uav.firmware_step();
  sample.firmware_time_s = uav.firmware_time_s();
  sample.dt_s = uav.dt_s();
  sample.body = body;
  sample.acceleration_world_m_s2 = uav.acceleration_world_m_s2();
  sample.sensors = uav.sensors();
  return sample;
}

}  // namespace cover::firmware_link
