// PX4's frames of the plant (px4_hil_frames.hpp), against hand-worked cases: ENU/FLU ->
// NED/FRD, the sensor groups' bits, the ground truth's attitude and geodetic position.
#include "cover/firmware_link/px4_hil_frames.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace cover::firmware_link {
namespace {

namespace fields = mavlink::hil_sensor_fields;
constexpr double kG = 9.81;

PlantSample resting_sample() {
  PlantSample s;
  s.firmware_step = 4;
  s.firmware_time_s = 0.004;
  s.dt_s = 0.001;
  sim::UavImuSample imu;
  imu.specific_force_flu_m_s2 = Eigen::Vector3d(0.0, 0.0, kG);  // at rest, FLU
  imu.angular_velocity_flu_rad_s = Eigen::Vector3d(0.1, 0.2, 0.3);
  s.sensors.imu = imu;
  return s;
}

TEST(Px4HilFrames, ImuAtRestReadsMinusGInFrdAndRatesFlipYAndZ) {
  const mavlink::HilSensor m = hil_sensor(resting_sample(), 4000);
  EXPECT_EQ(m.time_usec, 4000U);
  EXPECT_EQ(m.id, 0);
  EXPECT_EQ(m.fields_updated, fields::kImu);  // 63: IMU only, nothing else due
  EXPECT_FLOAT_EQ(m.xacc, 0.0F);
  EXPECT_FLOAT_EQ(m.yacc, 0.0F);
  EXPECT_FLOAT_EQ(m.zacc, static_cast<float>(-kG));
  EXPECT_FLOAT_EQ(m.xgyro, 0.1F);
  EXPECT_FLOAT_EQ(m.ygyro, -0.2F);
  EXPECT_FLOAT_EQ(m.zgyro, -0.3F);
}

TEST(Px4HilFrames, MagAndBaroAddTheirBitsWhenDue) {
  PlantSample s = resting_sample();
  sim::MagnetometerSample mag;
  mag.field_flu_gauss = Eigen::Vector3d(0.216, -0.009, -0.426);  // FLU, facing north
  s.sensors.magnetometer = mag;
  mavlink::HilSensor m = hil_sensor(s, 8000);
  EXPECT_EQ(m.fields_updated, 511U);
  EXPECT_FLOAT_EQ(m.xmag, 0.216F);
  EXPECT_FLOAT_EQ(m.ymag, 0.009F);
  EXPECT_FLOAT_EQ(m.zmag, 0.426F);  // the field points down: +z FRD
  sim::BarometerSample baro;
  baro.pressure_hpa = 955.0;
  baro.pressure_altitude_m = 488.2;
  baro.temperature_c = 11.8;
  s.sensors.barometer = baro;
  m = hil_sensor(s, 12000);
  EXPECT_EQ(m.fields_updated, 7167U);
  EXPECT_FLOAT_EQ(m.abs_pressure, 955.0F);  // hPa, as PX4 reads it
  EXPECT_FLOAT_EQ(m.pressure_alt, 488.2F);
  EXPECT_FLOAT_EQ(m.temperature, 11.8F);
}

TEST(Px4HilFrames, GroundTruthFacingEastIsYaw90InNed) {
  PlantSample s = resting_sample();
  // ENU yaw 0 faces east; NED yaw is measured from north: +90 degrees.
  s.body.attitude = sim::Quat(Eigen::Quaterniond::Identity());
  s.body.position_m = sim::Vec3(100.0, 200.0, 3.0);  // 100 m east, 200 m north, 3 m up
  s.body.velocity_m_s = sim::Vec3(1.0, 2.0, -0.5);   // east, north, down 0.5 m/s
  s.body.body_rate_rad_s = sim::Vec3(0.1, 0.2, 0.3);
  GeodeticHome home;
  const mavlink::HilStateQuaternion m = hil_state_quaternion(s, 5000, home, kG);
  const Eigen::Quaterniond q(m.attitude_quaternion[0], m.attitude_quaternion[1],
                             m.attitude_quaternion[2], m.attitude_quaternion[3]);
  const Eigen::Matrix3d r = q.toRotationMatrix();
  EXPECT_NEAR(std::atan2(r(1, 0), r(0, 0)), M_PI / 2.0, 1e-6);  // yaw
  EXPECT_NEAR(r(2, 2), 1.0, 1e-6);                              // level: FRD z down
  EXPECT_FLOAT_EQ(m.rollspeed, 0.1F);
  EXPECT_FLOAT_EQ(m.pitchspeed, -0.2F);
  EXPECT_FLOAT_EQ(m.yawspeed, -0.3F);
  EXPECT_EQ(m.vx, 200);  // north, cm/s
  EXPECT_EQ(m.vy, 100);  // east
  EXPECT_EQ(m.vz, 50);   // down
  EXPECT_EQ(m.alt, 491000);
  // 200 m north: 200 / 6378137 rad = 0.0017966 degrees.
  EXPECT_NEAR(m.lat, std::lround((home.latitude_deg + 0.00179663) * 1e7), 2);
  EXPECT_GT(m.lon, std::lround(home.longitude_deg * 1e7));
  EXPECT_EQ(m.zacc, -1000);  // at rest: -1 g in FRD z, mG
}

}  // namespace
}  // namespace cover::firmware_link
