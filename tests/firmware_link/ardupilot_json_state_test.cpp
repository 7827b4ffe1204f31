// The state line against ArduPilot's own reading of it (SIM_JSON.cpp recv_fdm and
// parse_sensors, replayed here): the text between the last two newlines, keys found with
// strstr, vectors read with sscanf("[%f, %f, %f]"), the readme's key list; and the frames
// against hand-worked conversions (ENU -> NED, FLU -> FRD).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include "cover/firmware_link/ardupilot_json_state.hpp"

namespace cover::firmware_link {
namespace {

constexpr double kG = 9.81;

// What ArduPilot takes from a datagram: '\n' -> NUL, the text between the last two NULs.
std::string as_firmware_frames_it(std::string datagram) {
  for (char& c : datagram) {
    if (c == '\n') c = '\0';
  }
  const auto p2 = datagram.rfind('\0');
  EXPECT_NE(p2, std::string::npos);
  EXPECT_GT(p2, 0u);
  const auto p1 = datagram.rfind('\0', p2 - 1);
  EXPECT_NE(p1, std::string::npos) << "no leading newline: the firmware would drop the line";
  return datagram.substr(p1 + 1, p2 - p1 - 1);
}

// parse_sensors: strstr for the key, past `key":`, then the sscanf of its type.
const char* after_key(const std::string& json, const char* key) {
  const std::string quoted = std::string("\"") + key + "\"";
  const char* p = std::strstr(json.c_str(), quoted.c_str());
  if (!p) return nullptr;
  return p + quoted.size() + 1;
}

Eigen::Vector3d vector3(const std::string& json, const char* key) {
  const char* p = after_key(json, key);
  EXPECT_NE(p, nullptr) << key;
  float x = NAN, y = NAN, z = NAN;
  EXPECT_EQ(std::sscanf(p, "[%f, %f, %f]", &x, &y, &z), 3) << key;
  return {x, y, z};
}

Eigen::Vector4d vector4(const std::string& json, const char* key) {
  const char* p = after_key(json, key);
  EXPECT_NE(p, nullptr) << key;
  float a = NAN, b = NAN, c = NAN, d = NAN;
  EXPECT_EQ(std::sscanf(p, "[%f, %f, %f, %f]", &a, &b, &c, &d), 4) << key;
  return {a, b, c, d};
}

PlantSample at_rest(const Eigen::Quaterniond& attitude_flu_to_enu) {
  PlantSample sample;
  sample.firmware_step = 2500;
  sample.firmware_time_s = 2.5;
  sample.dt_s = 0.001;
  sample.body.position_m = sim::Vec3(1.0, 2.0, 3.0);    // ENU
  sample.body.velocity_m_s = sim::Vec3(0.1, 0.2, 0.3);  // ENU
  sample.body.attitude = sim::Quat(attitude_flu_to_enu);
  return sample;
}

sim::UavImuSample imu_at_rest() {
  sim::UavImuSample imu;
  imu.specific_force_flu_m_s2 = {0.0, 0.0, kG};  // up, in FLU
  imu.angular_velocity_flu_rad_s = {0.1, 0.2, 0.3};
  return imu;
}

TEST(ArduPilotJsonState, TheFirmwareReadsEveryMandatoryKey) {
  const auto state =
      ardupilot_json_state(at_rest(Eigen::Quaterniond::Identity()), imu_at_rest(), true);
  const std::string datagram = write_ardupilot_json(state);
  ASSERT_EQ(datagram.front(), '\n');
  ASSERT_EQ(datagram.back(), '\n');
  const std::string json = as_firmware_frames_it(datagram);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');

  const char* t = after_key(json, "timestamp");
  ASSERT_NE(t, nullptr);
  EXPECT_DOUBLE_EQ(std::atof(t), 2.5);
  // imu.gyro, imu.accel_body: the section, then the key inside it.
  const char* imu = std::strstr(json.c_str(), "\"imu\"");
  ASSERT_NE(imu, nullptr);
  EXPECT_TRUE(std::strstr(imu, "\"gyro\""));
  EXPECT_TRUE(std::strstr(imu, "\"accel_body\""));
  // FLU -> FRD: y and z change sign. At rest the specific force reads (0, 0, -g).
  EXPECT_TRUE(vector3(json, "gyro").isApprox(Eigen::Vector3d(0.1, -0.2, -0.3), 1e-6));
  EXPECT_TRUE(vector3(json, "accel_body").isApprox(Eigen::Vector3d(0.0, 0.0, -kG), 1e-6));
  // ENU -> NED: (x, y, z) -> (y, x, -z).
  EXPECT_TRUE(vector3(json, "position").isApprox(Eigen::Vector3d(2.0, 1.0, -3.0), 1e-6));
  EXPECT_TRUE(vector3(json, "velocity").isApprox(Eigen::Vector3d(0.2, 0.1, -0.3), 1e-6));
  const char* sync = after_key(json, "no_time_sync");
  ASSERT_NE(sync, nullptr);
  EXPECT_EQ(std::strtol(sync, nullptr, 10), 1);
}

TEST(ArduPilotJsonState, RealtimeLeavesTheFirmwarePacingItself) {
  const auto state =
      ardupilot_json_state(at_rest(Eigen::Quaterniond::Identity()), imu_at_rest(), false);
  EXPECT_EQ(write_ardupilot_json(state).find("no_time_sync"), std::string::npos);
}

TEST(ArduPilotJsonState, QuaternionIsBodyFrdToNedWFirst) {
  // Identity in ENU/FLU: the nose points east, so in NED the vehicle is level at yaw +90 deg.
  {
    const std::string json = as_firmware_frames_it(write_ardupilot_json(
        ardupilot_json_state(at_rest(Eigen::Quaterniond::Identity()), imu_at_rest(), true)));
    const double h = std::sqrt(0.5);
    EXPECT_TRUE(vector4(json, "quaternion").isApprox(Eigen::Vector4d(h, 0.0, 0.0, h), 1e-6));
  }
  // Nose north (ENU yaw +90 deg): NED yaw 0, the identity.
  {
    const Eigen::Quaterniond north(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
    const std::string json = as_firmware_frames_it(
        write_ardupilot_json(ardupilot_json_state(at_rest(north), imu_at_rest(), true)));
    EXPECT_TRUE(vector4(json, "quaternion").isApprox(Eigen::Vector4d(1.0, 0.0, 0.0, 0.0), 1e-6));
  }
  // Nose north, rolled +30 deg about FLU's x (y left towards z up: the right side goes
  // down), which is FRD's +30 deg roll too: NED roll +30 deg, yaw 0.
  {
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ())) *
        Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitX()));
    const auto state = ardupilot_json_state(at_rest(q), imu_at_rest(), true);
    // Body FRD's y (right) in NED: a roll of +30 deg lowers it: down component +sin 30.
    const Eigen::Vector3d right_ned = state.attitude_frd_to_ned * Eigen::Vector3d::UnitY();
    EXPECT_NEAR(right_ned.z(), 0.5, 1e-9);
    EXPECT_NEAR(right_ned.y(), std::cos(M_PI / 6), 1e-9);
    const std::string json = as_firmware_frames_it(write_ardupilot_json(state));
    EXPECT_TRUE(
        vector4(json, "quaternion")
            .isApprox(Eigen::Vector4d(std::cos(M_PI / 12), std::sin(M_PI / 12), 0, 0), 1e-6));
  }
}

TEST(ArduPilotJsonState, TimestampKeepsMicroseconds) {
  // The firmware advances its clock by timestamp differences: a float would lose 1 ms steps
  // after ~4.6 h; the line carries the double.
  auto sample = at_rest(Eigen::Quaterniond::Identity());
  sample.firmware_time_s = 86400.001;
  const std::string json = as_firmware_frames_it(
      write_ardupilot_json(ardupilot_json_state(sample, imu_at_rest(), true)));
  EXPECT_NEAR(std::atof(after_key(json, "timestamp")) - 86400.0, 0.001, 1e-9);
}

TEST(ArduPilotJsonState, RefusesNonFiniteValues) {
  auto state = ardupilot_json_state(at_rest(Eigen::Quaterniond::Identity()), imu_at_rest(), true);
  state.velocity_ned_m_s.x() = NAN;
  EXPECT_THROW(write_ardupilot_json(state), std::invalid_argument);
}

}  // namespace
}  // namespace cover::firmware_link
