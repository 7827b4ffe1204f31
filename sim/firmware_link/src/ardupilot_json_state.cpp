#include "cover/firmware_link/ardupilot_json_state.hpp"

#include "cover/sim/frame_conventions.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace cover::firmware_link {
namespace {

using sim::enu_to_ned;
using sim::flu_to_frd;

void require_finite(double v, const char* what) {
  if (!std::isfinite(v)) {
    throw std::invalid_argument(std::string("ArduPilot JSON state: non-finite ") + what);
  }
}

void append_vector(std::string& out, const char* key, const double* v, int n) {
  char buffer[160];
  out += "\"";
  out += key;
  out += "\":[";
  for (int i = 0; i < n; ++i) {
    require_finite(v[i], key);
    std::snprintf(buffer, sizeof(buffer), i == 0 ? "%.9g" : ", %.9g", v[i]);
    out += buffer;
  }
  out += "]";
}

}  // namespace

ArduPilotJsonState ardupilot_json_state(const PlantSample& sample, const sim::UavImuSample& imu,
                                        bool no_time_sync) {
  ArduPilotJsonState state;
  state.timestamp_s = sample.firmware_time_s;
  state.gyro_frd_rad_s = flu_to_frd(imu.angular_velocity_flu_rad_s);
  state.accel_frd_m_s2 = flu_to_frd(imu.specific_force_flu_m_s2);
  state.position_ned_m = enu_to_ned(sample.body.position_m.eigen());
  state.velocity_ned_m_s = enu_to_ned(sample.body.velocity_m_s.eigen());
  state.attitude_frd_to_ned = sim::ned_frd_attitude(sample.body.attitude.eigen());
  state.no_time_sync = no_time_sync;
  return state;
}

std::string write_ardupilot_json(const ArduPilotJsonState& state) {
  require_finite(state.timestamp_s, "timestamp");
  std::string out = "\n{";
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "\"timestamp\":%.17g,", state.timestamp_s);
  out += buffer;
  out += "\"imu\":{";
  append_vector(out, "gyro", state.gyro_frd_rad_s.data(), 3);
  out += ",";
  append_vector(out, "accel_body", state.accel_frd_m_s2.data(), 3);
  out += "},";
  append_vector(out, "position", state.position_ned_m.data(), 3);
  out += ",";
  append_vector(out, "velocity", state.velocity_ned_m_s.data(), 3);
  out += ",";
  const Eigen::Quaterniond& q = state.attitude_frd_to_ned;
  const double wxyz[4] = {q.w(), q.x(), q.y(), q.z()};
  append_vector(out, "quaternion", wxyz, 4);
  if (state.no_time_sync) out += ",\"no_time_sync\":1";
  out += "}\n";
  return out;
}

}  // namespace cover::firmware_link
