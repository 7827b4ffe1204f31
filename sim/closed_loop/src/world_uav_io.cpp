#include "cover/sim/world_uav_io.hpp"

namespace cover::sim {

bool WorldUavInputs::relative_state(int ugv, mission::RelativeMeasurement& out) {
  if (!world_.relative_sensor().has_measurement() || ugv < 0 || ugv >= world_.ugv_count()) {
    return false;
  }
  out = world_.relative_sensor().latest(ugv);
  return true;
}

bool WorldUavInputs::ugv_imu(int ugv, mission::UgvImuMeasurement& out) {
  if (!world_.imu_sensor().has_reading() || ugv < 0 || ugv >= world_.ugv_count()) return false;
  const ImuReading& reading = world_.imu_sensor().latest(ugv);
  out = to_imu_measurement(reading.filtered, reading.speed);
  return true;
}

void PlantCommandOutput::write(const uav::StepOutput& step) {
  command_ = to_plant_command(step.output->command);
}

QuadrotorCommand to_plant_command(const mission::ControlCommand& command) {
  QuadrotorCommand plant;
  plant.thrust_m_s2 = command.armed ? command.thrust_m_s2 : 0.0;
  plant.body_rate_rad_s = Vec3(command.armed ? command.body_rate_rad_s : Eigen::Vector3d::Zero());
  return plant;
}

mission::UgvImuMeasurement to_imu_measurement(const ugv::FilteredImu& imu,
                                              const ugv::SpeedEstimate& speed) {
  mission::UgvImuMeasurement m;
  m.stamp_s = imu.stamp_s;
  m.motion.specific_force_m_s2 = imu.specific_force_m_s2;
  m.motion.angular_velocity_rad_s = imu.angular_velocity_rad_s;
  m.motion.angular_acceleration_rad_s2 = imu.angular_acceleration_rad_s2;
  m.motion.speed_m_s = speed.speed_m_s;
  m.motion.speed_source = speed.source;
  return m;
}

}  // namespace cover::sim
