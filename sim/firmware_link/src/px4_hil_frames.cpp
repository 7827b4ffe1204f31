#include "cover/firmware_link/px4_hil_frames.hpp"

#include "cover/sim/frame_conventions.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace cover::firmware_link {
namespace {

using sim::enu_to_ned;
using sim::flu_to_frd;
using sim::ned_frd_attitude;

constexpr double kEarthRadiusM = 6378137.0;  // WGS-84 equatorial: small offsets only

template <typename T>
T saturate(double value) {
  const double lo = std::numeric_limits<T>::lowest();
  const double hi = std::numeric_limits<T>::max();
  if (!std::isfinite(value)) return T{0};
  return static_cast<T>(std::lround(std::clamp(value, lo, hi)));
}

}  // namespace

mavlink::HilSensor hil_sensor(const PlantSample& sample, std::uint64_t time_usec) {
  namespace fields = mavlink::hil_sensor_fields;
  mavlink::HilSensor m;
  m.time_usec = time_usec;
  m.id = 0;
  if (sample.sensors.imu) {
    const Eigen::Vector3d f = flu_to_frd(sample.sensors.imu->specific_force_flu_m_s2);
    const Eigen::Vector3d w = flu_to_frd(sample.sensors.imu->angular_velocity_flu_rad_s);
    m.xacc = static_cast<float>(f.x());
    m.yacc = static_cast<float>(f.y());
    m.zacc = static_cast<float>(f.z());
    m.xgyro = static_cast<float>(w.x());
    m.ygyro = static_cast<float>(w.y());
    m.zgyro = static_cast<float>(w.z());
    m.fields_updated |= fields::kImu;
  }
  if (sample.sensors.magnetometer) {
    const Eigen::Vector3d b = flu_to_frd(sample.sensors.magnetometer->field_flu_gauss);
    m.xmag = static_cast<float>(b.x());
    m.ymag = static_cast<float>(b.y());
    m.zmag = static_cast<float>(b.z());
    m.fields_updated |= fields::kMag;
  }
  if (sample.sensors.barometer) {
    m.abs_pressure = static_cast<float>(sample.sensors.barometer->pressure_hpa);
    m.pressure_alt = static_cast<float>(sample.sensors.barometer->pressure_altitude_m);
    m.temperature = static_cast<float>(sample.sensors.barometer->temperature_c);
    m.fields_updated |= fields::kBaro;
  }
  return m;
}

mavlink::HilStateQuaternion hil_state_quaternion(const PlantSample& sample, std::uint64_t time_usec,
                                                 const GeodeticHome& home, double gravity_m_s2) {
  mavlink::HilStateQuaternion m;
  m.time_usec = time_usec;
  const Eigen::Quaterniond q = ned_frd_attitude(sample.body.attitude.eigen());
  m.attitude_quaternion = {static_cast<float>(q.w()), static_cast<float>(q.x()),
                           static_cast<float>(q.y()), static_cast<float>(q.z())};
  const Eigen::Vector3d w = flu_to_frd(sample.body.body_rate_rad_s.eigen());
  m.rollspeed = static_cast<float>(w.x());
  m.pitchspeed = static_cast<float>(w.y());
  m.yawspeed = static_cast<float>(w.z());

  const Eigen::Vector3d p = sample.body.position_m.eigen();  // ENU: x east, y north
  const double lat_rad = home.latitude_deg * M_PI / 180.0;
  const double lat = home.latitude_deg + p.y() / kEarthRadiusM * 180.0 / M_PI;
  const double lon =
      home.longitude_deg + p.x() / (kEarthRadiusM * std::cos(lat_rad)) * 180.0 / M_PI;
  m.lat = saturate<std::int32_t>(lat * 1e7);
  m.lon = saturate<std::int32_t>(lon * 1e7);
  m.alt = saturate<std::int32_t>((home.altitude_amsl_m + p.z()) * 1000.0);
  const Eigen::Vector3d v = enu_to_ned(sample.body.velocity_m_s.eigen()) * 100.0;
  m.vx = saturate<std::int16_t>(v.x());
  m.vy = saturate<std::int16_t>(v.y());
  m.vz = saturate<std::int16_t>(v.z());
  const double speed_cm_s = v.norm();
  m.ind_airspeed = saturate<std::uint16_t>(speed_cm_s);
  m.true_airspeed = m.ind_airspeed;
  // Specific force in FRD, mG: R^T (a - g) with g pointing down.
  const Eigen::Vector3d specific_enu =
      sample.acceleration_world_m_s2 + Eigen::Vector3d(0.0, 0.0, gravity_m_s2);
  const Eigen::Vector3d specific_flu =
      sample.body.attitude.eigen().normalized().conjugate() * specific_enu;
  const Eigen::Vector3d a = flu_to_frd(specific_flu) / gravity_m_s2 * 1000.0;
  m.xacc = saturate<std::int16_t>(a.x());
  m.yacc = saturate<std::int16_t>(a.y());
  m.zacc = saturate<std::int16_t>(a.z());
  return m;
}

}  // namespace cover::firmware_link
